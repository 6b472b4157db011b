// The lab with an area light, on both backends with validation on: the scene's light size reaches
// the reference, which the bench judges against with fractional visibility; the figures it reports
// are those of the reference traced here independently on the same surface points.
#include <gtest/gtest.h>

#include <algorithm>

#include "bench-both-backends.h"
#include "metrics.h"

namespace sp::test {
namespace {

TEST(AreaLightLab, BenchJudgesAgainstTheFractionalReferenceOnBothBackends) {
  scene::Scene s = scene::MakeBuiltinScene("default");
  s.light.angularDiameterDegrees = 3.0f;
  std::array<bench::RunResult, 2> r = BenchOnBothBackends(s, "basic", {}, 160, 90);
  eval::ReferenceTracer tracer(s);
  const eval::ReferenceLight light = eval::ReferenceLight::FromScene(s.light);
  for (const bench::RunResult& run : r) {
    SCOPED_TRACE(run.backend);
    EXPECT_EQ(run.lightSize, 3.0f);
    EXPECT_EQ(run.lightSamples, eval::ReferenceOptions{}.lightSamples);
    const tech::LabBuffers& f = run.firstFrame;
    eval::LabSurfacePoints p = eval::SurfacePointsOf(f);
    std::vector<float> expected(f.size(), 0.0f);
    tracer.Visibility(p.position.data(), p.normal.data(), p.valid.data(), p.size(), light, expected.data());
    EXPECT_EQ(run.firstReference, expected);
    size_t penumbra = std::count_if(expected.begin(), expected.end(), [](float v) { return v > 0.0f && v < 1.0f; });
    EXPECT_GT(penumbra, 50u);
    eval::Accuracy a = eval::MeasureAccuracy(f, expected.data());
    EXPECT_EQ(run.accuracy.receiving, a.receiving);
    EXPECT_EQ(run.accuracy.absErrorSum, a.absErrorSum);
    EXPECT_GT(a.meanAbsError(), 0.0);
    nlohmann::json j = bench::RunToJson(run, {});
    EXPECT_EQ(j["checks"]["light_size"].get<float>(), 3.0f);
    EXPECT_EQ(j["checks"]["reference_light_samples"].get<unsigned>(), eval::ReferenceOptions{}.lightSamples);
    EXPECT_NEAR(j["metrics"]["mean_abs_error"].get<double>(), a.meanAbsError(), 1e-6);
    std::printf("%s (%s): %zu penumbra pixels of %llu judged, mean |error| %.5f, misclassified %.3f %%\n", run.backend.c_str(),
                run.device.c_str(), penumbra, static_cast<unsigned long long>(a.receiving), a.meanAbsError(), a.misclassifiedPct());
  }
  ExpectSameAccuracyOnMesa(r, "default scene, 3 degree sun");
}

}  // namespace
}  // namespace sp::test
