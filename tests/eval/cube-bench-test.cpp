// The lab judges a point-light technique: `cube` names its light (Technique::LabLocalLight), the
// lab's lit pass writes that light's N.L and visibility, and the bench traces the reference from
// the point light. On the cube test room the technique agrees with the Embree reference and both
// backends give the same metrics.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "../techniques/cube-room.h"
#include "bench.h"
#include <sp/rhi/rhi.h>

namespace sp::test {
namespace {

class CubeBench : public ::testing::TestWithParam<const char*> {};

TEST_P(CubeBench, PointLightTechniqueIsJudgedAgainstThePointLightReference) {
  CubeRoom room = MakeCubeRoom();
  eval::ReferenceCache cache(room.scene, std::filesystem::path(SHADOWPORT_TEST_OUTPUT_DIR) / "reference-cache");
  bench::RunResult r[2];
  const Backend backends[2] = {Backend::Vulkan, Backend::OpenGL};
  for (int i = 0; i < 2; ++i) {
    bench::RunSpec spec;
    spec.scene = &room.scene;
    spec.technique = "cube";
    spec.params = {{"resolution", "512"}, {"storage", GetParam()}};
    spec.backend = backends[i];
    spec.width = 160;
    spec.height = 90;
    spec.frames = 1;
    spec.validate = true;
    r[i] = bench::RunOne(spec, cache);
    EXPECT_EQ(r[i].validationErrors, 0u) << BackendName(backends[i]) << ": " << r[i].lastValidationError;
  }
  const tech::LabBuffers& lab = r[0].firstFrame;
  size_t receiving = 0, referenceShadowed = 0;
  for (size_t i = 0; i < lab.size(); ++i)
    if (lab.receiving(i)) ++receiving, referenceShadowed += r[0].firstReference[i] == 0;
  EXPECT_EQ(r[0].accuracy.receiving, receiving);
  EXPECT_GT(receiving, 160u * 90u / 2) << "the room's surfaces face the point light";
  EXPECT_GT(referenceShadowed, 300u) << "the reference must see the spheres' shadows from the point light";
  // Misclassified pixels lie on shadow edges only (texel grid, 2x2 PCF, the tessellated spheres).
  EXPECT_LT(r[0].accuracy.misclassifiedPct(), 1.0) << "false lit " << r[0].accuracy.falseLitPct() << " %, false shadow " << r[0].accuracy.falseShadowPct() << " %";
  EXPECT_GT(r[0].texelsPerPixelMedian, 0.0);
  EXPECT_EQ(r[0].shadowMemoryBytes, 512u * 512u * 4u * (std::string(GetParam()) == "radial" ? 7u : 6u));
  bool mesa = r[0].device.find("llvmpipe") != std::string::npos && r[1].device.find("llvmpipe") != std::string::npos;
  if (mesa) {
    EXPECT_EQ(r[0].accuracy.falseLit, r[1].accuracy.falseLit);
    EXPECT_EQ(r[0].accuracy.falseShadow, r[1].accuracy.falseShadow);
    EXPECT_EQ(r[0].accuracy.absErrorSum, r[1].accuracy.absErrorSum);
    EXPECT_EQ(r[0].texelsPerPixelMedian, r[1].texelsPerPixelMedian);
  }
  EXPECT_EQ(r[0].judgedLocalLight, 0);
  EXPECT_EQ(bench::RunToJson(r[0], {})["checks"]["judged_local_light"], 0);
  ::testing::Test::RecordProperty("misclassified_pct", std::to_string(r[0].accuracy.misclassifiedPct()));
}

INSTANTIATE_TEST_SUITE_P(Storage, CubeBench, ::testing::Values("depth", "radial"));

}  // namespace
}  // namespace sp::test
