// The lab judges a point-light technique: `cube` names its light (Technique::LabLocalLight), the
// lab's lit pass writes that light's N.L and visibility, and the bench traces the reference from
// the point light. On the cube test room the technique agrees with the Embree reference and both
// backends give the same metrics.
#include <gtest/gtest.h>

#include <string>

#include "../techniques/cube-room.h"
#include "bench-both-backends.h"

namespace sp::test {
namespace {

class CubeBench : public ::testing::TestWithParam<const char*> {};

TEST_P(CubeBench, PointLightTechniqueIsJudgedAgainstThePointLightReference) {
  CubeRoom room = MakeCubeRoom();
  std::array<bench::RunResult, 2> r = BenchOnBothBackends(room.scene, "cube", {{"resolution", "512"}, {"storage", GetParam()}}, 160, 90);
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
  ExpectSameAccuracyOnMesa(r, "cube");
  EXPECT_EQ(r[0].judgedLocalLight, 0);
  EXPECT_EQ(bench::RunToJson(r[0], {})["checks"]["judged_local_light"], 0);
  ::testing::Test::RecordProperty("misclassified_pct", std::to_string(r[0].accuracy.misclassifiedPct()));
}

INSTANTIATE_TEST_SUITE_P(Storage, CubeBench, ::testing::Values("depth", "radial"));

}  // namespace
}  // namespace sp::test
