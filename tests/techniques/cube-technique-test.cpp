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
  std::unique_ptr<tech::Renderer> r = t.MakeRenderer(room.scene, W, H, params);
  RoomCheck total;
  for (const scene::Camera& cam : RoomCameras(room)) {
    r->RenderFrame(cam, room.scene.light);
    total.add(CheckRoomImage(room, cam, r->ReadColor(), W, H));
  }
  EXPECT_EQ(total.wrong, 0) << "of " << total.checked << " pixels checked";
  EXPECT_GT(total.checked, 20000);
  EXPECT_GT(total.shadowed, 2000);
  for (int f = 0; f < 6; ++f) EXPECT_GT(total.shadowPerFace[f], 40) << "shadow pixels checked on face " << f;
  // The edge sphere's shadow is checked on both sides of the +X/-Y edge.
  EXPECT_GT(total.edgeShadowPerFace[0], 20);
  EXPECT_GT(total.edgeShadowPerFace[3], 20);
}

// Face culling: a camera looking down at one corner of the floor sees only part of the cube; the
// faces it cannot see are skipped (fewer triangles drawn) and the picture is the same as with
// every face rendered. The exact-shadow test above runs with culling on (the default).
TEST_P(CubeTechniqueTest, FacesTheCameraCannotSeeAreSkippedWithoutChangingThePicture) {
  const uint32_t W = 96, H = 72;
  CubeRoom room = MakeCubeRoom();
  scene::Camera cam = room.scene.camera;
  cam.position = {-3.5f, 2.0f, -3.0f};
  cam.target = {-4.0f, 0.0f, -3.5f};
  cam.fovY = glm::radians(40.0f);
  std::vector<uint8_t> img[2];
  uint64_t triangles[2] = {};
  for (int cull = 0; cull < 2; ++cull) {
    std::unique_ptr<tech::Renderer> r = MakeRenderer(room.scene, W, H, {{"resolution", "256"}, {"cull_faces", std::to_string(cull)}});
    r->RenderFrame(cam, room.scene.light);
    img[cull] = r->ReadColor();
    triangles[cull] = r->technique().Stats().trianglesSubmitted;
  }
  EXPECT_LT(triangles[1], triangles[0]) << "the faces pointing away from the corner must be skipped";
  EXPECT_EQ(CompareImages("cull-faces", W, H, img[0].data(), img[1].data(), 0), 0u);
  // Each camera of the exact-shadow test still sees what it did (culling on there): the faces
  // skipped for it hold nothing it samples.
  for (const scene::Camera& c : RoomCameras(room)) {
    std::vector<uint8_t> both[2];
    for (int cull = 0; cull < 2; ++cull) {
      std::unique_ptr<tech::Renderer> r = MakeRenderer(room.scene, W, H, {{"resolution", "256"}, {"cull_faces", std::to_string(cull)}});
      r->RenderFrame(c, room.scene.light);
      both[cull] = r->ReadColor();
    }
    EXPECT_EQ(CompareImages("cull-faces-room", W, H, both[0].data(), both[1].data(), 0), 0u);
  }
}

TEST_P(CubeTechniqueTest, BadLightChoicesAreErrors) {
  CubeRoom room = MakeCubeRoom();
  ExpectBadPointLightChoicesRefused(room, [&](const std::map<std::string, std::string>& p) { MakeRenderer(room.scene, 16, 16, p)->RenderFrame(room.scene.camera, room.scene.light); });
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
