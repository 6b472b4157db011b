// The cube technique: the face matrices agree with the cube-map face table (CPU); in a closed room
// around a point light, spheres in every face direction and one on a face edge cast exactly the
// shadows a CPU segment-sphere test gives (both backends, validation on); both backends draw the
// same image; bad light choices are errors.
#include <array>
#include <random>

#include "backend-test.h"
#include "technique-renderer.h"
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
    return MakeTechniqueRenderer(device(), "cube", s, w, h, params);
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
  // A kernel's taps reach its half width plus the bilinear texel; its penumbra on the room's walls
  // stays within the one-pixel band at 512 texels per face up to 5x5.
  float reach = params.count("filter") && params.at("filter") != "hw2x2" ? float(std::stoi(params.at("kernel")) / 2 + 1) : 0.0f;
  CubeRoom room = MakeCubeRoom();
  ExpectExactRoomShadows(*t.MakeRenderer(room.scene, 160, 120, params), room, 160, 120, reach, std::stof(params.at("resolution")));
}

// Kernels wider than 2x2 step across face edges onto the neighbouring face: the exact shadows
// still hold (the edge sphere's on both sides of its edge), on both storages.
TEST_P(CubeTechniqueTest, WideKernelsKeepExactShadowsAcrossFaceEdges) {
  CheckRoomShadows(*this, {{"resolution", "512"}, {"filter", "box"}, {"kernel", "5"}});
  CheckRoomShadows(*this, {{"resolution", "512"}, {"filter", "gauss"}, {"kernel", "5"}});
  CheckRoomShadows(*this, {{"resolution", "512"}, {"filter", "box"}, {"kernel", "5"}, {"storage", "radial"}});
}

// Pixels of the bare room (no occluder) more than `tolerance` sRGB levels darker than the CPU's
// unshadowed lighting, over the three room cameras; `kernel` taps one texel apart at `resolution`.
// Points within the kernel's reach of a second wall are not counted (WithinKernelOfACorner).
int DarkenedPixelsOfTheBareRoom(CubeTechniqueTest& t, const std::map<std::string, std::string>& params, int tolerance) {
  const uint32_t W = 160, H = 120;
  const float resolution = std::stof(params.at("resolution")), reach = std::stoi(params.at("kernel")) / 2 + 1;
  CubeRoom room = MakeCubeRoom(false);
  std::unique_ptr<tech::Renderer> r = t.MakeRenderer(room.scene, W, H, params);
  int darkened = 0, checked = 0;
  for (const scene::Camera& cam : RoomCameras(room)) {
    r->RenderFrame(cam, room.scene.light);
    std::vector<uint8_t> img = r->ReadColor();
    std::vector<RoomPixel> expected = AnalyticRoom(room, cam, W, H);
    for (uint32_t i = 0; i < W * H; ++i) {
      const RoomPixel& e = expected[i];
      if (e.code != 0) continue;
      if (WithinKernelOfACorner(room, e, reach, resolution)) continue;
      int lit = EncodeSrgb8(0.8 * (room.scene.light.ambient + RoomLocalLight(room.scene, e.surface, e.normal)));
      ++checked;
      if (img[i * 4 + 1] < lit - tolerance && ++darkened <= 3)
        ADD_FAILURE() << "pixel " << i % W << "," << i / W << " at (" << e.surface.x << "," << e.surface.y << "," << e.surface.z << ") of the camera at " << cam.position.x << ": " << int(img[i * 4 + 1]) << " where the unshadowed light gives " << lit;
    }
  }
  EXPECT_GT(checked, 30000);
  return darkened;
}

// A wide kernel at a coarse resolution, in a room where nothing casts: no pixel may darken, on the
// walls the light grazes (the taps' receiver plane) or along the lines where the cube's face edges
// fall on the walls (taps on the neighbouring face). Comparing every tap with the receiver's own
// depth instead darkened 17,971 / 4,521 pixels (box / gauss, depth storage) and 56,590 / 10,657
// (radial); the receiver plane without its one-texel footprint left 80 (gauss, depth) along the
// face edges, where a tap's 2x2 texels straddle two faces.
TEST_P(CubeTechniqueTest, WideKernelsLeaveNoSeamAlongFaceEdges) {
  for (const char* filter : {"box", "gauss"})
    for (const char* storage : {"depth", "radial"})
      EXPECT_EQ(DarkenedPixelsOfTheBareRoom(*this, {{"resolution", "128"}, {"filter", filter}, {"kernel", "9"}, {"storage", storage}}, 3), 0)
          << filter << " 9x9, storage=" << storage;
}

// lights=all shadows every light that lights what the camera sees: the room's light split into
// two half-intensity lights at the same place must cast the one light's exact shadows (with one of
// the two shadowed, the shadows would be half lit), and a third light far outside the room, whose
// range meets nothing the camera sees, gets no cube (no more faces drawn than without it).
TEST_P(CubeTechniqueTest, AllLightsShadowsTheLightsThatLightWhatTheCameraSees) {
  const uint32_t W = 160, H = 120;
  CubeRoom room = MakeCubeRoom();
  scene::Scene split = room.scene;
  split.pointLights[0].color *= 0.5f;
  split.pointLights.push_back(split.pointLights[0]);
  scene::Scene withFar = split;
  withFar.pointLights.push_back({{200.0f, 3.0f, 0.0f}, {5.0f, 5.0f, 5.0f}, 10.0f});
  uint32_t faces[2] = {};
  int wrongWithOne = 0;
  for (const scene::Camera& cam : RoomCameras(room)) {
    const scene::Scene* scenes[2] = {&split, &withFar};
    for (int k = 0; k < 2; ++k) {
      std::unique_ptr<tech::Renderer> r = MakeRenderer(*scenes[k], W, H, {{"resolution", "512"}, {"lights", "all"}});
      r->RenderFrame(cam, room.scene.light);
      RoomCheck c = CheckRoomImage(room, cam, r->ReadColor(), W, H);
      EXPECT_EQ(c.wrong, 0) << "of " << c.checked;
      faces[k] += r->technique().Stats().layersRendered;
    }
    ::testing::ScopedTrace trace(__FILE__, __LINE__, "lights=one, expected to fail");
    std::unique_ptr<tech::Renderer> one = MakeRenderer(split, W, H, {{"resolution", "512"}});
    one->RenderFrame(cam, room.scene.light);
    std::vector<uint8_t> img = one->ReadColor();
    std::vector<RoomPixel> e = AnalyticRoom(room, cam, W, H);
    for (uint32_t i = 0; i < W * H; ++i)
      if (e[i].code == 1) wrongWithOne += img[i * 4 + 1] > EncodeSrgb8(0.8 * room.scene.light.ambient) + 8;
  }
  EXPECT_GT(faces[0], 6u) << "both lights' cubes are drawn";
  EXPECT_EQ(faces[1], faces[0]) << "the far light must get no faces";
  EXPECT_GT(wrongWithOne, 1000) << "with lights=one the other half light must light the shadows";
}

// resolution_from=screen: inside a light's range the face resolution is the largest; from far
// away, where the range sphere covers a few pixels, the smallest. The exact shadows hold with it.
TEST_P(CubeTechniqueTest, ScreenSizedResolutionFollowsTheLightsSizeOnScreen) {
  CubeRoom room = MakeCubeRoom();
  std::map<std::string, std::string> params = {{"resolution", "512"}, {"resolution_from", "screen"}, {"min_resolution", "64"}};
  CheckRoomShadows(*this, params);
  std::unique_ptr<tech::Renderer> r = MakeRenderer(room.scene, 160, 120, params);
  r->RenderFrame(room.scene.camera, room.scene.light);
  EXPECT_EQ(r->technique().Stats().memoryBytes, 6u * 512 * 512 * 4);
  scene::Camera far = room.scene.camera;
  far.position = {0.0f, 3.0f, 200.0f};
  far.target = {0.0f, 3.0f, 0.0f};
  far.farZ = 400.0f;
  r->RenderFrame(far, room.scene.light);
  EXPECT_EQ(r->technique().Stats().memoryBytes, 6u * 64 * 64 * 4);  // 16 / 200 of a 90-degree view of 120 pixels: 10 texels wanted
}

// King: skip the faces whose frustum meets no visible receiver (ExpectTheFaceWithoutReceiversSkipped).
TEST_P(CubeTechniqueTest, FacesWithoutVisibleReceiversAreSkipped) {
  ExpectTheFaceWithoutReceiversSkipped([&](const scene::Scene& s, uint32_t w, uint32_t h, int cull) {
    return MakeRenderer(s, w, h, {{"resolution", "256"}, {"cull_faces", std::to_string(cull)}});
  });
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

SP_INSTANTIATE_BACKEND_TESTS(CubeTechniqueTest);

// Bad input refused by name, no pixels checked: these run on the null backend too.
class CubeTechniqueValidationTest : public CubeTechniqueTest {};

TEST_P(CubeTechniqueValidationTest, BadLightChoicesAreErrors) {
  CubeRoom room = MakeCubeRoom();
  ExpectBadPointLightChoicesRefused(room, [&](const std::map<std::string, std::string>& p) { MakeRenderer(room.scene, 16, 16, p)->RenderFrame(room.scene.camera, room.scene.light); });
}

SP_INSTANTIATE_VALIDATION_TESTS(CubeTechniqueValidationTest);

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
