#include "sdsm/depth-analysis.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include <sp/tech/technique.h>

namespace sp::tech::sdsm {
namespace {

constexpr uint32_t kTile = 16, kGroupThreads = 256;

// cbuffer SdsmAnalysis in shaders-hlsl/sdsm/analysis.hlsli (D3D packing: every float3 is followed
// by a scalar in the same register).
struct AnalysisConstants {
  uint32_t depthSize[2];
  uint32_t tileCount[2];
  float depthA, depthB, fallbackNear, fallbackFar;
  glm::vec2 ndcScale, ndcOffset, rayScale, rayOffset;
  glm::vec3 lightRayX;
  uint32_t partitionCount;
  glm::vec3 lightRayY;
  uint32_t partitionScheme;
  glm::vec3 lightRayZ;
  uint32_t gapThreshold;
  glm::vec3 lightOrigin;
  uint32_t kmeansIterations;
};
static_assert(sizeof(AnalysisConstants) == 128);

uint32_t DivUp(uint32_t a, uint32_t b) { return (a + b - 1) / b; }

Ref<Buffer> StructuredBuffer(Device& device, uint32_t count, uint32_t stride, const char* name) {
  BUFFER_DESC d;
  d.ByteWidth = count * stride;
  d.BindFlags = BIND_UNORDERED_ACCESS | BIND_SHADER_RESOURCE;
  d.MiscFlags = RESOURCE_MISC_BUFFER_STRUCTURED;
  d.StructureByteStride = stride;
  Ref<Buffer> b = device.CreateBuffer(d);
  b->SetDebugName(name);
  return b;
}

}  // namespace

AnalysisTraffic EstimateTraffic(uint32_t width, uint32_t height, ReduceMode mode, uint32_t bins) {
  AnalysisTraffic t;
  uint64_t tiles = uint64_t(DivUp(width, kStripTile)) * DivUp(height, kStripTile);
  // Groups read every pixel of their tiles, edge tiles included only where inside the buffer.
  t.depthBufferBytes = uint64_t(width) * height * 4;
  t.reduceReadBytes = t.depthBufferBytes + (mode == ReduceMode::TwoPass ? tiles * 8 : 0);
  t.reduceWrittenBytes = mode == ReduceMode::TwoPass ? tiles * 8 + 8 : tiles * 8;
  // Every group also reads min/max (8 bytes), the bounds groups the splits (up to 36 bytes).
  t.histogramReadBytes = t.depthBufferBytes + tiles * 8;
  t.histogramWrittenBytes = tiles * std::min(bins, kStripTile * kStripTile) * 4;  // at most a bin per sample
  t.boundsReadBytes = t.depthBufferBytes + tiles * 36;
  return t;
}

DepthAnalysis::DepthAnalysis(Device& device, uint32_t bins) : device_(device), bins_(bins) {
  if (bins == 0 || bins % 256 != 0 || bins > 1024)
    throw std::invalid_argument("DepthAnalysis: histogramBins must be a multiple of 256 in [256, 1024], got " + std::to_string(bins));
  constants_ = MakeConstantBuffer(device, sizeof(AnalysisConstants), "SdsmAnalysis constants");

  results_ = MakeRawBuffer(device, kResultBytes, BIND_UNORDERED_ACCESS | BIND_SHADER_RESOURCE, "sdsm analysis results");
  resultsUav_ = MakeRawUav(device, results_.get());
  resultsSrv_ = MakeRawSrv(device, results_.get());
  histogram_ = StructuredBuffer(device, bins, 4, "sdsm depth histogram");
  histogramUav_ = device.CreateUnorderedAccessView(histogram_.get());

  std::vector<hlsl::Define> defines = {{"SDSM_BINS", std::to_string(bins)}};
  auto cs = [&](const char* file, const char* entry) {
    Ref<ComputeShader> s = device.CreateComputeShader(CompileTechniqueShader(std::string("sdsm/") + file, "cs_5_0", entry, defines));
    s->SetDebugName(std::string("sdsm ") + entry);
    return s;
  };
  reset_ = cs("histogram.hlsl", "ResetResults");
  histogramCs_ = cs("histogram.hlsl", "Histogram");
  reduceTiles_ = cs("reduce.hlsl", "ReduceTiles");
  reduceFinal_ = cs("reduce.hlsl", "ReduceFinal");
  reduceAtomic_ = cs("reduce.hlsl", "ReduceAtomic");
  partitions_ = cs("partitions.hlsl", "Partitions");
  bounds_ = cs("bounds.hlsl", "Bounds");
}

void DepthAnalysis::EnsureTiles(uint32_t count) {
  if (tiles_ && tiles_->GetDesc().ByteWidth >= count * 8) return;
  tiles_ = StructuredBuffer(device_, count, 8, "sdsm depth tiles");
  tilesUav_ = device_.CreateUnorderedAccessView(tiles_.get());
}

void DepthAnalysis::SetFrame(DeviceContext& ctx, const AnalysisFrame& f, const PartitionSettings& p) {
  if (p.count < 1 || p.count > kMaxPartitions)
    throw std::invalid_argument("DepthAnalysis: partition count must be in [1, 8], got " + std::to_string(p.count));
  width_ = f.width;
  height_ = f.height;
  tilesX_ = DivUp(f.width, kTile);
  tilesY_ = DivUp(f.height, kTile);
  if (tilesX_ > 65535 || tilesY_ > 65535) throw std::invalid_argument("DepthAnalysis: depth buffer too large");
  stripsX_ = DivUp(f.width, kStripTile);
  stripsY_ = DivUp(f.height, kStripTile);
  AnalysisConstants c{};
  c.depthSize[0] = f.width;
  c.depthSize[1] = f.height;
  c.tileCount[0] = tilesX_;
  c.tileCount[1] = tilesY_;
  c.depthA = f.depthA;
  c.depthB = f.depthB;
  c.fallbackNear = f.nearZ;
  c.fallbackFar = f.farZ;
  c.ndcScale = f.ndcScale;
  c.ndcOffset = f.ndcOffset;
  c.rayScale = f.rayScale;
  c.rayOffset = f.rayOffset;
  c.lightRayX = f.lightRayX;
  c.lightRayY = f.lightRayY;
  c.lightRayZ = f.lightRayZ;
  c.lightOrigin = f.lightOrigin;
  c.partitionCount = p.count;
  c.partitionScheme = uint32_t(p.scheme);
  c.gapThreshold = p.gapThreshold;
  c.kmeansIterations = p.kmeansIterations;
  ctx.UpdateSubresource(constants_.get(), 0, nullptr, &c, 0, 0);
}

void DepthAnalysis::BindOutputs(DeviceContext& ctx, UnorderedAccessView* second) {
  ctx.CSSetConstantBuffers(0, {constants_.get()});
  ctx.CSSetUnorderedAccessViews(0, {resultsUav_.get(), second});
}

void DepthAnalysis::Reset(DeviceContext& ctx, GpuTimer* timer) {
  GpuTimer::Scope timed(timer, ctx, "analysis");
  BindOutputs(ctx, histogramUav_.get());
  ctx.CSSetShader(reset_.get());
  ctx.Dispatch(DivUp(std::max(bins_, kResultWords), kGroupThreads), 1, 1);
}

void DepthAnalysis::Reduce(DeviceContext& ctx, ShaderResourceView* depth, ReduceMode mode, GpuTimer* timer) {
  GpuTimer::Scope timed(timer, ctx, "analysis");
  ctx.CSSetShaderResources(0, {depth});
  if (mode == ReduceMode::TwoPass) {
    EnsureTiles(stripsX_ * stripsY_);
    BindOutputs(ctx, tilesUav_.get());
    ctx.CSSetShader(reduceTiles_.get());
    ctx.Dispatch(stripsX_, stripsY_, 1);
    ctx.CSSetShader(reduceFinal_.get());
    ctx.Dispatch(1, 1, 1);
  } else {
    BindOutputs(ctx, nullptr);
    ctx.CSSetShader(reduceAtomic_.get());
    ctx.Dispatch(stripsX_, stripsY_, 1);
  }
}

void DepthAnalysis::BuildHistogram(DeviceContext& ctx, ShaderResourceView* depth, GpuTimer* timer) {
  GpuTimer::Scope timed(timer, ctx, "analysis");
  ctx.CSSetShaderResources(0, {depth});
  BindOutputs(ctx, histogramUav_.get());
  ctx.CSSetShader(histogramCs_.get());
  ctx.Dispatch(stripsX_, stripsY_, 1);
}

void DepthAnalysis::Partition(DeviceContext& ctx, GpuTimer* timer) {
  GpuTimer::Scope timed(timer, ctx, "analysis");
  BindOutputs(ctx, histogramUav_.get());
  ctx.CSSetShader(partitions_.get());
  ctx.Dispatch(1, 1, 1);
}

void DepthAnalysis::ReduceBounds(DeviceContext& ctx, ShaderResourceView* depth, GpuTimer* timer) {
  GpuTimer::Scope timed(timer, ctx, "analysis");
  ctx.CSSetShaderResources(0, {depth});
  BindOutputs(ctx, nullptr);
  ctx.CSSetShader(bounds_.get());
  ctx.Dispatch(stripsX_, stripsY_, 1);
}

void DepthAnalysis::Unbind(DeviceContext& ctx) {
  ctx.CSSetUnorderedAccessViews(0, {nullptr, nullptr});
  ctx.CSSetShaderResources(0, {nullptr});
}

void DepthAnalysis::Run(DeviceContext& ctx, ShaderResourceView* depth, const AnalysisFrame& frame, const AnalysisSettings& s,
                        GpuTimer* timer) {
  SetFrame(ctx, frame, s.partitions);
  // One scope for the chain: the timer does not nest a name inside itself.
  GpuTimer::Scope timed(timer, ctx, "analysis");
  Reset(ctx);
  Reduce(ctx, depth, s.reduce);
  BuildHistogram(ctx, depth);
  Partition(ctx);
  ReduceBounds(ctx, depth);
  Unbind(ctx);
}

}  // namespace sp::tech::sdsm
