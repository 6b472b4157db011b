#include "sdsm/caster-culling.h"

#include <cstring>
#include <map>
#include <stdexcept>
#include <tuple>

#include <sp/tech/technique.h>

namespace sp::tech::sdsm {
namespace {

// Structured-buffer elements of shaders-hlsl/sdsm/casters.hlsl (members at natural alignment).
struct GpuInstance {
  glm::vec3 worldMin;
  uint32_t batch;
  glm::vec3 worldMax;
  uint32_t pad;
};
static_assert(sizeof(GpuInstance) == 32);
struct GpuBatch {
  uint32_t indexCount, firstIndex;
  int32_t baseVertex;
  uint32_t listOffset;
};
static_assert(sizeof(GpuBatch) == 16);
struct GpuTransform {
  glm::vec4 rows[3];
};
static_assert(sizeof(GpuTransform) == 48);

struct CullConstants {  // cbuffer SdsmCull
  glm::mat4 lightView;
  uint32_t instanceCount, batchCount, partitionCount;
  float dilation;
};
static_assert(sizeof(CullConstants) == 80);
struct DrawConstants {  // cbuffer SdsmCasterDraw
  glm::mat4 viewProj;
  uint32_t listBase, matrixAddress, pad[2];
};
static_assert(sizeof(DrawConstants) == 80);

uint32_t DivUp(uint32_t a, uint32_t b) { return (a + b - 1) / b; }

Ref<Buffer> Structured(Device& device, const void* data, uint32_t count, uint32_t stride, uint32_t bind, const char* name) {
  BUFFER_DESC d;
  d.ByteWidth = count * stride;
  d.BindFlags = bind;
  d.MiscFlags = RESOURCE_MISC_BUFFER_STRUCTURED;
  d.StructureByteStride = stride;
  SUBRESOURCE_DATA init{data, 0, 0};
  Ref<Buffer> b = device.CreateBuffer(d, data ? &init : nullptr);
  b->SetDebugName(name);
  return b;
}

}  // namespace

CasterCuller::CasterCuller(Device& device, const scene::GpuScene& scene) : scene_(scene) {
  const scene::Scene& s = scene.scene();
  const std::vector<scene::DrawItem>& draws = scene.draws();
  if (draws.empty()) throw std::invalid_argument("CasterCuller: the scene has no draws");
  // Batches in order of first appearance, so the batch list is deterministic.
  std::map<std::tuple<uint32_t, uint32_t, int32_t>, uint32_t> batchOf;
  std::vector<uint32_t> casterBatch;
  for (uint32_t i = 0; i < draws.size(); ++i) {
    const scene::DrawItem& d = draws[i];
    auto key = std::make_tuple(d.indexCount, d.firstIndex, d.baseVertex);
    auto [it, added] = batchOf.emplace(key, uint32_t(batches_.size()));
    if (added) {
      Batch b;
      b.indexCount = d.indexCount;
      b.firstIndex = d.firstIndex;
      b.baseVertex = d.baseVertex;
      batches_.push_back(b);
    }
    batches_[it->second].casters.push_back(i);
    casterBatch.push_back(it->second);
    casters_.push_back(d.instance);
  }
  uint32_t offset = 0;
  std::vector<GpuBatch> gpuBatches;
  for (Batch& b : batches_) {
    b.listOffset = offset;
    offset += uint32_t(b.casters.size());
    gpuBatches.push_back({b.indexCount, b.firstIndex, b.baseVertex, b.listOffset});
  }
  std::vector<GpuInstance> instances;
  std::vector<GpuTransform> transforms;
  for (uint32_t i = 0; i < casters_.size(); ++i) {
    const scene::Instance& inst = s.instances[casters_[i]];
    instances.push_back({inst.worldBounds.min, casterBatch[i], inst.worldBounds.max, 0});
    GpuTransform t;
    for (int r = 0; r < 3; ++r) t.rows[r] = glm::vec4(inst.transform[0][r], inst.transform[1][r], inst.transform[2][r], inst.transform[3][r]);
    transforms.push_back(t);
  }
  const uint32_t n = casterCount(), nb = uint32_t(batches_.size());
  instances_ = Structured(device, instances.data(), n, sizeof(GpuInstance), BIND_SHADER_RESOURCE, "sdsm caster instances");
  batchBuffer_ = Structured(device, gpuBatches.data(), nb, sizeof(GpuBatch), BIND_SHADER_RESOURCE, "sdsm caster batches");
  transforms_ = Structured(device, transforms.data(), n, sizeof(GpuTransform), BIND_SHADER_RESOURCE, "sdsm caster transforms");
  visible_ = Structured(device, nullptr, n * kMaxPartitions, 4, BIND_SHADER_RESOURCE | BIND_UNORDERED_ACCESS, "sdsm visible casters");
  instancesSrv_ = device.CreateShaderResourceView(instances_.get());
  batchesSrv_ = device.CreateShaderResourceView(batchBuffer_.get());
  transformsSrv_ = device.CreateShaderResourceView(transforms_.get());
  visibleSrv_ = device.CreateShaderResourceView(visible_.get());
  visibleUav_ = device.CreateUnorderedAccessView(visible_.get());

  args_ = MakeRawBuffer(device, nb * kMaxPartitions * kArgsStride, BIND_UNORDERED_ACCESS, "sdsm caster draw args",
                        RESOURCE_MISC_DRAWINDIRECT_ARGS);
  argsUav_ = MakeRawUav(device, args_.get());
  cullConstants_ = MakeConstantBuffer(device, sizeof(CullConstants), "SdsmCull constants");
  BUFFER_DESC db;
  db.ByteWidth = sizeof(DrawConstants);
  db.Usage = USAGE_DYNAMIC;
  db.BindFlags = BIND_CONSTANT_BUFFER;
  db.CPUAccessFlags = CPU_ACCESS_WRITE;
  drawConstants_ = device.CreateBuffer(db);
  drawConstants_->SetDebugName("SdsmCasterDraw constants");

  reset_ = device.CreateComputeShader(CompileTechniqueShader("sdsm/casters.hlsl", "cs_5_0", "CullReset"));
  cull_ = device.CreateComputeShader(CompileTechniqueShader("sdsm/casters.hlsl", "cs_5_0", "CullCasters"));
  uint32_t elements;
  const INPUT_ELEMENT_DESC* el = scene::GpuScene::InputElements(&elements);
  ShaderBytecode vs = CompileTechniqueShader("sdsm/casters.hlsl", "vs_5_0", "VSCaster");
  ShaderBytecode vsId = CompileTechniqueShader("sdsm/casters.hlsl", "vs_5_0", "VSCasterId");
  ShaderBytecode vsGpu = CompileTechniqueShader("sdsm/casters.hlsl", "vs_5_0", "VSCasterGpu");
  vs_ = device.CreateVertexShader(vs);
  vsId_ = device.CreateVertexShader(vsId);
  vsGpu_ = device.CreateVertexShader(vsGpu);
  layout_ = device.CreateInputLayout(el, elements, vs);
  layoutId_ = device.CreateInputLayout(el, elements, vsId);
  layoutGpu_ = device.CreateInputLayout(el, elements, vsGpu);
}

void CasterCuller::Cull(DeviceContext& ctx, ShaderResourceView* results, const glm::mat4& lightView, uint32_t partitionCount,
                        float dilation, GpuTimer* timer) {
  if (partitionCount < 1 || partitionCount > kMaxPartitions) throw std::invalid_argument("CasterCuller::Cull: partitionCount must be in [1, 8]");
  GpuTimer::Scope timed(timer, ctx, "analysis");
  CullConstants c{lightView, casterCount(), uint32_t(batches_.size()), partitionCount, dilation};
  ctx.UpdateSubresource(cullConstants_.get(), 0, nullptr, &c, 0, 0);
  ctx.VSSetShaderResources(0, {nullptr, nullptr});
  ctx.CSSetConstantBuffers(0, {cullConstants_.get()});
  ctx.CSSetShaderResources(0, {results, instancesSrv_.get(), batchesSrv_.get()});
  ctx.CSSetUnorderedAccessViews(0, {argsUav_.get(), visibleUav_.get()});
  ctx.CSSetShader(reset_.get());
  ctx.Dispatch(DivUp(partitionCount * uint32_t(batches_.size()), 64), 1, 1);
  ctx.CSSetShader(cull_.get());
  ctx.Dispatch(DivUp(casterCount(), 64), partitionCount, 1);
  ctx.CSSetUnorderedAccessViews(0, {nullptr, nullptr});
  ctx.CSSetShaderResources(0, {nullptr, nullptr, nullptr});
}

uint32_t CasterCuller::DrawPartition(DeviceContext& ctx, uint32_t partition, const glm::mat4& viewProj, Shader shader) {
  if (partition >= kMaxPartitions) throw std::invalid_argument("CasterCuller::DrawPartition: partition out of range");
  bool id = shader == Shader::InstanceId;
  ctx.IASetInputLayout(id ? layoutId_.get() : layout_.get());
  ctx.VSSetShader(id ? vsId_.get() : vs_.get());
  return Draw(ctx, partition, viewProj, 0);
}

uint32_t CasterCuller::DrawPartition(DeviceContext& ctx, uint32_t partition, ShaderResourceView* matrices, uint32_t matrixAddress) {
  if (partition >= kMaxPartitions) throw std::invalid_argument("CasterCuller::DrawPartition: partition out of range");
  if (!matrices || matrixAddress % 16 != 0) throw std::invalid_argument("CasterCuller::DrawPartition: needs a matrix buffer and a 16-byte aligned address");
  ctx.IASetInputLayout(layoutGpu_.get());
  ctx.VSSetShader(vsGpu_.get());
  ctx.VSSetShaderResources(2, {matrices});
  return Draw(ctx, partition, glm::mat4(1.0f), matrixAddress);
}

uint32_t CasterCuller::Draw(DeviceContext& ctx, uint32_t partition, const glm::mat4& viewProj, uint32_t matrixAddress) {
  scene_.BindGeometry(ctx);
  ctx.VSSetShaderResources(0, {transformsSrv_.get(), visibleSrv_.get()});
  uint32_t draws = 0;
  for (uint32_t b = 0; b < batches_.size(); ++b) {
    DrawConstants d{viewProj, partition * casterCount() + batches_[b].listOffset, matrixAddress, {0, 0}};
    MAPPED_SUBRESOURCE m;
    ctx.Map(drawConstants_.get(), 0, MAP_WRITE_DISCARD, 0, &m);
    std::memcpy(m.pData, &d, sizeof(d));
    ctx.Unmap(drawConstants_.get(), 0);
    ctx.VSSetConstantBuffers(0, {drawConstants_.get()});
    ctx.DrawIndexedInstancedIndirect(args_.get(), (partition * uint32_t(batches_.size()) + b) * kArgsStride);
    ++draws;
  }
  return draws;
}

}  // namespace sp::tech::sdsm
