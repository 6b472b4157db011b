// The spot technique: in the cube test room with its point light replaced by a spot light pointing
// down, the spheres inside the cone cast exactly the shadows a CPU segment-sphere test gives
// (both backends, validation on); both backends draw the same image; the lab judges it against
// the spot light's reference; accel draws the same image as without it; bad light choices and
// accel parameters are errors.
#include "backend-test.h"
#include "technique-renderer.h"
#include "bench.h"
#include "cross-backend.h"
#include "cube-room.h"
#include <sp/tech/hpsm-counters.h>
#include <sp/tech/renderer.h>

namespace sp::test {
namespace {

CubeRoom SpotRoom() {
  CubeRoom room = MakeCubeRoom();
  scene::Scene& s = room.scene;
  s.name = "spot-room";
  scene::SpotLight spot;
  spot.position = room.light;
  spot.direction = glm::normalize(glm::vec3(0.1f, -1.0f, 0.05f));
  spot.color = s.pointLights[0].color;
  spot.range = s.pointLights[0].range;
  spot.innerConeAngle = glm::radians(35.0f);
  spot.outerConeAngle = glm::radians(55.0f);
  s.pointLights.clear();
  s.spotLights.push_back(spot);
  return room;
}

class SpotTechniqueTest : public BackendTest {
 public:
  std::unique_ptr<tech::Renderer> MakeRenderer(const scene::Scene& s, uint32_t w, uint32_t h, const std::map<std::string, std::string>& params) {
    return MakeTechniqueRenderer(device(), "spot", s, w, h, params);
  }
};

TEST_P(SpotTechniqueTest, SpheresInTheConeCastTheirExactShadows) {
  const uint32_t W = 160, H = 120;
  CubeRoom room = SpotRoom();
  std::unique_ptr<tech::Renderer> r = MakeRenderer(room.scene, W, H, {{"resolution", "1024"}});
  RoomCheck total;
  for (const scene::Camera& cam : RoomCameras(room)) {
    r->RenderFrame(cam, room.scene.light);
    total.add(CheckRoomImage(room, cam, r->ReadColor(), W, H));
  }
  EXPECT_EQ(total.wrong, 0) << "of " << total.checked << " pixels checked";
  EXPECT_GT(total.checked, 2500);
  // The -Y sphere and the edge sphere lie in the cone and shadow the floor.
  EXPECT_GT(total.shadowPerFace[3], 80);
  EXPECT_GT(total.edgeShadowPerFace[0] + total.edgeShadowPerFace[3], 40);
}

// accel (common/hpsm.hlsli) on a perspective map: the same image as without it, for a fixed kernel
// and for pcss, with most of the spot-lit floor decided by planes (post-projective depth of the
// floor is affine in texel space, so it is one plane however the light looks at it).
TEST_P(SpotTechniqueTest, AcceleratedFilteringDrawsTheSameImage) {
  const uint32_t W = 160, H = 120;
  CubeRoom room = SpotRoom();
  scene::Camera cam = RoomCameras(room)[0];
  for (const char* filter : {"gathercmp", "pcss"}) {
    std::map<std::string, std::string> p = {{"resolution", "512"}, {"filter", filter}, {"kernel", "5"}, {"pcss_max_kernel", "5"}, {"light_size", "0.1"}, {"slope_bias", "6"}};
    std::unique_ptr<tech::Renderer> plain = MakeRenderer(room.scene, W, H, p);
    plain->RenderFrame(cam, room.scene.light);
    std::vector<uint8_t> reference = plain->ReadColor();
    for (const char* accel : {"hpsm", "minmax"}) {
      p["accel"] = accel;
      std::unique_ptr<tech::Renderer> r = MakeRenderer(room.scene, W, H, p);
      r->RenderFrame(cam, room.scene.light);
      std::vector<uint8_t> img = r->ReadColor();
      tech::HpsmCounts st = dynamic_cast<const tech::HpsmCounterSource&>(r->technique()).HpsmDecisions();
      std::printf("[ spot ] %s, accel=%s: min/max %.3f, plane %.3f, filtered %.3f of %llu lookups\n", filter, accel, st.minMaxFraction(), st.planeFraction(),
                  st.filteredFraction(), (unsigned long long)st.total());
      EXPECT_GT(st.total(), W * H / 8) << filter << " " << accel;
      EXPECT_GT(st.filteredFraction(), 0.0) << "the spheres' shadow edges need the filter";
      if (std::string(accel) == "hpsm") {
        EXPECT_GT(st.planeFraction(), 0.5) << filter << ": the floor is one plane in the perspective map";
      }
      EXPECT_EQ(CompareImages(std::string("spot-accel-") + filter + "-" + accel, W, H, reference.data(), img.data(), 0), 0u) << filter << " " << accel;
    }
  }
}

SP_INSTANTIATE_BACKEND_TESTS(SpotTechniqueTest);

// Bad input refused by name, no pixels checked: these run on the null backend too.
class SpotTechniqueValidationTest : public SpotTechniqueTest {};

TEST_P(SpotTechniqueValidationTest, BadLightChoicesAreErrors) {
  CubeRoom room = SpotRoom();
  try {
    MakeRenderer(room.scene, 16, 16, {{"light", "1"}})->RenderFrame(room.scene.camera, room.scene.light);
    ADD_FAILURE() << "expected an error for a light the scene does not have";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("spot-room"), std::string::npos) << e.what();
  }
  room.scene.spotLights[0].outerConeAngle = glm::radians(85.0f);
  try {
    MakeRenderer(room.scene, 16, 16, {})->RenderFrame(room.scene.camera, room.scene.light);
    ADD_FAILURE() << "expected an error for a cone one perspective map cannot hold";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("cube"), std::string::npos) << e.what();
  }
  for (auto [param, value] : {std::pair{"hpsm_block", "2048"}, std::pair{"accel", "fast"}, std::pair{"hpsm_eps", "-1"}}) {
    TechniqueParams p = {{"accel", "hpsm"}, {"resolution", "1024"}};
    p[param] = value;
    ExpectConfigureRefused(device(), "spot", p, param);
  }
}

SP_INSTANTIATE_VALIDATION_TESTS(SpotTechniqueValidationTest);

TEST(SpotTechniqueCrossBackend, RoomRendersIdenticallyAndTheLabJudgesTheSpotLight) {
  const uint32_t W = 160, H = 120;
  CubeRoom room = SpotRoom();
  room.scene.camera = RoomCameras(room)[0];
  CrossBackendFrame f = RenderOnBothBackends("spot", {{"resolution", "512"}}, room.scene, W, H);
  size_t differing = CompareImages("spot-room", W, H, f.images[0].data(), f.images[1].data(), 0);
  if (f.mesa) {
    EXPECT_EQ(differing, 0u) << "Vulkan and GL images differ on Mesa; see the heat map in " << TestOutputDir();
  }

  // The lab: judged on the spot light (local light 0: the room has no point light), against Embree.
  eval::ReferenceCache cache(room.scene, TestOutputDir() / "reference-cache");
  bench::RunSpec spec;
  spec.scene = &room.scene;
  spec.technique = "spot";
  spec.params = {{"resolution", "1024"}};
  spec.backend = Backend::Vulkan;
  spec.width = 160;
  spec.height = 90;
  spec.frames = 1;
  spec.validate = true;
  bench::RunResult r = bench::RunOne(spec, cache);
  EXPECT_EQ(r.validationErrors, 0u) << r.lastValidationError;
  EXPECT_EQ(r.judgedLocalLight, 0);
  size_t shadowed = 0;
  for (size_t i = 0; i < r.firstFrame.size(); ++i) shadowed += r.firstFrame.receiving(i) && r.firstReference[i] == 0;
  EXPECT_GT(shadowed, 80u) << "the reference must see the spheres' shadows in the cone";
  EXPECT_LT(r.accuracy.misclassifiedPct(), 1.0) << "false lit " << r.accuracy.falseLitPct() << " %, false shadow " << r.accuracy.falseShadowPct() << " %";
  ::testing::Test::RecordProperty("misclassified_pct", std::to_string(r.accuracy.misclassifiedPct()));
}

}  // namespace
}  // namespace sp::test
