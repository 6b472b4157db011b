// The cube technique: the face matrices agree with the cube-map face table (CPU); in a closed room
// around a point light, spheres in every face direction and one on a face edge cast exactly the
// shadows a CPU segment-sphere test gives (both backends, validation on); both backends draw the
// same image; bad light choices are errors.
#include <array>
#include <random>

#include "backend-test.h"
#include "cross-backend.h"
#include "cube-room.h"
#include "cube/cube-faces.h"
#include <sp/tech/renderer.h>

namespace sp::test {
namespace {

// Face f's clip transform puts a direction d at NDC (sc / ma, -tc / ma) with window z = WindowZ(d),
// and d lies inside the frustum of the face FaceOf(d) picks.
TEST(CubeFaces, FaceMatricesFollowTheCubeMapFaceTable) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const glm::vec3 light(0.4f, 2.6f, -0.3f);
  const float n = 0.05f, f = 16.0f;
  for (int i = 0; i < 1000; ++i) {
    glm::vec3 d(u(rng), u(rng), u(rng));
    if (glm::length(d) < 0.1f) continue;
    d *= 5.0f;
    int face = tech::cube::FaceOf(d);
    tech::cube::FaceAxes ax = tech::cube::Face(face);
    float ma = glm::dot(ax.major, d);
    ASSERT_NEAR(ma, std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)}), 1e-5f);
    glm::vec4 c = tech::cube::FaceViewProj(face, light, n, f) * glm::vec4(light + d, 1.0f);
    ASSERT_NEAR(c.x / c.w, glm::dot(ax.s, d) / ma, 1e-5f);
    ASSERT_NEAR(c.y / c.w, -glm::dot(ax.t, d) / ma, 1e-5f);
    ASSERT_NEAR(c.z / c.w, tech::cube::WindowZ(d, n, f), 1e-5f);
    ASSERT_LE(std::abs(c.x / c.w), 1.0f + 1e-6f);
    ASSERT_LE(std::abs(c.y / c.w), 1.0f + 1e-6f);
  }
  // The D3D11 table itself, spot-checked: +X's u grows towards -z, -Y's v grows towards -z.
  EXPECT_EQ(tech::cube::Face(0).s, glm::vec3(0, 0, -1));
  EXPECT_EQ(tech::cube::Face(3).t, glm::vec3(0, 0, -1));
  EXPECT_NEAR(tech::cube::WindowZ({0, 0, n}, n, f), 0.0f, 1e-6f);
  EXPECT_NEAR(tech::cube::WindowZ({f, 0, 0}, n, f), 1.0f, 1e-6f);
}

class CubeTechniqueTest : public BackendTest {
 public:
  std::unique_ptr<tech::Renderer> MakeRenderer(const scene::Scene& s, uint32_t w, uint32_t h, const std::map<std::string, std::string>& params) {
    std::unique_ptr<tech::Technique> t = tech::CreateTechnique("cube");
    t->Configure(device(), tech::ParamValues::Parse("cube", t->Params(), params));
    return std::make_unique<tech::Renderer>(device(), s, std::move(t), w, h);
  }
};

int EncodeSrgb8(double v) {
  v = std::clamp(v, 0.0, 1.0);
  return int(std::lround((v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055) * 255.0));
}

// Renders the room from three cameras that together see all six faces' shadows and the edge
// sphere's on both sides of its edge, and checks every pixel away from shadow edges.
void CheckRoomShadows(CubeTechniqueTest& t, const std::map<std::string, std::string>& params);

TEST_P(CubeTechniqueTest, SpheresAroundAPointLightCastTheirExactShadowsOnEveryFace) { CheckRoomShadows(*this, {{"resolution", "512"}}); }

// The radial-distance variant (R32_FLOAT cube, compared in the shader) gives the same shadows.
TEST_P(CubeTechniqueTest, RadialDistanceStorageCastsTheSameExactShadows) {
  CheckRoomShadows(*this, {{"resolution", "512"}, {"storage", "radial"}});
}

void CheckRoomShadows(CubeTechniqueTest& t, const std::map<std::string, std::string>& params) {
  const uint32_t W = 160, H = 120;
  CubeRoom room = MakeCubeRoom();
  const scene::PointLight& pl = room.scene.pointLights[0];
  std::unique_ptr<tech::Renderer> r = t.MakeRenderer(room.scene, W, H, params);
  scene::Camera cams[3] = {room.scene.camera, room.scene.camera, room.scene.camera};
  cams[0].position = {4.2f, 5.5f, 4.2f}, cams[0].target = {-1.5f, 0.5f, -1.5f};   // floor, -X and -Z walls
  cams[1].position = {-4.2f, 0.6f, -4.2f}, cams[1].target = {1.5f, 4.0f, 1.5f};   // ceiling, +X and +Z walls
  // cams[2]: the scene's camera, on the floor around the +X/-Y edge and the +X wall.
  std::array<int, 6> shadowPerFace{}, edgeShadowPerFace{};
  int checked = 0, wrong = 0, shadowed = 0;
  for (int ci = 0; ci < 3; ++ci) {
    r->RenderFrame(cams[ci], room.scene.light);
    std::vector<uint8_t> img = r->ReadColor();
    std::vector<RoomPixel> expected = AnalyticRoom(room, cams[ci], W, H);
    int wrongHere = 0;
    for (uint32_t y = 1; y + 1 < H; ++y)
      for (uint32_t x = 1; x + 1 < W; ++x) {
        const RoomPixel& e = expected[y * W + x];
        if (e.code != 0 && e.code != 1) continue;
        bool nearEdge = false;  // one pixel either side of any change (texel grid, 2x2 PCF)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) nearEdge |= expected[(y + dy) * W + (x + dx)].code != e.code;
        if (nearEdge) continue;
        // Lit and shadowed colours of this point (green channel), as local-lights.hlsli shades it.
        glm::vec3 v = pl.position - e.surface;
        double d = glm::length(v), q = d / pl.range;
        double local = pl.color.g * std::clamp(1 - q * q * q * q, 0.0, 1.0) / (d * d) * std::max(0.0, double(glm::dot(e.normal, v)) / d);
        int lit = EncodeSrgb8(0.8 * (room.scene.light.ambient + local)), dark = EncodeSrgb8(0.8 * room.scene.light.ambient);
        if (lit - dark < 16) continue;  // too little light to tell
        int got = img[(y * W + x) * 4 + 1];
        int shadow = std::abs(got - dark) < std::abs(got - lit) ? 1 : 0;
        ++checked;
        shadowed += e.code;
        int face = tech::cube::FaceOf(e.surface - pl.position);
        if (e.code == 1) ++shadowPerFace[face];
        if (e.code == 1 && e.occluder == int(room.edgeSphere)) ++edgeShadowPerFace[face];
        if (shadow != e.code) {
          ++wrong, ++wrongHere;
          if (wrong <= 5) ADD_FAILURE() << "camera " << ci << " pixel " << x << "," << y << " (face " << face << "): got " << got << ", expected " << (e.code ? "shadow " : "lit ") << (e.code ? dark : lit);
        }
      }
    if (wrongHere) WritePng(TestOutputDir() / ("room-" + std::to_string(ci) + ".png"), W, H, img.data());
  }
  EXPECT_EQ(wrong, 0) << "of " << checked << " pixels checked";
  EXPECT_GT(checked, 20000);
  EXPECT_GT(shadowed, 2000);
  for (int f = 0; f < 6; ++f) EXPECT_GT(shadowPerFace[f], 40) << "shadow pixels checked on face " << f;
  // The edge sphere's shadow is checked on both sides of the +X/-Y edge.
  EXPECT_GT(edgeShadowPerFace[0], 20);
  EXPECT_GT(edgeShadowPerFace[3], 20);
}

TEST_P(CubeTechniqueTest, BadLightChoicesAreErrors) {
  CubeRoom room = MakeCubeRoom();
  try {
    MakeRenderer(room.scene, 16, 16, {{"light", "1"}})->RenderFrame(room.scene.camera, room.scene.light);
    ADD_FAILURE() << "expected an error for a light the scene does not have";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("cube-room"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("1 point light"), std::string::npos) << e.what();
  }
  try {
    MakeRenderer(room.scene, 16, 16, {{"near", "20"}})->RenderFrame(room.scene.camera, room.scene.light);
    ADD_FAILURE() << "expected an error for near beyond the light's range";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("near"), std::string::npos) << e.what();
  }
}

SP_INSTANTIATE_BACKEND_TESTS(CubeTechniqueTest);

class CubeTechniqueCrossBackend : public ::testing::TestWithParam<const char*> {};

TEST_P(CubeTechniqueCrossBackend, RoomRendersIdenticallyOnBothBackends) {
  const uint32_t W = 160, H = 120;
  CubeRoom room = MakeCubeRoom();
  CrossBackendFrame f = RenderOnBothBackends("cube", {{"resolution", "256"}, {"storage", GetParam()}}, room.scene, W, H);
  size_t differing = CompareImages(std::string("cube-room-") + GetParam(), W, H, f.images[0].data(), f.images[1].data(), 0);
  if (f.mesa) {
    EXPECT_EQ(differing, 0u) << "Vulkan and GL images differ on Mesa; see the heat map in " << TestOutputDir();
  } else {
    EXPECT_LT(differing, size_t(W * H / 200)) << "more than 0.5% of pixels differ across backends";
  }
}

INSTANTIATE_TEST_SUITE_P(Storage, CubeTechniqueCrossBackend, ::testing::Values("depth", "radial"));

}  // namespace
}  // namespace sp::test
