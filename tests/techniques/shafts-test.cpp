// Sun shafts in basic (shaders-hlsl/common/shafts.hlsli): the in-scattering of the floating-box
// scene against the same step sum computed on the CPU from the known geometry, shafts=0 against the
// technique without the parameter, the walk per secondary texel (minmax, hpsm) against the plain
// march, the fraction of lookups it skips, and the parameters' errors.
//
// Tolerances: colours are 8-bit sRGB, so a difference of two decoded ones is within half a step
// of each of the true one. Steps within a few texels of the shadow volume's sides (or of the box,
// where the slope bias moves the stored depth) may go either way with the texel grid; the CPU
// bounds them by counting them lit and shadowed. The accelerated walks add the same weights in
// the same order as the plain march, so their images are compared exactly.
#include <glm/glm.hpp>

#include "backend-test.h"
#include "technique-renderer.h"
#include "floating-box.h"
#include <sp/tech/renderer.h>
#include <sp/tech/shaft-counters.h>

namespace sp::test {
namespace {

constexpr uint32_t W = 64, H = 64;
constexpr int kSteps = 64;
constexpr float kDensity = 0.01f;

class ShaftsTest : public BackendTest {
 protected:
  std::unique_ptr<tech::Renderer> Render(const scene::Scene& s, std::map<std::string, std::string> params) {
    params.emplace("resolution", "256");
    auto r = MakeTechniqueRenderer(device(), "basic", s, W, H, params);
    r->RenderFrame(s.camera, s.light);
    return r;
  }
  static std::map<std::string, std::string> Shafts(const char* accel) {
    return {{"shafts", "1"}, {"shaft_steps", std::to_string(kSteps)}, {"shaft_density", std::to_string(kDensity)}, {"shaft_accel", accel}};
  }
};

// The colour target is sRGB: decode, and bound the rounding of a stored value by half its step.
double Linear(double v8) {
  double c = v8 / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}
double HalfStep(uint8_t v) { return (Linear(std::min(255.0, v + 0.5)) - Linear(std::max(0.0, v - 0.5))) / 2.0; }

float DistanceToBox(glm::vec3 p) {
  glm::vec3 d = glm::max(glm::max(kBoxMin - p, p - kBoxMax), glm::vec3(0.0f));
  return glm::length(d);
}

// The shader's step sum for the view ray of pixel (x, y), from the camera to the floor: lit steps
// counted shadowed (lo) and lit (hi) where the texel grid may decide either way.
struct Bounds {
  double lo = 0, hi = 0;
  int shadowedSteps = 0;
};
Bounds CpuInScatter(const scene::Scene& s, uint32_t x, uint32_t y, float texelWorld) {
  glm::mat4 inv = glm::inverse(s.camera.projection(float(W) / H) * s.camera.view());
  glm::vec4 a = inv * glm::vec4((x + 0.5f) / W * 2 - 1, 1 - (y + 0.5f) / H * 2, 0.0f, 1.0f);
  glm::vec4 b = inv * glm::vec4((x + 0.5f) / W * 2 - 1, 1 - (y + 0.5f) / H * 2, 1.0f, 1.0f);
  glm::vec3 o = glm::vec3(a) / a.w, d = glm::normalize(glm::vec3(b) / b.w - o);
  glm::vec3 cam = s.camera.position;
  glm::vec3 p = o + d * (-o.y / d.y);
  glm::vec3 toLight = s.light.towardsLight();
  // Two unit vectors across the light direction, to probe the shadow volume's sides.
  glm::vec3 u = glm::normalize(glm::cross(toLight, glm::vec3(0, 0, 1))), v = glm::cross(toLight, u);
  double dt = glm::length(p - cam) / kSteps;
  float delta = 2.5f * texelWorld;
  Bounds r;
  for (int k = 0; k < kSteps; ++k) {
    glm::vec3 xk = cam + (p - cam) * ((k + 0.5f) / kSteps);
    bool lit = RayBox(xk, toLight, kBoxMin, kBoxMax) < 0;
    bool sure = DistanceToBox(xk) > delta;
    for (int i = 0; i < 8 && sure; ++i) {
      float ang = float(i) * 0.785398f;
      glm::vec3 q = xk + delta * (std::cos(ang) * u + std::sin(ang) * v);
      sure = (RayBox(q, toLight, kBoxMin, kBoxMax) < 0) == lit;
    }
    double w = kDensity * dt * std::exp(-kDensity * dt * (k + 0.5));
    if (lit || !sure) r.hi += w;
    if (lit && sure) r.lo += w;
    r.shadowedSteps += !lit;
  }
  return r;
}

TEST_P(ShaftsTest, InScatteringIsTheCpuStepSumOfTheKnownGeometry) {
  scene::Scene s = FloatingBox(true);
  std::vector<uint8_t> plain = Render(s, {})->ReadColor();
  std::vector<uint8_t> shafts = Render(s, Shafts("none"))->ReadColor();
  std::vector<int> floor = AnalyticFloor(s, W, H);
  // The map is fitted to the scene's bounds: its texels are at most the bounds' diagonal / 256 wide.
  float texelWorld = glm::length(s.bounds.extent()) / 256.0f;
  int checked = 0, throughShadow = 0, wrong = 0, undecided = 0;
  double worst = 0;
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      if (floor[y * W + x] < 0) continue;
      size_t i = (size_t(y) * W + x) * 4;
      ASSERT_LT(shafts[i], 255) << "saturated at " << x << "," << y << ": lower kDensity";
      double gpu = (Linear(shafts[i]) - Linear(plain[i])) / s.light.color.r;
      Bounds b = CpuInScatter(s, x, y, texelWorld);
      double tol = (HalfStep(shafts[i]) + HalfStep(plain[i])) / s.light.color.r + 1e-4;
      double off = std::max(b.lo - tol - gpu, gpu - b.hi - tol);
      worst = std::max(worst, std::max(0.0, off + tol));
      if (off > 0 && wrong < 5) std::printf("pixel %u,%u: gpu %.4f, cpu [%.4f, %.4f]\n", x, y, gpu, b.lo, b.hi);
      undecided += b.hi > b.lo;
      wrong += off > 0;
      ++checked;
      throughShadow += b.shadowedSteps > 4;
    }
  std::printf("[ shafts ] %d floor pixels, %d whose ray crosses the box's shadow, %d with steps near its edge; largest |gpu - cpu bounds| %.5f\n", checked,
              throughShadow, undecided, worst);
  EXPECT_GT(checked, int(W * H / 3));
  EXPECT_GT(throughShadow, 50) << "the camera must look through the shadow volume";
  EXPECT_EQ(wrong, 0);
}

TEST_P(ShaftsTest, ShaftsOffIsTheTechniqueWithoutThem) {
  scene::Scene s = FloatingBox(true);
  std::vector<uint8_t> reference = Render(s, {})->ReadColor();
  std::vector<uint8_t> off = Render(s, {{"shafts", "0"}, {"shaft_steps", "7"}, {"shaft_density", "3"}})->ReadColor();
  EXPECT_EQ(CompareImages("shafts-off", W, H, reference.data(), off.data(), 0), 0u);
  std::vector<uint8_t> on = Render(s, Shafts("none"))->ReadColor();
  EXPECT_GT(CompareImages("shafts-on", W, H, reference.data(), on.data(), 0), W * H / 4) << "shafts=1 must change the picture";
}

TEST_P(ShaftsTest, WalkingPerSecondaryTexelGivesThePlainMarchAndSkipsLookups) {
  scene::Scene s = FloatingBox(true);
  std::vector<uint8_t> reference = Render(s, Shafts("none"))->ReadColor();
  for (const char* accel : {"minmax", "hpsm"}) {
    for (const char* surface : {"none", "same"}) {
      std::map<std::string, std::string> p = Shafts(accel);
      if (std::string(surface) == "same") p["accel"] = accel;
      std::unique_ptr<tech::Renderer> r = Render(s, p);
      std::vector<uint8_t> img = r->ReadColor();
      auto* source = dynamic_cast<const tech::ShaftCounterSource*>(&r->technique());
      ASSERT_NE(source, nullptr);
      tech::ShaftCounts c = source->ShaftSteps();
      std::printf("[ shafts ] shaft_accel=%s accel=%s: %llu steps looked up, %llu skipped (%.3f)\n", accel, std::string(surface) == "same" ? accel : "none",
                  (unsigned long long)c.lookedUp, (unsigned long long)c.skipped, c.skippedFraction());
      EXPECT_EQ(CompareImages(std::string("shafts-") + accel + "-" + surface, W, H, reference.data(), img.data(), 0), 0u) << accel << " " << surface;
      EXPECT_GT(c.lookedUp, 0u) << "the shadow's edges need lookups";
      // Blocks of 8 texels (2 with accel=minmax's hw2x2 footprint) over air and a flat floor: most
      // runs lie wholly in front of the floor and outside the box's shadow. Measured 0.965 to 0.995.
      EXPECT_GT(c.skippedFraction(), 0.9) << accel << " " << surface;
    }
  }
}

TEST_P(ShaftsTest, BadParametersAreRefusedNamingTheParameter) {
  auto refuses = [&](std::map<std::string, std::string> p, const std::string& name) {
    std::unique_ptr<tech::Technique> t = tech::CreateTechnique("basic");
    try {
      t->Configure(device(), tech::ParamValues::Parse("basic", t->Params(), p));
      ADD_FAILURE() << "accepted, expected an error naming " << name;
    } catch (const std::exception& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  };
  refuses({{"shafts", "2"}}, "shafts");
  refuses({{"shafts", "1"}, {"shaft_steps", "0"}}, "shaft_steps");
  refuses({{"shafts", "1"}, {"shaft_density", "0"}}, "shaft_density");
  refuses({{"shafts", "1"}, {"shaft_density", "-1"}}, "shaft_density");
  refuses({{"shafts", "1"}, {"shaft_accel", "fast"}}, "shaft_accel");
  refuses({{"shaft_accel", "hpsm"}}, "shaft_accel");
  refuses({{"shafts", "1"}, {"shaft_accel", "hpsm"}, {"accel", "minmax"}}, "shaft_accel");
  refuses({{"shafts", "1"}, {"shaft_accel", "minmax"}, {"hpsm_block", "6"}}, "hpsm_block");
  refuses({{"shafts", "1"}, {"shaft_accel", "hpsm"}, {"hpsm_block", "256"}, {"resolution", "128"}}, "hpsm_block");
}

SP_INSTANTIATE_BACKEND_TESTS(ShaftsTest);

}  // namespace
}  // namespace sp::test
