#include "asm/gpu-allocation.h"

#include <cstring>
#include <stdexcept>
#include <string>

namespace sp::tech::asmap {
namespace {

// Word offsets in State and Args: must match shaders-hlsl/asm/gpu-allocation.hlsl.
constexpr uint32_t kStateWords = 16;
constexpr uint32_t kCountRequests = 5, kCountIterations = 9, kContinue = 10, kCountResident = 11;
constexpr uint32_t kTouchArgs = 0, kDeferArgs = 3, kPublishArgs = 6, kCopyArgs = 9, kAnalyzeArgs = 13, kClearArgs = 16, kDrawArgs = 20;
constexpr uint32_t kEmpty = 0xffffffffu, kPinned = 0xffffffffu;
constexpr uint32_t kOrderMax = 2048;  // CSOrder's sort, one group

uint32_t Groups(uint32_t n, uint32_t size) { return (n + size - 1) / size; }

// cbuffer AsmGpu.
struct AllocationConstants {
  uint32_t frameNumber, slotCount, batchPages, drawCount, orderedSlots, maxLevel, requestCapacity, pad0;
  uint32_t analyzeGroups[2], viewArgs, pad2;
};

}  // namespace

GpuAllocation::GpuAllocation(Device& device, uint32_t slots, uint32_t pageSize, uint32_t poolPages, uint32_t batchPages, uint32_t maxLevel,
                             uint32_t firstRefinedLevel)
    : slots_(slots), pageSize_(pageSize), poolPages_(poolPages), batch_(batchPages), maxLevel_(maxLevel), firstRefined_(firstRefinedLevel),
      device_(device) {
  const uint32_t rw = BIND_UNORDERED_ACCESS | BIND_SHADER_RESOURCE;
  state_ = MakeRawBuffer(device, kStateWords * 4, rw, "asm gpu state");
  slotBuf_ = MakeRawBuffer(device, slots * 8, BIND_UNORDERED_ACCESS, "asm gpu slots");
  bins_ = MakeRawBuffer(device, (512 + kOrderMax) * 4, BIND_UNORDERED_ACCESS, "asm gpu age bins and slot order");
  changes_ = MakeRawBuffer(device, 2 * batch_ * 8, rw, "asm gpu table changes");
  newPages_ = MakeRawBuffer(device, batch_ * 8, rw, "asm gpu new pages");
  stateUav_ = MakeRawUav(device, state_.get());
  slotUav_ = MakeRawUav(device, slotBuf_.get());
  binsUav_ = MakeRawUav(device, bins_.get());
  changesUav_ = MakeRawUav(device, changes_.get());
  newPagesUav_ = MakeRawUav(device, newPages_.get());
  stateSrv_ = MakeRawSrv(device, state_.get());
  changesSrv_ = MakeRawSrv(device, changes_.get());
  newPagesSrv_ = MakeRawSrv(device, newPages_.get());
  constants_ = MakeConstantBuffer(device, sizeof(AllocationConstants), "AsmGpu constants");
  publishConstants_ = MakeConstantBuffer(device, 16, "AsmPublish constants");
  BUFFER_DESC sd;
  sd.ByteWidth = kStateWords * 4;
  sd.Usage = USAGE_STAGING;
  sd.CPUAccessFlags = CPU_ACCESS_READ;
  staging_ = device.CreateBuffer(sd);
  staging_->SetDebugName("asm gpu counters readback");

  // The scratch array: one page-sized depth slice per page rendered in an iteration.
  TEXTURE2D_DESC td;
  td.Width = td.Height = pageSize;
  td.ArraySize = batch_;
  td.Format = FORMAT_R32_TYPELESS;
  td.BindFlags = BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE;
  scratch_ = device.CreateTexture2D(td);
  scratch_->SetDebugName("asm gpu page scratch");
  DEPTH_STENCIL_VIEW_DESC dv;
  dv.Format = FORMAT_D32_FLOAT;
  dv.ViewDimension = DSV_DIMENSION_TEXTURE2DARRAY;
  dv.Texture2DArray = {0, 0, batch_};
  scratchDsv_ = device.CreateDepthStencilView(scratch_.get(), &dv);
  scratchSrv_ = MakeSliceArraySrv(device, scratch_.get());

  auto cs = [&](const char* entry) { return device.CreateComputeShader(CompileTechniqueShader("asm/gpu-allocation.hlsl", "cs_5_0", entry)); };
  prepare_ = cs("CSPrepare");
  touch_ = cs("CSTouch");
  histogram_ = cs("CSAgeHistogram");
  assign_ = cs("CSAssign");
  order_ = cs("CSOrder");
  scatter_ = cs("CSScatter");
  defer_ = cs("CSDefer");
  publish_ = device.CreateComputeShader(CompileTechniqueShader("asm/gpu-publish.hlsl", "cs_5_0", "CSPublish"));
  pageVs_ = device.CreateVertexShader(CompileTechniqueShader("asm/gpu-pages.hlsl", "vs_5_0", "VSPage"));
  copyVs_ = device.CreateVertexShader(CompileTechniqueShader("asm/gpu-pages.hlsl", "vs_5_0", "VSCopy"));
  copyPs_ = device.CreatePixelShader(CompileTechniqueShader("asm/gpu-pages.hlsl", "ps_5_0", "PSCopy"));
  clearVs_ = device.CreateVertexShader(CompileTechniqueShader("asm/gpu-pages.hlsl", "vs_5_0", "VSClearSlice"));
  RASTERIZER_DESC rd;
  rd.CullMode = CULL_NONE;
  copyRasterizer_ = device.CreateRasterizerState(rd);
  DEPTH_STENCIL_DESC dd;
  dd.DepthFunc = COMPARISON_ALWAYS;
  copyDepth_ = device.CreateDepthStencilState(dd);
  bytes_ = uint64_t(kStateWords) * 4 + uint64_t(slots) * 8 + (512 + kOrderMax) * 4 + uint64_t(batch_) * 24 + uint64_t(batch_) * pageSize * pageSize * 4;
}

void GpuAllocation::Reset(DeviceContext& ctx, const std::vector<std::pair<uint32_t, uint32_t>>& pinned) {
  std::vector<uint32_t> slots(size_t(slots_) * 2);
  for (uint32_t s = 0; s < slots_; ++s) slots[2 * s] = kEmpty, slots[2 * s + 1] = 0;
  for (const auto& [key, slot] : pinned) {
    if (slot >= slots_) throw std::logic_error("asm gpu: pinned slot " + std::to_string(slot) + " outside the pool");
    slots[2 * slot] = key;
    slots[2 * slot + 1] = kPinned;
  }
  ctx.UpdateSubresource(slotBuf_.get(), 0, nullptr, slots.data(), 0, 0);
  uint32_t state[kStateWords] = {};
  state[kCountResident] = uint32_t(pinned.size());
  ctx.UpdateSubresource(state_.get(), 0, nullptr, state, 0, 0);
}

void GpuAllocation::BeginFrame(DeviceContext& ctx) {
  ++frame_;
  if (frame_ == kPinned) frame_ = 1;  // after 2^32 frames; kPinned must never be a frame number
  // The frame counters (requests, rendered, evicted, unserved, iterations) restart and iteration
  // 0 runs; resident stays.
  const uint32_t words[6] = {0, 0, 0, 0, 0, 1};
  BOX box{kCountRequests * 4, 0, 0, (kContinue + 1) * 4, 1, 1};
  ctx.UpdateSubresource(state_.get(), 0, &box, words, 0, 0);
}

void GpuAllocation::Refine(DeviceContext& ctx, SceneDrawer& drawer, const GpuAllocationTargets& t, GpuTimer* timer) {
  {
    GpuTimer::Scope timed(timer, ctx, "allocation");
    Allocate(ctx, drawer, t);
    Publish(ctx, t);
  }
  GpuTimer::Scope timed(timer, ctx, "pages");
  RenderNewPages(ctx, drawer, t);
}

void GpuAllocation::Allocate(DeviceContext& ctx, SceneDrawer& drawer, const GpuAllocationTargets& t) {
  if (!drawTemplate_) {
    // The scene's draw items are fixed once the technique draws: their argument template is made
    // on the first refinement, and args_ holds the passes' arguments followed by one draw's per item.
    std::vector<uint32_t> words = drawer.IndirectArgsOfDraws();
    drawCount_ = uint32_t(words.size() / 5);
    words.resize(std::max<size_t>(words.size(), 4));
    BUFFER_DESC d;
    d.ByteWidth = uint32_t(words.size() * 4);
    d.BindFlags = BIND_SHADER_RESOURCE;
    d.MiscFlags = RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS;
    SUBRESOURCE_DATA init{words.data(), 0, 0};
    drawTemplate_ = device_.CreateBuffer(d, &init);
    drawTemplate_->SetDebugName("asm gpu draw argument template");
    drawTemplateSrv_ = MakeRawSrv(device_, drawTemplate_.get());
    args_ = MakeRawBuffer(device_, (kDrawArgs + 10 * std::max(drawCount_, 1u)) * 4, BIND_UNORDERED_ACCESS, "asm gpu indirect arguments",
                      RESOURCE_MISC_DRAWINDIRECT_ARGS);
    argsUav_ = MakeRawUav(device_, args_.get());
    bytes_ += uint64_t(words.size()) * 4 + uint64_t(kDrawArgs + 10 * drawCount_) * 4;
  }
  if (missingCapacity_ < t.requestCapacity) {
    missing_ = MakeRawBuffer(device_, t.requestCapacity * 4, BIND_UNORDERED_ACCESS, "asm gpu missing pages");
    missingUav_ = MakeRawUav(device_, missing_.get());
    bytes_ += uint64_t(t.requestCapacity - missingCapacity_) * 4;
    missingCapacity_ = t.requestCapacity;
  }
  AllocationConstants c{frame_, slots_, batch_, drawCount_, slots_ <= kOrderMax ? 1u : 0u, maxLevel_, t.requestCapacity, 0, {t.analyzeGroups[0], t.analyzeGroups[1]},
                        ViewArgsByte() / 4, 0};
  ctx.UpdateSubresource(constants_.get(), 0, nullptr, &c, 0, 0);
  if (t.requestCount) {
    BOX box{0, 0, 0, 4, 1, 1};
    ctx.CopySubresourceRegion(state_.get(), 0, 0, 0, 0, t.requestCount, 0, &box);
  } else {
    ctx.CopyStructureCount(state_.get(), 0, t.requestsUav);
  }

  // The page tables are read here and written by Publish: no stage may hold them as a resource.
  ctx.PSSetShaderResources(0, {nullptr, nullptr});
  ctx.CSSetConstantBuffers(0, {constants_.get()});
  ctx.CSSetShaderResources(0, {t.requestsSrv, t.tableSrv, drawTemplateSrv_.get()});
  ctx.CSSetUnorderedAccessViews(0, {stateUav_.get(), argsUav_.get(), slotUav_.get(), binsUav_.get(), missingUav_.get(), changesUav_.get(),
                                    newPagesUav_.get(), t.requestedUav});
  ctx.CSSetShader(prepare_.get());
  ctx.Dispatch(1, 1, 1);
  ctx.CSSetShader(touch_.get());
  ctx.DispatchIndirect(args_.get(), kTouchArgs * 4);
  ctx.CSSetShader(histogram_.get());
  ctx.Dispatch(Groups(slots_, 64), 1, 1);
  ctx.CSSetShader(assign_.get());
  ctx.Dispatch(1, 1, 1);
  ctx.CSSetShader(order_.get());
  ctx.Dispatch(1, 1, 1);
  ctx.CSSetShader(scatter_.get());
  ctx.Dispatch(Groups(slots_ <= kOrderMax ? batch_ : slots_, 64), 1, 1);
  ctx.CSSetShader(defer_.get());
  ctx.DispatchIndirect(args_.get(), kDeferArgs * 4);
  UnorderedAccessView* none[8] = {};
  ctx.CSSetUnorderedAccessViews(0, 8, none, nullptr);
  ctx.CSSetShaderResources(0, {nullptr, nullptr, nullptr});
}

void GpuAllocation::Publish(DeviceContext& ctx, const GpuAllocationTargets& t) {
  if (tableOfUavs_ != t.table) {
    tableUavs_.assign(maxLevel_ + 1, nullptr);
    for (uint32_t l = firstRefined_; l <= maxLevel_; ++l) {
      UNORDERED_ACCESS_VIEW_DESC d;
      d.Format = FORMAT_R32_UINT;
      d.ViewDimension = UAV_DIMENSION_TEXTURE2D;
      d.Texture2D = {maxLevel_ - l};
      tableUavs_[l] = device_.CreateUnorderedAccessView(t.table, &d);
    }
    tableOfUavs_ = t.table;
  }
  ctx.CSSetShader(publish_.get());
  ctx.CSSetConstantBuffers(0, {publishConstants_.get()});
  ctx.CSSetShaderResources(0, {stateSrv_.get(), changesSrv_.get()});
  for (uint32_t l = firstRefined_; l <= maxLevel_; ++l) {
    const uint32_t level[4] = {l, 0, 0, 0};
    ctx.UpdateSubresource(publishConstants_.get(), 0, nullptr, level, 0, 0);
    ctx.CSSetUnorderedAccessViews(0, {tableUavs_[l].get()});
    ctx.DispatchIndirect(args_.get(), kPublishArgs * 4);
  }
  ctx.CSSetUnorderedAccessViews(0, {nullptr});
  ctx.CSSetShaderResources(0, {nullptr, nullptr});
}

void GpuAllocation::RenderNewPages(DeviceContext& ctx, SceneDrawer& drawer, const GpuAllocationTargets& t) {
  // Depth of every new page into its scratch slice: the page's own viewport and scissor. The
  // slices are reset by a triangle per new page at depth 1 (clearing the whole array every
  // iteration cost batch slices, however few pages were new).
  ctx.OMSetRenderTargets(0, nullptr, scratchDsv_.get());
  VIEWPORT vp{0, 0, float(pageSize_), float(pageSize_), 0, 1};
  RECT sc{0, 0, int32_t(pageSize_), int32_t(pageSize_)};
  ctx.RSSetViewports(1, &vp);
  ctx.RSSetScissorRects(1, &sc);
  ctx.RSSetState(copyRasterizer_.get());
  ctx.OMSetDepthStencilState(copyDepth_.get(), 0);
  ctx.IASetInputLayout(nullptr);
  ctx.IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  ctx.VSSetShader(clearVs_.get());
  ctx.PSSetShader(nullptr);
  ctx.DrawInstancedIndirect(args_.get(), kClearArgs * 4);
  ctx.RSSetState(t.pageRasterizer);
  ctx.OMSetDepthStencilState(nullptr, 0);
  ctx.VSSetConstantBuffers(2, {t.shadowConstants});
  ctx.VSSetShaderResources(2, {newPagesSrv_.get()});
  drawer.DrawDepthIndirect(ctx, glm::mat4(1.0f), {pageVs_.get(), nullptr}, args_.get(), kDrawArgs * 4);

  // Copy each slice to its pool slot.
  ctx.OMSetRenderTargets(0, nullptr, t.poolDsv);
  float pool = float(poolPages_ * pageSize_);
  VIEWPORT pv{0, 0, pool, pool, 0, 1};
  ctx.RSSetViewports(1, &pv);
  ctx.RSSetState(copyRasterizer_.get());
  ctx.OMSetDepthStencilState(copyDepth_.get(), 0);
  ctx.IASetInputLayout(nullptr);
  ctx.IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  ctx.VSSetShader(copyVs_.get());
  ctx.PSSetShader(copyPs_.get());
  ctx.PSSetShaderResources(3, {scratchSrv_.get()});
  ctx.DrawInstancedIndirect(args_.get(), kCopyArgs * 4);
  ctx.PSSetShaderResources(3, {nullptr});
  ctx.VSSetShaderResources(2, {nullptr});
  ctx.OMSetRenderTargets(0, nullptr, nullptr);
  ctx.OMSetDepthStencilState(nullptr, 0);
}

uint32_t GpuAllocation::ViewArgsByte() const { return (kDrawArgs + 5 * drawCount_) * 4; }
uint32_t GpuAllocation::AnalyzeArgsByte() const { return kAnalyzeArgs * 4; }

GpuAllocation::Counters GpuAllocation::Read(DeviceContext& ctx) const {
  ctx.CopyResource(staging_.get(), state_.get());
  MAPPED_SUBRESOURCE m;
  if (!ctx.Map(staging_.get(), 0, MAP_READ, 0, &m)) throw std::runtime_error("asm gpu: Map of the counters readback failed");
  uint32_t w[kStateWords];
  std::memcpy(w, m.pData, sizeof(w));
  ctx.Unmap(staging_.get(), 0);
  return {w[kCountRequests], w[kCountRequests + 1], w[kCountRequests + 2], w[kCountRequests + 3], w[kCountResident], w[kCountIterations]};
}

}  // namespace sp::tech::asmap
