// Sample Distribution Shadow Maps (Lauritzen, Salvi, Lefohn, I3D 2011): the GPU analysis of the
// camera depth buffer that the `sdsm` technique drives. All passes are compute shaders
// (shaders-hlsl/sdsm/) writing one small results buffer, each reading what the previous one left
// there, so a frame's analysis needs no CPU readback:
//
//   Reset       results and histogram to their neutral values
//   Reduce      min/max view depth of non-sky pixels (depth 1.0 = sky): per 64x64 tile (a thread
//               per row, in registers), then a second pass over the tiles (TwoPass) or
//               InterlockedMin/Max on the float bits (Atomic)
//   Histogram   N bins of log view depth between that min and max
//   Partition   K + 1 split distances by the chosen scheme (partitions.h)
//   Bounds      light-space box of each partition's samples (analysis-frame.h for the light frame)
//
// The results layout is kWord* in analysis-frame.h; DecodeResults turns a copy into numbers. The
// buffer is read on the GPU by CasterCuller (caster-culling.h) and on the CPU through
// AnalysisReadback (analysis-readback.h).
#pragma once
#include <sp/rhi/rhi.h>

#include <sp/tech/gpu-timer.h>
#include "sdsm/analysis-frame.h"
#include "sdsm/partitions.h"

namespace sp::tech::sdsm {

enum class ReduceMode { TwoPass, Atomic };

// SDSM_STRIP of shaders-hlsl/sdsm/analysis.hlsli.
constexpr uint32_t kStripTile = 64;

struct AnalysisSettings {
  ReduceMode reduce = ReduceMode::TwoPass;
  PartitionSettings partitions;
};

// Memory traffic of the passes for a depth buffer, counted from what each shader reads and writes
// (not measured): for comparing reduction strategies with one read of the depth buffer.
struct AnalysisTraffic {
  uint64_t depthBufferBytes = 0;    // one read of the camera depth
  uint64_t reduceReadBytes = 0;     // depth + (TwoPass) the tile results
  uint64_t reduceWrittenBytes = 0;  // tile results + final words, or one atomic pair per tile
  uint64_t histogramReadBytes = 0;
  uint64_t histogramWrittenBytes = 0;  // upper bound: every group adds all its non-zero bins
  uint64_t boundsReadBytes = 0;
};
AnalysisTraffic EstimateTraffic(uint32_t width, uint32_t height, ReduceMode mode, uint32_t histogramBins);

class DepthAnalysis {
 public:
  // histogramBins: a multiple of 256, at most 1024 (the partition pass's groupshared copy).
  explicit DepthAnalysis(Device& device, uint32_t histogramBins = kDefaultHistogramBins);

  // The whole analysis of one frame. cameraDepth: an R32_FLOAT view of the camera's depth (not
  // bound as depth target meanwhile), frame.width x frame.height. Leaves the compute UAV and SRV
  // slots it used unbound.
  void Run(DeviceContext& ctx, ShaderResourceView* cameraDepth, const AnalysisFrame& frame, const AnalysisSettings& settings,
           GpuTimer* timer = nullptr);

  // The same passes one by one (Run calls them in this order after SetFrame). Each step binds what
  // it needs; SetFrame writes the constants all of them read.
  void SetFrame(DeviceContext& ctx, const AnalysisFrame& frame, const PartitionSettings& partitions);
  void Reset(DeviceContext& ctx, GpuTimer* timer = nullptr);
  void Reduce(DeviceContext& ctx, ShaderResourceView* cameraDepth, ReduceMode mode, GpuTimer* timer = nullptr);
  void BuildHistogram(DeviceContext& ctx, ShaderResourceView* cameraDepth, GpuTimer* timer = nullptr);
  void Partition(DeviceContext& ctx, GpuTimer* timer = nullptr);
  void ReduceBounds(DeviceContext& ctx, ShaderResourceView* cameraDepth, GpuTimer* timer = nullptr);
  void Unbind(DeviceContext& ctx);

  // kResultBytes, raw; BIND_UNORDERED_ACCESS | BIND_SHADER_RESOURCE, USAGE_DEFAULT (so tests may
  // UpdateSubresource it).
  Buffer* results() const { return results_.get(); }
  ShaderResourceView* resultsSrv() const { return resultsSrv_.get(); }  // ByteAddressBuffer
  Buffer* histogram() const { return histogram_.get(); }                // histogramBins() uints
  uint32_t histogramBins() const { return bins_; }
  // The b0 constants SetFrame wrote (for passes measured against the analysis, analysis-cost.h).
  Buffer* constants() const { return constants_.get(); }

 private:
  void EnsureTiles(uint32_t count);
  void BindOutputs(DeviceContext& ctx, UnorderedAccessView* second);

  Device& device_;
  uint32_t bins_;
  uint32_t width_ = 0, height_ = 0, tilesX_ = 0, tilesY_ = 0, stripsX_ = 0, stripsY_ = 0;
  Ref<Buffer> constants_, results_, histogram_, tiles_;
  Ref<UnorderedAccessView> resultsUav_, histogramUav_, tilesUav_;
  Ref<ShaderResourceView> resultsSrv_;
  Ref<ComputeShader> reset_, reduceTiles_, reduceFinal_, reduceAtomic_, histogramCs_, partitions_, bounds_;
};

}  // namespace sp::tech::sdsm
