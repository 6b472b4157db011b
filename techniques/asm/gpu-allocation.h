// Adaptive shadow maps, allocation=gpu: the refinement's allocation and page rendering on the
// GPU, with no CPU readback (shaders-hlsl/asm/gpu-allocation.hlsl, gpu-publish.hlsl,
// gpu-pages.hlsl say what each pass does). The technique (asm-technique.cpp) keeps the page
// tables, pool, analysis and pinned coarse levels; this class turns an analysis' request stream
// into resident pages: LRU slot assignment at frame granularity, change records published into
// the page tables, new pages drawn with indirect instanced draws into a scratch array and copied
// into their pool slots. Counters stay on the GPU until the lab asks for them.
#pragma once
#include <cstdint>
#include <utility>
#include <vector>

#include <sp/tech/technique.h>

namespace sp::tech::asmap {

// The technique's resources the allocation reads or writes (owned by the technique).
struct GpuAllocationTargets {
  Texture2D* table = nullptr;                  // R32_UINT, mip m = level maxLevel - m, SRV + UAV
  ShaderResourceView* tableSrv = nullptr;
  ShaderResourceView* requestsSrv = nullptr;   // the analysis' request stream (StructuredBuffer<uint>)
  UnorderedAccessView* requestsUav = nullptr;  // the same, append view (its hidden count)
  UnorderedAccessView* requestedUav = nullptr; // the per-frame request bitmap
  Buffer* shadowConstants = nullptr;           // cbuffer AsmShadow (b2)
  DepthStencilView* poolDsv = nullptr;
  RasterizerState* pageRasterizer = nullptr;   // depth bias, no depth clip, scissor on
  uint32_t requestCapacity = 0;                // elements of the request stream
  Buffer* requestCount = nullptr;              // word 0: the stream's length (compaction=prefix);
                                               // null: the append view's hidden counter
  uint32_t analyzeGroups[2] = {0, 0};          // the analysis' dispatch over the view
};

class GpuAllocation {
 public:
  // slots: pool pages; batchPages: pages rendered per iteration at most (scratch slices);
  // levels 0..maxLevel, of which firstRefinedLevel.. change (the ones below are pinned).
  GpuAllocation(Device& device, uint32_t slots, uint32_t pageSize, uint32_t poolPages, uint32_t batchPages, uint32_t maxLevel,
                uint32_t firstRefinedLevel);

  // Every slot free except the pinned pages: (request key, slot) each, kept resident until the
  // next Reset. The page tables themselves are the technique's to reset.
  void Reset(DeviceContext& ctx, const std::vector<std::pair<uint32_t, uint32_t>>& pinned);
  // A new frame: pages used from now on are this frame's (not evictable until the next); the
  // frame counters restart.
  void BeginFrame(DeviceContext& ctx);
  // One iteration after an analysis: allocate, publish the table changes ("allocation" pass of
  // the timer), render the new pages ("pages").
  void Refine(DeviceContext& ctx, SceneDrawer& drawer, const GpuAllocationTargets& t, GpuTimer* timer);

  struct Counters {
    uint32_t requests = 0, rendered = 0, evicted = 0, unserved = 0, resident = 0, iterations = 0;
  };
  // The frame's counters so far. Reads the GPU (waits for it): for tests and the lab only.
  Counters Read(DeviceContext& ctx) const;
  uint64_t Bytes() const { return bytes_; }
  // After the first Refine: the arguments the next iteration's analysis runs with (the GPU's early
  // exit): the view pass's draws (SceneDrawer::DrawDepthIndirect, one instance or none) and the
  // analysis dispatch (all its groups or none), in Args().
  Buffer* Args() const { return args_.get(); }
  uint32_t ViewArgsByte() const;
  uint32_t AnalyzeArgsByte() const;

 private:
  void Allocate(DeviceContext& ctx, SceneDrawer& drawer, const GpuAllocationTargets& t);
  void Publish(DeviceContext& ctx, const GpuAllocationTargets& t);
  void RenderNewPages(DeviceContext& ctx, SceneDrawer& drawer, const GpuAllocationTargets& t);

  uint32_t slots_, pageSize_, poolPages_, batch_, maxLevel_, firstRefined_;
  uint32_t frame_ = 0, drawCount_ = 0, missingCapacity_ = 0;
  uint64_t bytes_ = 0;
  Device& device_;
  Ref<Buffer> state_, args_, slotBuf_, bins_, missing_, changes_, newPages_, drawTemplate_, constants_, publishConstants_, staging_;
  Ref<UnorderedAccessView> stateUav_, argsUav_, slotUav_, binsUav_, missingUav_, changesUav_, newPagesUav_;
  Ref<ShaderResourceView> stateSrv_, changesSrv_, newPagesSrv_, drawTemplateSrv_;
  std::vector<Ref<UnorderedAccessView>> tableUavs_;  // per level (index = level); made on first use
  Texture2D* tableOfUavs_ = nullptr;
  Ref<Texture2D> scratch_;
  Ref<DepthStencilView> scratchDsv_;
  Ref<ShaderResourceView> scratchSrv_;
  Ref<ComputeShader> prepare_, touch_, histogram_, assign_, order_, scatter_, defer_, publish_;
  Ref<VertexShader> pageVs_, copyVs_, clearVs_;
  Ref<PixelShader> copyPs_;
  Ref<RasterizerState> copyRasterizer_;
  Ref<DepthStencilState> copyDepth_;
};

}  // namespace sp::tech::asmap
