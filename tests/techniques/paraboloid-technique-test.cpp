// The paraboloid technique: the hemisphere mapping inverts and both hemispheres meet at the rim
// (CPU); in the cube technique's closed room around a point light (walls split finely, since the
// technique's known error grows with triangle size), tessellated spheres in every direction and
// one centred on the seam plane cast exactly the shadows a CPU segment-sphere test gives, for
// every axis (both backends, validation on); both backends draw the same images; bad light
// choices are errors. The known failure on coarse geometry is measured in
// tests/eval/paraboloid-bench-test.cpp.
#include <random>

#include "backend-test.h"
#include "technique-renderer.h"
#include "cross-backend.h"
#include "cube-room.h"
#include "paraboloid/paraboloid-map.h"
#include <sp/tech/renderer.h>

namespace sp::test {
namespace {

namespace pb = tech::paraboloid;

TEST(ParaboloidMap, HemispheresMapOntoTheUnitDiskAndMeetAtTheRim) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const glm::vec3 light(0.4f, 2.6f, -0.3f);
  for (int axis = 0; axis < 3; ++axis) {
    for (int h = 0; h < 2; ++h) {
      glm::mat4 view = pb::HemisphereView(axis, h, light);
      EXPECT_LT(glm::length(glm::vec3(view * glm::vec4(light, 1.0f))), 1e-6f);
      glm::vec3 a(0.0f);
      a[axis] = h == 0 ? 1.0f : -1.0f;
      glm::vec3 onAxis(view * glm::vec4(light + 3.0f * a, 1.0f));
      EXPECT_NEAR(onAxis.z, 3.0f, 1e-5f);
      EXPECT_NEAR(glm::length(pb::Ndc(onAxis)), 0.0f, 1e-6f);  // the axis is the disk's centre
    }
    for (int i = 0; i < 1000; ++i) {
      glm::vec3 d(u(rng), u(rng), u(rng));
      if (glm::length(d) < 0.1f) continue;
      int h = pb::HemisphereOf(axis, d);
      glm::vec3 f(pb::HemisphereView(axis, h, light) * glm::vec4(light + d, 1.0f));
      ASSERT_GE(f.z, 0.0f);
      glm::vec2 ndc = pb::Ndc(f);
      ASSERT_LE(glm::length(ndc), 1.0f + 1e-6f);
      ASSERT_LT(glm::distance(pb::Direction(ndc), glm::normalize(f)), 1e-5f);
      // The seam: a direction in the plane through the light lies on the rim of both maps, at
      // mirrored points (the back frame negates the axis only).
      glm::vec3 s = d;
      s[axis] = 0.0f;
      if (glm::length(s) < 0.1f) continue;
      glm::vec2 n0 = pb::Ndc(glm::vec3(pb::HemisphereView(axis, 0, light) * glm::vec4(light + s, 1.0f)));
      glm::vec2 n1 = pb::Ndc(glm::vec3(pb::HemisphereView(axis, 1, light) * glm::vec4(light + s, 1.0f)));
      ASSERT_NEAR(glm::length(n0), 1.0f, 1e-5f);
      ASSERT_LT(glm::distance(n0, n1), 1e-5f);
    }
  }
  // Drawn past the rim by 2 texels of a 1024 map: NDC radius 1 + 4 / 1024.
  float z = pb::DiscardZ(1024, 2.0f);
  EXPECT_LT(z, 0.0f);
  EXPECT_NEAR(glm::length(pb::Ndc({std::sqrt(1 - z * z), 0.0f, z})), 1.0f + 4.0f / 1024.0f, 1e-5f);
  EXPECT_NEAR(pb::Depth(0.05f, 0.05f, 16.0f), 0.0f, 1e-7f);
  EXPECT_NEAR(pb::Depth(16.0f, 0.05f, 16.0f), 1.0f, 1e-7f);
}

// The cube room with its walls split into 64 x 64 cells (0.16 m x 0.09 m), and one more sphere
// centred on the seam plane of a y-axis map (the plane y = light.y), its shadow half in each
// hemisphere on the +Z wall.
struct ParaboloidRoom {
  CubeRoom room = MakeCubeRoom();
  size_t seamSphere = 0;
  ParaboloidRoom() {
    room.scene.meshes[0] = scene::MakePlane(64);
    seamSphere = room.spheres.size();
    room.spheres.push_back({room.light + glm::normalize(glm::vec3(0.6f, 0.0f, 1.0f)) * 1.9f, 0.3f});
    uint32_t sphere = room.scene.instances.back().mesh;
    const CubeRoom::Sphere& s = room.spheres.back();
    room.scene.addInstance(sphere, glm::scale(glm::translate(glm::mat4(1.0f), s.center), glm::vec3(2 * s.radius)), glm::vec3(0.5f));
    room.scene.finalize();
  }
};

// Shadow pixels of `occluder` away from shadow edges, per side of the plane through the light
// normal to `axis`.
std::array<int, 2> ShadowPixelsPerHemisphere(const CubeRoom& room, const scene::Camera& cam, uint32_t W, uint32_t H, int occluder, int axis) {
  std::vector<RoomPixel> e = AnalyticRoom(room, cam, W, H);
  std::array<int, 2> n{};
  for (uint32_t y = 1; y + 1 < H; ++y)
    for (uint32_t x = 1; x + 1 < W; ++x) {
      const RoomPixel& p = e[y * W + x];
      if (p.code != 1 || p.occluder != occluder) continue;
      bool inside = true;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) inside &= e[(y + dy) * W + (x + dx)].code == 1;
      if (inside) ++n[pb::HemisphereOf(axis, p.surface - room.light)];
    }
  return n;
}

class ParaboloidTechniqueTest : public BackendTest {
 public:
  std::unique_ptr<tech::Renderer> MakeRenderer(const scene::Scene& s, uint32_t w, uint32_t h, const std::map<std::string, std::string>& params) {
    return MakeTechniqueRenderer(device(), "paraboloid", s, w, h, params);
  }
};

// Every pixel more than one pixel from a change of the expected answer is right, for each axis and
// both depth modes, from the cube test's three cameras and one facing the seam sphere's shadow.
// 1024 texels per hemisphere: a paraboloid map's texels span 4 / 1024 rad at its centre and half
// that at its rim, so its coarsest texels match those of a 512 cube face's centre.
TEST_P(ParaboloidTechniqueTest, SpheresAroundAPointLightCastTheirExactShadowsAcrossTheSeam) {
  const uint32_t W = 160, H = 120;
  ParaboloidRoom pr;
  const CubeRoom& room = pr.room;
  std::vector<scene::Camera> cams = RoomCameras(room);
  scene::Camera seam = room.scene.camera;
  seam.position = {0.0f, 3.2f, 3.0f}, seam.target = {3.5f, 2.6f, 5.0f};
  cams.push_back(seam);
  struct Case {
    const char* axis;
    const char* depth;
  };
  for (Case c : {Case{"y", "vertex"}, Case{"x", "vertex"}, Case{"z", "vertex"}, Case{"y", "exact"}}) {
    SCOPED_TRACE(std::string("axis=") + c.axis + " depth=" + c.depth);
    int axis = c.axis[0] - 'x';
    std::unique_ptr<tech::Renderer> r = MakeRenderer(room.scene, W, H, {{"resolution", "1024"}, {"axis", c.axis}, {"depth", c.depth}});
    RoomCheck total;
    std::array<int, 2> seamShadow{}, shadowPerHemisphere{};
    for (const scene::Camera& cam : cams) {
      r->RenderFrame(cam, room.scene.light);
      total.add(CheckRoomImage(room, cam, r->ReadColor(), W, H));
      std::array<int, 2> s = ShadowPixelsPerHemisphere(room, cam, W, H, int(pr.seamSphere), axis);
      for (int o = 0; o < int(room.spheres.size()); ++o) {
        std::array<int, 2> all = ShadowPixelsPerHemisphere(room, cam, W, H, o, axis);
        shadowPerHemisphere[0] += all[0], shadowPerHemisphere[1] += all[1];
      }
      seamShadow[0] += s[0], seamShadow[1] += s[1];
    }
    EXPECT_EQ(total.wrong, 0) << "of " << total.checked << " pixels checked";
    EXPECT_GT(total.checked, 25000);
    EXPECT_GT(total.shadowed, 2000);
    EXPECT_GT(shadowPerHemisphere[0], 500);
    EXPECT_GT(shadowPerHemisphere[1], 500);
    if (axis == 1) {
      EXPECT_GT(seamShadow[0], 40) << "the seam sphere's shadow above the seam";
      EXPECT_GT(seamShadow[1], 40) << "the seam sphere's shadow below the seam";
    }
    std::printf("paraboloid axis=%s depth=%s: %d wrong of %d checked, %d in shadow (%d / %d per hemisphere; seam sphere %d / %d)\n", c.axis, c.depth,
                total.wrong, total.checked, total.shadowed, shadowPerHemisphere[0], shadowPerHemisphere[1], seamShadow[0], seamShadow[1]);
  }
}

SP_INSTANTIATE_BACKEND_TESTS(ParaboloidTechniqueTest);

// Bad input refused by name, no pixels checked: these run on the null backend too.
class ParaboloidTechniqueValidationTest : public ParaboloidTechniqueTest {};

TEST_P(ParaboloidTechniqueValidationTest, BadLightChoicesAreErrors) {
  CubeRoom room = MakeCubeRoom();
  ExpectBadPointLightChoicesRefused(room, [&](const std::map<std::string, std::string>& p) { MakeRenderer(room.scene, 16, 16, p)->RenderFrame(room.scene.camera, room.scene.light); });
  scene::Scene dark = scene::MakeBuiltinScene("default");  // no point light at all
  try {
    MakeRenderer(dark, 16, 16, {})->RenderFrame(dark.camera, dark.light);
    ADD_FAILURE() << "expected an error for a scene without point lights";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'default' has 0 point light"), std::string::npos) << e.what();
  }
  try {
    MakeRenderer(room.scene, 16, 16, {{"axis", "w"}});
    ADD_FAILURE() << "expected an error for an unknown axis";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("axis"), std::string::npos) << e.what();
  }
}

SP_INSTANTIATE_VALIDATION_TESTS(ParaboloidTechniqueValidationTest);

// Both backends draw the same pixels: the exact room, and the coarse room where the linear
// interpolation across large triangles shapes the shadows.
class ParaboloidTechniqueCrossBackend : public ::testing::TestWithParam<const char*> {};

TEST_P(ParaboloidTechniqueCrossBackend, RendersIdenticallyOnBothBackends) {
  const uint32_t W = 160, H = 120;
  ParaboloidRoom pr;
  scene::Scene s = std::string(GetParam()) == "room" ? pr.room.scene : scene::MakeBuiltinScene(GetParam());
  for (const char* depth : {"vertex", "exact"}) {
    CrossBackendFrame f = RenderOnBothBackends("paraboloid", {{"resolution", "512"}, {"depth", depth}}, s, W, H);
    size_t differing = CompareImages(std::string("paraboloid-") + GetParam() + "-" + depth, W, H, f.images[0].data(), f.images[1].data(), 0);
    if (f.mesa) {
      EXPECT_EQ(differing, 0u) << depth << ": Vulkan and GL images differ on Mesa; see the heat map in " << TestOutputDir();
    } else {
      EXPECT_LT(differing, size_t(W * H / 200)) << depth << ": more than 0.5% of pixels differ across backends";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, ParaboloidTechniqueCrossBackend, ::testing::Values("room", "paraboloid-coarse"),
                         [](const auto& info) { return std::string(info.param) == "room" ? std::string("room") : std::string("coarse"); });

}  // namespace
}  // namespace sp::test
