// PCSS's one average blocker depth, measured where it can go wrong (the plank scenes' regions,
// scene::Scene::regions), on both backends with validation on, 3-degree sun, csm with
// receiver-plane bias and pcss_max_kernel 31 (wide enough for the high plank's penumbra, so the
// clamp is not what is measured): the bench's per-region figures are those of
// eval::MeasureRegionAccuracy on the frame it read back; far from the high plank PCSS does as well
// on stacked-planks as on single-plank; under the high plank's penumbra, where its blocker search
// finds both planks, it does much worse (the known failure, docs/soft-shadows.md part 5c).
#include <gtest/gtest.h>

#include <cstdio>

#include "bench-both-backends.h"
#include "metrics.h"

namespace sp::test {
namespace {

// Far from the high plank the pixels, the reference and the blockers found are the same in both
// scenes; only the cascade fit differs (the high plank widens the casters' bounds, so the map's
// texels do), which moved fixed kernels' penumbra MAE there by up to 7% (part 5c, hw2x2): twice
// that is allowed.
constexpr double kFarRatio = 0.15;
// Under the high plank's penumbra: a box k times as wide as a straight edge's penumbra gives
// |x / w - x / (k w)| over the ramp |x| < w / 2, a mean of (1 - 1/k) / 4; the blocker average
// there mixes depths 0.6 and 3 m, so the low plank's kernel is several times too wide (k = 2:
// 0.125). Those pixels are about a third of the region's penumbra (the rest is the high plank's,
// which PCSS gets about as right as the single plank's, ~0.03), so the region's penumbra MAE
// is about 0.03 + 0.125 / 3 = 0.07 for k = 2, over twice single-plank's ~0.03 (measured: 0.055
// against 0.028); 1.5 times leaves room for a kernel less than twice too wide.
constexpr double kUnderRatio = 1.5;

const eval::Accuracy& RegionOf(const bench::RunResult& r, const std::string& name) {
  for (const auto& [n, a] : r.regions)
    if (n == name) return a;
  ADD_FAILURE() << r.scene << " has no region " << name;
  return r.accuracy;
}

TEST(PlankRegionsLab, PcssBlockerAverageFailsUnderTheHighPlanksPenumbraOnly) {
  const std::map<std::string, std::string> params = {{"bias", "receiver-plane"}, {"filter", "pcss"}, {"light_size", "3"},
                                                     {"pcss_max_kernel", "31"}};
  std::map<std::string, std::array<bench::RunResult, 2>> runs;
  for (const char* name : {"single-plank", "stacked-planks"}) {
    scene::Scene s = scene::MakeBuiltinScene(name);
    s.light.angularDiameterDegrees = 3.0f;
    runs[name] = BenchOnBothBackends(s, "csm", params, 320, 180);
    for (const bench::RunResult& r : runs[name]) {
      SCOPED_TRACE(std::string(name) + " " + r.backend);
      ASSERT_EQ(r.regions.size(), s.regions.size());
      for (size_t k = 0; k < s.regions.size(); ++k) {
        eval::Accuracy a = eval::MeasureRegionAccuracy(r.firstFrame, r.firstReference.data(), s.regions[k]);
        EXPECT_EQ(r.regions[k].first, s.regions[k].name);
        EXPECT_EQ(r.regions[k].second.receiving, a.receiving);
        EXPECT_EQ(r.regions[k].second.penumbraAbsErrorSum, a.penumbraAbsErrorSum);
        EXPECT_EQ(r.regions[k].second.umbraVisibilitySum, a.umbraVisibilitySum);
        EXPECT_GT(a.penumbra, 20u) << s.regions[k].name;
        EXPECT_GT(a.umbra, 20u) << s.regions[k].name;
        std::printf("%s %s %s: %llu pixels, penumbra MAE %.4f (%llu), umbra leak %.4f of %llu, umbra mean %.4f\n", name,
                    r.backend.c_str(), s.regions[k].name.c_str(), static_cast<unsigned long long>(a.receiving),
                    a.penumbraMeanAbsError(), static_cast<unsigned long long>(a.penumbra), a.umbraLeakFraction(),
                    static_cast<unsigned long long>(a.umbra), a.umbraMeanVisibility());
      }
    }
  }
  for (int b = 0; b < 2; ++b) {
    const bench::RunResult &one = runs["single-plank"][b], &two = runs["stacked-planks"][b];
    SCOPED_TRACE(one.backend);
    const eval::Accuracy &farOne = RegionOf(one, "far"), &farTwo = RegionOf(two, "far");
    const eval::Accuracy &underOne = RegionOf(one, "under-high-penumbra"), &underTwo = RegionOf(two, "under-high-penumbra");
    // Far: the same pixels, the same reference, no second blocker in reach.
    EXPECT_EQ(farOne.receiving, farTwo.receiving);
    EXPECT_NEAR(farTwo.penumbraMeanAbsError(), farOne.penumbraMeanAbsError(), kFarRatio * farOne.penumbraMeanAbsError());
    EXPECT_EQ(farTwo.umbraLeaked, 0u);
    EXPECT_GT(underTwo.penumbraMeanAbsError(), kUnderRatio * underOne.penumbraMeanAbsError());
    // Light bleeding: with one blocker depth the kernel is the penumbra's own width, so no umbra
    // pixel (farther than half a kernel from the edge) sees a lit texel; the mixed average widens
    // it past the umbra's edge. At least 1% of the region's umbra lit above kUmbraLeakThreshold
    // (3.3% at 320x180, part 5c).
    EXPECT_EQ(underOne.umbraLeaked, 0u);
    EXPECT_GT(underTwo.umbraLeakFraction(), 0.01);
  }
}

}  // namespace
}  // namespace sp::test
