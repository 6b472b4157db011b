// The perspective-warp techniques (psm, lispsm, tsm) end to end on both backends: the shadow of a
// floating box against the analytic one for 1 and 2 cascades and both depth modes; the lookup
// reads the texel the CPU fit predicts; the singular configurations (light from behind the
// viewer, nearly so, duelling frusta) render with no NaN and the shadow present; and Vulkan and
// GL draw identical images.
#include <cmath>
#include <glm/ext/matrix_transform.hpp>

#include "backend-test.h"
#include "technique-renderer.h"
#include "cross-backend.h"
#include "floating-box.h"
#include "warps/warp-technique.h"
#include <sp/tech/renderer.h>

namespace sp::test {
namespace {

using tech::warps::WarpTechnique;

const char* const kWarps[] = {"psm", "lispsm", "tsm"};

class WarpTechniqueTest : public BackendTest {
 protected:
  std::unique_ptr<tech::Renderer> MakeRenderer(const std::string& name, const scene::Scene& s, uint32_t w, uint32_t h,
                                               std::map<std::string, std::string> params, bool lab = false) {
    params.emplace("resolution", "512");
    return MakeTechniqueRenderer(device(), name, s, w, h, params, LabOptions(lab));
  }
  static WarpTechnique& Warp(tech::Renderer& r) { return static_cast<WarpTechnique&>(r.technique()); }
};

bool Finite(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

// The 2x2 comparison filter reaches one texel; the warped texels of this view are at most about
// a pixel, so a 2-pixel band around the analytic edge covers the soft edge, as in the csm test.
TEST_P(WarpTechniqueTest, ShadowMatchesAnalyticShadowOfAFloatingBox) {
  const uint32_t W = 128, H = 128;
  scene::Scene s = FloatingBox(true);
  std::vector<int> expected = AnalyticFloor(s, W, H);
  for (const char* warp : kWarps)
    for (const char* cascades : {"1", "2"})
      for (const char* depth : {"warped", "linear"}) {
        std::string name = std::string(warp) + "-c" + cascades + "-" + depth;
        SCOPED_TRACE(name);
        std::unique_ptr<tech::Renderer> r = MakeRenderer(warp, s, W, H, {{"cascades", cascades}, {"depth", depth}});
        r->RenderFrame(s.camera, s.light);
        const std::vector<tech::warps::WarpFit>& fits = Warp(*r).lastFits();
        ASSERT_EQ(fits.size(), size_t(std::stoi(cascades)));
        EXPECT_FALSE(fits[0].fellBack) << "the test view must actually be warped";
        std::vector<uint8_t> img = r->ReadColor();
        Comparison c = CompareWithAnalytic(img, expected, W, H, 2);
        EXPECT_GT(c.checked, int(W * H / 3));
        EXPECT_GT(c.shadow, 200);
        EXPECT_EQ(c.wrong, 0);
        if (c.wrong) WritePng(TestOutputDir() / (name + ".png"), W, H, img.data());
      }
}

// The PCF family and the receiver-plane bias on the warped maps: the same box shadow. A wider
// kernel softens the edge over more warped texels (about a pixel each here), so the band grows
// with the kernel; with the receiver plane, the slope bias is off, so the plane alone keeps the
// floor free of acne.
TEST_P(WarpTechniqueTest, FiltersAndReceiverPlaneBiasKeepTheShadow) {
  const uint32_t W = 128, H = 128;
  scene::Scene s = FloatingBox(true);
  std::vector<int> expected = AnalyticFloor(s, W, H);
  struct Case {
    const char* warp;
    std::map<std::string, std::string> params;
    int band;
  };
  const Case cases[] = {
      {"lispsm", {{"filter", "box"}, {"kernel", "3"}}, 3},
      {"tsm", {{"filter", "gauss"}, {"kernel", "5"}}, 4},
      {"psm", {{"filter", "gathercmp"}, {"kernel", "5"}}, 4},
      {"lispsm", {{"filter", "box"}, {"kernel", "5"}, {"receiver_plane", "1"}, {"slope_bias", "0"}}, 4},
      {"tsm", {{"filter", "poisson"}, {"kernel", "5"}, {"receiver_plane", "1"}, {"linear_slope_bias", "0"}}, 4},
  };
  for (const Case& k : cases) {
    std::string name = k.warp;
    for (const auto& [key, v] : k.params) name += "-" + key + "=" + v;
    SCOPED_TRACE(name);
    std::unique_ptr<tech::Renderer> r = MakeRenderer(k.warp, s, W, H, k.params);
    r->RenderFrame(s.camera, s.light);
    std::vector<uint8_t> img = r->ReadColor();
    Comparison c = CompareWithAnalytic(img, expected, W, H, k.band);
    EXPECT_GT(c.checked, int(W * H / 3));
    EXPECT_GT(c.shadow, 80);  // shadowed pixels outside the band: 102 with a 4-pixel band
    EXPECT_EQ(c.wrong, 0);
    if (c.wrong) WritePng(TestOutputDir() / (name + ".png"), W, H, img.data());
  }
}

// Receiver-plane bias on a steep receiver under a small flat occluder: a post under a wider cap,
// the light 4 degrees off vertical, so the post's lit-facing side (N.L = sin 4 = 0.07) lies in the
// cap's shadow all the way down (the overhang of 1 reaches 1 / tan 4 = 14 below the cap). The
// receiver's slope is steep and the cap's flat: with the footprint term unbounded (a full texel
// of the receiver's slope) 62 to 70 of the side's 1,251 pixels near the cap were lit in 5 of the
// 6 cases; bounded (RECEIVER_PLANE_MAX_FOOTPRINT in shaders-hlsl/warps/shadow.hlsli), none.
TEST_P(WarpTechniqueTest, ReceiverPlaneBiasDoesNotLeakOnSteepReceivers) {
  const uint32_t W = 128, H = 128;
  scene::Scene s;
  s.name = "capped-post";
  uint32_t plane = s.addMesh(scene::MakePlane(1));
  uint32_t box = s.addMesh(scene::MakeBox());
  const glm::vec3 postMin(-0.5f, 0.0f, -0.5f), postMax(0.5f, 4.0f, 0.5f), capMin(-1.5f, 4.0f, -1.5f), capMax(1.5f, 4.3f, 1.5f);
  auto addBox = [&](glm::vec3 lo, glm::vec3 hi) {
    s.addInstance(box, glm::scale(glm::translate(glm::mat4(1.0f), (lo + hi) * 0.5f), hi - lo), glm::vec3(0.8f));
  };
  s.addInstance(plane, glm::scale(glm::mat4(1.0f), glm::vec3(20, 1, 20)), glm::vec3(0.8f));
  addBox(postMin, postMax);
  addBox(capMin, capMax);
  s.camera.position = {7.0f, 3.0f, 3.0f};
  s.camera.target = {0.0f, 2.0f, 0.0f};
  s.camera.fovY = glm::radians(45.0f);
  s.camera.nearZ = 1.0f;
  s.camera.farZ = 40.0f;
  const float tilt = glm::radians(4.0f);
  s.light.direction = glm::vec3(-std::sin(tilt), -std::cos(tilt), 0.0f);
  s.finalize();
  const glm::vec3 toLight = s.light.towardsLight();
  for (const char* warp : kWarps)
    for (const char* depth : {"warped", "linear"}) {
      std::string name = std::string("capped-post-") + warp + "-" + depth;
      SCOPED_TRACE(name);
      std::unique_ptr<tech::Renderer> r = MakeRenderer(warp, s, W, H, {{"depth", depth}, {"filter", "box"}, {"receiver_plane", "1"}}, true);
      r->RenderFrame(s.camera, s.light, tech::LitPass::Lab);
      tech::LabBuffers lab = r->ReadLab();
      int side = 0, leaked = 0;
      for (size_t i = 0; i < lab.size(); ++i) {
        glm::vec3 p(lab.position[i]);
        // The post's +x face, away from its edges and from the cap by more than a texel or two.
        if (!lab.receiving(i) || std::abs(p.x - postMax.x) > 1e-3f || std::abs(p.z) > 0.4f || p.y < 0.2f || p.y > 3.9f) continue;
        ASSERT_GE(RayBox(p + toLight * 1e-3f, toLight, capMin, capMax), 0.0f) << "the whole side is in the cap's shadow";
        ++side;
        leaked += lab.visibility[i] > 0.5f;
      }
      EXPECT_GT(side, 300);
      EXPECT_EQ(leaked, 0) << "of " << side << " pixels of the post's shadowed side";
      if (leaked) WritePng(TestOutputDir() / (name + ".png"), W, H, lab.color.data());
    }
}

// The lab's lookup is the texel ToTexel computes on the CPU, in the cascade interval selection
// picks, and every receiving pixel reads a map.
TEST_P(WarpTechniqueTest, LookupReadsWhereTheCpuFitSays) {
  const uint32_t W = 96, H = 96, N = 512;
  scene::Scene s = FloatingBox(true);
  for (const char* warp : kWarps) {
    SCOPED_TRACE(warp);
    std::unique_ptr<tech::Renderer> r = MakeRenderer(warp, s, W, H, {{"cascades", "2"}}, true);
    r->RenderFrame(s.camera, s.light, tech::LitPass::Lab);
    tech::LabBuffers lab = r->ReadLab();
    WarpTechnique& t = Warp(*r);
    ASSERT_EQ(t.Layers().size(), 2u);
    EXPECT_EQ(t.Stats().memoryBytes, 2ull * N * N * 4);
    size_t receiving = 0, covered = 0, mismatch = 0, layer1 = 0;
    for (size_t i = 0; i < lab.size(); ++i) {
      if (!lab.receiving(i)) continue;
      ++receiving;
      int layer = int(lab.lookup[i].x);
      if (layer < 0) continue;
      ++covered;
      layer1 += layer == 1;
      glm::vec3 expect = tech::warps::ToTexel(t.lastFits()[layer], glm::vec3(lab.position[i]), float(N));
      // The shader's float matrix product against the CPU's, both from the same float matrix.
      if (glm::length(glm::vec2(expect) - glm::vec2(lab.lookup[i].y, lab.lookup[i].z)) > 0.05f) ++mismatch;
    }
    EXPECT_GT(receiving, lab.size() / 2);
    EXPECT_EQ(covered, receiving);
    EXPECT_EQ(mismatch, 0u);
    EXPECT_GT(layer1, 0u) << "the second cascade is read";
  }
}

// Light along the view (from behind the viewer, exactly and 10 degrees off), perpendicular to it,
// and against it (duelling frusta, 162 degrees): each warp falls back or blends towards the uniform map; the
// fits are finite, visibility is never NaN, and the box's visible shadow is drawn where the ray
// test puts it.
TEST_P(WarpTechniqueTest, SingularConfigurationsRenderWithoutNanAndWithTheShadow) {
  const uint32_t W = 128, H = 128;
  struct Case {
    const char* name;
    scene::Scene scene;
  };
  std::vector<Case> cases;
  {
    // The box near the image's edge: with the light along the view its shadow lies behind it,
    // visible only where it reaches towards the vanishing point, the image's centre.
    scene::Scene s = FloatingBox(true);
    s.camera.target = {5.0f, 0.0f, -2.0f};
    s.light.direction = s.camera.forward();
    cases.push_back({"behind", s});
    glm::vec3 side = glm::normalize(glm::cross(s.camera.forward(), glm::vec3(0, 1, 0)));
    s.light.direction = glm::vec3(glm::rotate(glm::mat4(1.0f), glm::radians(10.0f), side) * glm::vec4(s.camera.forward(), 0.0f));
    cases.push_back({"behind-10", s});
  }
  {
    // The light perpendicular to the view, in the plane it spans with the vertical: for PSM a
    // light "at infinity" in post-projective space too (the inverted projection's boundary).
    scene::Scene s = FloatingBox(true);
    glm::vec3 f = s.camera.forward(), down(0.0f, -1.0f, 0.0f);
    s.light.direction = glm::normalize(down - f * glm::dot(f, down));
    cases.push_back({"perpendicular", s});
  }
  {
    // Duelling frusta: the camera looks 3 degrees down along -z, the light comes towards it 15
    // degrees down (gamma = 162, within TSM's fade band and PSM's fallback; steeper would leave
    // the lit floor too dark for the test's threshold, a light from below lights no floor).
    scene::Scene s = FloatingBox(true);
    s.camera.position = {-1.0f, 5.0f, 20.0f};
    s.camera.target = s.camera.position + glm::vec3(0.0f, -std::sin(glm::radians(3.0f)), -std::cos(glm::radians(3.0f)));
    s.light.direction = glm::vec3(0.0f, -std::sin(glm::radians(15.0f)), std::cos(glm::radians(15.0f)));
    cases.push_back({"duelling", s});
  }
  for (Case& k : cases) {
    std::vector<int> expected = AnalyticFloor(k.scene, W, H);
    for (const char* warp : kWarps)
      for (const char* depth : {"warped", "linear"}) {
        std::string name = std::string(k.name) + "-" + warp + "-" + depth;
        SCOPED_TRACE(name);
        std::unique_ptr<tech::Renderer> r = MakeRenderer(warp, k.scene, W, H, {{"depth", depth}}, true);
        r->RenderFrame(k.scene.camera, k.scene.light, tech::LitPass::Lab);
        for (const tech::warps::WarpFit& f : Warp(*r).lastFits()) {
          EXPECT_TRUE(Finite(f.viewProj));
          EXPECT_TRUE(std::isfinite(f.linearDepth.x + f.linearDepth.y + f.linearDepth.z + f.linearDepth.w));
        }
        tech::LabBuffers lab = r->ReadLab();
        size_t nan = 0;
        for (size_t i = 0; i < lab.size(); ++i)
          if (lab.drawn(i) && (!std::isfinite(lab.visibility[i]) || !std::isfinite(lab.lookup[i].y + lab.lookup[i].z))) ++nan;
        EXPECT_EQ(nan, 0u);
        Comparison c = CompareWithAnalytic(lab.color, expected, W, H, 2);
        EXPECT_GT(c.shadow, 40) << "the box's shadow must be visible";
        EXPECT_EQ(c.wrong, 0);
        if (c.wrong) WritePng(TestOutputDir() / (name + ".png"), W, H, lab.color.data());
      }
  }
}

// The fallback band on the GPU: the light turns from 3 to 25 degrees off the view axis (from
// behind the viewer), through PSM's and TSM's fade (5 to 20 degrees) and LiSPSM's sin(gamma)
// weakening, one degree per frame. At every frame the floor's shadow is right and no lookup is
// NaN. Between frames, the texel each rendered surface point reads (the lab's lookup; 95th
// percentile over the pixels) moves: by up to 36 texels a degree where TSM's warp fades in, which
// is the transition spread over the band, not a pop. A pop is concentrated at one light
// direction and survives refining the step (as in WarpContinuity.NoPopThroughTheFallbackBand on
// the CPU): the step that moves most is cut into 8 and no eighth may carry more than 35 % of its
// move (a smooth change puts about 1/8 in each). A hard switch to the uniform map would put the
// whole jump between the warp and the switched-off warp (30 to 177 texels at 12 degrees here) into
// one eighth.
TEST_P(WarpTechniqueTest, NoPopThroughTheFallbackBandOnTheGpu) {
  const uint32_t W = 96, H = 96;
  scene::Scene s = FloatingBox(true);
  const glm::vec3 forward = s.camera.forward();
  const glm::vec3 side = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
  auto lightAt = [&](float degrees) {
    scene::DirectionalLight l = s.light;
    l.direction = glm::vec3(glm::rotate(glm::mat4(1.0f), glm::radians(-degrees), side) * glm::vec4(forward, 0.0f));
    return l;
  };
  // The 95th percentile of the texel distance between two lookups, over the pixels both map.
  auto move = [](const tech::LabBuffers& a, const tech::LabBuffers& b) {
    std::vector<float> d;
    for (size_t i = 0; i < a.size(); ++i)
      if (a.receiving(i) && b.receiving(i) && a.lookup[i].x >= 0 && b.lookup[i].x >= 0)
        d.push_back(glm::length(glm::vec2(a.lookup[i].y - b.lookup[i].y, a.lookup[i].z - b.lookup[i].z)));
    if (d.empty()) return 0.0f;
    std::nth_element(d.begin(), d.begin() + d.size() * 95 / 100, d.end());
    return d[d.size() * 95 / 100];
  };
  const std::map<std::string, std::map<std::string, std::string>> switchedOff = {
      {"psm", {{"slide_back", "1000000"}}}, {"lispsm", {{"n_scale", "1000000"}}}, {"tsm", {{"focus", "0"}}}};
  for (const char* warp : kWarps) {
    SCOPED_TRACE(warp);
    std::unique_ptr<tech::Renderer> r = MakeRenderer(warp, s, W, H, {}, true);
    auto render = [&](float degrees) {
      scene::Scene lit = s;
      lit.light = lightAt(degrees);
      r->RenderFrame(s.camera, lit.light, tech::LitPass::Lab);
      tech::LabBuffers lab = r->ReadLab();
      size_t nan = 0;
      for (size_t i = 0; i < lab.size(); ++i)
        if (lab.drawn(i) && (!std::isfinite(lab.visibility[i]) || !std::isfinite(lab.lookup[i].y + lab.lookup[i].z))) ++nan;
      EXPECT_EQ(nan, 0u) << degrees << " degrees";
      Comparison c = CompareWithAnalytic(lab.color, AnalyticFloor(lit, W, H), W, H, 2);
      EXPECT_EQ(c.wrong, 0) << degrees << " degrees";
      return lab;
    };
    std::unique_ptr<tech::Renderer> off = MakeRenderer(warp, s, W, H, switchedOff.at(warp), true);
    off->RenderFrame(s.camera, lightAt(12.0f), tech::LitPass::Lab);
    const float jump = move(render(12.0f), off->ReadLab());
    EXPECT_GT(jump, 16.0f) << "a hard switch at 12 degrees would be a visible jump";

    tech::LabBuffers previous = render(3.0f);
    float largest = 0.0f;
    int largestAt = 3;
    for (int g = 4; g <= 25; ++g) {
      tech::LabBuffers lab = render(float(g));
      float m = move(lab, previous);
      if (m > largest) largest = m, largestAt = g - 1;
      previous = std::move(lab);
    }
    previous = render(float(largestAt));
    float eighth = 0.0f;
    for (int j = 1; j <= 8; ++j) {
      tech::LabBuffers lab = render(float(largestAt) + float(j) / 8.0f);
      eighth = std::max(eighth, move(lab, previous));
      previous = std::move(lab);
    }
    EXPECT_LT(eighth, 0.35f * largest) << "the step from " << largestAt << " degrees moves " << largest << " texels";
    EXPECT_LT(largest, jump);
  }
}

// Every parameter's lit pass and depth shaders create on this backend (one lighting variant).
TEST_P(WarpTechniqueTest, ConfiguresWithEveryDepthModeAndReportsLayers) {
  for (const char* warp : kWarps)
    for (const char* depth : {"warped", "linear"})
      for (const char* cascades : {"1", "4"}) {
        std::unique_ptr<tech::Technique> t = tech::CreateTechnique(warp);
        EXPECT_NO_THROW(t->Configure(device(), tech::ParamValues::Parse(warp, t->Params(), {{"depth", depth}, {"cascades", cascades}, {"resolution", "64"}})));
        EXPECT_EQ(t->Layers().size(), size_t(std::stoi(cascades)));
      }
  // The defaults: TSM stores linear depth, as its paper does; the others warped depth.
  for (const char* warp : kWarps) {
    std::unique_ptr<tech::Technique> t = tech::CreateTechnique(warp);
    tech::ParamValues p = tech::ParamValues::Parse(warp, t->Params(), {});
    EXPECT_EQ(p.getChoice("depth"), std::string(warp) == "tsm" ? "linear" : "warped") << warp;
    EXPECT_EQ(p.getInt("cascades"), 1);
    EXPECT_EQ(p.getInt("resolution"), 2048);
  }
}

SP_INSTANTIATE_BACKEND_TESTS(WarpTechniqueTest);

// Vulkan and GL on Mesa draw identical images for every warp, cascades=2, both depth modes.
TEST(WarpTechniqueCrossBackend, IdenticalOnBothBackends) {
  const uint32_t W = 128, H = 96;
  scene::Scene s = FloatingBox(true);
  for (const char* warp : kWarps)
    for (const char* depth : {"warped", "linear"}) {
      std::string name = std::string("warp-") + warp + "-" + depth;
      CrossBackendFrame f = RenderOnBothBackends(warp, {{"cascades", "2"}, {"depth", depth}, {"resolution", "512"}}, s, W, H);
      size_t differing = CompareImages(name, W, H, f.images[0].data(), f.images[1].data(), 0);
      if (f.mesa) {
        EXPECT_EQ(differing, 0u) << name << ": Vulkan and GL images differ on Mesa; see " << TestOutputDir();
      } else {
        EXPECT_LT(differing, size_t(W * H / 200)) << name;
      }
    }
}

}  // namespace
}  // namespace sp::test
