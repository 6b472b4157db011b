// The paraboloid technique's known failure, measured by the bench against the Embree reference
// traced from the point light: on paraboloid-coarse (walls and boxes of two triangles a face) the
// per-vertex projection with linear interpolation between vertices misclassifies far more pixels
// than on paraboloid-fine (the same surfaces split into triangles under 0.5 m), and far more than
// the cube technique does on the same coarse room (cube maps are projective: straight edges stay
// straight). Every figure is the same on both backends.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "bench-both-backends.h"

namespace sp::test {
namespace {

struct Measured {
  double misclassifiedPct = 0, falseLitPct = 0, falseShadowPct = 0;
};

Measured Bench(const scene::Scene& s, const std::string& technique, const std::map<std::string, std::string>& params) {
  std::array<bench::RunResult, 2> r = BenchOnBothBackends(s, technique, params, 160, 90);
  EXPECT_EQ(r[0].judgedLocalLight, 0);
  EXPECT_GT(r[0].accuracy.receiving, 160u * 90u / 2) << s.name << ": the room's surfaces face the point light";
  ExpectSameAccuracyOnMesa(r, s.name + " " + technique);
  const eval::Accuracy& a = r[0].accuracy;
  std::printf("%s %s: misclassified %.3f %% (false lit %.3f, false shadow %.3f) of %llu pixels\n", s.name.c_str(), technique.c_str(), a.misclassifiedPct(),
              a.falseLitPct(), a.falseShadowPct(), (unsigned long long)a.receiving);
  return {a.misclassifiedPct(), a.falseLitPct(), a.falseShadowPct()};
}

TEST(ParaboloidBench, CoarseGeometryMisclassifiesFarMoreThanFineGeometryAndThanCube) {
  const scene::Scene coarse = scene::MakeBuiltinScene("paraboloid-coarse"), fine = scene::MakeBuiltinScene("paraboloid-fine");
  const std::map<std::string, std::string> params = {{"resolution", "1024"}};
  Measured pc = Bench(coarse, "paraboloid", params), pf = Bench(fine, "paraboloid", params);
  Measured cc = Bench(coarse, "cube", {{"resolution", "512"}});
  EXPECT_GT(pc.misclassifiedPct, 3.0 * pf.misclassifiedPct) << "coarse " << pc.misclassifiedPct << " % against fine " << pf.misclassifiedPct << " %";
  EXPECT_GT(pc.misclassifiedPct, 3.0 * cc.misclassifiedPct) << "paraboloid " << pc.misclassifiedPct << " % against cube " << cc.misclassifiedPct << " %";
  // On fine geometry the paraboloid is as right as cube: shadow-edge pixels only.
  EXPECT_LT(pf.misclassifiedPct, 1.0);
  ::testing::Test::RecordProperty("coarse_misclassified_pct", std::to_string(pc.misclassifiedPct));
  ::testing::Test::RecordProperty("fine_misclassified_pct", std::to_string(pf.misclassifiedPct));
}

}  // namespace
}  // namespace sp::test
