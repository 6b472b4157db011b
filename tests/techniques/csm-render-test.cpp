// Cascaded shadow maps on both backends: the shadow of a floating box against the analytic one
// for 1 and 4 cascades, array and atlas storage and every filter; atlas and array agree; both
// selections cover the view and read the texels the CPU fit predicts; casters in front of the
// near plane still cast; every parameter combination's lit pass compiles; and on terrain-city,
// culling, texel density against basic, and debug pictures (cascade tint, density, light views).
#include <glm/ext/matrix_transform.hpp>
#include <set>

#include "backend-test.h"
#include "technique-renderer.h"
#include "cross-backend.h"
#include "csm/csm-technique.h"
#include "floating-box.h"
#include "metrics.h"
#include <sp/tech/renderer.h>

namespace sp::test {
namespace {

using tech::csm::CsmTechnique;

class CsmTechniqueTest : public BackendTest {
 protected:
  std::unique_ptr<tech::Renderer> MakeRenderer(const scene::Scene& s, uint32_t w, uint32_t h, const std::map<std::string, std::string>& params,
                                               bool lab = false, const std::string& name = "csm") {
    return MakeTechniqueRenderer(device(), name, s, w, h, params, LabOptions(lab));
  }
  static CsmTechnique& Csm(tech::Renderer& r) { return static_cast<CsmTechnique&>(r.technique()); }
};

// Filters reach at most kernel/2 + 1 texels; the test's texels are smaller than its pixels, so a
// 2-pixel band around every analytic edge covers the soft edge of all of them.
TEST_P(CsmTechniqueTest, ShadowMatchesAnalyticShadowOfAFloatingBox) {
  const uint32_t W = 128, H = 128;
  scene::Scene s = FloatingBox(true);
  std::vector<int> expected = AnalyticFloor(s, W, H);
  for (const char* cascades : {"1", "4"})
    for (const char* filter : {"hw2x2", "box", "gauss", "gathercmp", "poisson"}) {
      std::vector<uint8_t> images[2];
      for (int atlas = 0; atlas < 2; ++atlas) {
        SCOPED_TRACE(std::string("cascades=") + cascades + " filter=" + filter + " storage=" + (atlas ? "atlas" : "array"));
        std::unique_ptr<tech::Renderer> r =
            MakeRenderer(s, W, H, {{"cascades", cascades}, {"filter", filter}, {"resolution", "512"}, {"storage", atlas ? "atlas" : "array"}});
        r->RenderFrame(s.camera, s.light);
        images[atlas] = r->ReadColor();
        Comparison c = CompareWithAnalytic(images[atlas], expected, W, H, 2);
        EXPECT_GT(c.checked, int(W * H / 3));
        EXPECT_GT(c.shadow, 200);
        EXPECT_EQ(c.wrong, 0);
        if (c.wrong) WritePng(TestOutputDir() / (std::string("c") + cascades + "-" + filter + (atlas ? "-atlas" : "-array") + ".png"), W, H, images[atlas].data());
      }
      // The two storages render the same maps (the atlas regions are the array's slices) and
      // differ only in the rounding of the lookup coordinates.
      EXPECT_LE(CompareImages(std::string("atlas-vs-array-") + cascades + "-" + filter, W, H, images[0].data(), images[1].data(), 8), size_t(W * H / 500))
          << "cascades=" << cascades << " filter=" << filter;
    }
  // Blending, map selection, the other bias modes and the other fits and splits.
  const std::map<std::string, std::string> others[] = {
      {{"blend", "0.3"}},
      {{"blend", "0.3"}, {"select", "map"}, {"filter", "gauss"}, {"kernel", "5"}},
      {{"bias", "normal"}, {"normal_offset", "1.5"}, {"filter", "poisson"}},
      {{"bias", "receiver-plane"}, {"filter", "box"}, {"storage", "atlas"}},
      {{"fit", "scene"}, {"focus", "scene"}, {"stabilize", "0"}, {"filter", "gathercmp"}, {"kernel", "7"}},
      {{"split", "manual"}, {"cascades", "3"}, {"splits", "0.2,0.5"}, {"select", "map"}},
  };
  for (std::map<std::string, std::string> p : others) {
    std::string name;
    for (const auto& [k, v] : p) name += k + "=" + v + " ";
    SCOPED_TRACE(name);
    p["resolution"] = "512";
    std::unique_ptr<tech::Renderer> r = MakeRenderer(s, W, H, p);
    r->RenderFrame(s.camera, s.light);
    std::vector<uint8_t> img = r->ReadColor();
    Comparison c = CompareWithAnalytic(img, expected, W, H, 2);
    EXPECT_GT(c.checked, int(W * H / 3));
    EXPECT_EQ(c.wrong, 0);
    if (c.wrong) WritePng(TestOutputDir() / (name + ".png"), W, H, img.data());
  }
}

// Interval and map selection both give every receiving pixel a cascade; map selection picks the
// first cascade holding the point, never a later one than interval selection; the lookup's texel
// is the one the CPU fit computes, in the region of its cascade, for both storages.
TEST_P(CsmTechniqueTest, SelectionsCoverTheViewAndReadWhereTheCpuFitSays) {
  const uint32_t W = 160, H = 120;
  scene::Scene s = FloatingBox(true);
  const uint32_t N = 256;
  for (const char* storage : {"array", "atlas"}) {
    std::vector<glm::vec4> intervalLookup;
    for (const char* select : {"interval", "map"}) {
      SCOPED_TRACE(std::string(storage) + " " + select);
      std::unique_ptr<tech::Renderer> r = MakeRenderer(s, W, H, {{"select", select}, {"storage", storage}, {"resolution", std::to_string(N)}}, true);
      r->RenderFrame(s.camera, s.light, tech::LitPass::Lab);
      tech::LabBuffers lab = r->ReadLab();
      CsmTechnique& t = Csm(*r);
      const tech::csm::CascadeSet& fit = t.lastFit();
      ASSERT_EQ(t.Layers().size(), 4u);
      EXPECT_EQ(t.Layers()[0].width, N);
      EXPECT_EQ(t.Stats().memoryBytes, 4ull * N * N * 4);  // four slices, or a 2x2 atlas
      size_t receiving = 0, covered = 0, texelMismatch = 0, layerMismatch = 0, later = 0;
      std::set<int> layers;
      for (size_t i = 0; i < lab.size(); ++i) {
        if (!lab.receiving(i)) continue;
        ++receiving;
        int layer = int(lab.lookup[i].x);
        if (layer < 0) continue;
        ++covered;
        layers.insert(layer);
        glm::vec3 p(lab.position[i]);
        glm::vec3 expect = fit.cascades[layer].texel(p, N);
        if (glm::length(glm::vec2(expect) - glm::vec2(lab.lookup[i].y, lab.lookup[i].z)) > 0.05f) ++texelMismatch;
        if (std::string(select) == "interval") {
          float depth = glm::dot(p - s.camera.position, s.camera.forward());
          int cpu = 0;
          while (cpu < 3 && depth >= fit.cascades[cpu].splitFar) ++cpu;
          bool nearSplit = false;
          for (float d : fit.splits) nearSplit |= std::abs(depth - d) < 1e-3f * d;
          if (!nearSplit && cpu != layer) ++layerMismatch;
        } else if (!intervalLookup.empty() && intervalLookup[i].x >= 0 && layer > intervalLookup[i].x) {
          ++later;
        }
      }
      EXPECT_GT(receiving, lab.size() / 2);
      EXPECT_EQ(covered, receiving) << "receiving pixels without a cascade";
      EXPECT_EQ(texelMismatch, 0u);
      EXPECT_EQ(layerMismatch, 0u);
      EXPECT_EQ(later, 0u);
      EXPECT_GE(layers.size(), 2u);
      if (std::string(select) == "interval") intervalLookup = lab.lookup;
    }
  }
}

// Receivers focus puts the near plane just before the receivers and their casters as the
// instance bounds say; bounds that understate a caster put it in front of the near plane, where
// depth clamping (DepthClipEnable = FALSE) pancakes it onto the plane and it still casts.
TEST_P(CsmTechniqueTest, CasterInFrontOfTheNearPlaneStillCasts) {
  const uint32_t W = 128, H = 128;
  scene::Scene s = FloatingBox(false);
  // A narrow view, so the visible floor lies behind the box as seen from the light.
  s.camera.fovY = glm::radians(20.0f);
  scene::Bounds flat;
  flat.extend(glm::vec3(kBoxMin.x, 0.0f, kBoxMin.z));
  flat.extend(glm::vec3(kBoxMax.x, 0.01f, kBoxMax.z));
  s.instances[1].worldBounds = flat;
  s.bounds = scene::Bounds{};
  for (const scene::Instance& inst : s.instances) s.bounds.extend(inst.worldBounds);
  std::unique_ptr<tech::Renderer> r = MakeRenderer(s, W, H, {{"cascades", "1"}, {"resolution", "512"}});
  r->RenderFrame(s.camera, s.light);
  const tech::csm::CascadeSet& fit = Csm(*r).lastFit();
  scene::Bounds realBox;
  realBox.extend(kBoxMin);
  realBox.extend(kBoxMax);
  float boxNear = -realBox.transformed(fit.lightView).max.z;
  EXPECT_LT(boxNear, fit.cascades[0].zNear - 1.0f) << "the box must lie in front of the near plane";
  std::vector<uint8_t> img = r->ReadColor();
  Comparison c = CompareWithAnalytic(img, AnalyticFloor(s, W, H), W, H, 2);
  EXPECT_GT(c.shadow, 300);
  EXPECT_EQ(c.wrong, 0);
  if (c.wrong) WritePng(TestOutputDir() / "pancaked.png", W, H, img.data());
}

// Every combination of the parameters that shape the lighting shader: its lit pass, normal and
// lab, compiles and links. Only filter and kernel are defines (the rest are constants), so the
// combinations share a few variants, each compiled once.
TEST_P(CsmTechniqueTest, EveryParameterCombinationsLitPassCompiles) {
  std::map<std::string, std::map<std::string, std::string>> variants;  // defines -> one parameter set
  size_t combinations = 0;
  for (const char* filter : {"hw2x2", "box", "gauss", "gathercmp", "poisson"})
    for (const char* kernel : {"3", "5", "7", "9"})
      for (const char* bias : {"const", "slope", "normal", "receiver-plane"})
        for (const char* select : {"interval", "map"})
          for (const char* blend : {"0", "0.2"})
            for (const char* storage : {"array", "atlas"}) {
              std::map<std::string, std::string> p = {{"filter", filter}, {"kernel", kernel}, {"bias", bias}, {"select", select},
                                                      {"blend", blend},   {"storage", storage}, {"resolution", "64"}};
              tech::csm::CsmSettings settings = tech::csm::SettingsFrom(tech::ParamValues::Parse("csm", tech::csm::CsmParams(), p));
              std::string key;
              for (const hlsl::Define& d : CsmTechnique::Defines(settings)) key += d.name + "=" + d.value + " ";
              variants.emplace(key, p);
              ++combinations;
            }
  EXPECT_EQ(combinations, 640u);
  EXPECT_EQ(variants.size(), 17u);  // hw2x2 + 4 filters x 4 kernels
  // Each variant configured on the device (its resources and states), and its lit pass created.
  for (const auto& [key, p] : variants) {
    CsmTechnique t;
    t.Configure(device(), tech::ParamValues::Parse("csm", t.Params(), p));
    for (tech::LitPass pass : {tech::LitPass::Normal, tech::LitPass::Lab}) {
      auto [vs, ps] = tech::Renderer::CompileLitShaders(t, pass);
      if (pass == tech::LitPass::Normal) {
        EXPECT_NO_THROW(device().CreateVertexShader(vs)) << key;
      }
      EXPECT_NO_THROW(device().CreatePixelShader(ps)) << key;
    }
  }
}

// A colour per cascade, shaded by the frame's luminance.
std::vector<uint8_t> CascadeTint(const tech::LabBuffers& lab) {
  static const uint8_t kColors[8][3] = {{255, 90, 90}, {90, 220, 90}, {90, 120, 255}, {240, 220, 70},
                                        {220, 90, 220}, {70, 220, 220}, {250, 160, 60}, {160, 160, 160}};
  std::vector<uint8_t> out(lab.size() * 4);
  for (size_t i = 0; i < lab.size(); ++i) {
    int layer = int(lab.lookup[i].x);
    float lum = (lab.color[i * 4] + lab.color[i * 4 + 1] + lab.color[i * 4 + 2]) / (3.0f * 255.0f);
    for (int k = 0; k < 3; ++k) {
      float base = layer >= 0 && lab.drawn(i) ? kColors[layer % 8][k] / 255.0f : 0.5f;
      out[i * 4 + k] = uint8_t(std::min(255.0f, 255.0f * base * (0.35f + 0.9f * lum)));
    }
    out[i * 4 + 3] = 255;
  }
  return out;
}

// The depth of one cascade's region as grey (near light, dark; far or empty, light).
std::vector<uint8_t> LightView(const std::vector<float>& texels, uint32_t rowTexels, const tech::csm::CascadeRegion& r, uint32_t n, uint32_t slicePixels) {
  std::vector<uint8_t> out(size_t(n) * n * 4);
  const float* base = texels.data() + size_t(r.slice) * slicePixels;
  for (uint32_t y = 0; y < n; ++y)
    for (uint32_t x = 0; x < n; ++x) {
      float d = base[size_t(r.y + y) * rowTexels + r.x + x];
      uint8_t v = uint8_t(std::clamp(d, 0.0f, 1.0f) * 255.0f);
      uint8_t* o = &out[(size_t(y) * n + x) * 4];
      o[0] = o[1] = o[2] = v;
      o[3] = 255;
    }
  return out;
}

// terrain-city, the scene cascades exist for: culling keeps each cascade's triangles below the
// scene's, cascades give more texels per pixel than basic's single map of the same size, and the
// debug pictures (cascade tint, texel density, each cascade's light view) land in the test's
// output directory.
TEST_P(CsmTechniqueTest, TerrainCityCullsAndBeatsBasicOnTexelDensity) {
  const uint32_t W = 192, H = 108, N = 512;
  scene::Scene s = scene::MakeBuiltinScene("terrain-city");
  double median[2];
  for (int k = 0; k < 2; ++k) {
    bool csm = k == 1;
    std::unique_ptr<tech::Renderer> r =
        csm ? MakeRenderer(s, W, H, {{"resolution", std::to_string(N)}, {"storage", "atlas"}}, true)
            : MakeRenderer(s, W, H, {{"resolution", std::to_string(2 * N)}}, true, "basic");  // the same memory
    r->RenderFrame(s.camera, s.light, tech::LitPass::Lab);
    tech::LabBuffers lab = r->ReadLab();
    eval::LogHistogram hist;
    eval::AddTexelDensity(lab, hist);
    median[k] = hist.percentile(0.5);
    if (!csm) continue;
    CsmTechnique& t = Csm(*r);
    EXPECT_EQ(t.Stats().memoryBytes, r->technique().Stats().memoryBytes);
    const std::vector<uint64_t>& tris = t.lastCascadeTriangles();
    uint64_t sum = 0;
    for (uint64_t n : tris) {
      EXPECT_LE(n, s.triangleCount());
      sum += n;
    }
    std::printf("terrain-city triangles per cascade: %llu %llu %llu %llu of %zu\n", (unsigned long long)tris[0], (unsigned long long)tris[1],
                (unsigned long long)tris[2], (unsigned long long)tris[3], s.triangleCount());
    EXPECT_EQ(t.Stats().trianglesSubmitted, sum);
    EXPECT_LT(tris[0], s.triangleCount() / 2) << "the nearest cascade covers a few metres of the city";

    std::filesystem::path dir = TestOutputDir();
    std::vector<uint8_t> tint = CascadeTint(lab);
    WritePng(dir / "cascades.png", W, H, tint.data());
    uint32_t hh = 0;
    std::vector<uint8_t> density = eval::TexelDensityHeatMap(lab, &hh);
    WritePng(dir / "density.png", W, hh, density.data());
    Texture2D* map = t.shadowTexture();
    TEXTURE2D_DESC md = map->GetDesc();
    std::vector<float> texels = ReadAs<float>(ReadTexture(device(), ctx(), map, 0));
    for (int c = 0; c < 4; ++c) {
      std::vector<uint8_t> view = LightView(texels, md.Width, t.region(c), N, md.Width * md.Height);
      WritePng(dir / ("light-view-" + std::to_string(c) + ".png"), N, N, view.data());
    }
  }
  EXPECT_GT(median[1], 2.0 * median[0]) << "texels per pixel: basic " << median[0] << ", csm " << median[1];
}

SP_INSTANTIATE_BACKEND_TESTS(CsmTechniqueTest);

// As basic's cross-backend test: on Mesa's shared rasterizer both backends give the same image,
// elsewhere up to 0.5% of pixels may differ at shadow edges.
TEST(CsmCrossBackend, DefaultSceneRendersIdenticallyOnBothBackends) {
  const uint32_t W = 192, H = 108;
  CrossBackendFrame f = RenderOnBothBackends("csm", {{"resolution", "512"}, {"filter", "poisson"}, {"blend", "0.2"}},
                                             scene::MakeBuiltinScene("default"), W, H);
  size_t differing = CompareImages("default-csm", W, H, f.images[0].data(), f.images[1].data(), 0);
  EXPECT_LE(differing, f.mesa ? 0u : size_t(W * H / 200));
}

}  // namespace
}  // namespace sp::test
