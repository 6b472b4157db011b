// The bench runner end to end: a run gives the same metric values on both backends (exactly, on
// Mesa), passes validation, fills every results field; flicker is zero for a static camera, zero
// for the basic technique on the slow pan (its map is fitted to the scene, not the view, so it
// does not move) and positive for a map fitted to the view without texel snapping, which slides
// under the pan and makes shadow edges crawl.
#include <gtest/gtest.h>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>

#include "backend-test.h"
#include "bench.h"

namespace sp::test {
namespace {

// A map fitted around the camera's look-at point (half the scene's size across), moved with the
// camera without snapping to whole texels: the textbook source of shimmering shadow edges. It
// reuses the basic technique's lighting include.
class ViewFitTechnique final : public tech::Technique {
 public:
  std::string Name() const override { return "test-view-fit"; }
  std::vector<tech::ParamSpec> Params() const override {
    return {{tech::ParamSpec::Int, "resolution", "shadow map size", "512", 16, 4096, {}}};
  }
  void Configure(Device& device, const tech::ParamValues& p) override {
    size_ = uint32_t(p.getInt("resolution"));
    map_ = tech::MakeDepthMap(device, size_, size_, "view-fitted shadow map");
    RASTERIZER_DESC rd;
    rd.FrontCounterClockwise = true;
    rd.DepthBias = 200;
    rd.SlopeScaledDepthBias = 2.0f;
    rd.DepthClipEnable = false;
    rasterizer_ = device.CreateRasterizerState(rd);
    // basic's lit shader reads the map as a one-slice Texture2DArray.
    array_ = tech::MakeSliceArraySrv(device, map_.texture.get());
    sampler_ = tech::MakeShadowComparisonSampler(device);
    constants_ = tech::MakeConstantBuffer(device, sizeof(Constants), "view-fitted shadow constants");
  }
  void RenderShadows(DeviceContext& ctx, tech::SceneDrawer& drawer, const tech::FrameInputs& f) override {
    tech::GpuTimer::Scope timed(f.timer, ctx, "shadow");
    glm::vec3 dir = glm::normalize(f.light.direction);
    glm::vec3 center = f.camera.target;
    float radius = glm::length(f.scene->bounds.extent()) * 0.25f;
    glm::mat4 view = glm::lookAtRH(center - dir * radius, center, glm::vec3(0, 1, 0));
    scene::Bounds ls = f.scene->bounds.transformed(view);
    glm::mat4 viewProj = glm::orthoRH_ZO(-radius, radius, -radius, radius, -ls.max.z, -ls.min.z) * view;
    Constants c{viewProj, glm::vec2(float(size_)), glm::vec2(0.0f), {}};
    ctx.UpdateSubresource(constants_.get(), 0, nullptr, &c, 0, 0);
    ShaderResourceView* none = nullptr;
    ctx.PSSetShaderResources(0, 1, &none);
    ctx.OMSetRenderTargets(0, nullptr, map_.dsv.get());
    ctx.ClearDepthStencilView(map_.dsv.get(), CLEAR_DEPTH, 1.0f, 0);
    VIEWPORT vp{0, 0, float(size_), float(size_), 0, 1};
    ctx.RSSetViewports(1, &vp);
    ctx.RSSetState(rasterizer_.get());
    ctx.OMSetDepthStencilState(nullptr, 0);
    triangles_ = drawer.DrawDepth(ctx, viewProj);
  }
  std::string LightingInclude() const override { return "basic/shadow.hlsli"; }
  void BindLighting(DeviceContext& ctx) override {
    ctx.PSSetConstantBuffers(2, {constants_.get()});
    ctx.PSSetShaderResources(0, {array_.get()});
    ctx.PSSetSamplers(0, {sampler_.get()});
  }
  tech::ShadowStats Stats() const override { return {uint64_t(size_) * size_ * 4, triangles_}; }
  std::vector<tech::ShadowLayer> Layers() const override { return {{size_, size_}}; }

 private:
  // basic's cbuffer BasicShadow: the matrix and map size this technique sets, then basic's filter
  // and shaft settings, left zero (its defines select neither). Room to spare, so basic can grow.
  struct Constants {
    glm::mat4 m;
    glm::vec2 size, pad;
    float rest[44];
  };
  static_assert(sizeof(Constants) == 256);

  uint32_t size_ = 0;
  tech::DepthMap map_;
  Ref<ShaderResourceView> array_;
  Ref<RasterizerState> rasterizer_;
  Ref<SamplerState> sampler_;
  Ref<Buffer> constants_;
  uint64_t triangles_ = 0;
};

std::filesystem::path CacheDir() { return std::filesystem::path(SHADOWPORT_TEST_OUTPUT_DIR) / "reference-cache"; }

bench::RunSpec Spec(const scene::Scene& s, const scene::CameraPath* path, Backend backend, bool viewFit = false) {
  bench::RunSpec spec;
  spec.scene = &s;
  spec.technique = "basic";
  if (viewFit) spec.make = [] { return std::make_unique<ViewFitTechnique>(); };
  spec.params = viewFit ? std::map<std::string, std::string>{} : std::map<std::string, std::string>{{"resolution", "1024"}};
  spec.backend = backend;
  spec.width = 160;
  spec.height = 90;
  spec.frames = 3;
  spec.path = path;
  return spec;
}

// Both backends run on Mesa's shared rasterizer and render bit-identical images (the toolchain
// fixes the order of arithmetic, rhi/src/hlsl/spirv-arith.cpp), so every metric computed from the
// images must be equal, to the last bit. Elsewhere sub-pixel precision and filter weights may
// differ on shadow edges: about 0.5% of pixels (tests/techniques/basic-technique-test.cpp), which
// bounds the accuracy and density figures' difference; the tolerances below allow that.
TEST(BenchCrossBackend, MetricsAreIdenticalOnBothBackendsAndValidationIsClean) {
  scene::Scene s = scene::MakeBuiltinScene("default");
  eval::ReferenceCache cache(s, CacheDir());
  bench::RunResult r[2];
  const Backend backends[2] = {Backend::Vulkan, Backend::OpenGL};
  for (int i = 0; i < 2; ++i) {
    bench::RunSpec spec = Spec(s, &s.cameraPath("slow-pan"), backends[i]);
    spec.validate = true;
    r[i] = bench::RunOne(spec, cache);
    EXPECT_EQ(r[i].validationErrors, 0u) << BackendName(backends[i]);
  }
  EXPECT_GT(r[0].accuracy.receiving, 160u * 90u * 3u / 2u);
  EXPECT_GT(r[0].texelsPerPixelMedian, 0.0);
  EXPECT_GT(r[0].utilization, 0.0);
  EXPECT_EQ(r[0].flicker.unmatched, 0u) << "the same camera drawn twice must give the same surface points";
  EXPECT_EQ(r[1].flicker.unmatched, 0u);
  bool mesa = r[0].device.find("llvmpipe") != std::string::npos && r[1].device.find("llvmpipe") != std::string::npos;
  if (mesa) {
    EXPECT_EQ(r[0].accuracy.receiving, r[1].accuracy.receiving);
    EXPECT_EQ(r[0].accuracy.falseLit, r[1].accuracy.falseLit);
    EXPECT_EQ(r[0].accuracy.falseShadow, r[1].accuracy.falseShadow);
    EXPECT_EQ(r[0].accuracy.absErrorSum, r[1].accuracy.absErrorSum);
    EXPECT_EQ(r[0].texelsPerPixelMedian, r[1].texelsPerPixelMedian);
    EXPECT_EQ(r[0].texelsPerPixelP05, r[1].texelsPerPixelP05);
    EXPECT_EQ(r[0].utilization, r[1].utilization);
    EXPECT_EQ(r[0].flicker.sum, r[1].flicker.sum);
    EXPECT_EQ(r[0].flickerReprojected.sum, r[1].flickerReprojected.sum);
    EXPECT_EQ(r[0].flickerReprojectedReference.sum, r[1].flickerReprojectedReference.sum);
  } else {
    EXPECT_NEAR(r[0].accuracy.misclassifiedPct(), r[1].accuracy.misclassifiedPct(), 0.5);
    EXPECT_NEAR(r[0].texelsPerPixelMedian, r[1].texelsPerPixelMedian, 0.01 * r[0].texelsPerPixelMedian);
    EXPECT_NEAR(r[0].utilization, r[1].utilization, 0.01 * r[0].utilization);
  }
  EXPECT_EQ(r[0].shadowMemoryBytes, r[1].shadowMemoryBytes);
  EXPECT_EQ(r[0].shadowTriangles, r[1].shadowTriangles);
  for (const bench::RunResult& x : r) {
    EXPECT_GT(x.gpuMs.count("shadow"), 0u);
    EXPECT_GT(x.gpuMs.count("lit"), 0u);
    EXPECT_GT(x.gpuMs.at("total"), 0.0);
    EXPECT_GT(x.cpuMs, 0.0);
  }

  nlohmann::json j = bench::RunToJson(r[0], {{"color", "x.png"}});
  for (const char* k : {"scene", "technique", "params", "backend", "size", "frames", "device", "metrics", "series", "images"})
    EXPECT_TRUE(j.contains(k)) << k;
  for (const char* k : {"misclassified_pct", "false_lit_pct", "false_shadow_pct", "mean_abs_error", "texels_per_pixel_median",
                        "texels_per_pixel_p05", "max_aliasing_error", "storage_factor", "utilization", "flicker", "gpu_ms", "cpu_ms", "shadow_memory_bytes", "shadow_triangles"})
    EXPECT_TRUE(j["metrics"].contains(k)) << k;
  EXPECT_TRUE(j["metrics"]["gpu_ms"].contains("total"));
  EXPECT_EQ(j["params"]["resolution"], "1024");
  EXPECT_EQ(j["params"]["depth_bias"], "200") << "defaults are recorded too";
}

// An accelerated filter's decisions are recorded (fractions summing to 1), and only for it, on
// both backends.
TEST(BenchHpsm, RecordsTheDecisionFractionsOfAnAcceleratedFilter) {
  scene::Scene s = scene::MakeBuiltinScene("default");
  eval::ReferenceCache cache(s, CacheDir());
  for (Backend backend : {Backend::Vulkan, Backend::OpenGL}) {
    bench::RunSpec spec = Spec(s, nullptr, backend);
    spec.frames = 2;
    spec.validate = true;
    spec.params = {{"resolution", "1024"}, {"filter", "box"}, {"kernel", "5"}, {"slope_bias", "6"}, {"accel", "hpsm"}};
    bench::RunResult r = bench::RunOne(spec, cache);
    EXPECT_EQ(r.validationErrors, 0u) << BackendName(backend);
    ASSERT_EQ(r.hpsmDecisions.size(), 3u) << BackendName(backend);
    EXPECT_NEAR(r.hpsmDecisions["minmax"] + r.hpsmDecisions["plane"] + r.hpsmDecisions["filtered"], 1.0, 1e-9);
    EXPECT_GT(r.hpsmDecisions["plane"], 0.5) << "the default scene's floor is planar";
    EXPECT_TRUE(bench::RunToJson(r, {})["metrics"].contains("hpsm_decisions"));
    spec.params["accel"] = "none";
    bench::RunResult plain = bench::RunOne(spec, cache);
    EXPECT_TRUE(plain.hpsmDecisions.empty());
    EXPECT_FALSE(bench::RunToJson(plain, {})["metrics"].contains("hpsm_decisions"));
  }
}
// Adaptive shadow maps record each frame's refinement: on a static view the first frame renders
// pages and a later one renders none (converged), with nothing unserved in the default pool; other
// techniques record nothing. Both backends give the same counts.
TEST(BenchAsm, RecordsTheRefinementOfEveryFrame) {
  scene::Scene s = scene::MakeBuiltinScene("default");
  eval::ReferenceCache cache(s, CacheDir());
  std::vector<std::vector<tech::AsmCounters>> perBackend;
  for (Backend backend : {Backend::Vulkan, Backend::OpenGL}) {
    bench::RunSpec spec = Spec(s, nullptr, backend);  // no path: the scene camera, still
    spec.technique = "asm";
    spec.params = {};
    spec.validate = true;
    bench::RunResult r = bench::RunOne(spec, cache);
    EXPECT_EQ(r.validationErrors, 0u) << BackendName(backend);
    ASSERT_EQ(r.asmRefinement.size(), size_t(spec.frames)) << BackendName(backend);
    EXPECT_GT(r.asmRefinement[0].pagesRendered, 0u) << "the first frame refines";
    EXPECT_EQ(r.asmRefinement.back().pagesRendered, 0u) << "a static view converges";
    nlohmann::json a = bench::RunToJson(r, {})["metrics"]["asm_refinement"];
    ASSERT_TRUE(a.is_object());
    EXPECT_EQ(a["frames"].size(), size_t(spec.frames));
    EXPECT_GE(a["converged_frame"].get<int>(), 1);
    EXPECT_EQ(a["unserved_total"].get<uint64_t>(), 0u);
    perBackend.push_back(r.asmRefinement);
  }
  for (size_t i = 0; i < perBackend[0].size(); ++i) {
    EXPECT_EQ(perBackend[0][i].requests, perBackend[1][i].requests) << "frame " << i;
    EXPECT_EQ(perBackend[0][i].pagesRendered, perBackend[1][i].pagesRendered) << "frame " << i;
  }
  bench::RunResult basic = bench::RunOne(Spec(s, nullptr, Backend::Vulkan), cache);
  EXPECT_TRUE(basic.asmRefinement.empty());
  EXPECT_FALSE(bench::RunToJson(basic, {})["metrics"].contains("asm_refinement"));
}

class BenchFlicker : public ::testing::TestWithParam<Backend> {};

TEST_P(BenchFlicker, StaticCameraGivesZero) {
  scene::Scene s = scene::MakeBuiltinScene("default");
  eval::ReferenceCache cache(s, CacheDir());
  for (bool viewFit : {false, true}) {
    bench::RunResult r = bench::RunOne(Spec(s, nullptr, GetParam(), viewFit), cache);
    EXPECT_GT(r.flicker.pixels, 0u);
    EXPECT_EQ(r.flicker.sum, 0.0) << r.technique;
    EXPECT_EQ(r.flickerReprojected.sum, 0.0) << r.technique;
    EXPECT_EQ(r.flickerReprojectedReference.sum, 0.0) << r.technique;
  }
}

TEST_P(BenchFlicker, SlowPanMovesAViewFittedMapButNotTheSceneFittedOne) {
  scene::Scene s = scene::MakeBuiltinScene("default");
  eval::ReferenceCache cache(s, CacheDir());
  const scene::CameraPath& pan = s.cameraPath("slow-pan");
  bench::RunResult basic = bench::RunOne(Spec(s, &pan, GetParam()), cache);
  bench::RunResult viewFit = bench::RunOne(Spec(s, &pan, GetParam(), true), cache);
  // Exactly the same world points: the reference is zero by construction, and so is the basic
  // technique, whose map does not depend on the camera.
  EXPECT_GT(basic.flicker.pixels, 0u);
  EXPECT_EQ(basic.flicker.sum, 0.0);
  EXPECT_GT(viewFit.flicker.mean(), 1e-4);
  // Reprojection compares points up to half a pixel apart, so even the reference changes near
  // edges: its value is the method's noise floor, and the world-stable basic technique stays
  // near it while the sliding map rises above it.
  double floor = basic.flickerReprojectedReference.mean();
  EXPECT_GT(floor, 0.0);
  EXPECT_LT(basic.flickerReprojected.mean(), 2.0 * floor);
  EXPECT_GT(viewFit.flickerReprojected.mean(), basic.flickerReprojected.mean());
}

INSTANTIATE_TEST_SUITE_P(Backends, BenchFlicker, ::testing::Values(Backend::Vulkan, Backend::OpenGL), BackendParamName);

}  // namespace
}  // namespace sp::test
