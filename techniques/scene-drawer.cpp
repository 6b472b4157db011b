#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

#include <sp/tech/technique.h>

namespace sp::tech {

namespace {

// Constant buffer layouts; must match shaders-hlsl/common/frame.hlsli (D3D packing).
struct FrameConstants {
  glm::mat4 viewProj;
  glm::vec3 cameraPos;
  float ambient;
  glm::vec3 toLight;
  float frameTime;
  glm::vec3 lightColor;
  float pad;
};
static_assert(sizeof(FrameConstants) == 112);

struct ObjectConstants {
  glm::mat4 world;
  glm::vec3 albedo;
  float pad;
};
static_assert(sizeof(ObjectConstants) == 80);

Ref<Buffer> DynamicConstants(Device& device, uint32_t size, const char* name) { return MakeDynamicBuffer(device, size, BIND_CONSTANT_BUFFER, name); }

template <class T>
void Upload(DeviceContext& ctx, Buffer* b, const T& value) {
  MAPPED_SUBRESOURCE m;
  ctx.Map(b, 0, MAP_WRITE_DISCARD, 0, &m);
  std::memcpy(m.pData, &value, sizeof(T));
  ctx.Unmap(b, 0);
}

}  // namespace

ShaderBytecode CompileTechniqueShader(const std::string& rel, const std::string& target, const std::string& entry,
                                      const std::vector<hlsl::Define>& defines) {
  hlsl::CompileOptions o;
  o.target = target;
  o.entryPoint = entry;
  o.defines = defines;
  o.includeDirs = {ShaderDirectory()};
  return hlsl::CompileFile(ShaderDirectory() / rel, o);
}

SceneDrawer::SceneDrawer(Device& device, const scene::GpuScene& gpu) : gpu_(gpu) {
  frame_ = DynamicConstants(device, sizeof(FrameConstants), "Frame constants");
  object_ = DynamicConstants(device, sizeof(ObjectConstants), "Object constants");
  ShaderBytecode vs = CompileTechniqueShader("common/depth-only.hlsl", "vs_5_0", "VSMain");
  depthVs_ = device.CreateVertexShader(vs);
  uint32_t n;
  const INPUT_ELEMENT_DESC* el = scene::GpuScene::InputElements(&n);
  depthLayout_ = device.CreateInputLayout(el, n, vs);
}

void SceneDrawer::SetFrame(DeviceContext& ctx, const glm::mat4& viewProj, const FrameInputs* lighting) {
  FrameConstants f{};
  f.viewProj = viewProj;
  if (lighting) {
    f.cameraPos = lighting->camera.position;
    f.ambient = lighting->light.ambient;
    f.toLight = lighting->light.towardsLight();
    f.lightColor = lighting->light.color;
  }
  Upload(ctx, frame_.get(), f);
}

void SceneDrawer::SetObject(DeviceContext& ctx, uint32_t instance) {
  const scene::Instance& inst = gpu_.scene().instances[instance];
  ObjectConstants o{};
  o.world = inst.transform;
  o.albedo = inst.albedo;
  Upload(ctx, object_.get(), o);
}

void SceneDrawer::BindConstants(DeviceContext& ctx, ShaderStage stage) {
  Buffer* cbs[] = {frame_.get(), object_.get()};
  if (stage == ShaderStage::Vertex) ctx.VSSetConstantBuffers(0, 2, cbs);
  if (stage == ShaderStage::Pixel) ctx.PSSetConstantBuffers(0, 2, cbs);
}

uint64_t SceneDrawer::DrawDepth(DeviceContext& ctx, const glm::mat4& viewProj) {
  return DrawDepth(ctx, viewProj, [](uint32_t) { return true; });
}

uint64_t SceneDrawer::DrawDepth(DeviceContext& ctx, const glm::mat4& viewProj, const std::function<bool(uint32_t instance)>& keep) {
  return DrawDepth(ctx, viewProj, keep, DepthShaders{});
}

void SceneDrawer::BindDepthPass(DeviceContext& ctx, const glm::mat4& viewProj, const DepthShaders& shaders) {
  SetFrame(ctx, viewProj, nullptr);
  gpu_.BindGeometry(ctx);
  // The caller's VS has depth-only's input signature, so depth-only's layout serves it too.
  ctx.IASetInputLayout(depthLayout_.get());
  ctx.VSSetShader(shaders.vs ? shaders.vs : depthVs_.get());
  ctx.PSSetShader(shaders.ps);
  BindConstants(ctx, ShaderStage::Vertex);
  if (shaders.ps) BindConstants(ctx, ShaderStage::Pixel);
}

uint64_t SceneDrawer::DrawDepth(DeviceContext& ctx, const glm::mat4& viewProj, const std::function<bool(uint32_t instance)>& keep,
                                const DepthShaders& shaders) {
  BindDepthPass(ctx, viewProj, shaders);
  uint64_t triangles = 0;
  for (const scene::DrawItem& d : gpu_.draws()) {
    if (!keep(d.instance)) continue;
    SetObject(ctx, d.instance);
    ctx.DrawIndexed(d.indexCount, d.firstIndex, d.baseVertex);
    triangles += d.indexCount / 3;
  }
  return triangles;
}

void SceneDrawer::DrawDepthIndirect(DeviceContext& ctx, const glm::mat4& viewProj, const DepthShaders& shaders, Buffer* args, uint32_t firstArgsByte) {
  BindDepthPass(ctx, viewProj, shaders);
  uint32_t offset = firstArgsByte;
  for (const scene::DrawItem& d : gpu_.draws()) {
    SetObject(ctx, d.instance);
    ctx.DrawIndexedInstancedIndirect(args, offset);
    offset += 20;
  }
}

std::vector<uint32_t> SceneDrawer::IndirectArgsOfDraws() const {
  std::vector<uint32_t> words;
  for (const scene::DrawItem& d : gpu_.draws()) {
    // D3D11_DRAW_INDEXED_INSTANCED_INDIRECT_ARGS: IndexCountPerInstance, InstanceCount,
    // StartIndexLocation, BaseVertexLocation, StartInstanceLocation.
    uint32_t item[5] = {d.indexCount, 0, d.firstIndex, uint32_t(d.baseVertex), 0};
    words.insert(words.end(), item, item + 5);
  }
  return words;
}

uint64_t SceneDrawer::DrawDepthLayered(DeviceContext& ctx, const glm::mat4* viewProj, uint32_t layers,
                                       const std::function<bool(uint32_t instance, uint32_t layer)>& keep) {
  Device& device = *ctx.GetDevice();
  if (!device.Info().vsRenderTargetArrayIndex)
    throw std::invalid_argument(std::string("DrawDepthLayered: the ") + BackendName(device.GetBackend()) +
                                " device lacks DeviceInfo::vsRenderTargetArrayIndex (a vertex shader writing SV_RenderTargetArrayIndex)");
  if (layers == 0 || layers > kMaxDepthLayers)
    throw std::invalid_argument("DrawDepthLayered: layers=" + std::to_string(layers) + " is outside 1.." + std::to_string(kMaxDepthLayers));
  if (!layeredVs_) {
    // Made on first use, so passes that never draw layered pay nothing for it.
    ShaderBytecode layered = CompileTechniqueShader("common/depth-layered.hlsl", "vs_5_0", "VSMain");
    layeredVs_ = device.CreateVertexShader(layered);
    layerViews_ = DynamicConstants(device, sizeof(glm::mat4) * kMaxDepthLayers, "LayerViews constants");
    layerList_ = DynamicConstants(device, sizeof(uint32_t) * kMaxDepthLayers, "LayerList constants");
  }
  struct {
    glm::mat4 m[kMaxDepthLayers];
  } views{};
  for (uint32_t l = 0; l < layers; ++l) views.m[l] = viewProj[l];
  Upload(ctx, layerViews_.get(), views);
  // Frame still reaches the shader (frame.hlsli declares it); its viewProj is unused here.
  SetFrame(ctx, viewProj[0], nullptr);
  gpu_.BindGeometry(ctx);
  // depth-layered.hlsl reads what depth-only.hlsl reads (the draw checks the layout fits).
  ctx.IASetInputLayout(depthLayout_.get());
  ctx.VSSetShader(layeredVs_.get());
  ctx.PSSetShader(nullptr);
  BindConstants(ctx, ShaderStage::Vertex);
  Buffer* layerCbs[] = {layerViews_.get(), layerList_.get()};
  ctx.VSSetConstantBuffers(7, 2, layerCbs);
  uint64_t triangles = 0;
  for (const scene::DrawItem& d : gpu_.draws()) {
    struct {
      uint32_t layer[kMaxDepthLayers];
    } list{};
    uint32_t count = 0;
    for (uint32_t l = 0; l < layers; ++l)
      if (keep(d.instance, l)) list.layer[count++] = l;
    if (count == 0) continue;
    SetObject(ctx, d.instance);
    Upload(ctx, layerList_.get(), list);
    ctx.DrawIndexedInstanced(d.indexCount, count, d.firstIndex, d.baseVertex, 0);
    triangles += uint64_t(count) * (d.indexCount / 3);
  }
  return triangles;
}

}  // namespace sp::tech
