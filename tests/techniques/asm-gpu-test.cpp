// Adaptive shadow maps with allocation=gpu against the paper's readback mode, on both backends:
// on a static view both modes end with the same resident pages (read back from the page tables
// each mode wrote) and the same picture, for either marking; a small gpu_batch defers pages to
// later iterations without losing any; pages stay cached across frames and a light change
// invalidates them; under a full pool both backends evict the same pages in both modes.
#include <cmath>
#include <cstdio>
#include <glm/ext/matrix_transform.hpp>

#include "backend-test.h"
#include "cross-backend.h"
#include "floating-box.h"
#include "metrics.h"
#include "technique-renderer.h"
#include <sp/tech/asm-counters.h>
#include <sp/tech/renderer.h>
#include "scene-fit.h"

namespace sp::test {
namespace {

class AsmGpuAllocationTest : public BackendTest {};

const tech::AsmCounterSource& Source(tech::Renderer& r) { return dynamic_cast<tech::AsmCounterSource&>(r.technique()); }

// A low oblique view along the floating box's shadow edge (x = -1): its near part needs fine
// levels, its far part coarse ones, so the page set spans many levels.
scene::Scene ObliqueBox() {
  scene::Scene s = FloatingBox(true);
  s.camera.position = {-0.7f, 0.3f, 1.5f};
  s.camera.target = {-1.1f, 0.0f, -0.5f};
  s.camera.nearZ = 0.05f;
  return s;
}

const TechniqueParams kSmallPages = {{"effective_resolution", "8192"}, {"page_size", "32"}, {"pool_pages", "24"}, {"resident_levels", "2"}, {"iterations", "8"}};

struct Converged {
  std::vector<uint32_t> pages;
  std::vector<uint8_t> image;
  tech::AsmCounters first, last;
};

// Frames of one view until a frame renders no page (at most 4).
Converged RenderUntilConverged(Device& device, const scene::Scene& s, TechniqueParams params, uint32_t w, uint32_t h) {
  auto r = MakeTechniqueRenderer(device, "asm", s, w, h, params);
  Converged c;
  for (int frame = 0; frame < 4; ++frame) {
    r->RenderFrame(s.camera, s.light);
    c.last = Source(*r).AsmFrameCounters();
    if (frame == 0) c.first = c.last;
    if (frame > 0 && c.last.pagesRendered == 0) break;
  }
  c.pages = Source(*r).AsmResidentPages();
  c.image = r->ReadColor();
  return c;
}

int DifferentPixels(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  int n = 0;
  for (size_t i = 0; i + 3 < a.size(); i += 4) n += a[i] != b[i] || a[i + 1] != b[i + 1] || a[i + 2] != b[i + 2];
  return n;
}

TEST_P(AsmGpuAllocationTest, SamePageSetAndPictureAsReadbackOnAStaticView) {
  const uint32_t W = 160, H = 96;
  scene::Scene s = ObliqueBox();
  for (const char* mark : {"edges", "visible"}) {
    SCOPED_TRACE(mark);
    TechniqueParams p = kSmallPages;
    p["mark"] = mark;
    p["allocation"] = "readback";
    Converged readback = RenderUntilConverged(device(), s, p, W, H);
    p["allocation"] = "gpu";
    Converged gpu = RenderUntilConverged(device(), s, p, W, H);
    EXPECT_EQ(readback.last.unserved, 0u);
    EXPECT_EQ(gpu.last.unserved, 0u);
    EXPECT_GT(readback.pages.size(), 5u + 10u) << "the view must refine beyond the 5 pinned pages";
    EXPECT_EQ(gpu.pages, readback.pages) << "resident pages differ";
    // The same refinement, step for step: the GPU's early exit stops where the CPU's loop does.
    EXPECT_EQ(gpu.first.iterations, readback.first.iterations);
    EXPECT_EQ(gpu.first.requests, readback.first.requests);
    EXPECT_EQ(gpu.first.pagesRendered, readback.first.pagesRendered);
    EXPECT_EQ(gpu.last.iterations, 1u);
    size_t levels[16] = {};
    for (uint32_t k : gpu.pages) ++levels[k >> 28];
    std::printf("asm %s: frame 0: %u iterations, %u requests, %u pages (readback %u, %u, %u); %zu resident pages (readback %zu); by level:", mark,
                gpu.first.iterations, gpu.first.requests, gpu.first.pagesRendered, readback.first.iterations, readback.first.requests,
                readback.first.pagesRendered, gpu.pages.size(), readback.pages.size());
    for (int l = 0; l < 9; ++l) std::printf(" %zu", levels[l]);
    int diff = DifferentPixels(gpu.image, readback.image);
    std::printf("; %d pixels differ\n", diff);
    EXPECT_EQ(diff, 0);
    if (diff) {
      WritePng(TestOutputDir() / (std::string("gpu-") + mark + ".png"), W, H, gpu.image.data());
      WritePng(TestOutputDir() / (std::string("readback-") + mark + ".png"), W, H, readback.image.data());
    }
  }
}

// compaction=prefix (the paper's stream compaction by a prefix sum) against the append buffer:
// the same requests, so the same pages and picture, in both modes and for either marking.
TEST_P(AsmGpuAllocationTest, PrefixSumCompactionRequestsWhatTheAppendBufferDoes) {
  const uint32_t W = 160, H = 96;
  scene::Scene s = ObliqueBox();
  for (const char* allocation : {"readback", "gpu"})
    for (const char* mark : {"edges", "visible"}) {
      SCOPED_TRACE(std::string(allocation) + " " + mark);
      TechniqueParams p = kSmallPages;
      p["allocation"] = allocation;
      p["mark"] = mark;
      Converged append = RenderUntilConverged(device(), s, p, W, H);
      p["compaction"] = "prefix";
      Converged prefix = RenderUntilConverged(device(), s, p, W, H);
      EXPECT_GT(prefix.first.requests, 10u);
      EXPECT_EQ(prefix.first.requests, append.first.requests);
      EXPECT_EQ(prefix.first.pagesRendered, append.first.pagesRendered);
      EXPECT_EQ(prefix.pages, append.pages);
      EXPECT_EQ(DifferentPixels(prefix.image, append.image), 0);
      std::printf("asm %s %s: prefix compaction %u requests, %zu pages (append %u, %zu)\n", allocation, mark, prefix.first.requests,
                  prefix.pages.size(), append.first.requests, append.pages.size());
    }
}

// clipmap=4: level L is refined only within the 4 x 4 pages around the camera's page at that level
// (one more page around it for the filter footprint's neighbours with mark=visible), so far
// receivers use coarser pages than they ask for; the pages stay correct (the floating box's
// shadow), and both modes still agree.
TEST_P(AsmGpuAllocationTest, ClipmapRefinesEachLevelOnlyAroundTheCamera) {
  const uint32_t W = 160, H = 96;
  scene::Scene s = ObliqueBox();
  glm::mat4 fit = tech::FitOrthoToBounds(s.bounds, s.light.direction).viewProj;
  glm::vec4 eye = fit * glm::vec4(s.camera.position, 1.0f);
  glm::vec2 cameraUV(eye.x / eye.w * 0.5f + 0.5f, 0.5f - eye.y / eye.w * 0.5f);
  TechniqueParams p = kSmallPages;
  p["mark"] = "visible";
  Converged full = RenderUntilConverged(device(), s, p, W, H);
  p["clipmap"] = "4";
  Converged readback = RenderUntilConverged(device(), s, p, W, H);
  p["allocation"] = "gpu";
  Converged gpu = RenderUntilConverged(device(), s, p, W, H);
  EXPECT_EQ(gpu.pages, readback.pages);
  EXPECT_EQ(DifferentPixels(gpu.image, readback.image), 0);
  int outside = 0, fine = 0;
  for (uint32_t k : gpu.pages) {
    uint32_t level = k >> 28, x = k & 0x3fffu, y = (k >> 14) & 0x3fffu;
    if (level < 2) continue;  // the resident levels
    ++fine;
    int n = 1 << level, cx = int(std::floor(cameraUV.x * n)), cy = int(std::floor(cameraUV.y * n));
    int dx = int(x) - cx, dy = int(y) - cy;
    outside += dx < -2 - 1 || dx > 1 + 1 || dy < -2 - 1 || dy > 1 + 1;
  }
  EXPECT_GT(fine, 5);
  EXPECT_EQ(outside, 0) << "pages beyond their level's window (plus the footprint's margin)";
  EXPECT_LT(gpu.pages.size(), full.pages.size()) << "the windows must leave out some of the pages the view asks for";
  std::printf("asm clipmap 4: %zu resident pages (%d refined, %d outside the windows), without: %zu\n", gpu.pages.size(), fine, outside,
              full.pages.size());
  // Correct, coarser shadows: the floating box seen from above, clipped.
  scene::Scene top = FloatingBox(false);
  TechniqueParams q = {{"effective_resolution", "8192"}, {"page_size", "64"}, {"pool_pages", "16"}, {"resident_levels", "2"}, {"clipmap", "2"}};
  for (const char* allocation : {"readback", "gpu"}) {
    q["allocation"] = allocation;
    auto r = MakeTechniqueRenderer(device(), "asm", top, 128, 128, q);
    r->RenderFrame(top.camera, top.light);
    Comparison c = CompareWithAnalytic(r->ReadColor(), AnalyticFloor(top, 128, 128), 128, 128, 3);
    EXPECT_GT(c.shadow, 200) << allocation;
    EXPECT_EQ(c.wrong, 0) << allocation;
  }
}

// gpu_batch 3: at most three pages drawn per iteration, the rest asked for again by the next
// iteration's analysis; with enough iterations the same pages end resident.
TEST_P(AsmGpuAllocationTest, SmallBatchDefersPagesWithoutLosingThem) {
  const uint32_t W = 160, H = 96;
  scene::Scene s = ObliqueBox();
  TechniqueParams p = kSmallPages;
  p["allocation"] = "gpu";
  p["mark"] = "visible";
  Converged wide = RenderUntilConverged(device(), s, p, W, H);
  p["gpu_batch"] = "3";
  p["iterations"] = "64";
  auto r = MakeTechniqueRenderer(device(), "asm", s, W, H, p);
  r->RenderFrame(s.camera, s.light);
  tech::AsmCounters n = Source(*r).AsmFrameCounters();
  EXPECT_LE(n.pagesRendered - 5, 3u * n.iterations);
  EXPECT_LT(n.iterations, 64u) << "the iterations after the last page must not run";
  EXPECT_EQ(n.unserved, 0u);
  std::vector<uint32_t> pages = Source(*r).AsmResidentPages();
  EXPECT_EQ(pages, wide.pages);
  std::printf("asm gpu_batch 3: %u pages rendered in %u iterations, %zu resident (batch 64: %zu)\n", n.pagesRendered, n.iterations, pages.size(),
              wide.pages.size());
}

// Pages stay resident across frames (the second frame of a view draws none); a new light
// direction invalidates every page, and the shadow follows the new light.
TEST_P(AsmGpuAllocationTest, PagesAreCachedUntilTheLightMoves) {
  const uint32_t W = 128, H = 128;
  scene::Scene s = FloatingBox(false);
  TechniqueParams p = kSmallPages;
  p["allocation"] = "gpu";
  auto r = MakeTechniqueRenderer(device(), "asm", s, W, H, p);
  r->RenderFrame(s.camera, s.light);
  tech::AsmCounters first = Source(*r).AsmFrameCounters();
  r->RenderFrame(s.camera, s.light);
  tech::AsmCounters second = Source(*r).AsmFrameCounters();
  EXPECT_GT(first.pagesRendered, 5u);
  EXPECT_EQ(second.pagesRendered, 0u);
  EXPECT_EQ(second.resident, first.resident);
  s.light.direction = glm::normalize(glm::vec3(1.0f, -1.5f, 0.3f));
  r->RenderFrame(s.camera, s.light);
  tech::AsmCounters moved = Source(*r).AsmFrameCounters();
  EXPECT_GT(moved.pagesRendered, 5u) << "the pinned pages and the new edge's pages are drawn again";
  Comparison c = CompareWithAnalytic(r->ReadColor(), AnalyticFloor(s, W, H), W, H, 2);
  EXPECT_GT(c.shadow, 200);
  EXPECT_EQ(c.wrong, 0) << "the shadow must follow the moved light";
  std::printf("asm gpu caching: %u pages, then %u, after the light moved %u (%d checked, %d wrong)\n", first.pagesRendered, second.pagesRendered,
              moved.pagesRendered, c.checked, c.wrong);
}

SP_INSTANTIATE_BACKEND_TESTS(AsmGpuAllocationTest);

// Two close-ups of the shadow's two edges, alternated, with a pool of 25 pages for 5 pinned and
// more than 20 wanted: every frame evicts. Which pages go must not depend on the order in which
// the GPU's atomics and appends happened to run, which differs between lavapipe and llvmpipe:
// the same pages, counters and pictures on both backends, in both modes.
TEST(AsmCrossBackend, FullPoolEvictsTheSamePagesOnBothBackends) {
  const uint32_t W = 128, H = 128;
  scene::Scene s = FloatingBox(false);
  scene::Camera views[2];
  for (int v = 0; v < 2; ++v) {
    float x = v == 0 ? -1.0f : 3.0f;
    views[v].position = {x, 1.5f, 0.001f};
    views[v].target = {x, 0.0f, 0.0f};
    views[v].up = {0.0f, 0.0f, -1.0f};
    views[v].fovY = glm::radians(50.0f);
    views[v].nearZ = 0.5f;
    views[v].farZ = 10.0f;
  }
  for (const char* allocation : {"readback", "gpu"}) {
    SCOPED_TRACE(allocation);
    TechniqueParams p = {{"effective_resolution", "8192"}, {"page_size", "32"}, {"pool_pages", "5"}, {"resident_levels", "2"}, {"mark", "visible"},
                         {"allocation", allocation}};
    struct Trace {
      std::vector<std::vector<uint32_t>> pages;
      std::vector<uint32_t> rendered, evicted;
      std::vector<uint8_t> image;
      bool llvmpipe = false;
    } trace[2];
    const Backend backends[2] = {Backend::Vulkan, Backend::OpenGL};
    for (int b = 0; b < 2; ++b) {
      DeviceDesc dd;
      dd.backend = backends[b];
      Ref<Device> dev = CreateDevice(dd);
      trace[b].llvmpipe = dev->Info().deviceName.find("llvmpipe") != std::string::npos;
      auto r = MakeTechniqueRenderer(*dev, "asm", s, W, H, p);
      for (int frame = 0; frame < 6; ++frame) {
        r->RenderFrame(views[frame % 2], s.light);
        tech::AsmCounters n = Source(*r).AsmFrameCounters();
        trace[b].rendered.push_back(n.pagesRendered);
        trace[b].evicted.push_back(n.evicted);
        trace[b].pages.push_back(Source(*r).AsmResidentPages());
      }
      trace[b].image = r->ReadColor();
      EXPECT_EQ(dev->ValidationErrorCount(), 0u) << BackendName(backends[b]) << ": " << dev->LastValidationError();
    }
    uint32_t evictions = 0;
    for (uint32_t e : trace[0].evicted) evictions += e;
    EXPECT_GT(evictions, 10u) << "the views must compete for the pool";
    std::printf("asm %s full pool, pages rendered per frame:", allocation);
    for (uint32_t n : trace[0].rendered) std::printf(" %u", n);
    std::printf(" (vulkan), evicted %u in all\n", evictions);
    if (!(trace[0].llvmpipe && trace[1].llvmpipe)) continue;  // the equality is Mesa's (same rasterizer)
    EXPECT_EQ(trace[0].rendered, trace[1].rendered);
    EXPECT_EQ(trace[0].evicted, trace[1].evicted);
    EXPECT_EQ(trace[0].pages, trace[1].pages) << "resident pages differ between the backends";
    EXPECT_EQ(DifferentPixels(trace[0].image, trace[1].image), 0);
  }
}

}  // namespace
}  // namespace sp::test
