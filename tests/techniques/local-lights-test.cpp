// Local lights in the lit pass: a floor under a point light and a spot light, shaded as glTF
// recommends (range falloff, spot cone), compared pixel by pixel with the same lighting computed on
// the CPU; the renderer refuses scenes it cannot shade.
#include <algorithm>
#include <cmath>
#include <glm/ext/matrix_transform.hpp>

#include "backend-test.h"
#include "technique-renderer.h"
#include <sp/tech/renderer.h>

namespace sp::test {
namespace {

// A 16 x 16 floor seen from straight above; the directional light is black, so what is not ambient
// comes from the local lights.
scene::Scene LitFloor() {
  scene::Scene s;
  s.name = "local-lights-floor";
  s.addInstance(s.addMesh(scene::MakePlane(4)), glm::scale(glm::mat4(1.0f), glm::vec3(16, 1, 16)), glm::vec3(0.8f, 0.7f, 0.6f));
  s.camera.position = {0.0f, 14.0f, 0.001f};
  s.camera.target = {0.0f, 0.0f, 0.0f};
  s.camera.up = {0.0f, 0.0f, -1.0f};
  s.camera.fovY = glm::radians(60.0f);
  s.camera.nearZ = 1.0f;
  s.camera.farZ = 40.0f;
  s.light.color = glm::vec3(0.0f);
  s.light.ambient = 0.05f;
  s.pointLights.push_back({{-3.5f, 2.0f, 1.0f}, {3.0f, 2.0f, 1.0f}, 6.0f});
  scene::SpotLight spot;
  spot.position = {3.0f, 3.0f, -1.0f};
  spot.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.0f));
  spot.color = {2.0f, 4.0f, 6.0f};
  spot.range = 9.0f;
  spot.innerConeAngle = glm::radians(20.0f);
  spot.outerConeAngle = glm::radians(35.0f);
  s.spotLights.push_back(spot);
  s.finalize();
  return s;
}

// glTF's recommended falloff (KHR_lights_punctual), as documented in scene.h.
glm::vec3 CpuLocalLighting(const scene::Scene& s, glm::vec3 p, glm::vec3 n) {
  glm::vec3 sum(0.0f);
  auto add = [&](glm::vec3 pos, glm::vec3 color, float range, float cone) {
    glm::vec3 v = pos - p;
    double d = glm::length(v);
    double r = d / range;
    double falloff = std::clamp(1.0 - r * r * r * r, 0.0, 1.0) / (d * d);
    double ndotl = std::max(0.0, double(glm::dot(n, v)) / d);
    sum += color * float(falloff * ndotl * cone);
  };
  for (const scene::PointLight& l : s.pointLights) add(l.position, l.color, l.range, 1.0f);
  for (const scene::SpotLight& l : s.spotLights) {
    double cd = glm::dot(glm::normalize(l.direction), glm::normalize(p - l.position));
    double ci = std::cos(double(l.innerConeAngle)), co = std::cos(double(l.outerConeAngle));
    double t = std::clamp((cd - co) / std::max(1e-3, ci - co), 0.0, 1.0);
    add(l.position, l.color, l.range, float(t * t));
  }
  return sum;
}

int EncodeSrgb(double v) {
  v = std::clamp(v, 0.0, 1.0);
  double e = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
  return int(std::lround(e * 255.0));
}

class LocalLightsTest : public BackendTest {
 protected:
  std::unique_ptr<tech::Renderer> MakeRenderer(const scene::Scene& s, uint32_t w, uint32_t h) {
    return MakeTechniqueRenderer(device(), "basic", s, w, h, {{"resolution", "256"}});
  }
};

TEST_P(LocalLightsTest, FloorUnderAPointAndASpotLightMatchesTheCpuLighting) {
  const uint32_t W = 128, H = 128;
  scene::Scene s = LitFloor();
  std::unique_ptr<tech::Renderer> r = MakeRenderer(s, W, H);
  r->RenderFrame(s.camera, s.light);
  std::vector<uint8_t> img = r->ReadColor();

  glm::mat4 inv = glm::inverse(s.camera.projection(float(W) / H) * s.camera.view());
  const glm::vec3 albedo = s.instances[0].albedo;
  int checked = 0, wrong = 0, maxDiff = 0, litByPoint = 0, litBySpot = 0, ambientOnly = 0;
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      glm::vec4 a = inv * glm::vec4((x + 0.5f) / W * 2 - 1, 1 - (y + 0.5f) / H * 2, 0.0f, 1.0f);
      glm::vec4 b = inv * glm::vec4((x + 0.5f) / W * 2 - 1, 1 - (y + 0.5f) / H * 2, 1.0f, 1.0f);
      glm::vec3 o = glm::vec3(a) / a.w, d = glm::vec3(b) / b.w - o;
      glm::vec3 p = o + d * (-o.y / d.y);
      if (std::abs(p.x) > 7.9f || std::abs(p.z) > 7.9f) continue;
      glm::vec3 local = CpuLocalLighting(s, p, {0, 1, 0});
      ++checked;
      litByPoint += p.x < 0 && local.r > 0.1f;
      litBySpot += p.x > 0 && local.b > 0.1f;
      ambientOnly += local.r + local.g + local.b == 0.0f;
      for (int c = 0; c < 3; ++c) {
        int expected = EncodeSrgb(albedo[c] * (s.light.ambient + local[c]));
        int diff = std::abs(int(img[(y * W + x) * 4 + c]) - expected);
        maxDiff = std::max(maxDiff, diff);
        // Rasterized positions differ from the CPU's ray-floor intersection by rounding; where the
        // lighting is steep (right under a light) that is worth a level or two of sRGB.
        if (diff > 3 && ++wrong <= 5) ADD_FAILURE() << "pixel " << x << "," << y << " channel " << c << ": " << int(img[(y * W + x) * 4 + c]) << ", expected " << expected;
      }
    }
  EXPECT_EQ(wrong, 0) << "max difference " << maxDiff;
  EXPECT_GT(checked, int(W * H / 2));
  EXPECT_GT(litByPoint, 500) << "the point light's pool must be on the floor";
  EXPECT_GT(litBySpot, 300) << "the spot light's cone must be on the floor";
  EXPECT_GT(ambientOnly, 500) << "the floor must have pixels out of every light's reach";
  if (wrong) WritePng(TestOutputDir() / "local-lights.png", W, H, img.data());
}

SP_INSTANTIATE_BACKEND_TESTS(LocalLightsTest);

// Bad input refused by name, no pixels checked: these run on the null backend too.
class LocalLightsValidationTest : public LocalLightsTest {};

// Scenes without local lights render as before (covered by every other technique test); scenes
// with more lights than the lit pass holds, or a light it cannot shade, are refused by name.
TEST_P(LocalLightsValidationTest, RendererRefusesLightsItCannotShade) {
  scene::Scene s = LitFloor();
  for (uint32_t i = 0; i < tech::kMaxLocalLights; ++i) s.pointLights.push_back({{0, 1, 0}, {1, 1, 1}, 3.0f});
  try {
    MakeRenderer(s, 16, 16);
    ADD_FAILURE() << "expected an error for " << s.pointLights.size() + s.spotLights.size() << " local lights";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("local-lights-floor"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(std::to_string(tech::kMaxLocalLights)), std::string::npos) << e.what();
  }
  s = LitFloor();
  s.spotLights[0].outerConeAngle = s.spotLights[0].innerConeAngle;
  try {
    MakeRenderer(s, 16, 16);
    ADD_FAILURE() << "expected an error for a spot light without a cone";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("local light 1 (spot)"), std::string::npos) << e.what();
  }
  s = LitFloor();
  s.pointLights[0].range = 0.0f;
  EXPECT_THROW(MakeRenderer(s, 16, 16), std::invalid_argument);
}

SP_INSTANTIATE_VALIDATION_TESTS(LocalLightsValidationTest);

}  // namespace
}  // namespace sp::test
