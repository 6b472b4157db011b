// Adaptive shadow maps (Lefohn et al. 2005, "Dynamic Adaptive Shadow Maps on Graphics
// Hardware"), with the paper's CPU-readback refinement. The light's view of the scene bounds is
// a quadtree of virtual pages: level 0 is one page, level L has 2^L x 2^L; a mip hierarchy of
// page tables (one R32_UINT texture, mip m = level maxLevel - m) maps each virtual page to a
// page of the physical pool (one depth texture of poolPages x poolPages pages) or to "not
// resident". Each frame, up to `iterations` times: the camera's view is drawn with the current
// pages (asm/analysis.hlsl PSView), a compute pass finds shadow boundaries with a Sobel filter
// and appends the page each boundary pixel needs (de-duplicated), the request stream is read
// back, the CPU allocates pages (asm/page-allocator.h, LRU), writes their page-table entries and
// renders depth into each new page (viewport and scissor on its pool rectangle, the light's
// projection cropped to the page). Levels 0..resident_levels-1 stay resident, so every point has
// a page. The lookup is asm/shadow.hlsli.
//
// allocation=gpu is the GPU-driven variant (asm/gpu-allocation.h): the same analysis, but the
// request stream never reaches the CPU; allocation, page-table updates and page rendering
// (indirect draws) run on the GPU every iteration, and pages stay cached across frames until the
// light's fit changes. mark=visible makes the analysis request the page of every visible sample
// (with its filter footprint's neighbours) instead of only shadow boundaries, as virtual shadow
// maps do; it works with either allocation.
#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include <sp/tech/technique.h>

#include <sp/tech/asm-counters.h>
#include "asm/gpu-allocation.h"
#include "asm/page-allocator.h"
#include "scene-fit.h"

namespace sp::tech {
namespace {

using asmap::PageAllocator;
using asmap::PageKey;

constexpr uint32_t kNotResident = 0xffffffffu;
constexpr uint32_t kMaxLevel = 12;  // the request encoding holds 14-bit page coordinates

bool PowerOfTwo(uint32_t v) { return v && (v & (v - 1)) == 0; }
uint32_t Log2(uint32_t v) {
  uint32_t l = 0;
  while ((1u << l) < v) ++l;
  return l;
}

class AsmTechnique final : public Technique, public AsmCounterSource {
 public:
  std::string Name() const override { return "asm"; }

  std::vector<ParamSpec> Params() const override {
    return {
        {ParamSpec::Int, "effective_resolution", "texels per side of the finest page-table level over the light's view of the scene (page_size * 2^levels)", "16384", 16, 131072, {}},
        {ParamSpec::Int, "page_size", "texels per side of a page (a power of two)", "128", 8, 1024, {}},
        {ParamSpec::Int, "pool_pages", "pages per side of the physical pool (the pool holds pool_pages^2 pages, pool_pages * page_size texels per side)", "16", 1, 256, {}},
        {ParamSpec::Int, "resident_levels", "coarse levels 0..n-1 kept resident at all times (so every point has a page, and shadows too small for the analysis to see at coarser levels are still drawn)", "4", 1, 6, {}},
        {ParamSpec::Int, "iterations", "refinement iterations (analysis, readback, allocation, page rendering) per frame at most", "4", 1, 64, {}},
        {ParamSpec::Choice, "allocation", "readback: the paper's refinement (requests read back, pages allocated and drawn by the CPU); gpu: allocation, page tables and page drawing on the GPU, nothing read back", "readback", 0, 0, {"readback", "gpu"}},
        {ParamSpec::Choice, "mark", "which pixels request pages: edges (Sobel boundaries of the shadow, the paper) or visible (every visible sample and its filter footprint, as virtual shadow maps)", "edges", 0, 0, {"edges", "visible"}},
        {ParamSpec::Choice, "compaction", "how the analysis' requests become a dense stream: append (an AppendStructuredBuffer's counter) or prefix (the paper's stream compaction: a prefix sum over four request slots per pixel, order-preserving)", "append", 0, 0, {"append", "prefix"}},
        {ParamSpec::Int, "clipmap", "0: any level may be refined anywhere; W > 0: level L is refined only within the W x W pages around the camera's page (a clipmap of levels, as virtual shadow maps for a directional light), coarser levels serving the rest", "0", 0, 4096, {}},
        {ParamSpec::Int, "gpu_batch", "allocation=gpu: pages allocated and drawn per iteration at most (slices of the scratch depth array); the rest wait for the next iteration", "64", 1, 2048, {}},
        {ParamSpec::Float, "edge_threshold", "Sobel gradient magnitude of the shadow term above which a pixel is a shadow boundary", "0.1", 0.0, 8.0, {}},
        {ParamSpec::Int, "depth_bias", "D3D11 DepthBias (units of the depth format)", "200", -1e7, 1e7, {}},
        {ParamSpec::Float, "slope_bias", "D3D11 SlopeScaledDepthBias", "2.0", -100, 100, {}},
    };
  }

  void Configure(Device& device, const ParamValues& p) override {
    uint32_t eff = uint32_t(p.getInt("effective_resolution"));
    pageSize_ = uint32_t(p.getInt("page_size"));
    poolPages_ = uint32_t(p.getInt("pool_pages"));
    uint32_t resident = uint32_t(p.getInt("resident_levels"));
    iterations_ = uint32_t(p.getInt("iterations"));
    edgeThreshold_ = p.getFloat("edge_threshold");
    if (!PowerOfTwo(pageSize_)) throw std::invalid_argument("page_size: " + std::to_string(pageSize_) + " is not a power of two");
    if (eff % pageSize_ != 0 || !PowerOfTwo(eff / pageSize_))
      throw std::invalid_argument("effective_resolution: " + std::to_string(eff) + " is not page_size (" + std::to_string(pageSize_) +
                                  ") times a power of two");
    maxLevel_ = Log2(eff / pageSize_);
    if (maxLevel_ > kMaxLevel)
      throw std::invalid_argument("effective_resolution: " + std::to_string(eff) + " needs " + std::to_string(maxLevel_ + 1) +
                                  " page-table levels with page_size " + std::to_string(pageSize_) + "; at most " + std::to_string(kMaxLevel + 1));
    if (resident > maxLevel_ + 1)
      throw std::invalid_argument("resident_levels: " + std::to_string(resident) + " exceeds the " + std::to_string(maxLevel_ + 1) + " levels there are");
    residentLevels_ = resident;
    uint32_t poolSize = poolPages_ * pageSize_;
    if (poolSize > 16384)
      throw std::invalid_argument("pool_pages: " + std::to_string(poolPages_) + " pages of " + std::to_string(pageSize_) + " texels make a pool of " +
                                  std::to_string(poolSize) + " texels per side; at most 16384 (D3D11's texture limit)");
    uint64_t pinned = 0;
    for (uint32_t l = 0; l < resident; ++l) pinned += uint64_t(1) << (2 * l);
    uint64_t capacity = uint64_t(poolPages_) * poolPages_;
    if (capacity <= pinned)
      throw std::invalid_argument("pool_pages: " + std::to_string(poolPages_) + "^2 = " + std::to_string(capacity) + " pages cannot hold the " +
                                  std::to_string(pinned) + " pages of resident levels 0.." + std::to_string(resident - 1) +
                                  " and leave room for refinement; raise pool_pages or lower resident_levels");
    gpuAllocation_ = p.getChoice("allocation") == "gpu";
    markVisible_ = p.getChoice("mark") == "visible";
    prefixCompaction_ = p.getChoice("compaction") == "prefix";
    clipPages_ = uint32_t(p.getInt("clipmap"));
    if (clipPages_ == 1) throw std::invalid_argument("clipmap: 1 page per level cannot hold a footprint; 0 (off) or at least 2");
    if (gpuAllocation_ && !device.Info().vsRenderTargetArrayIndex)
      throw std::invalid_argument(std::string("allocation: gpu draws each new page into its own slice with SV_RenderTargetArrayIndex from the vertex shader, which this ") +
                                  BackendName(device.GetBackend()) + " device lacks (DeviceInfo::vsRenderTargetArrayIndex)");
    device_ = &device;
    allocator_ = std::make_unique<PageAllocator>(uint32_t(capacity));
    pool_ = MakeDepthMap(device, poolSize, poolSize, "asm page pool");

    TEXTURE2D_DESC td;
    td.Width = td.Height = 1u << maxLevel_;
    td.MipLevels = maxLevel_ + 1;
    td.Format = FORMAT_R32_UINT;
    td.BindFlags = BIND_SHADER_RESOURCE | (gpuAllocation_ ? BIND_UNORDERED_ACCESS : 0u);
    table_ = device.CreateTexture2D(td);
    table_->SetDebugName("asm page tables");
    tableSrv_ = device.CreateShaderResourceView(table_.get());
    tables_.assign(maxLevel_ + 1, {});
    tableBytes_ = 0;
    for (uint32_t l = 0; l <= maxLevel_; ++l) {
      tables_[l].assign(size_t(1) << (2 * l), kNotResident);
      tableBytes_ += uint64_t(4) << (2 * l);
      UploadLevel(*device.GetImmediateContext(), l);
    }
    // The per-frame request bitmap: one bit per virtual page of every level.
    uint64_t pages = ((uint64_t(1) << (2 * (maxLevel_ + 1))) - 1) / 3;
    bitmapWords_ = uint32_t((pages + 31) / 32);
    requested_ = MakeRawBuffer(device, bitmapWords_ * 4, BIND_UNORDERED_ACCESS, "asm requested pages");
    requestedUav_ = MakeRawUav(device, requested_.get());
    countBuffer_ = MakeRawBuffer(device, 16, BIND_SHADER_RESOURCE, "asm request count");
    countStaging_ = MakeStaging(device, 16, "asm request count readback");

    RASTERIZER_DESC rd;
    rd.FrontCounterClockwise = true;
    rd.DepthBias = p.getInt("depth_bias");
    rd.SlopeScaledDepthBias = p.getFloat("slope_bias");
    rd.DepthClipEnable = false;  // casters in front of the fitted near plane still cast
    rd.ScissorEnable = true;     // never write outside the page
    pageRasterizer_ = device.CreateRasterizerState(rd);
    RASTERIZER_DESC cd;
    cd.CullMode = CULL_NONE;
    cd.ScissorEnable = true;
    clearRasterizer_ = device.CreateRasterizerState(cd);
    RASTERIZER_DESC vd;
    vd.CullMode = CULL_NONE;
    viewRasterizer_ = device.CreateRasterizerState(vd);
    DEPTH_STENCIL_DESC dd;
    dd.DepthFunc = COMPARISON_ALWAYS;
    clearDepth_ = device.CreateDepthStencilState(dd);
    dd.DepthFunc = COMPARISON_LESS_EQUAL;
    redrawDepth_ = device.CreateDepthStencilState(dd);

    constants_ = MakeConstantBuffer(device, sizeof(Constants), "AsmShadow constants");
    analysisConstants_ = MakeConstantBuffer(device, sizeof(AnalysisConstants), "AsmAnalysis constants");
    clearVs_ = device.CreateVertexShader(CompileTechniqueShader("asm/analysis.hlsl", "vs_5_0", "VSClearPage"));
    viewVs_ = device.CreateVertexShader(CompileTechniqueShader("asm/analysis.hlsl", "vs_5_0", "VSView"));
    viewPs_ = device.CreatePixelShader(CompileTechniqueShader("asm/analysis.hlsl", "ps_5_0", "PSView"));
    analyzeCs_ = device.CreateComputeShader(
        CompileTechniqueShader("asm/analysis.hlsl", "cs_5_0", "CSAnalyze", {{"ASM_PREFIX_COMPACTION", prefixCompaction_ ? "1" : "0"}}));
    if (prefixCompaction_) {
      countBlocksCs_ = device.CreateComputeShader(CompileTechniqueShader("asm/compaction.hlsl", "cs_5_0", "CSCountBlocks"));
      scanBlocksCs_ = device.CreateComputeShader(CompileTechniqueShader("asm/compaction.hlsl", "cs_5_0", "CSScanBlocks"));
      scatterCs_ = device.CreateComputeShader(CompileTechniqueShader("asm/compaction.hlsl", "cs_5_0", "CSScatter"));
      compactionConstants_ = MakeConstantBuffer(device, 16, "AsmCompaction constants");
      prefixCount_ = MakeRawBuffer(device, 16, BIND_UNORDERED_ACCESS, "asm compacted request count");
      prefixCountUav_ = MakeRawUav(device, prefixCount_.get());
    }
    lastFit_ = glm::mat4(0.0f);
    viewWidth_ = viewHeight_ = 0;
    gpu_.reset();
    if (gpuAllocation_) {
      uint32_t batch = uint32_t(std::min<uint64_t>(uint64_t(p.getInt("gpu_batch")), capacity - pinned));
      gpu_ = std::make_unique<asmap::GpuAllocation>(device, uint32_t(capacity), pageSize_, poolPages_, batch, maxLevel_, residentLevels_);
    }
  }

  void RenderShadows(DeviceContext& ctx, SceneDrawer& drawer, const FrameInputs& frame) override {
    GpuTimer::Scope timed(frame.timer, ctx, "shadow");
    lightViewProj_ = FitOrthoToBounds(frame.scene->bounds, frame.light.direction).viewProj;  // level 0's page
    glm::vec4 eye = lightViewProj_ * glm::vec4(frame.camera.position, 1.0f);
    glm::vec2 cameraUV(eye.x / eye.w * 0.5f + 0.5f, 0.5f - eye.y / eye.w * 0.5f);
    Constants c{lightViewProj_, float(pageSize_), float(maxLevel_), float(poolPages_), float(poolPages_ * pageSize_), float(residentLevels_ - 1),
                float(clipPages_), cameraUV};
    ctx.UpdateSubresource(constants_.get(), 0, nullptr, &c, 0, 0);
    EnsureViewTargets(frame.width, frame.height);
    counters_ = {};
    trianglesSubmitted_ = 0;
    gpuRead_ = false;
    // The pages hold depth for one light view: a new light direction or scene bounds invalidate them.
    bool invalidated = lightViewProj_ != lastFit_;
    if (invalidated) {
      allocator_->Reset();
      for (uint32_t l = 0; l <= maxLevel_; ++l) {
        std::fill(tables_[l].begin(), tables_[l].end(), kNotResident);
        UploadLevel(ctx, l);
      }
      lastFit_ = lightViewProj_;
    }
    // The resident levels: requested every frame by the CPU (allocation=gpu: only after an
    // invalidation, then handed to the GPU's slots as pinned).
    if (!gpuAllocation_ || invalidated) {
      allocator_->BeginFrame();
      std::vector<PageKey> fresh;
      for (uint32_t l = 0; l < residentLevels_; ++l)
        for (uint32_t y = 0; y < (1u << l); ++y)
          for (uint32_t x = 0; x < (1u << l); ++x) Serve({l, x, y}, true, fresh);
      RenderPages(ctx, drawer, fresh, frame.timer);
      if (gpuAllocation_) {
        std::vector<std::pair<uint32_t, uint32_t>> pinned;
        for (const PageKey& k : fresh) pinned.push_back({(k.level << 28) | (k.y << 14) | k.x, *allocator_->SlotOf(k)});
        gpu_->Reset(ctx, pinned);
      }
    }
    // Cleared on the GPU: at 131072 effective texels in 64-texel pages the bitmap is 700 KB, too
    // much to upload from a CPU array of zeros every frame.
    const uint32_t zero[4] = {0, 0, 0, 0};
    ctx.ClearUnorderedAccessViewUint(requestedUav_.get(), zero);
    if (gpuAllocation_) {
      RefineOnGpu(ctx, drawer, frame);
      return;
    }

    std::vector<PageKey> fresh;
    for (uint32_t it = 0; it < iterations_; ++it) {
      std::vector<uint32_t> requests = Analyze(ctx, drawer, frame);
      // The stream's order is the order of the GPU's appends, which differs between drivers; in
      // key order (coarse levels first) a full pool serves and evicts the same pages everywhere.
      std::sort(requests.begin(), requests.end());
      ++counters_.iterations;
      fresh.clear();
      for (uint32_t r : requests) Serve({r >> 28, r & 0x3fffu, (r >> 14) & 0x3fffu}, false, fresh);
      counters_.requests += uint32_t(requests.size());
      if (fresh.empty()) break;
      RenderPages(ctx, drawer, fresh, frame.timer);
    }
    counters_.unserved = allocator_->unserved();
    counters_.resident = allocator_->resident();
    counters_.evicted = allocator_->evictions();
  }

  std::string LightingInclude() const override { return "asm/shadow.hlsli"; }

  void BindLighting(DeviceContext& ctx) override {
    ctx.PSSetConstantBuffers(2, {constants_.get()});
    ctx.PSSetShaderResources(0, {pool_.srv.get(), tableSrv_.get()});
  }

  ShadowStats Stats() const override {
    if (gpuAllocation_) AsmFrameCounters();  // the triangles drawn into pages are counted on the GPU
    uint64_t poolTexels = uint64_t(poolPages_ * pageSize_) * (poolPages_ * pageSize_);
    uint64_t bytes = poolTexels * 4 + tableBytes_ + uint64_t(bitmapWords_) * 4 + requestBytes_ + (gpu_ ? gpu_->Bytes() : 0);
    return {bytes, trianglesSubmitted_, counters_.pagesRendered};
  }
  std::vector<ShadowLayer> Layers() const override { return {{poolPages_ * pageSize_, poolPages_ * pageSize_}}; }
  AsmCounters AsmFrameCounters() const override {
    if (!gpuAllocation_ || gpuRead_) return counters_;
    // allocation=gpu keeps its counters on the GPU; reading them waits for the frame's work.
    asmap::GpuAllocation::Counters g = gpu_->Read(*device_->GetImmediateContext());
    counters_.requests = g.requests;
    counters_.pagesRendered += g.rendered;
    counters_.evicted = g.evicted;
    counters_.unserved = g.unserved;
    counters_.resident = g.resident;
    counters_.iterations = g.iterations;
    trianglesSubmitted_ += uint64_t(g.rendered) * sceneTriangles_;
    gpuRead_ = true;
    return counters_;
  }

  // Every resident page (level << 28 | y << 14 | x), ascending, read back from the page tables
  // on the GPU (what the lookup sees, whichever mode wrote them).
  std::vector<uint32_t> AsmResidentPages() const override {
    DeviceContext& ctx = *device_->GetImmediateContext();
    TEXTURE2D_DESC d = table_->GetDesc();
    d.Usage = USAGE_STAGING;
    d.BindFlags = 0;
    d.CPUAccessFlags = CPU_ACCESS_READ;
    Ref<Texture2D> staging = device_->CreateTexture2D(d);
    ctx.CopyResource(staging.get(), table_.get());
    std::vector<uint32_t> keys;
    for (uint32_t l = 0; l <= maxLevel_; ++l) {
      uint32_t n = 1u << l, mip = maxLevel_ - l;
      MAPPED_SUBRESOURCE m;
      if (!ctx.Map(staging.get(), mip, MAP_READ, 0, &m)) throw std::runtime_error("asm: Map of the page-table readback failed");
      for (uint32_t y = 0; y < n; ++y) {
        const uint32_t* row = reinterpret_cast<const uint32_t*>(static_cast<const uint8_t*>(m.pData) + size_t(y) * m.RowPitch);
        for (uint32_t x = 0; x < n; ++x)
          if (row[x] != kNotResident) keys.push_back((l << 28) | (y << 14) | x);
      }
      ctx.Unmap(staging.get(), mip);
    }
    std::sort(keys.begin(), keys.end());
    return keys;
  }

 private:
  // cbuffer AsmShadow in shaders-hlsl/asm/shadow.hlsli.
  struct Constants {
    glm::mat4 lightViewProj;
    float pageSize, maxLevel, poolPages, poolSize;
    float finestPinned, clipPages;
    glm::vec2 cameraUV;
  };
  static_assert(sizeof(Constants) == 96);
  // cbuffer AsmAnalysis in shaders-hlsl/asm/analysis.hlsl.
  struct AnalysisConstants {
    uint32_t w, h, maxLevel;
    float threshold;
    uint32_t markVisible;
    float pageSize;
    uint32_t pad[2];
  };

  // allocation=gpu: `iterations` analyses, each followed by the GPU's allocation and page
  // drawing. The CPU cannot know when nothing is left to do, so it records every iteration; one
  // after an iteration that placed and deferred no page draws no instances and dispatches no
  // groups (the arguments come from the GPU), so only the first costs a full analysis when the
  // view's pages are resident.
  void RefineOnGpu(DeviceContext& ctx, SceneDrawer& drawer, const FrameInputs& frame) {
    sceneTriangles_ = 0;
    for (const scene::DrawItem& d : drawer.gpu().draws()) sceneTriangles_ += d.indexCount / 3;
    gpu_->BeginFrame(ctx);
    asmap::GpuAllocationTargets t;
    t.table = table_.get();
    t.tableSrv = tableSrv_.get();
    t.requestsSrv = requestsSrv_.get();
    t.requestsUav = requestsUav_.get();
    t.requestedUav = requestedUav_.get();
    t.shadowConstants = constants_.get();
    t.poolDsv = pool_.dsv.get();
    t.pageRasterizer = pageRasterizer_.get();
    t.requestCapacity = requestCapacity_;
    if (prefixCompaction_) t.requestCount = prefixCount_.get();
    t.analyzeGroups[0] = (viewWidth_ + 7) / 8;
    t.analyzeGroups[1] = (viewHeight_ + 7) / 8;
    for (uint32_t it = 0; it < iterations_; ++it) {
      {
        GpuTimer::Scope timed(frame.timer, ctx, "analysis");
        DrawAnalysis(ctx, drawer, frame, it > 0);
      }
      gpu_->Refine(ctx, drawer, t, frame.timer);
    }
  }

  static Ref<Buffer> MakeStaging(Device& device, uint32_t bytes, const char* name) {
    BUFFER_DESC d;
    d.ByteWidth = bytes;
    d.Usage = USAGE_STAGING;
    d.CPUAccessFlags = CPU_ACCESS_READ;
    Ref<Buffer> b = device.CreateBuffer(d);
    b->SetDebugName(name);
    return b;
  }

  void UploadLevel(DeviceContext& ctx, uint32_t level) {
    uint32_t n = 1u << level;
    ctx.UpdateSubresource(table_.get(), maxLevel_ - level, nullptr, tables_[level].data(), n * 4, n * n * 4);
  }
  void SetEntry(DeviceContext& ctx, const PageKey& k, uint32_t value) {
    uint32_t n = 1u << k.level;
    tables_[k.level][size_t(k.y) * n + k.x] = value;
    BOX box{k.x, k.y, 0, k.x + 1, k.y + 1, 1};
    ctx.UpdateSubresource(table_.get(), maxLevel_ - k.level, &box, &value, 4, 4);
  }

  // A page this frame needs: allocated (table entry written, queued in `fresh` for rendering)
  // unless resident; a page it evicts loses its table entry.
  void Serve(const PageKey& k, bool pinned, std::vector<PageKey>& fresh) {
    if (k.level > maxLevel_ || k.x >= (1u << k.level) || k.y >= (1u << k.level))
      throw std::runtime_error("asm: the analysis requested page (" + std::to_string(k.level) + ", " + std::to_string(k.x) + ", " + std::to_string(k.y) +
                               ") outside the page tables");
    PageAllocator::Result r = allocator_->Request(k, pinned);
    DeviceContext& ctx = *device_->GetImmediateContext();
    if (r.evicted) SetEntry(ctx, *r.evicted, kNotResident);
    if (r.created) {
      SetEntry(ctx, k, r.slot);
      fresh.push_back(k);
    }
  }

  // Whether an instance's world box may reach the page's square (its corners not all beyond one of
  // the four side planes). Depth is not tested: casters in front of the near plane still cast
  // (depth clip is off). allocation=gpu draws every instance into every page (its pages are known
  // only to the GPU); the depth written is the same.
  static bool MayCoverPage(const scene::Bounds& b, const glm::mat4& viewProj) {
    int left = 0, right = 0, below = 0, above = 0;
    for (int i = 0; i < 8; ++i) {
      glm::vec4 c = viewProj * glm::vec4(i & 1 ? b.max.x : b.min.x, i & 2 ? b.max.y : b.min.y, i & 4 ? b.max.z : b.min.z, 1.0f);
      left += c.x < -c.w;
      right += c.x > c.w;
      below += c.y < -c.w;
      above += c.y > c.w;
    }
    return left < 8 && right < 8 && below < 8 && above < 8;
  }

  // The light's projection cropped to a virtual page: its uv square becomes NDC [-1, 1].
  glm::mat4 PageViewProj(const PageKey& k) const {
    float n = float(1u << k.level);
    // NDC x = 2u - 1 and y = 1 - 2v; the page spans u in [x/n, (x+1)/n], v in [y/n, (y+1)/n].
    float x0 = 2.0f * k.x / n - 1.0f, x1 = 2.0f * (k.x + 1) / n - 1.0f;
    float y1 = 1.0f - 2.0f * k.y / n, y0 = 1.0f - 2.0f * (k.y + 1) / n;
    glm::mat4 crop(1.0f);
    crop[0][0] = 2.0f / (x1 - x0);
    crop[1][1] = 2.0f / (y1 - y0);
    crop[3][0] = -(x0 + x1) / (x1 - x0);
    crop[3][1] = -(y0 + y1) / (y1 - y0);
    return crop * lightViewProj_;
  }

  void RenderPages(DeviceContext& ctx, SceneDrawer& drawer, const std::vector<PageKey>& pages, GpuTimer* timer) {
    if (pages.empty()) return;
    GpuTimer::Scope timed(timer, ctx, "pages");
    ShaderResourceView* none[2] = {};
    ctx.PSSetShaderResources(0, 2, none);
    ctx.OMSetRenderTargets(0, nullptr, pool_.dsv.get());
    for (const PageKey& k : pages) {
      uint32_t slot = *allocator_->SlotOf(k);
      uint32_t px = (slot % poolPages_) * pageSize_, py = (slot / poolPages_) * pageSize_;
      VIEWPORT vp{float(px), float(py), float(pageSize_), float(pageSize_), 0, 1};
      RECT sc{int32_t(px), int32_t(py), int32_t(px + pageSize_), int32_t(py + pageSize_)};
      ctx.RSSetViewports(1, &vp);
      ctx.RSSetScissorRects(1, &sc);
      // Reset the page's depth: a viewport-covering triangle at depth 1, depth test ALWAYS.
      ctx.RSSetState(clearRasterizer_.get());
      ctx.OMSetDepthStencilState(clearDepth_.get(), 0);
      ctx.IASetInputLayout(nullptr);
      ctx.IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
      ctx.VSSetShader(clearVs_.get());
      ctx.PSSetShader(nullptr);
      ctx.Draw(3, 0);
      ctx.RSSetState(pageRasterizer_.get());
      ctx.OMSetDepthStencilState(nullptr, 0);
      glm::mat4 viewProj = PageViewProj(k);
      const std::vector<scene::Instance>& instances = drawer.gpu().scene().instances;
      trianglesSubmitted_ += drawer.DrawDepth(ctx, viewProj, [&](uint32_t i) { return MayCoverPage(instances[i].worldBounds, viewProj); });
      ++counters_.pagesRendered;
    }
    ctx.OMSetRenderTargets(0, nullptr, nullptr);
  }

  void EnsureViewTargets(uint32_t w, uint32_t h) {
    if (w == viewWidth_ && h == viewHeight_) return;
    Device& device = *device_;
    viewWidth_ = w;
    viewHeight_ = h;
    TEXTURE2D_DESC td;
    td.Width = w;
    td.Height = h;
    td.Format = FORMAT_R32G32B32A32_FLOAT;
    td.BindFlags = BIND_RENDER_TARGET | BIND_SHADER_RESOURCE;
    view_ = device.CreateTexture2D(td);
    view_->SetDebugName("asm analysis view");
    viewRtv_ = device.CreateRenderTargetView(view_.get());
    viewSrv_ = device.CreateShaderResourceView(view_.get());
    TEXTURE2D_DESC dd = td;
    dd.Format = FORMAT_D32_FLOAT;
    dd.BindFlags = BIND_DEPTH_STENCIL;
    viewDepth_ = device.CreateTexture2D(dd);
    viewDsv_ = device.CreateDepthStencilView(viewDepth_.get());
    // At most one request per pixel (four with mark=visible: the filter footprint's pages) and one
    // per page: the stream cannot overflow.
    uint64_t pages = ((uint64_t(1) << (2 * (maxLevel_ + 1))) - 1) / 3;
    uint32_t capacity = uint32_t(std::min<uint64_t>(uint64_t(w) * h * (markVisible_ ? 4 : 1), pages));
    BUFFER_DESC bd;
    bd.ByteWidth = capacity * 4;
    bd.BindFlags = BIND_UNORDERED_ACCESS | (gpuAllocation_ ? BIND_SHADER_RESOURCE : 0u);
    bd.MiscFlags = RESOURCE_MISC_BUFFER_STRUCTURED;
    bd.StructureByteStride = 4;
    requests_ = device.CreateBuffer(bd);
    requests_->SetDebugName("asm requests");
    UNORDERED_ACCESS_VIEW_DESC ud;
    ud.Format = FORMAT_UNKNOWN;
    ud.ViewDimension = UAV_DIMENSION_BUFFER;
    ud.Buffer = {0, capacity, BUFFER_UAV_FLAG_APPEND};
    requestsUav_ = device.CreateUnorderedAccessView(requests_.get(), &ud);
    requestsSrv_ = gpuAllocation_ ? device.CreateShaderResourceView(requests_.get()) : nullptr;
    requestsStaging_ = MakeStaging(device, capacity * 4, "asm requests readback");
    requestCapacity_ = capacity;
    requestBytes_ = uint64_t(capacity) * 4;
    if (prefixCompaction_) {
      ud.Buffer.Flags = 0;
      requestsPlainUav_ = device.CreateUnorderedAccessView(requests_.get(), &ud);
      BUFFER_DESC pd;
      pd.ByteWidth = w * h * 4 * 4;
      pd.BindFlags = BIND_UNORDERED_ACCESS | BIND_SHADER_RESOURCE;
      pd.MiscFlags = RESOURCE_MISC_BUFFER_STRUCTURED;
      pd.StructureByteStride = 4;
      pixelRequests_ = device.CreateBuffer(pd);
      pixelRequests_->SetDebugName("asm request slots per pixel");
      pixelRequestsUav_ = device.CreateUnorderedAccessView(pixelRequests_.get());
      pixelRequestsSrv_ = device.CreateShaderResourceView(pixelRequests_.get());
      uint32_t blocks = (w * h * 4 + 1023) / 1024;
      blockSums_ = MakeRawBuffer(device, blocks * 8, BIND_UNORDERED_ACCESS, "asm compaction block sums");
      blockSumsUav_ = MakeRawUav(device, blockSums_.get());
      requestBytes_ += uint64_t(w) * h * 16 + blocks * 8;
    }
  }

  // One analysis: the camera's view with the current pages, the Sobel pass appending requests,
  // and the readback of the request stream (waits for the GPU: the paper's CpuReadback).
  std::vector<uint32_t> Analyze(DeviceContext& ctx, SceneDrawer& drawer, const FrameInputs& frame) {
    {
      GpuTimer::Scope timed(frame.timer, ctx, "analysis");
      DrawAnalysis(ctx, drawer, frame);
    }
    GpuTimer::Scope timed(frame.timer, ctx, "readback");
    CopyRequestCount(ctx, countBuffer_.get());
    ctx.CopyResource(countStaging_.get(), countBuffer_.get());
    uint32_t count = ReadWords(ctx, countStaging_.get(), 1)[0];
    if (count > requestCapacity_) throw std::runtime_error("asm: request count " + std::to_string(count) + " exceeds the request buffer");
    if (count == 0) return {};
    BOX box{0, 0, 0, count * 4, 1, 1};
    ctx.CopySubresourceRegion(requestsStaging_.get(), 0, 0, 0, 0, requests_.get(), 0, &box);
    return ReadWords(ctx, requestsStaging_.get(), count);
  }

  // The camera's view with the current pages, and the pass appending this frame's new requests.
  // early: allocation=gpu's iterations after the first, drawn and dispatched with the arguments the
  // previous iteration's allocation wrote (nothing when it placed and deferred no page).
  void DrawAnalysis(DeviceContext& ctx, SceneDrawer& drawer, const FrameInputs& frame, bool early = false) {
    ShaderResourceView* none[2] = {};
    ctx.CSSetShaderResources(0, 2, none);
    RenderTargetView* rtv = viewRtv_.get();
    ctx.OMSetRenderTargets(1, &rtv, viewDsv_.get());
    // An early iteration draws the same geometry from the same camera over the previous
    // iteration's view: with LESS_EQUAL the nearest surface overwrites itself and nothing else
    // passes, so no clear is needed, and an iteration that draws nothing costs nothing.
    const float clear[4] = {-1, -1, 1, -1};
    if (!early) {
      ctx.ClearRenderTargetView(viewRtv_.get(), clear);
      ctx.ClearDepthStencilView(viewDsv_.get(), CLEAR_DEPTH, 1.0f, 0);
    }
    VIEWPORT vp{0, 0, float(viewWidth_), float(viewHeight_), 0, 1};
    ctx.RSSetViewports(1, &vp);
    ctx.RSSetState(viewRasterizer_.get());
    ctx.OMSetDepthStencilState(early ? redrawDepth_.get() : nullptr, 0);
    BindLighting(ctx);
    glm::mat4 camera = frame.cameraProj * frame.cameraView;
    if (early)
      drawer.DrawDepthIndirect(ctx, camera, {viewVs_.get(), viewPs_.get()}, gpu_->Args(), gpu_->ViewArgsByte());
    else
      trianglesViewed_ = drawer.DrawDepth(ctx, camera, [](uint32_t) { return true; }, {viewVs_.get(), viewPs_.get()});
    ctx.OMSetRenderTargets(0, nullptr, nullptr);

    AnalysisConstants ac{viewWidth_, viewHeight_, maxLevel_, edgeThreshold_, markVisible_ ? 1u : 0u, float(pageSize_), {0, 0}};
    ctx.UpdateSubresource(analysisConstants_.get(), 0, nullptr, &ac, 0, 0);
    ctx.CSSetShader(analyzeCs_.get());
    ctx.CSSetConstantBuffers(0, {analysisConstants_.get()});
    ctx.CSSetShaderResources(0, {viewSrv_.get()});
    UnorderedAccessView* uavs[2] = {requestedUav_.get(), prefixCompaction_ ? pixelRequestsUav_.get() : requestsUav_.get()};
    const uint32_t counts[2] = {0xffffffffu, 0};
    ctx.CSSetUnorderedAccessViews(0, 2, uavs, counts);
    if (early)
      ctx.DispatchIndirect(gpu_->Args(), gpu_->AnalyzeArgsByte());
    else
      ctx.Dispatch((viewWidth_ + 7) / 8, (viewHeight_ + 7) / 8, 1);
    UnorderedAccessView* noUavs[2] = {};
    ctx.CSSetUnorderedAccessViews(0, 2, noUavs, nullptr);
    ctx.CSSetShaderResources(0, 2, none);
    if (prefixCompaction_) Compact(ctx, frame.timer);
  }

  // compaction=prefix (asm/compaction.hlsl): the request slots of every pixel packed into the
  // request stream, its length into prefixCount_.
  void Compact(DeviceContext& ctx, GpuTimer* timer) {
    GpuTimer::Scope timed(timer, ctx, "compaction");
    uint32_t slots = viewWidth_ * viewHeight_ * 4, blocks = (slots + 1023) / 1024;
    const uint32_t c[4] = {slots, blocks, 0, 0};
    ctx.UpdateSubresource(compactionConstants_.get(), 0, nullptr, c, 0, 0);
    ctx.CSSetConstantBuffers(0, {compactionConstants_.get()});
    ctx.CSSetShaderResources(0, {pixelRequestsSrv_.get()});
    ctx.CSSetUnorderedAccessViews(0, {blockSumsUav_.get(), requestsPlainUav_.get(), prefixCountUav_.get()});
    ctx.CSSetShader(countBlocksCs_.get());
    ctx.Dispatch(blocks, 1, 1);
    ctx.CSSetShader(scanBlocksCs_.get());
    ctx.Dispatch(1, 1, 1);
    ctx.CSSetShader(scatterCs_.get());
    ctx.Dispatch(blocks, 1, 1);
    ctx.CSSetUnorderedAccessViews(0, {nullptr, nullptr, nullptr});
    ctx.CSSetShaderResources(0, {nullptr});
  }

  // The request stream's length into word 0 of `dst`: the append buffer's hidden counter, or
  // the prefix sum's total.
  void CopyRequestCount(DeviceContext& ctx, Buffer* dst) {
    if (!prefixCompaction_) {
      ctx.CopyStructureCount(dst, 0, requestsUav_.get());
      return;
    }
    BOX box{0, 0, 0, 4, 1, 1};
    ctx.CopySubresourceRegion(dst, 0, 0, 0, 0, prefixCount_.get(), 0, &box);
  }

  static std::vector<uint32_t> ReadWords(DeviceContext& ctx, Buffer* staging, uint32_t n) {
    MAPPED_SUBRESOURCE m;
    if (!ctx.Map(staging, 0, MAP_READ, 0, &m)) throw std::runtime_error("asm: Map of the request readback failed");
    std::vector<uint32_t> words(n);
    std::memcpy(words.data(), m.pData, size_t(n) * 4);
    ctx.Unmap(staging, 0);
    return words;
  }

  Device* device_ = nullptr;
  uint32_t pageSize_ = 128, poolPages_ = 16, maxLevel_ = 0, residentLevels_ = 2, iterations_ = 4;
  float edgeThreshold_ = 0.1f;
  std::unique_ptr<PageAllocator> allocator_;
  DepthMap pool_;
  Ref<Texture2D> table_;
  Ref<ShaderResourceView> tableSrv_;
  std::vector<std::vector<uint32_t>> tables_;  // CPU copy of each level's entries
  uint64_t tableBytes_ = 0, requestBytes_ = 0;
  uint32_t requestCapacity_ = 0;
  uint32_t bitmapWords_ = 0;
  Ref<Buffer> requested_, requests_, requestsStaging_, countBuffer_, countStaging_;
  Ref<UnorderedAccessView> requestedUav_, requestsUav_;
  Ref<ShaderResourceView> requestsSrv_;
  bool prefixCompaction_ = false;
  uint32_t clipPages_ = 0;
  Ref<Buffer> pixelRequests_, blockSums_, prefixCount_, compactionConstants_;
  Ref<UnorderedAccessView> pixelRequestsUav_, blockSumsUav_, prefixCountUav_, requestsPlainUav_;
  Ref<ShaderResourceView> pixelRequestsSrv_;
  Ref<ComputeShader> countBlocksCs_, scanBlocksCs_, scatterCs_;
  bool gpuAllocation_ = false, markVisible_ = false;
  std::unique_ptr<asmap::GpuAllocation> gpu_;
  uint64_t sceneTriangles_ = 0;
  mutable bool gpuRead_ = false;
  Ref<Texture2D> view_, viewDepth_;
  Ref<RenderTargetView> viewRtv_;
  Ref<ShaderResourceView> viewSrv_;
  Ref<DepthStencilView> viewDsv_;
  uint32_t viewWidth_ = 0, viewHeight_ = 0;
  Ref<RasterizerState> pageRasterizer_, clearRasterizer_, viewRasterizer_;
  Ref<DepthStencilState> clearDepth_, redrawDepth_;
  Ref<Buffer> constants_, analysisConstants_;
  Ref<VertexShader> clearVs_, viewVs_;
  Ref<PixelShader> viewPs_;
  Ref<ComputeShader> analyzeCs_;
  glm::mat4 lightViewProj_{1.0f}, lastFit_{0.0f};
  mutable uint64_t trianglesSubmitted_ = 0;
  uint64_t trianglesViewed_ = 0;
  mutable AsmCounters counters_;
};

}  // namespace

std::unique_ptr<Technique> MakeAsmTechnique() { return std::make_unique<AsmTechnique>(); }

}  // namespace sp::tech
