// Private interface of the OpenGL 4.5 backend (EGL, headless, direct state access).
//
// Ownership: GLDevice owns the EGL context; every core object carries one of the Backend
// structs below, which frees its GL names in its destructor (the device makes its context
// current first, so objects can be released from any point in the program's flow on the device's
// thread). GLContext owns the caches that refer to GL names (framebuffers, program pipelines,
// bound units); deleting a name tells the context to forget it, because GL reuses names.
#pragma once
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "backend.h"
#include "shader-bindings.h"

namespace sp::gl {

using namespace sp::detail;

class GLDevice;
class GLContext;

// ---------------------------------------------------------------------------------------------
// Formats (gl-formats.cpp)

struct GLFormat {
  GLenum internal = 0;     // sized internal format (storage, views, images, texture buffers)
  GLenum extFormat = 0;    // client format/type that reproduces D3D's memory layout byte for byte
  GLenum extType = 0;
  bool integer = false;    // *_INTEGER client formats, integer samplers
  bool depth = false, stencil = false;
  // Vertex attribute (size 0: not a vertex format).
  GLint attribSize = 0;
  GLenum attribType = 0;
  bool attribNormalized = false;
  bool attribInteger = false;
  bool textureBuffer = false;  // in GL's texture-buffer format table
  bool image = false;          // in GL's image load/store format table
};

// Format used for a FORMAT in views and transfers. Depth-family formats map to their depth
// storage format; TYPELESS colour formats to the typed member used for storage.
const GLFormat& FormatOf(FORMAT format);
// The format a texture is stored in: depth formats for BIND_DEPTH_STENCIL textures (and the
// packed depth-stencil families, which have no colour equivalent), otherwise FormatOf.
const GLFormat& StorageFormatOf(const TextureShape& shape);
bool IsDepthStorage(const TextureShape& shape);

// ---------------------------------------------------------------------------------------------
// Backend objects

// A CPU-visible GL buffer (staging resources): persistently mapped, coherent, with a fence on
// the last GPU command that used it so Map waits exactly as long as needed.
struct GLStagingMemory {
  GLuint buffer = 0;
  uint8_t* ptr = nullptr;
  GLsync fence = nullptr;
  void Create(GLsizeiptr size, const void* init);
  void Destroy(GLDevice& dev);
  void MarkGpuUse();          // after a GPU command that reads or writes the buffer
  bool Wait(bool doNotWait);  // false: still busy and doNotWait
};

struct GLBuffer : detail::BackendObject {
  GLDevice* dev = nullptr;
  GLuint name = 0;
  uint32_t size = 0;
  USAGE usage = USAGE_DEFAULT;
  bool constant = false;
  // Constant buffers keep the D3D-packed contents on the CPU for the std140 repack path.
  std::vector<uint8_t> shadow;
  // GPU-side writes (copies into the buffer) make `shadow` stale; it is read back only when a
  // repack or a partial update needs it, so a GPU copy into a constant buffer does not wait.
  bool shadowStale = false;
  uint64_t version = 1;  // bumped on every write to a constant buffer
  // A DYNAMIC constant buffer's writes (Map WRITE_DISCARD) stay in `shadow` and reach draws
  // through the context's upload ring, one slice per version: orphaning `name` on every Unmap
  // cost Mesa a reallocation per draw. `name` is brought up to date only when a copy reads it.
  bool storageStale = false;
  GLStagingMemory staging;  // USAGE_STAGING: `name` is staging.buffer
  bool mappedGL = false;    // USAGE_DYNAMIC non-constant buffer mapped through GL
  ~GLBuffer() override;
};

// Brings a constant buffer's CPU copy up to date after GPU writes (CopyResource and friends).
void RefreshShadow(GLBuffer& b);
// Writes `shadow` into the GL storage of a constant buffer whose writes went to the ring only.
void RefreshStorage(GLBuffer& b);

struct SubresourceLayout {
  uint64_t offset = 0;
  uint32_t rowPitch = 0, depthPitch = 0;
  uint32_t width = 1, height = 1, depth = 1;
};

struct GLTexture : detail::BackendObject {
  GLDevice* dev = nullptr;
  TextureShape shape;
  GLuint name = 0;  // 0 for staging textures
  GLenum target = 0;
  const GLFormat* storage = nullptr;
  // USAGE_STAGING: a GL buffer laid out as D3D maps the texture.
  GLStagingMemory staging;
  std::vector<SubresourceLayout> subresources;
  // D24S8 staging subresources holding GL's packing (depth high, stencil low) after a GPU copy;
  // converted to D3D's packing before the CPU or another copy sees them.
  std::vector<uint8_t> glPacked;
  // USAGE_DYNAMIC: CPU memory behind Map(WRITE_DISCARD), uploaded on Unmap.
  std::vector<std::vector<uint8_t>> dynamicData;
  ~GLTexture() override;
  bool isStaging() const { return shape.usage == USAGE_STAGING; }
  // Whether the storage has layers (1D, 2D and 2D multisample arrays; cube maps are 2D arrays).
  bool arrayed() const;
};

struct GLView : detail::BackendObject {
  enum class Kind : uint8_t { Texture, TypedBuffer, StorageBuffer };
  GLDevice* dev = nullptr;
  Kind kind = Kind::Texture;
  GLuint texture = 0;      // the storage texture, a texture view, or a buffer texture
  bool ownsTexture = false;
  GLenum target = 0;
  const GLFormat* format = nullptr;  // the view's format (that of `texture` too)
  // Framebuffer attachment (RTV/DSV) or image binding (UAV).
  GLint level = 0;
  GLint layer = -1;  // -1: whole texture (layered when it has layers)
  bool layered = false;
  // Buffer views: the byte range (bound as a storage block, or behind the buffer texture).
  GLuint buffer = 0;
  GLintptr offset = 0;
  GLsizeiptr size = 0;
  GLuint counter = 0;  // hidden counter of append/counter UAVs
  GLuint clearView = 0;  // UAVs of non-integer formats: a same-size uint view for bit-exact clears, made on first clear
  ~GLView() override;
};

struct GLSampler : detail::BackendObject {
  GLDevice* dev = nullptr;
  GLuint name = 0;
  ~GLSampler() override;
};

struct GLShader : detail::BackendObject {
  GLDevice* dev = nullptr;
  const Shader* owner = nullptr;
  GLuint program = 0;
  GLuint dualSourceProgram = 0;  // pixel shaders writing SV_Target1, compiled on first use
  GLuint computePipeline = 0;
  bool writesTarget1 = false;
  ~GLShader() override;
};

struct GLQuerySegment;  // gl-query.cpp
struct GLQuery : detail::BackendObject {
  GLDevice* dev = nullptr;
  QUERY type = QUERY_EVENT;
  GLuint name = 0;  // TIMESTAMP
  GLsync fence = nullptr;  // EVENT, TIMESTAMP_DISJOINT
  bool ended = false;
  std::vector<std::shared_ptr<GLQuerySegment>> segments;  // OCCLUSION
  ~GLQuery() override;
};

// ---------------------------------------------------------------------------------------------
// The device

// The device backend. It owns the EGL context; the core (sp::Device) owns it, and destroys it
// only after the immediate context and every object's GL names are gone.
class GLDevice final : public detail::DeviceBackend {
 public:
  GLDevice(Device& core, const DeviceDesc& desc);
  ~GLDevice() override;

  void MakeCurrent() const;
  EGLDisplay eglDisplay() const { return display_; }
  EGLContext eglContext() const { return egl_; }
  void* x11Display() const { return x11Display_; }
  GLContext* context() const { return context_; }
  void DetachContext() { context_ = nullptr; }

  // Names are released through these so the context's caches forget them.
  void DeleteTexture(GLuint name);
  void DeleteBuffer(GLuint name);
  void DeleteSampler(GLuint name);
  void DeleteProgram(GLuint name);
  void DeleteProgramPipeline(GLuint name);

  GLint ssboAlignment = 16, uboAlignment = 256, tboAlignment = 16;
  bool hasFilterMinmax = false;
  PFNGLPOLYGONOFFSETCLAMPEXTPROC polygonOffsetClamp = nullptr;
  const DeviceInfo& info() const { return info_; }
  bool suppressDebugMessages = false;  // while compiling: failures are reported as sp::Error
  void OnDebugMessage(GLenum source, GLenum type, GLuint id, GLenum severity, const char* message);

  std::unique_ptr<detail::BackendObject> CreateBufferBackend(Buffer& buffer, const SUBRESOURCE_DATA* init) override;
  std::unique_ptr<detail::BackendObject> CreateTextureBackend(Texture& texture, const SUBRESOURCE_DATA* init) override;
  std::unique_ptr<detail::BackendObject> CreateViewBackend(View& view) override;
  std::unique_ptr<detail::BackendObject> CreateSamplerBackend(SamplerState& sampler) override;
  std::unique_ptr<detail::BackendObject> CreateShaderBackend(Shader& shader) override;
  std::unique_ptr<detail::BackendObject> CreateQueryBackend(Query& query) override;
  std::unique_ptr<detail::ContextBackend> CreateContextBackend() override;
  std::unique_ptr<detail::SwapChainBackend> CreateSwapChainBackend(const SwapChainDesc& desc, unsigned long visualId) override;
  uint32_t FormatSupportBackend(FORMAT format) const override;
  uint32_t MaxSampleCountBackend(FORMAT format) const override;
  bool SampleCountSupportedBackend(FORMAT format, uint32_t count) const override;

 private:
  void Init(const DeviceDesc& desc);
  void InitFormatSupport();
  std::vector<GLint> SampleCounts(GLenum internal) const;

  void* x11Display_ = nullptr;  // DeviceDesc::x11Display
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext egl_ = EGL_NO_CONTEXT;
  GLContext* context_ = nullptr;
  std::array<uint32_t, 128> support_{};
  std::array<std::vector<GLint>, 128> samples_{};
  // Mesa's "glValidateProgramPipeline: ... does not meet strict OpenGL ES 3.1 requirements"
  // message, once recognised (its id is assigned at run time); 0 until then.
  GLuint esPipelineMessageId_ = 0;
};

// Entry points of the per-area files, called by GLDevice.
std::unique_ptr<detail::BackendObject> CreateGLBuffer(GLDevice& dev, Buffer& buffer, const SUBRESOURCE_DATA* init);
std::unique_ptr<detail::BackendObject> CreateGLTexture(GLDevice& dev, Texture& texture, const SUBRESOURCE_DATA* init);
std::unique_ptr<detail::BackendObject> CreateGLView(GLDevice& dev, View& view);
std::unique_ptr<detail::BackendObject> CreateGLSampler(GLDevice& dev, SamplerState& sampler);
std::unique_ptr<detail::BackendObject> CreateGLShader(GLDevice& dev, Shader& shader);
std::unique_ptr<detail::BackendObject> CreateGLQuery(GLDevice& dev, Query& query);
std::unique_ptr<detail::ContextBackend> CreateGLContext(GLDevice& dev);

// A program for a pixel shader whose SV_Target1 is the second source of dual-source blending.
GLuint DualSourceProgram(GLDevice& dev, GLShader& shader);

// ---------------------------------------------------------------------------------------------
// Helpers shared by the transfer code

// A D3D region (x, y, z or array layer, extent) in the coordinates GL uses for a target: 1D
// arrays keep layers in y, 2D arrays and cubes in z.
struct GLRegion {
  GLint x = 0, y = 0, z = 0;
  GLsizei w = 1, h = 1, d = 1;
};
GLRegion RegionOf(GLenum target, uint32_t x, uint32_t y, uint32_t z, uint32_t w, uint32_t h, uint32_t d);

// D24S8 packing conversions, in place, for `count` texels.
void D24S8ToD3D(uint32_t* texels, size_t count);
void D24S8ToGL(uint32_t* texels, size_t count);

// Uploads D3D-laid-out rows (rowPitch/depthPitch) into a region of a texture, from client memory
// or, when `pbo` is non-zero, from that buffer at byte offset `data`.
void UploadRegion(GLTexture& t, const detail::Subresource& sub, uint32_t x, uint32_t y, uint32_t z, uint32_t w, uint32_t h, uint32_t d,
                  const void* data, uint32_t rowPitch, uint32_t depthPitch, GLuint pbo = 0);

inline GLTexture& GL(const Texture* t) { return detail::BackendAs<GLTexture>(t); }
inline GLBuffer& GL(const Buffer* b) { return detail::BackendAs<GLBuffer>(b); }
inline GLView& GL(const View* v) { return detail::BackendAs<GLView>(v); }

GLenum CompareFunc(COMPARISON_FUNC f);

[[noreturn]] void ThrowError(ErrorId id, const std::string& call, const std::string& object, const std::string& detail);

}  // namespace sp::gl
