// The sdsm technique on both backends: the floating box's shadow against the analytic one for every
// partition scheme and cull mode (readback, latent and gpu give the same image for a static
// camera); tight boxes are no larger than frustum slices; cull=gpu renders what cull=readback
// does, fits the same boxes and maps nothing back while rendering; quantize=1 keeps sizes powers of
// two and offsets on the world texel grid while the camera moves; every lit-shader variant
// compiles; bad values list the valid ones; the paper's Figures 2 and 4 as PNGs; and on
// terrain-city sdsm gives more texels per pixel than csm with the same cascades and resolution.
#include <cmath>
#include <cstdio>

#include "backend-test.h"
#include "technique-renderer.h"
#include "bench.h"
#include "floating-box.h"
#include <sp/tech/renderer.h>
#include "sdsm/sdsm-technique.h"

namespace sp::test {
namespace {

using tech::sdsm::PartitionFit;
using tech::sdsm::SdsmTechnique;
using Params = std::map<std::string, std::string>;

std::string Describe(const Params& p) {
  std::string s;
  for (const auto& [k, v] : p) s += k + "=" + v + " ";
  return s;
}

bool IsPowerOfTwo(float x) {
  int e;
  return std::frexp(x, &e) == 0.5f;
}

class SdsmTechniqueTest : public BackendTest {
 protected:
  std::unique_ptr<tech::Renderer> MakeRenderer(const scene::Scene& s, uint32_t w, uint32_t h, Params params, bool lab = false) {
    if (!params.count("resolution")) params["resolution"] = "512";
    return MakeTechniqueRenderer(device(), "sdsm", s, w, h, params, LabOptions(lab));
  }
  static SdsmTechnique& Sdsm(tech::Renderer& r) { return static_cast<SdsmTechnique&>(r.technique()); }
  std::vector<PartitionFit> Fits(tech::Renderer& r) {
    SdsmTechnique& t = Sdsm(r);
    return t.settings().cull == tech::sdsm::CullMode::Gpu ? t.ReadGpuFits(ctx()) : t.lastFits();
  }
};

// Three frames of a static camera: latent (latency 2) uses the first frame's results in the third.
// Conservative uses other (frustum-slice) maps, so only its shadow is checked, not its pixels.
TEST_P(SdsmTechniqueTest, EverySchemeAndCullModeShadowsTheFloatingBoxCorrectly) {
  const uint32_t W = 128, H = 128;
  scene::Scene s = FloatingBox(true);
  std::vector<int> expected = AnalyticFloor(s, W, H);
  for (const char* scheme : {"log", "adaptive-log", "kmeans"}) {
    std::vector<uint8_t> readbackImage;
    for (const char* cull : {"readback", "latent", "gpu", "conservative"}) {
      Params p = {{"partition", scheme}, {"cull", cull}};
      SCOPED_TRACE(Describe(p));
      std::unique_ptr<tech::Renderer> r = MakeRenderer(s, W, H, p);
      for (int i = 0; i < 3; ++i) r->RenderFrame(s.camera, s.light);
      std::vector<uint8_t> img = r->ReadColor();
      Comparison c = CompareWithAnalytic(img, expected, W, H, 2);
      EXPECT_GT(c.checked, int(W * H / 3));
      EXPECT_GT(c.shadow, 200);
      EXPECT_EQ(c.wrong, 0);
      if (c.wrong) WritePng(TestOutputDir() / (std::string(scheme) + "-" + cull + ".png"), W, H, img.data());
      const SdsmTechnique& t = Sdsm(*r);
      uint64_t readbacks = std::string(cull) == "readback" ? 3 : std::string(cull) == "latent" ? 1 : 0;
      EXPECT_EQ(t.frameReadbacks(), readbacks);
      if (std::string(cull) == "readback") {
        readbackImage = img;
      } else if (std::string(cull) != "conservative") {
        EXPECT_EQ(CompareImages(std::string(scheme) + "-" + cull + "-vs-readback", W, H, img.data(), readbackImage.data(), 0), 0u);
      }
    }
  }
}

// Per partition, the box of its samples lies inside its frustum slice, so with the same padding
// the tight map covers at most the slice's area; over all partitions strictly less.
TEST_P(SdsmTechniqueTest, TightBoxesAreNoLargerThanFrustumSlices) {
  scene::Scene s = FloatingBox(true);
  for (const char* cull : {"readback", "gpu"}) {
    std::vector<PartitionFit> fits[2];
    for (int tight = 0; tight < 2; ++tight) {
      std::unique_ptr<tech::Renderer> r = MakeRenderer(s, 128, 128, {{"cull", cull}, {"tight", std::to_string(tight)}, {"partition", "kmeans"}});
      r->RenderFrame(s.camera, s.light);
      fits[tight] = Fits(*r);
    }
    ASSERT_EQ(fits[0].size(), 4u);
    double sum[2] = {0, 0};
    for (size_t p = 0; p < 4; ++p) {
      SCOPED_TRACE(std::string(cull) + " partition " + std::to_string(p));
      ASSERT_EQ(fits[0][p].empty, fits[1][p].empty);
      if (fits[0][p].empty) continue;
      EXPECT_LE(fits[1][p].area(), fits[0][p].area() * 1.0001f);
      for (int t = 0; t < 2; ++t) sum[t] += fits[t][p].area();
      std::printf("[%s] partition %zu: light-space area tight %.3f, slice %.3f\n", cull, p, fits[1][p].area(), fits[0][p].area());
    }
    EXPECT_LT(sum[1], sum[0] * 0.9);
  }
}

// cull=gpu makes the same fits on the GPU as FitPartition on the CPU (same operations), culls by
// the same rule and so renders the same image, with no Map while rendering; Stats() reads the
// indirect records back for the triangle count.
TEST_P(SdsmTechniqueTest, GpuModeMatchesReadbackWithoutReadingBack) {
  const uint32_t W = 160, H = 120;
  scene::Scene s = FloatingBox(true);
  const Params variants[] = {
      {},
      {{"tight", "0"}, {"partition", "adaptive-log"}},
      {{"quantize", "1"}, {"dilation", "0.25"}},
      {{"filter", "gauss"}, {"kernel", "5"}, {"bias", "normal"}, {"blend", "0.2"}},
  };
  for (const Params& v : variants) {
    SCOPED_TRACE(Describe(v));
    std::vector<uint8_t> img[2];
    std::vector<PartitionFit> fits[2];
    uint64_t triangles[2];
    for (int gpu = 0; gpu < 2; ++gpu) {
      Params p = v;
      p["cull"] = gpu ? "gpu" : "readback";
      std::unique_ptr<tech::Renderer> r = MakeRenderer(s, W, H, p);
      for (int i = 0; i < 2; ++i) r->RenderFrame(s.camera, s.light);
      img[gpu] = r->ReadColor();
      SdsmTechnique& t = Sdsm(*r);
      EXPECT_EQ(t.frameReadbacks(), gpu ? 0u : 2u);
      triangles[gpu] = t.Stats().trianglesSubmitted;
      EXPECT_EQ(t.statsReadbacks(), gpu ? 1u : 0u);
      fits[gpu] = Fits(*r);
    }
    EXPECT_EQ(CompareImages("gpu-vs-readback-" + Describe(v), W, H, img[1].data(), img[0].data(), 0), 0u);
    EXPECT_EQ(triangles[1], triangles[0]);
    EXPECT_GT(triangles[0], 0u);
    ASSERT_EQ(fits[0].size(), fits[1].size());
    for (size_t p = 0; p < fits[0].size(); ++p) {
      ASSERT_EQ(fits[0][p].empty, fits[1][p].empty) << p;
      if (fits[0][p].empty) continue;
      for (int a = 0; a < 3; ++a) {
        float tol = 1e-5f * (1.0f + std::abs(fits[0][p].min[a]) + std::abs(fits[0][p].max[a]));
        EXPECT_NEAR(fits[1][p].min[a], fits[0][p].min[a], tol) << "partition " << p << " axis " << a;
        EXPECT_NEAR(fits[1][p].max[a], fits[0][p].max[a], tol) << "partition " << p << " axis " << a;
      }
      EXPECT_NEAR(fits[1][p].splitFar, fits[0][p].splitFar, 1e-5f * fits[0][p].splitFar) << p;
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
          EXPECT_NEAR(fits[1][p].viewProj[c][r], fits[0][p].viewProj[c][r], 1e-4f * (1.0f + std::abs(fits[0][p].viewProj[c][r])));
    }
  }
}

// The camera translates a little each frame (the light frame keeps its axes): every partition's
// sides stay powers of two and its corner on the texel grid anchored at the world origin.
TEST_P(SdsmTechniqueTest, QuantizeKeepsPowerOfTwoSizesOnTheWorldTexelGrid) {
  scene::Scene s = FloatingBox(true);
  for (const char* cull : {"readback", "gpu"}) {
    std::unique_ptr<tech::Renderer> r = MakeRenderer(s, 128, 128, {{"cull", cull}, {"quantize", "1"}});
    scene::Camera cam = s.camera;
    for (int frame = 0; frame < 4; ++frame) {
      SCOPED_TRACE(std::string(cull) + " frame " + std::to_string(frame));
      r->RenderFrame(cam, s.light);
      const SdsmTechnique& t = Sdsm(*r);
      glm::vec3 grid(t.lastLightView()[3]);
      size_t checked = 0;
      for (const PartitionFit& f : Fits(*r)) {
        if (f.empty) continue;
        ++checked;
        for (int a = 0; a < 2; ++a) {
          float size = f.max[a] - f.min[a];
          float rounded = std::exp2(std::round(std::log2(size)));
          EXPECT_NEAR(size, rounded, 1e-5f * rounded) << "axis " << a;
          EXPECT_TRUE(IsPowerOfTwo(rounded));
          float k = (f.min[a] - grid[a]) / (rounded / 512.0f);
          EXPECT_NEAR(k, std::round(k), 2e-3f) << "axis " << a;
        }
      }
      EXPECT_GE(checked, 3u);
      glm::vec3 step(0.013f, 0.004f, -0.021f);
      cam.position += step;
      cam.target += step;
    }
  }
}

// Only the shared csm parameters shape the lit shader; each of their variants (csm's 17
// comparison variants plus every moment kind and precision) configures and compiles, normal and
// lab. The sdsm parameters change none of the defines.
TEST_P(SdsmTechniqueTest, EveryParametersLitShaderCompiles) {
  auto defines = [](const Params& p) {
    std::string key;
    tech::sdsm::SdsmSettings s = tech::sdsm::SdsmSettingsFrom(tech::ParamValues::Parse("sdsm", tech::sdsm::SdsmParams(), p));
    for (const hlsl::Define& d : tech::csm::CsmTechnique::Defines(s.csm)) key += d.name + "=" + d.value + " ";
    return key;
  };
  const std::string base = defines({});
  for (const char* partition : {"log", "adaptive-log", "kmeans"})
    for (const char* cull : {"conservative", "readback", "latent", "gpu"})
      for (const char* flag : {"0", "1"})
        EXPECT_EQ(defines({{"partition", partition}, {"cull", cull}, {"tight", flag}, {"quantize", flag}, {"dilation", "1"}}), base);
  std::map<std::string, Params> variants;
  for (const char* filter : {"hw2x2", "box", "gauss", "gathercmp", "poisson"})
    for (const char* kernel : {"3", "5", "7", "9"}) variants.emplace(defines({{"filter", filter}, {"kernel", kernel}}), Params{{"filter", filter}, {"kernel", kernel}});
  for (const std::string& m : tech::MomentFilterNames())
    for (const char* precision : {"fp16", "fp32"}) variants.emplace(defines({{"filter", m}, {"precision", precision}}), Params{{"filter", m}, {"precision", precision}});
  EXPECT_EQ(variants.size(), 27u);
  for (auto [key, p] : variants) {
    p["resolution"] = "128";
    SdsmTechnique t;
    t.Configure(device(), tech::ParamValues::Parse("sdsm", t.Params(), p));
    for (tech::LitPass pass : {tech::LitPass::Normal, tech::LitPass::Lab}) {
      auto [vs, ps] = tech::Renderer::CompileLitShaders(t, pass);
      if (pass == tech::LitPass::Normal) {
        EXPECT_NO_THROW(device().CreateVertexShader(vs)) << key;
      }
      EXPECT_NO_THROW(device().CreatePixelShader(ps)) << key;
    }
  }
}

// Moment filters run through MomentMaps as in csm; the floating box still shadows correctly.
TEST_P(SdsmTechniqueTest, MomentFilterShadowsTheFloatingBox) {
  const uint32_t W = 128, H = 128;
  scene::Scene s = FloatingBox(true);
  for (const char* cull : {"readback", "gpu"}) {
    SCOPED_TRACE(cull);
    std::unique_ptr<tech::Renderer> r = MakeRenderer(s, W, H, {{"cull", cull}, {"filter", "evsm4"}, {"blur", "0.05"}});
    r->RenderFrame(s.camera, s.light);
    std::vector<uint8_t> img = r->ReadColor();
    Comparison c = CompareWithAnalytic(img, AnalyticFloor(s, W, H), W, H, 3);
    EXPECT_GT(c.shadow, 150);
    EXPECT_LE(c.wrong, c.checked / 200);
    std::printf("[%s] evsm4: %d of %d floor pixels wrong\n", cull, c.wrong, c.checked);
    if (c.wrong) WritePng(TestOutputDir() / (std::string("evsm4-") + cull + ".png"), W, H, img.data());
  }
}

TEST(SdsmTechniqueParams, BadValuesListTheValidOnes) {
  std::unique_ptr<tech::Technique> t = tech::CreateTechnique("sdsm");
  auto message = [&](const Params& p) {
    try {
      tech::sdsm::SdsmSettingsFrom(tech::ParamValues::Parse("sdsm", t->Params(), p));
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_NE(message({{"partition", "pssm"}}).find("partition takes log|adaptive-log|kmeans"), std::string::npos);
  EXPECT_NE(message({{"cull", "none"}}).find("cull takes conservative|readback|latent|gpu"), std::string::npos);
  EXPECT_NE(message({{"tight", "2"}}).find("tight takes an integer in [0, 1]"), std::string::npos);
  EXPECT_NE(message({{"latency", "0"}}).find("latency takes an integer in [1, 8]"), std::string::npos);
  EXPECT_NE(message({{"quantize", "yes"}}).find("quantize takes an integer in [0, 1]"), std::string::npos);
  EXPECT_NE(message({{"dilation", "-1"}}).find("dilation takes a number in [0, 1000000]"), std::string::npos);
  EXPECT_NE(message({{"cascades", "9"}}).find("cascades takes an integer in [1, 8]"), std::string::npos);
  EXPECT_NE(message({{"filter", "pcf"}}).find("filter takes hw2x2|box|gauss|gathercmp|poisson|pcss|vsm|"), std::string::npos);
  EXPECT_NE(message({{"split", "log"}}).find("(valid: partition, tight, cull, latency, quantize, dilation, cascades, resolution,"), std::string::npos);
  std::string small = message({{"resolution", "16"}, {"filter", "poisson"}, {"kernel", "9"}});
  EXPECT_NE(small.find("technique 'sdsm': resolution=16"), std::string::npos) << small;
  EXPECT_NE(message({{"filter", "evsm4"}, {"bleed", "2"}}).find("technique 'sdsm'"), std::string::npos);
  // The shared parameters are csm's, name for name and range for range.
  for (const tech::ParamSpec& spec : t->Params())
    for (const tech::ParamSpec& c : tech::csm::CsmParams())
      if (c.name == spec.name) {
        EXPECT_TRUE(c.min == spec.min && c.max == spec.max && c.choices == spec.choices && c.defaultValue == spec.defaultValue) << c.name;
      }
}

// Figure 2 (histogram of log view depth with the partitions) and Figure 4 (the samples in light
// space with the partitions' boxes) of terrain-city; every analysed sample lies in the fitted box
// of its partition.
TEST_P(SdsmTechniqueTest, DebugFiguresOfTerrainCity) {
  scene::Scene s = scene::MakeBuiltinScene("terrain-city");
  std::unique_ptr<tech::Renderer> r = MakeRenderer(s, 192, 108, {{"cull", "readback"}, {"partition", "adaptive-log"}});
  r->RenderFrame(s.camera, s.light);
  tech::sdsm::SdsmDebugFrame d = Sdsm(*r).ReadDebugFrame(ctx());
  ASSERT_TRUE(d.results.covered());
  EXPECT_EQ(d.samples.size(), d.results.samples);
  size_t outside = 0;
  for (const glm::vec3& p : d.samples) {
    const PartitionFit& f = d.fits[size_t(p.z)];
    outside += f.empty || p.x < f.min.x || p.x > f.max.x || p.y < f.min.y || p.y > f.max.y;
  }
  EXPECT_LE(outside, d.samples.size() / 1000) << "samples outside their partition's box";
  std::vector<uint8_t> fig2 = tech::sdsm::RenderHistogramImage(d.histogram, d.results.zMin, d.results.zMax, d.results.splits, 512, 160);
  std::vector<uint8_t> fig4 = tech::sdsm::RenderLightSpaceImage(d.samples, d.fits, 768, 256);
  WritePng(TestOutputDir() / "figure2-histogram.png", 512, 160, fig2.data());
  WritePng(TestOutputDir() / "figure4-light-space.png", 768, 256, fig4.data());
  std::printf("figures in %s\n", TestOutputDir().string().c_str());
}

// The lab's texel density through the bench API: SDSM spends the same maps on the visible samples
// only, csm on the whole frustum slice of each cascade.
TEST_P(SdsmTechniqueTest, BeatsCsmOnTexelDensityOnTerrainCity) {
  scene::Scene s = scene::MakeBuiltinScene("terrain-city");
  eval::ReferenceCache cache(s, std::filesystem::path(SHADOWPORT_TEST_OUTPUT_DIR) / "reference-cache");
  bench::RunResult run[2];
  const char* names[2] = {"csm", "sdsm"};
  for (int i = 0; i < 2; ++i) {
    bench::RunSpec spec;
    spec.scene = &s;
    spec.technique = names[i];
    spec.params = {{"cascades", "4"}, {"resolution", "1024"}};
    spec.backend = backend();
    spec.width = 160;
    spec.height = 90;
    spec.frames = 2;
    spec.path = &s.cameraPath("slow-pan");
    run[i] = bench::RunOne(spec, cache);
    std::printf("[%s] %s: texels/px median %.3f p05 %.3f, utilization %.4f, misclassified %.3f%%\n", BackendName(backend()), names[i],
                run[i].texelsPerPixelMedian, run[i].texelsPerPixelP05, run[i].utilization, run[i].accuracy.misclassifiedPct());
  }
  EXPECT_GT(run[1].texelsPerPixelMedian, run[0].texelsPerPixelMedian * 1.5);
  EXPECT_GT(run[1].utilization, run[0].utilization);
}

SP_INSTANTIATE_BACKEND_TESTS(SdsmTechniqueTest);

}  // namespace
}  // namespace sp::test
