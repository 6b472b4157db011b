// The lab's metrics on buffers built on the CPU, where every answer is known by construction:
// accuracy counts and the 0.5 threshold, percentiles of the logarithmic histogram, utilization
// as distinct texels over all layers, and both flicker measures (exact and reprojected).
#include <gtest/gtest.h>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>

#include "metrics.h"

namespace sp::test {
namespace {

// A w x h frame where every pixel receives light (drawn, facing the light), lit, with no map read.
tech::LabBuffers Frame(uint32_t w, uint32_t h) {
  tech::LabBuffers b;
  b.width = w;
  b.height = h;
  b.position.assign(b.size(), glm::vec4(0, 0, 0, 1));
  b.normal.assign(b.size(), glm::vec4(0, 1, 0, 1));
  b.visibility.assign(b.size(), 1.0f);
  b.lookup.assign(b.size(), glm::vec4(-1, 0, 0, 0));
  b.color.assign(b.size() * 4, 128);
  b.albedo.assign(b.size() * 4, 200);
  return b;
}

TEST(LabMetrics, AccuracySplitsFalseLitAndFalseShadowOverReceivingPixelsOnly) {
  tech::LabBuffers b = Frame(10, 1);
  std::vector<uint8_t> ref = {1, 1, 1, 1, 0, 0, 0, 0, 1, 0};
  // 0..3 reference lit: 3 is filtered just under the threshold (false shadow), 2 exactly at it (lit).
  b.visibility = {1.0f, 0.75f, 0.5f, 0.49f, 0.0f, 0.25f, 0.5f, 1.0f, 0.0f, 1.0f};
  b.position[8].w = 0.0f;  // sky: not judged
  b.normal[9].w = 0.0f;    // facing away from the light: not judged
  eval::Accuracy a = eval::MeasureAccuracy(b, ref.data());
  EXPECT_EQ(a.receiving, 8u);
  EXPECT_EQ(a.falseShadow, 1u);  // pixel 3
  EXPECT_EQ(a.falseLit, 2u);     // pixels 6 (0.5 counts as lit) and 7
  EXPECT_DOUBLE_EQ(a.misclassifiedPct(), 100.0 * 3 / 8);
  EXPECT_DOUBLE_EQ(a.falseLitPct() + a.falseShadowPct(), a.misclassifiedPct());
  double err = 0.0 + 0.25 + 0.5 + 0.51 + 0.0 + 0.25 + 0.5 + 1.0;
  EXPECT_NEAR(a.meanAbsError(), err / 8, 1e-6);
}

// A fractional reference (an area light's penumbra): the mean absolute error is against the
// fraction, and a pixel is misclassified when it and the reference fall on different sides of 0.5.
TEST(LabMetrics, MeanAbsoluteErrorAgainstAFractionalReference) {
  tech::LabBuffers b = Frame(7, 1);
  std::vector<float> ref = {1.0f, 0.75f, 0.5f, 0.25f, 0.0f, 0.625f, 0.5f};
  b.visibility = {1.0f, 0.5f, 0.5f, 0.5f, 0.25f, 0.375f, 0.0f};
  b.normal[6].w = 0.0f;  // not judged
  eval::Accuracy a = eval::MeasureAccuracy(b, ref.data());
  EXPECT_EQ(a.receiving, 6u);
  EXPECT_EQ(a.falseLit, 1u);     // pixel 3: 0.5 against 0.25
  EXPECT_EQ(a.falseShadow, 1u);  // pixel 5: 0.375 against 0.625
  EXPECT_DOUBLE_EQ(a.meanAbsError(), (0.0 + 0.25 + 0.0 + 0.25 + 0.25 + 0.25) / 6);
  // The penumbra alone: judged pixels whose reference is strictly between 0 and 1 (1, 2, 3, 5).
  EXPECT_EQ(a.penumbra, 4u);
  EXPECT_DOUBLE_EQ(a.penumbraMeanAbsError(), (0.25 + 0.0 + 0.25 + 0.25) / 4);
  eval::Accuracy twice = a;
  twice.add(a);
  EXPECT_EQ(twice.penumbra, 8u);
  EXPECT_DOUBLE_EQ(twice.penumbraMeanAbsError(), a.penumbraMeanAbsError());

  // A reference of 0/1 bytes judges exactly as the same values in float.
  std::vector<uint8_t> bytes = {1, 1, 0, 0, 0, 1, 1};
  std::vector<float> floats(bytes.begin(), bytes.end());
  eval::Accuracy x = eval::MeasureAccuracy(b, bytes.data()), y = eval::MeasureAccuracy(b, floats.data());
  EXPECT_EQ(x.falseLit, y.falseLit);
  EXPECT_EQ(x.falseShadow, y.falseShadow);
  EXPECT_EQ(x.absErrorSum, y.absErrorSum);
  EXPECT_EQ(x.penumbra, 0u) << "a hard reference has no penumbra";
  EXPECT_EQ(x.penumbraMeanAbsError(), 0.0);

  // The reference picture shades with the fraction: half the sun is between none and all of it.
  scene::DirectionalLight sun;
  tech::LabBuffers one = Frame(1, 1);
  auto red = [&](float v) { return int(eval::ReferenceImage(one, &v, sun)[0]); };
  EXPECT_LT(red(0.0f), red(0.5f));
  EXPECT_LT(red(0.5f), red(1.0f));
  // The error map: a technique matching a fractional reference shows no tint.
  uint32_t h = 0;
  float half = 0.5f;
  one.visibility = {0.5f};
  std::vector<uint8_t> same = eval::ErrorHeatMap(one, &half, &h);
  EXPECT_EQ(same[0], same[1]);
  EXPECT_EQ(same[1], same[2]);
}

TEST(LabMetrics, HistogramPercentilesAreWithinABinOfTheExactOnesAndExactForConstantData) {
  eval::LogHistogram h;
  std::vector<double> v;
  for (int i = 1; i <= 1000; ++i) v.push_back(0.01 * i);  // 0.01 .. 10
  for (double x : v) h.add(x);
  h.add(0.0);  // not positive: ignored
  h.add(std::numeric_limits<double>::infinity());
  EXPECT_EQ(h.count(), 1000u);
  // Nearest-rank percentiles: 500th and 50th values.
  EXPECT_NEAR(h.percentile(0.5), 5.0, 5.0 * 0.003);
  EXPECT_NEAR(h.percentile(0.05), 0.5, 0.5 * 0.003);
  eval::LogHistogram constant;
  for (int i = 0; i < 100; ++i) constant.add(0.65689);
  EXPECT_DOUBLE_EQ(constant.percentile(0.5), 0.65689);
  EXPECT_DOUBLE_EQ(constant.percentile(0.05), 0.65689);
  EXPECT_EQ(eval::LogHistogram().percentile(0.5), 0.0);
}

TEST(LabMetrics, UtilizationCountsDistinctTexelsOfEveryLayer) {
  tech::LabBuffers b = Frame(6, 1);
  // Two pixels in one texel of layer 0, one on layer 0's far edge (coordinate == size belongs to
  // the last texel), one on layer 1, one outside every layer, one not receiving.
  b.lookup = {{0, 1.2f, 2.7f, 1}, {0, 1.9f, 2.1f, 1}, {0, 4.0f, 4.0f, 1}, {1, 0.5f, 0.5f, 1}, {-1, 0, 0, 0}, {0, 3.5f, 0.5f, 1}};
  b.normal[5].w = 0.0f;
  std::vector<tech::ShadowLayer> layers = {{4, 4}, {2, 2}};
  EXPECT_DOUBLE_EQ(eval::MeasureUtilization(b, layers), 3.0 / 20.0);
}

TEST(LabMetrics, ExactFlickerComparesTheSameSurfacePoints) {
  tech::LabBuffers now = Frame(4, 1), before = Frame(4, 1);
  for (uint32_t i = 0; i < 4; ++i) now.position[i] = before.position[i] = glm::vec4(float(i), 0, 0, 1);
  now.visibility = {1.0f, 0.0f, 0.5f, 1.0f};
  before.visibility = {1.0f, 1.0f, 0.25f, 0.0f};
  before.position[3].x += 1e-4f;  // not the same point: left out and counted
  eval::Flicker f = eval::MeasureFlicker(now, before);
  EXPECT_EQ(f.pixels, 3u);
  EXPECT_EQ(f.unmatched, 1u);
  EXPECT_DOUBLE_EQ(f.mean(), (0.0 + 1.0 + 0.25) / 3);
}

// A camera over a plane: each pixel's world point is its ray's hit with y = 0.
tech::LabBuffers PlaneSeenFrom(const glm::vec3& eye, uint32_t w, uint32_t h) {
  tech::LabBuffers b = Frame(w, h);
  glm::mat4 view = glm::lookAtRH(eye, eye + glm::vec3(0, -1, 0), glm::vec3(0, 0, -1));
  b.viewProj = glm::perspectiveRH_ZO(glm::radians(60.0f), float(w) / float(h), 0.1f, 100.0f) * view;
  b.cameraPosition = eye;
  glm::mat4 inv = glm::inverse(b.viewProj);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      glm::vec4 ndc((x + 0.5f) / w * 2 - 1, 1 - (y + 0.5f) / h * 2, 0.5f, 1.0f);
      glm::vec4 p = inv * ndc;
      glm::vec3 d = glm::normalize(glm::vec3(p) / p.w - eye);
      glm::vec3 hit = eye + d * (-eye.y / d.y);
      b.position[y * w + x] = glm::vec4(hit, 1.0f);
      b.visibility[y * w + x] = hit.x < 0.4f ? 0.0f : 1.0f;  // a shadow edge fixed in the world
    }
  return b;
}

TEST(LabMetrics, ReprojectedFlickerIsZeroForAStaticCameraAndSmallForAWorldFixedEdge) {
  tech::LabBuffers a = PlaneSeenFrom({0, 10, 0}, 64, 48);
  eval::Flicker still = eval::MeasureReprojectedFlicker(a, a.visibility.data(), a, a.visibility.data());
  EXPECT_EQ(still.pixels, a.size());
  EXPECT_EQ(still.sum, 0.0);
  // A shift of a third of a pixel: only pixels beside the edge can sample the other side.
  float pixel = 2.0f * 10.0f * std::tan(glm::radians(30.0f)) / 48.0f;
  tech::LabBuffers b = PlaneSeenFrom({pixel / 3.0f, 10, 0}, 64, 48);
  eval::Flicker moved = eval::MeasureReprojectedFlicker(a, a.visibility.data(), b, b.visibility.data());
  EXPECT_GT(moved.pixels, b.size() * 9 / 10);
  EXPECT_GT(moved.sum, 0.0);
  EXPECT_LE(moved.sum, 48.0) << "at most one column of pixels beside the edge";
  // A surface at another distance in the previous frame is not the same point: rejected.
  tech::LabBuffers c = a;
  for (glm::vec4& p : c.position) p.y += 0.5f;
  EXPECT_EQ(eval::MeasureReprojectedFlicker(c, c.visibility.data(), a, a.visibility.data()).pixels, 0u);
}

TEST(LabMetrics, TexelDensityBandsAreOctavesAroundOne) {
  EXPECT_EQ(eval::TexelDensityColor(1.0f), eval::TexelDensityColor(1.3f));
  EXPECT_NE(eval::TexelDensityColor(1.0f), eval::TexelDensityColor(0.5f));
  EXPECT_EQ(eval::TexelDensityColor(1e-9f), eval::TexelDensityColor(1.0f / 32));
  EXPECT_EQ(eval::TexelDensityColor(1e9f), eval::TexelDensityColor(32.0f));
}

// A region is the union of its world boxes (LabBuffers::position); only judged pixels inside it
// count, and the umbra counts (reference exactly 0) and their light bleeding follow the same
// pixels. Pixel i sits at x = i; boxes [0.5, 2.5] and [5, 6] hold pixels 1, 2, 5, 6.
TEST(LabMetrics, RegionAccuracyCountsOnlyPixelsInItsBoxesAndTheUmbraLeak) {
  tech::LabBuffers b = Frame(9, 1);
  for (uint32_t i = 0; i < 9; ++i) b.position[i] = glm::vec4(float(i), 0.0f, 0.0f, 1.0f);
  std::vector<float> ref = {0.0f, 0.0f, 0.0f, 0.0f, 0.5f, 0.0f, 0.5f, 1.0f, 0.0f};
  b.visibility = {0.9f, 0.1f, 0.3f, 0.0f, 0.75f, 0.05f, 0.25f, 1.0f, 1.0f};
  b.normal[2].w = 0.0f;  // in a box but not judged
  scene::Region region{"r", {}};
  scene::Bounds box;
  box.extend({0.5f, -1.0f, -1.0f});
  box.extend({2.5f, 1.0f, 1.0f});
  region.boxes.push_back(box);
  box = {};
  box.extend({5.0f, 0.0f, 0.0f});  // a flat box: its faces are inside
  box.extend({6.0f, 0.0f, 0.0f});
  region.boxes.push_back(box);
  eval::Accuracy a = eval::MeasureRegionAccuracy(b, ref.data(), region);
  EXPECT_EQ(a.receiving, 3u);  // pixels 1, 5, 6
  EXPECT_EQ(a.umbra, 2u);      // 1, 5
  // 0.1 is not above kUmbraLeakThreshold (0.1), 0.05 neither: no leak.
  EXPECT_EQ(a.umbraLeaked, 0u);
  EXPECT_NEAR(a.umbraMeanVisibility(), (0.1 + 0.05) / 2, 1e-7);
  EXPECT_EQ(a.penumbra, 1u);  // 6
  EXPECT_NEAR(a.penumbraMeanAbsError(), 0.25, 1e-7);
  EXPECT_NEAR(a.meanAbsError(), (0.1 + 0.05 + 0.25) / 3, 1e-7);

  // The whole frame: umbra pixels 0, 1, 3, 5, 8 (2 is not judged); 0 (0.9) and 8 (1.0) leak.
  eval::Accuracy all = eval::MeasureAccuracy(b, ref.data());
  EXPECT_EQ(all.umbra, 5u);
  EXPECT_EQ(all.umbraLeaked, 2u);
  EXPECT_NEAR(all.umbraLeakFraction(), 0.4, 1e-12);
  EXPECT_NEAR(all.umbraMeanVisibility(), (0.9 + 0.1 + 0.0 + 0.05 + 1.0) / 5, 1e-7);
  eval::Accuracy twice = all;
  twice.add(all);
  EXPECT_EQ(twice.umbraLeaked, 4u);
  EXPECT_NEAR(twice.umbraMeanVisibility(), all.umbraMeanVisibility(), 1e-12);

  // A region with no box holds nothing.
  EXPECT_EQ(eval::MeasureRegionAccuracy(b, ref.data(), scene::Region{"empty", {}}).receiving, 0u);
}

}  // namespace
}  // namespace sp::test
