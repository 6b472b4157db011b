// The interface every shadow technique implements. A technique:
//  - declares its parameters (names, ranges, defaults) so `--param k=v` is validated for it;
//  - records its shadow passes for a frame (scene, camera, light given);
//  - provides the lighting side: an HLSL include defining ShadowVisibility() and the resources it
//    reads, bound into the registers reserved for techniques (b2-b5, t0-t15, s0-s3); for the lab,
//    the include also defines ShadowLocate() and ShadowTexel() (shaders-hlsl/common/
//    shadow-lookup.hlsli) and the technique lists its map layers (Layers());
//  - times its own passes with FrameInputs::timer ("shadow", "analysis", "blur", ...).
// Adding a technique = a folder in techniques/, its HLSL in shaders-hlsl/, one registry line.
#pragma once
#include <functional>
#include <glm/glm.hpp>
#include <map>
#include <memory>
#include <sp/rhi/rhi.h>
#include <string>
#include <vector>

#include <sp/scene/gpu-scene.h>
#include <sp/tech/gpu-timer.h>

namespace sp::tech {

// --- Parameters

struct ParamSpec {
  // Text: any value; the technique validates it in Configure (e.g. a list of numbers).
  enum Kind { Int, Float, Choice, Text } kind = Int;
  std::string name;
  std::string help;
  std::string defaultValue;
  double min = 0, max = 0;             // Int and Float
  std::vector<std::string> choices;    // Choice
};

// Parsed, validated parameter values (every declared parameter present, defaults filled in).
class ParamValues {
 public:
  int getInt(const std::string& name) const;
  float getFloat(const std::string& name) const;
  const std::string& getChoice(const std::string& name) const;
  const std::map<std::string, std::string>& all() const { return values_; }

  // Validates `given` (name -> text) against `specs`; throws std::invalid_argument naming the
  // parameter and listing the valid names or values.
  static ParamValues Parse(const std::string& technique, const std::vector<ParamSpec>& specs,
                           const std::map<std::string, std::string>& given);

 private:
  std::map<std::string, std::string> values_;
};

// --- Per-frame context

// Shaders compiled for techniques: the same options everywhere (shaders-hlsl/ include path, cache).
ShaderBytecode CompileTechniqueShader(const std::string& relativePath, const std::string& target, const std::string& entry,
                                      const std::vector<hlsl::Define>& defines = {});

// The techniques compile their HLSL (shaders-hlsl/) at run time. ShaderDirectory() is, in order:
// the folder given to SetShaderDirectory(); $SHADOWPORT_SHADER_DIR; the installed package's
// share/shadowport/shaders-hlsl when the program was built with find_package(ShadowPort) (the
// package defines SHADOWPORT_PACKAGE_SHADER_DIR, registered below); the source tree the library
// was built from; the install prefix it was configured with. Throws std::runtime_error naming
// every place it looked when none holds the shaders.
std::filesystem::path ShaderDirectory();
void SetShaderDirectory(const std::filesystem::path& directory);  // empty: back to the search
bool RegisterPackageShaderDirectory(const char* directory);

#ifdef SHADOWPORT_PACKAGE_SHADER_DIR
// Defined by ShadowPortConfig.cmake for programs linking ShadowPort::techniques, so that a
// relocated install (cmake --install --prefix anywhere) uses its own shaders with no set-up.
inline const bool kShadowPortPackageShadersRegistered = RegisterPackageShaderDirectory(SHADOWPORT_PACKAGE_SHADER_DIR);
#endif

// A local light as the lit pass shades it (shaders-hlsl/common/local-lights.hlsli): the scene's
// point lights first, in order, then its spot lights, so local light i < scene.pointLights.size()
// is point light i. Local-light techniques name the lights they shadow by this index.
struct LocalLight {
  enum Type { Point = 0, Spot = 1 } type = Point;
  glm::vec3 position{0.0f};
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  // spot: unit axis, the way the light travels
  glm::vec3 color{1.0f};
  float range = 10.0f;
  float cosInner = 1.0f, cosOuter = -1.0f;  // spot: cosines of the cone angles; point: -1 (no cone)
};
std::vector<LocalLight> LocalLightsOf(const scene::Scene& scene);
// The lit pass shades at most this many local lights; the Renderer refuses scenes with more.
constexpr uint32_t kMaxLocalLights = 32;

struct FrameInputs {
  const scene::Scene* scene = nullptr;
  scene::Camera camera;
  scene::DirectionalLight light;
  // The scene's local lights (LocalLightsOf), shaded by the lit pass after the directional light.
  // Directional techniques ignore them; a local-light technique shadows some of them, and its
  // lighting include defines SP_LOCAL_SHADOWS and LocalShadowVisibility(light index, ...) (see
  // shaders-hlsl/common/local-lights.hlsli), returning 1 for the lights it does not shadow.
  std::vector<LocalLight> localLights;
  uint32_t width = 0, height = 0;  // of the lit pass
  glm::mat4 cameraView{1.0f}, cameraProj{1.0f};
  // Set while the lab measures GPU time; techniques bracket their passes with
  // GpuTimer::Scope(timer, ctx, "shadow") (a null timer makes the scope a no-op).
  GpuTimer* timer = nullptr;
};

// Draws the scene's geometry from a given view-projection with the depth-only shader (what every
// shadow pass does); owned by the renderer, offered to techniques.
class SceneDrawer {
 public:
  SceneDrawer(Device& device, const scene::GpuScene& gpu);
  // Binds the depth-only pipeline and draws every instance; returns triangles submitted. The
  // caller has set render targets, viewport and rasterizer state.
  uint64_t DrawDepth(DeviceContext& ctx, const glm::mat4& viewProj);
  // The same for the instances `keep` accepts (a technique's culling against its light frustum).
  uint64_t DrawDepth(DeviceContext& ctx, const glm::mat4& viewProj, const std::function<bool(uint32_t instance)>& keep);
  // The same with a technique's own shaders in place of depth-only's (e.g. a pixel shader that
  // writes SV_Depth). `vs` must read depth-only's vertex input (POSITION) and may read Frame and
  // Object (b0, b1), which are bound to both stages; `ps` may be null. The caller binds anything
  // else they read.
  struct DepthShaders {
    VertexShader* vs = nullptr;
    PixelShader* ps = nullptr;
  };
  uint64_t DrawDepth(DeviceContext& ctx, const glm::mat4& viewProj, const std::function<bool(uint32_t instance)>& keep,
                     const DepthShaders& shaders);
  // Every draw item once, with DrawIndexedInstancedIndirect: item i's arguments are the 20 bytes at
  // firstArgsByte + 20 i of `args` (RESOURCE_MISC_DRAWINDIRECT_ARGS), written on the GPU, so the
  // instance count can come from a compute pass the CPU never reads (adaptive shadow maps'
  // allocation=gpu draws each new page as one instance). IndirectArgsOfDraws gives the items'
  // arguments with InstanceCount 0, in that order. `shaders` as DrawDepth's; the triangle count
  // is the GPU's to know, so none is returned.
  void DrawDepthIndirect(DeviceContext& ctx, const glm::mat4& viewProj, const DepthShaders& shaders, Buffer* args, uint32_t firstArgsByte);
  std::vector<uint32_t> IndirectArgsOfDraws() const;
  // One pass into `layers` layers of a layered depth target (a DSV_DIMENSION_TEXTURE2DARRAY
  // view of that many slices, bound by the caller with viewport and rasterizer state): layer l is
  // drawn with viewProj[l], and each draw item is submitted once, instanced once per layer
  // keep(instance, l) accepts, its vertex shader choosing the layer (SV_RenderTargetArrayIndex).
  // Writes the same depth as a DrawDepth per layer. Needs DeviceInfo::vsRenderTargetArrayIndex
  // (throws std::invalid_argument naming it otherwise); layers <= kMaxDepthLayers. Binds VS b7, b8.
  static constexpr uint32_t kMaxDepthLayers = 8;
  uint64_t DrawDepthLayered(DeviceContext& ctx, const glm::mat4* viewProj, uint32_t layers,
                            const std::function<bool(uint32_t instance, uint32_t layer)>& keep);
  // Writes Frame (b0) for a pass and Object (b1) per instance; used by the lit pass too.
  void SetFrame(DeviceContext& ctx, const glm::mat4& viewProj, const FrameInputs* lighting);
  void SetObject(DeviceContext& ctx, uint32_t instance);
  void BindConstants(DeviceContext& ctx, ShaderStage stage);
  const scene::GpuScene& gpu() const { return gpu_; }

 private:
  // Frame constants, geometry, the depth-only input layout and the pass's shaders and constants.
  void BindDepthPass(DeviceContext& ctx, const glm::mat4& viewProj, const DepthShaders& shaders);
  const scene::GpuScene& gpu_;
  Ref<Buffer> frame_, object_;
  Ref<VertexShader> depthVs_;
  Ref<InputLayout> depthLayout_;
  Ref<VertexShader> layeredVs_;  // made by the first DrawDepthLayered
  Ref<Buffer> layerViews_, layerList_;
};

// --- Resources every technique makes the same way (technique-resources.cpp)

// A depth map rendered as D32_FLOAT and read as R32_FLOAT (an R32_TYPELESS texture).
struct DepthMap {
  Ref<Texture2D> texture;
  Ref<DepthStencilView> dsv;
  Ref<ShaderResourceView> srv;
};
DepthMap MakeDepthMap(Device& device, uint32_t width, uint32_t height, const char* name);
// One D32_FLOAT depth-stencil view per array slice of a shadow-map array (R32_TYPELESS, single
// or multisampled), for techniques that render one cascade or partition per slice.
std::vector<Ref<DepthStencilView>> MakeSliceDepthViews(Device& device, Texture2D* texture);
// The R32_FLOAT Texture2DArray view of every slice of such an array, for comparison lookups.
Ref<ShaderResourceView> MakeSliceArraySrv(Device& device, Texture2D* texture);
// The comparison sampler of the lighting includes: bilinear 2x2 PCF, LESS_EQUAL (receiver at or
// in front of the stored depth is lit), BORDER addressing with depth 1 so outside the map is lit.
Ref<SamplerState> MakeShadowComparisonSampler(Device& device);
Ref<Buffer> MakeConstantBuffer(Device& device, uint32_t bytes, const char* name);
// USAGE_DYNAMIC with CPU write access: rewritten every frame through Map(WRITE_DISCARD).
Ref<Buffer> MakeDynamicBuffer(Device& device, uint32_t bytes, uint32_t bindFlags, const char* name);
// A buffer for raw (ByteAddressBuffer) views, and its whole-buffer raw views.
Ref<Buffer> MakeRawBuffer(Device& device, uint32_t bytes, uint32_t bindFlags, const char* name, uint32_t extraMiscFlags = 0);
Ref<UnorderedAccessView> MakeRawUav(Device& device, Buffer* buffer);
Ref<ShaderResourceView> MakeRawSrv(Device& device, Buffer* buffer);

// One layer of a technique's shadow maps as the lab's ShadowLocate() numbers them (a cascade, an
// array slice, an atlas region): its size in texels. Layer i of Layers() is layer id i in HLSL.
struct ShadowLayer {
  uint32_t width = 0, height = 0;
};

struct ShadowStats {
  uint64_t memoryBytes = 0;        // shadow resources
  uint64_t trianglesSubmitted = 0; // in shadow passes, last frame
  uint32_t layersRendered = 0;     // shadow-map layers drawn last frame (cube faces); 0 when not counted
};

class Technique {
 public:
  virtual ~Technique() = default;
  virtual std::string Name() const = 0;
  virtual std::vector<ParamSpec> Params() const = 0;
  // Called once with validated parameters, before the first frame.
  virtual void Configure(Device& device, const ParamValues& params) = 0;
  // Records the shadow passes of one frame. Leaves render targets in any state.
  virtual void RenderShadows(DeviceContext& ctx, SceneDrawer& drawer, const FrameInputs& frame) = 0;
  // The lighting include (relative to shaders-hlsl/) and its defines.
  virtual std::string LightingInclude() const = 0;
  virtual std::vector<hlsl::Define> LightingDefines() const { return {}; }
  // Binds what ShadowVisibility() reads, into PS registers b2-b5, t0-t15, s0-s3.
  virtual void BindLighting(DeviceContext& ctx) = 0;
  virtual ShadowStats Stats() const = 0;
  // The layers ShadowLocate() can return, for the lab's utilization metric (valid after Configure).
  virtual std::vector<ShadowLayer> Layers() const = 0;
  // The texture holding the shadow map(s) ShadowLocate() reads (array slices: cascades,
  // partitions, cube faces; an atlas as one slice), for programs that show it (samples/viewer's
  // shadow-map view); valid after the first RenderShadows. Null: no single map texture to show.
  virtual Texture2D* ShadowMapTexture() const { return nullptr; }
  // The light the lab judges this technique on in `scene`: -1 (every directional technique) the
  // directional light; otherwise the local light (LocalLightsOf(scene) index) whose shadow
  // ShadowLocate() reports. The lab's lit pass then writes that light's N.L (0 where it lights
  // nothing: beyond its range, outside a spot's outer cone) and LocalShadowVisibility() for it,
  // and the bench traces the reference from its position.
  virtual int LabLocalLight(const scene::Scene& scene) const { return -1; }
};

// --- Registry (techniques/registry.cpp: one line per technique)

std::unique_ptr<Technique> CreateTechnique(const std::string& name);  // throws std::invalid_argument
std::vector<std::string> TechniqueNames();

}  // namespace sp::tech
