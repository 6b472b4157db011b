// The lab judges vsdct as it judges cube (tests/eval/cube-bench-test.cpp): on the cube test room,
// against the Embree reference traced from the point light, with the 2x2 filter and with a box
// kernel through guard bands; misclassification stays on shadow edges, the metrics are the same
// on both backends, and the reported memory and texel density are the faces' (the guard band adds
// memory, not density).
#include <gtest/gtest.h>

#include <string>

#include "../techniques/cube-room.h"
#include "bench-both-backends.h"

namespace sp::test {
namespace {

struct VsdctBenchCase {
  const char* filter;
  const char* kernel;
  uint32_t guard;
};

class VsdctBench : public ::testing::TestWithParam<VsdctBenchCase> {};

TEST_P(VsdctBench, PointLightTechniqueIsJudgedAgainstThePointLightReference) {
  const VsdctBenchCase& c = GetParam();
  CubeRoom room = MakeCubeRoom();
  std::array<bench::RunResult, 2> r =
      BenchOnBothBackends(room.scene, "vsdct", {{"resolution", "512"}, {"filter", c.filter}, {"kernel", c.kernel}, {"guard", std::to_string(c.guard)}}, 160, 90);
  std::array<bench::RunResult, 2> cube = BenchOnBothBackends(room.scene, "cube", {{"resolution", "512"}}, 160, 90);
  EXPECT_EQ(r[0].judgedLocalLight, 0);
  EXPECT_GT(r[0].accuracy.receiving, 160u * 90u / 2) << "the room's surfaces face the point light";
  EXPECT_LT(r[0].accuracy.misclassifiedPct(), 1.0) << "false lit " << r[0].accuracy.falseLitPct() << " %, false shadow " << r[0].accuracy.falseShadowPct() << " %";
  // The faces are the cube technique's, so is the texel density the lab measures on them.
  EXPECT_NEAR(r[0].texelsPerPixelMedian, cube[0].texelsPerPixelMedian, 1e-3 * cube[0].texelsPerPixelMedian);
  const uint64_t tile = 512 + 2 * c.guard;
  EXPECT_EQ(r[0].shadowMemoryBytes, 3 * tile * 2 * tile * 4 + 6 * 16);
  ExpectSameAccuracyOnMesa(r, std::string("vsdct ") + c.filter);
  ::testing::Test::RecordProperty("misclassified_pct", std::to_string(r[0].accuracy.misclassifiedPct()));
  ::testing::Test::RecordProperty("cube_misclassified_pct", std::to_string(cube[0].accuracy.misclassifiedPct()));
}

INSTANTIATE_TEST_SUITE_P(Filter, VsdctBench, ::testing::Values(VsdctBenchCase{"hw2x2", "3", 1}, VsdctBenchCase{"box", "5", 3}),
                         [](const ::testing::TestParamInfo<VsdctBenchCase>& i) { return std::string(i.param.filter); });

}  // namespace
}  // namespace sp::test
