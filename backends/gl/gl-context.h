// The GL immediate context: D3D11 draws, dispatches and transfers on one GL context, with a
// cache of the GL state it has set so redundant calls are skipped.
#pragma once
#include "gl-internal.h"

namespace sp::gl {

// Calls `apply` and records `value` unless the cache already holds it.
template <class T, class F>
inline void SetCached(std::optional<T>& cache, const T& value, F&& apply) {
  if (!cache || !(*cache == value)) {
    apply();
    cache = value;
  }
}

struct Attachment {
  GLuint texture = 0;
  GLint level = 0;
  GLint layer = -1;  // -1: the whole texture (layered for arrays and 3D)
  auto operator<=>(const Attachment&) const = default;
};

struct FramebufferKey {
  std::array<Attachment, SIMULTANEOUS_RENDER_TARGET_COUNT> colors{};
  Attachment depth;
  GLenum depthPoint = 0;  // GL_DEPTH_ATTACHMENT or GL_DEPTH_STENCIL_ATTACHMENT
  uint32_t emptyWidth = 0, emptyHeight = 0, emptyLayers = 0;  // framebuffers without attachments
  auto operator<=>(const FramebufferKey&) const = default;
};

struct RangeBinding {
  GLuint buffer = 0;
  GLintptr offset = 0;
  GLsizeiptr size = 0;
  bool operator==(const RangeBinding&) const = default;
};

struct ImageBinding {
  GLuint texture = 0;
  GLint level = 0;
  bool layered = false;
  GLint layer = 0;
  GLenum format = 0;
  bool operator==(const ImageBinding&) const = default;
};

struct StencilFace {
  GLenum func = GL_ALWAYS;
  GLint ref = 0;
  GLuint readMask = 0xff;
  GLenum fail = GL_KEEP, depthFail = GL_KEEP, pass = GL_KEEP;
  GLuint writeMask = 0xff;
  bool operator==(const StencilFace&) const = default;
};

struct BlendEquation {
  GLenum srcRGB = GL_ONE, dstRGB = GL_ZERO, srcAlpha = GL_ONE, dstAlpha = GL_ZERO;
  GLenum opRGB = GL_FUNC_ADD, opAlpha = GL_FUNC_ADD;
  bool operator==(const BlendEquation&) const = default;
};

struct AttribFormat {
  GLint size = 0;
  GLenum type = 0;
  bool normalized = false, integer = false;
  bool operator==(const AttribFormat&) const = default;
};

struct VertexBinding {
  GLuint buffer = 0;
  GLintptr offset = 0;
  GLsizei stride = 0;
  GLuint divisor = 0;
  bool operator==(const VertexBinding&) const = default;
};

constexpr uint32_t kMaxAttribs = 16;
constexpr uint32_t kTextureUnits = 64;
constexpr uint32_t kUniformBindings = 48;
constexpr uint32_t kStorageBindings = 64;
constexpr uint32_t kImageUnits = PS_CS_UAV_REGISTER_COUNT;

// What GL currently has set (nullopt: unknown, set on next use).
struct GLStateCache {
  std::optional<bool> cull, polygonOffsetFill, polygonOffsetLine, depthClamp, scissorTest, primitiveRestart;
  std::optional<GLenum> cullFace, frontFace, polygonMode;
  std::optional<std::array<float, 3>> polygonOffset;
  std::array<std::optional<std::array<float, 4>>, VIEWPORT_AND_SCISSORRECT_OBJECT_COUNT_PER_PIPELINE> viewports;
  std::array<std::optional<std::array<double, 2>>, VIEWPORT_AND_SCISSORRECT_OBJECT_COUNT_PER_PIPELINE> depthRanges;
  std::array<std::optional<std::array<GLint, 4>>, VIEWPORT_AND_SCISSORRECT_OBJECT_COUNT_PER_PIPELINE> scissors;
  std::optional<bool> depthTest, depthMask, stencilTest;
  std::optional<GLenum> depthFunc;
  std::array<std::optional<StencilFace>, 2> stencil;  // front, back
  std::array<std::optional<bool>, SIMULTANEOUS_RENDER_TARGET_COUNT> blend;
  std::array<std::optional<BlendEquation>, SIMULTANEOUS_RENDER_TARGET_COUNT> blendEquations;
  std::array<std::optional<uint8_t>, SIMULTANEOUS_RENDER_TARGET_COUNT> colorMasks;
  std::optional<std::array<float, 4>> blendColor;
  std::optional<bool> alphaToCoverage, sampleMaskEnabled;
  std::optional<uint32_t> sampleMask;

  std::optional<GLuint> drawFramebuffer, readFramebuffer, pipeline;
  std::array<std::optional<GLuint>, kTextureUnits> textures, samplers;
  std::array<std::optional<RangeBinding>, kUniformBindings> uniformBuffers;
  std::array<std::optional<RangeBinding>, kStorageBindings> storageBuffers;
  std::array<std::optional<ImageBinding>, kImageUnits> images;
  std::array<std::optional<AttribFormat>, kMaxAttribs> attribFormats;
  std::array<std::optional<bool>, kMaxAttribs> attribEnabled;
  std::array<std::optional<VertexBinding>, kMaxAttribs> vertexBindings;
  std::optional<GLuint> elementBuffer;
};

class GLContext final : public detail::ContextBackend {
 public:
  explicit GLContext(GLDevice& dev);
  ~GLContext() override;

  void Draw(const PipelineState& state, uint32_t dirty, const detail::DrawArgs& args) override;
  void Dispatch(const PipelineState& state, uint32_t dirty, uint32_t x, uint32_t y, uint32_t z, Buffer* argsBuffer,
                uint32_t argsOffset) override;
  void ClearRenderTargetView(RenderTargetView* rtv, const float rgba[4]) override;
  void ClearDepthStencilView(DepthStencilView* dsv, uint32_t clearFlags, float depth, uint8_t stencil) override;
  void ClearUnorderedAccessView(UnorderedAccessView* uav, const detail::UavClearValue& value) override;
  void CopyResource(Resource* dst, Resource* src) override;
  void CopySubresourceRegion(Resource* dst, const detail::Subresource& dstSub, uint32_t dstX, uint32_t dstY, uint32_t dstZ, Resource* src,
                             const detail::Subresource& srcSub, const BOX& srcBox) override;
  void UpdateSubresource(Resource* dst, const detail::Subresource& dstSub, const BOX& box, const void* data, uint32_t rowPitch,
                         uint32_t depthPitch) override;
  bool Map(Resource* resource, const detail::Subresource& sub, MAP type, uint32_t flags, MAPPED_SUBRESOURCE* out) override;
  void Unmap(Resource* resource, const detail::Subresource& sub) override;
  void GenerateMips(ShaderResourceView* srv) override;
  void ResolveSubresource(Resource* dst, const detail::Subresource& dstSub, Resource* src, const detail::Subresource& srcSub, FORMAT format) override;
  void CopyStructureCount(Buffer* dst, uint32_t dstOffset, UnorderedAccessView* src) override;
  void SetUavCounter(UnorderedAccessView* uav, uint32_t value) override;
  void Begin(Query* query) override;
  void End(Query* query) override;
  bool GetData(Query* query, void* data, uint32_t size, uint32_t flags) override;
  void Flush() override;
  void WaitIdle() override;

  // GL names are reused after deletion: caches must not keep them.
  void ForgetTexture(GLuint name);
  void ForgetBuffer(GLuint name);
  void ForgetSampler(GLuint name);
  void ForgetProgram(GLuint name);
  void ForgetPipeline(GLuint name);

  GLDevice& device() { return dev_; }
  GLStateCache& cache() { return cache_; }

  // gl-framebuffer.cpp
  static Attachment AttachmentOf(const View* view);
  static GLenum DepthAttachmentPoint(const View* dsv);
  GLuint Framebuffer(const FramebufferKey& key, const char* call);
  void BindDrawFramebuffer(GLuint fbo);
  void BindReadFramebuffer(GLuint fbo);

  // gl-state.cpp: fixed-function state from the pipeline, and the pieces clears override.
  void ApplyRasterizer(const PipelineState& s);
  void ApplyViewports(const PipelineState& s);
  void ApplyDepthStencil(const PipelineState& s);
  void ApplyBlend(const PipelineState& s, bool hasPixelShader);
  void SetScissorTest(bool enabled);
  void SetPrimitiveRestart(bool enabled);  // checked at every indexed draw: follows the topology
  void SetColorMask(uint32_t drawBuffer, uint8_t mask);
  void SetDepthMask(bool write);
  void SetStencilWriteMask(GLuint mask);

  // Upload ring for repacked constant buffers and scratch data.
  GLintptr UploadToRing(const void* data, size_t size);
  GLuint ring() const { return ring_; }
  uint64_t ringGeneration() const { return ringGeneration_; }

  // Occlusion segments (gl-query.cpp).
  void SplitOcclusionSegment();

  // Queries still open in GL when the context goes away.
  std::vector<GLQuery*> activeOcclusion;
  std::shared_ptr<GLQuerySegment> currentSegment;

 private:
  // gl-context.cpp
  void ApplyProgram(const PipelineState& s);
  void ApplyFramebuffer(const PipelineState& s);
  void ApplyInput(const PipelineState& s);
  GLbitfield BindStage(const PipelineState& s, ShaderStage stage);
  void BindUniformBlock(const Shader& shader, size_t bindingIndex, const Buffer* buffer);
  void BindRange(GLenum target, GLuint index, const RangeBinding& r);
  void BindTexture(GLuint unit, GLuint texture, GLuint sampler);
  GLuint IndexScratch(const PipelineState& s);

  GLDevice& dev_;
  GLStateCache cache_;
  // Groups of draw state (in the core's dirty bits) whose GL state the context changed itself
  // since the last draw: clears, the swap chain's blit, compute, objects deleted from the cache.
  uint32_t disturbed_ = detail::DIRTY_ALL;
  GLuint vao_ = 0;
  GLuint loadSampler_ = 0;  // point sampler for Load/texelFetch and MS textures
  std::map<FramebufferKey, GLuint> framebuffers_;
  std::map<std::pair<GLuint, GLuint>, GLuint> pipelines_;  // (vs program, ps program) -> pipeline
  void NewRing(size_t size);
  GLuint ring_ = 0;
  uint8_t* ringData_ = nullptr;  // persistently mapped, coherent
  size_t ringSize_ = 0, ringCursor_ = 0;
  uint64_t ringGeneration_ = 0;
  GLuint indexScratch_ = 0;
  size_t indexScratchSize_ = 0;
  // Last repacked upload per uniform binding: (buffer uid, version, ring generation, repack table).
  struct RepackRecord {
    uint64_t uid = 0, version = 0, generation = 0, shaderUid = 0;
    size_t bindingIndex = 0;
    RangeBinding range;
  };
  std::array<RepackRecord, kUniformBindings> repacked_{};
};

}  // namespace sp::gl
