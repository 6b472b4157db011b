// Adaptive shadow maps (technique asm) end to end, on both backends and in both allocation modes
// (readback: the paper's; gpu: no readback): the shadow of the floating box matches the analytic
// shadow; a shadow edge seen up close is as sharp as a map of the effective resolution gives (and
// basic at 2048 is measurably blurrier); a small pool serves what it can and counts the rest;
// impossible parameters are refused naming the parameter.
#include <cmath>
#include <cstdio>
#include <glm/ext/matrix_transform.hpp>

#include "backend-test.h"
#include "floating-box.h"
#include "technique-renderer.h"
#include <sp/tech/asm-counters.h>
#include "metrics.h"
#include "reference.h"
#include <sp/tech/renderer.h>

namespace sp::test {
namespace {

class AsmTechniqueTest : public BackendTest {};

tech::AsmCounters CountersOf(tech::Renderer& r) { return dynamic_cast<tech::AsmCounterSource&>(r.technique()).AsmFrameCounters(); }

const char* const kAllocations[] = {"readback", "gpu"};

TechniqueParams With(TechniqueParams p, const char* allocation) {
  p["allocation"] = allocation;
  return p;
}

TEST_P(AsmTechniqueTest, ShadowMatchesAnalyticShadowOfAFloatingBox) {
  for (const char* allocation : kAllocations) {
    SCOPED_TRACE(allocation);
    const uint32_t W = 128, H = 128;
    scene::Scene s = FloatingBox(false);
    auto r = MakeTechniqueRenderer(device(), "asm", s, W, H,
                                   With({{"effective_resolution", "8192"}, {"page_size", "64"}, {"pool_pages", "16"}, {"resident_levels", "2"}}, allocation));
    r->RenderFrame(s.camera, s.light);
    std::vector<uint8_t> img = r->ReadColor();
    Comparison c = CompareWithAnalytic(img, AnalyticFloor(s, W, H), W, H, 2);
    EXPECT_GT(c.checked, int(W * H / 2));
    EXPECT_GT(c.shadow, 200);
    EXPECT_EQ(c.wrong, 0) << "pixels whose shadowing differs from the analytic answer";
    if (c.wrong) WritePng(TestOutputDir() / "floating-box.png", W, H, img.data());
    tech::AsmCounters n = CountersOf(*r);
    EXPECT_GT(n.requests, 0u) << "the shadow's boundary must request pages";
    EXPECT_GT(n.pagesRendered, 5u) << "more than the resident levels 0 and 1 (5 pages)";
    EXPECT_EQ(n.unserved, 0u);
    EXPECT_EQ(n.resident, n.pagesRendered);
    // The same view again: every page it needs is resident, one analysis finds nothing new (the
    // GPU mode records its other iterations, but they find nothing to run).
    r->RenderFrame(s.camera, s.light);
    tech::AsmCounters again = CountersOf(*r);
    EXPECT_EQ(again.pagesRendered, 0u);
    EXPECT_EQ(again.iterations, 1u);
    EXPECT_EQ(again.resident, n.resident);
    EXPECT_EQ(CompareWithAnalytic(r->ReadColor(), AnalyticFloor(s, W, H), W, H, 2).wrong, 0);
  }
}

// Pixels of the middle row strictly inside the shadow edge's ramp (10% to 90% of the way from
// shadow to lit, in linear intensity), camera centred on the edge.
int EdgeRampPixels(const std::vector<uint8_t>& img, uint32_t w, uint32_t h) {
  auto linear = [&](uint32_t x) {
    float s = img[((h / 2) * w + x) * 4 + 1] / 255.0f;
    return std::pow((s + 0.055f) / 1.055f, 2.4f);
  };
  float lo = 1e9f, hi = -1e9f;
  for (uint32_t x = 0; x < w; ++x) lo = std::min(lo, linear(x)), hi = std::max(hi, linear(x));
  EXPECT_GT(hi - lo, 0.3f) << "the row must cross the shadow edge";
  int ramp = 0;
  for (uint32_t x = 0; x < w; ++x) {
    float v = (linear(x) - lo) / (hi - lo);
    ramp += v > 0.1f && v < 0.9f;
  }
  return ramp;
}

// The floating box's shadow edge at x = -1 (cast by the box's lower edge at x = -3, y = 2, the
// light going +x and down at 45 degrees), seen from 8 cm above the floor. A map of texel size t
// (light space) filtered by the 2x2 comparison filter has a linear ramp 1 texel wide, which on
// the floor is sqrt(2) t along x: 10%..90% is 0.8 sqrt(2) t.
TEST_P(AsmTechniqueTest, ShadowEdgeIsAsSharpAsTheEffectiveResolution) {
  const uint32_t W = 128, H = 64;
  scene::Scene s = FloatingBox(false);
  scene::Camera cam;
  cam.position = {-1.0f, 0.08f, 0.0001f};
  cam.target = {-1.0f, 0.0f, 0.0f};
  cam.up = {0.0f, 0.0f, -1.0f};
  cam.fovY = glm::radians(50.0f);
  cam.nearZ = 0.01f;
  cam.farZ = 10.0f;
  // The light's view as the techniques fit it: its y axis runs along the floor's x here.
  glm::vec3 dir = glm::normalize(s.light.direction);
  glm::mat4 view = glm::lookAtRH(s.bounds.center() - dir * glm::length(s.bounds.extent()) * 0.5f, s.bounds.center(), glm::vec3(0, 1, 0));
  scene::Bounds ls = s.bounds.transformed(view);
  float extent = ls.max.y - ls.min.y;
  float pixel = 2.0f * cam.nearZ * std::tan(cam.fovY / 2) * (float(W) / H) / W * (cam.position.y / cam.nearZ);  // floor units per pixel
  auto expectedRamp = [&](float resolution) { return 0.8f * std::sqrt(2.0f) * extent / resolution / pixel; };

  for (const char* allocation : kAllocations) {
    SCOPED_TRACE(allocation);
    auto a = MakeTechniqueRenderer(device(), "asm", s, W, H,
                                   With({{"effective_resolution", "32768"}, {"page_size", "128"}, {"pool_pages", "8"}, {"resident_levels", "2"}, {"edge_threshold", "0.02"}},
                                        allocation));
    a->RenderFrame(cam, s.light);
    std::vector<uint8_t> asmImg = a->ReadColor();
    auto b = MakeTechniqueRenderer(device(), "basic", s, W, H, {{"resolution", "2048"}});
    b->RenderFrame(cam, s.light);
    std::vector<uint8_t> basicImg = b->ReadColor();
    // The same pages at a lower effective resolution: the edge must be as blurred as that map's.
    auto c = MakeTechniqueRenderer(device(), "asm", s, W, H,
                                   With({{"effective_resolution", "4096"}, {"page_size", "128"}, {"pool_pages", "8"}, {"resident_levels", "2"}, {"edge_threshold", "0.02"}},
                                        allocation));
    c->RenderFrame(cam, s.light);
    std::vector<uint8_t> coarseImg = c->ReadColor();
    int asmRamp = EdgeRampPixels(asmImg, W, H), basicRamp = EdgeRampPixels(basicImg, W, H), coarseRamp = EdgeRampPixels(coarseImg, W, H);
    float asmExpected = expectedRamp(32768.0f), basicExpected = expectedRamp(2048.0f), coarseExpected = expectedRamp(4096.0f);
    EXPECT_GE(coarseRamp, int(std::floor(coarseExpected)) - 1) << "expected " << coarseExpected << " px for effective resolution 4096";
    EXPECT_LE(coarseRamp, int(std::ceil(coarseExpected)) + 1) << "expected " << coarseExpected << " px for effective resolution 4096";
    // Sampling a ramp of width w at pixel centres gives between floor(w) and ceil(w) + 1 pixels inside.
    EXPECT_LE(asmRamp, int(std::ceil(asmExpected)) + 1) << "expected " << asmExpected << " px for effective resolution 32768";
    EXPECT_GE(basicRamp, int(std::floor(basicExpected)) - 1) << "expected " << basicExpected << " px for basic at 2048";
    EXPECT_LE(basicRamp, int(std::ceil(basicExpected)) + 1) << "expected " << basicExpected << " px for basic at 2048";
    EXPECT_GE(basicRamp, 3 * std::max(asmRamp, 1));
    EXPECT_EQ(CountersOf(*a).unserved, 0u);
    std::printf("asm %s edge: ramp %d px (expected %.2f for 32768), asm 4096: %d px (expected %.2f), basic 2048: %d px (expected %.2f); %u pages, %u iterations\n",
                allocation, asmRamp, asmExpected, coarseRamp, coarseExpected, basicRamp, basicExpected, CountersOf(*a).pagesRendered, CountersOf(*a).iterations);
    if (HasFailure()) {
      WritePng(TestOutputDir() / "edge-asm.png", W, H, asmImg.data());
      WritePng(TestOutputDir() / "edge-basic.png", W, H, basicImg.data());
      WritePng(TestOutputDir() / "edge-asm-4096.png", W, H, coarseImg.data());
    }
  }
}

// A pool of 9 pages with 5 pinned cannot hold the edge's pages (level 3 of 32-texel pages): the
// rest are unserved, and the shadow still comes from the coarser resident levels (no hole, no
// wrong page), blurrier, hence the wider band.
TEST_P(AsmTechniqueTest, FullPoolCountsUnservedRequestsAndStillShadows) {
  for (const char* allocation : kAllocations) {
    SCOPED_TRACE(allocation);
    const uint32_t W = 128, H = 128;
    scene::Scene s = FloatingBox(false);
    auto r = MakeTechniqueRenderer(device(), "asm", s, W, H,
                                   With({{"effective_resolution", "8192"}, {"page_size", "32"}, {"pool_pages", "3"}, {"resident_levels", "2"}}, allocation));
    r->RenderFrame(s.camera, s.light);
    tech::AsmCounters n = CountersOf(*r);
    EXPECT_GT(n.unserved, 0u);
    EXPECT_EQ(n.resident, 9u);
    Comparison c = CompareWithAnalytic(r->ReadColor(), AnalyticFloor(s, W, H), W, H, 6);
    EXPECT_GT(c.shadow, 100);
    EXPECT_EQ(c.wrong, 0);
    std::printf("asm %s full pool: %u requests, %u unserved, %u resident; %d checked, %d wrong\n", allocation, n.requests, n.unserved, n.resident, c.checked,
                c.wrong);
  }
}

// Misclassification against the ray-traced reference on the built-in default scene, beside
// basic's at its default 2048: asm refines only where the analysis sees a shadow boundary, and a
// shadow the resident levels miss entirely stays missed (the paper's limitation); with the default
// four resident levels it must be within 0.1 percentage points of basic (with two it was 0.346 %
// against 0.122 %, which this bound refuses).
double Misclassified(Device& device, const scene::Scene& s, const std::string& technique, const TechniqueParams& params) {
  const uint32_t W = 160, H = 96;
  auto r = MakeTechniqueRenderer(device, technique, s, W, H, params, LabOptions(true));
  r->RenderFrame(s.camera, s.light, tech::LitPass::Lab);
  tech::LabBuffers lab = r->ReadLab();
  eval::ReferenceTracer tracer(s);
  eval::LabSurfacePoints p = eval::SurfacePointsOf(lab);
  std::vector<float> reference(lab.size(), 0.0f);
  tracer.Visibility(p.position.data(), p.normal.data(), p.valid.data(), p.size(), eval::ReferenceLight::FromScene(s.light), reference.data());
  return eval::MeasureAccuracy(lab, reference.data()).misclassifiedPct();
}

TEST_P(AsmTechniqueTest, MisclassificationAgainstTheReferenceIsSmall) {
  scene::Scene s = scene::MakeBuiltinScene("default");
  double basicPct = Misclassified(device(), s, "basic", {});
  for (const char* allocation : kAllocations) {
      double asmPct = Misclassified(device(), s, "asm", With({}, allocation));
      std::printf("default scene 160x96: asm %s misclassified %.3f %%, basic 2048 %.3f %%\n", allocation, asmPct, basicPct);
      EXPECT_LT(asmPct, 0.5) << allocation;
      EXPECT_LE(asmPct, basicPct + 0.1) << allocation;
  }
}

// Two close-ups of different parts of the shadow, alternated, with a pool too small for both:
// each view evicts the other's pages (LRU), and every frame still matches the analytic shadow, so
// an evicted page's table entry is gone before its pool slot holds another page.
TEST_P(AsmTechniqueTest, EvictedPagesLeaveTheTablesAcrossViews) {
  for (const char* allocation : kAllocations) {
    SCOPED_TRACE(allocation);
    const uint32_t W = 128, H = 128;
    scene::Scene s = FloatingBox(false);
    auto r = MakeTechniqueRenderer(device(), "asm", s, W, H,
                                   With({{"effective_resolution", "8192"}, {"page_size", "32"}, {"pool_pages", "5"}, {"resident_levels", "2"}}, allocation));
    scene::Camera views[2];
    for (int v = 0; v < 2; ++v) {
      float x = v == 0 ? -1.0f : 3.0f;  // the shadow's two edges across x
      views[v].position = {x, 1.5f, 0.001f};  // below the box (y 2..4), which stays out of view
      views[v].target = {x, 0.0f, 0.0f};
      views[v].up = {0.0f, 0.0f, -1.0f};
      views[v].fovY = glm::radians(50.0f);
      views[v].nearZ = 0.5f;
      views[v].farZ = 10.0f;
    }
    uint32_t evicted = 0;
    for (int frame = 0; frame < 4; ++frame) {
      s.camera = views[frame % 2];
      r->RenderFrame(s.camera, s.light);
      tech::AsmCounters n = CountersOf(*r);
      if (frame > 0) evicted += n.evicted;
      Comparison c = CompareWithAnalytic(r->ReadColor(), AnalyticFloor(s, W, H), W, H, 3);
      std::printf("asm %s views: frame %d: %u pages rendered, %u evicted, %u unserved, %u resident; %d checked, %d wrong\n", allocation, frame,
                  n.pagesRendered, n.evicted, n.unserved, n.resident, c.checked, c.wrong);
      EXPECT_GT(c.checked, int(W * H / 2));
      EXPECT_GT(c.shadow, 100);
      EXPECT_EQ(c.wrong, 0) << "frame " << frame;
      if (frame > 0) EXPECT_EQ(n.resident, 25u) << "the pool stays full once filled";
    }
    EXPECT_GT(evicted, 0u) << "the views must compete for the pool";
  }
}

TEST_P(AsmTechniqueTest, RefusesImpossibleParametersNamingThem) {
  ExpectConfigureRefused(device(), "asm", {{"page_size", "96"}}, "page_size");
  ExpectConfigureRefused(device(), "asm", {{"effective_resolution", "20000"}}, "effective_resolution");
  ExpectConfigureRefused(device(), "asm", {{"effective_resolution", "128"}, {"page_size", "64"}, {"resident_levels", "3"}}, "resident_levels");
  ExpectConfigureRefused(device(), "asm", {{"pool_pages", "9"}}, "pool_pages");  // 81 pages, the default 4 resident levels pin 85
  ExpectConfigureRefused(device(), "asm", {{"pool_pages", "2"}, {"resident_levels", "2"}}, "pool_pages");
  ExpectConfigureRefused(device(), "asm", {{"pool_pages", "200"}, {"page_size", "128"}}, "pool_pages");
  ExpectConfigureRefused(device(), "asm", {{"effective_resolution", "131072"}, {"page_size", "16"}}, "effective_resolution");
  ExpectConfigureRefused(device(), "asm", {{"allocation", "cpu"}}, "allocation");
  ExpectConfigureRefused(device(), "asm", {{"allocation", "gpu"}, {"gpu_batch", "0"}}, "gpu_batch");
}

SP_INSTANTIATE_BACKEND_TESTS(AsmTechniqueTest);

}  // namespace
}  // namespace sp::test
