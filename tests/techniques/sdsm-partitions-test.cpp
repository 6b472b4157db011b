// SDSM CPU side (techniques/sdsm/partitions.h, analysis-frame.h), no device: the partition rules
// on small hand-made histograms, the light frame, the order-preserving float keys, the results
// encoding, the shadow projection of a box, and the histogram image (the paper's Figure 2).
#include <gtest/gtest.h>

#include <cmath>
#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <limits>

#include "backend-test.h"
#include <sp/scene/scene.h>
#include "sdsm/analysis-frame.h"
#include "sdsm/partitions.h"

namespace sp::test {
namespace {

using namespace tech::sdsm;

TEST(SdsmPartitions, LogSplitsFollowTheFormulaBetweenTheTightRange) {
  const float zMin = 2.0f, zMax = 500.0f;
  std::vector<uint32_t> h(1024, 1);
  for (uint32_t K = 1; K <= kMaxPartitions; ++K) {
    PartitionResult r = ComputePartitions({PartitionScheme::Log, K}, zMin, zMax, h, 0.1f, 1000.0f);
    ASSERT_EQ(r.splits.size(), K + 1);
    EXPECT_EQ(r.splits.front(), zMin);
    EXPECT_EQ(r.splits.back(), zMax);
    for (uint32_t i = 1; i < K; ++i) EXPECT_NEAR(r.splits[i], zMin * std::pow(zMax / zMin, float(i) / K), 2e-5f * r.splits[i]);
  }
  // Without gaps adaptive-log is log.
  EXPECT_EQ(ComputePartitions({PartitionScheme::AdaptiveLog, 5}, zMin, zMax, h, 0, 0).splits,
            ComputePartitions({PartitionScheme::Log, 5}, zMin, zMax, h, 0, 0).splits);
}

TEST(SdsmPartitions, AdaptiveLogFollowsItsRuleOnASmallHistogram) {
  // 16 bins: occupied 0-3 and 12-15 (M = 8), gap 4-11 at occupied measure 4, ending at bin 12.
  std::vector<uint32_t> h(16, 0);
  for (uint32_t b : {0u, 1u, 2u, 3u, 12u, 13u, 14u, 15u}) h[b] = 5;
  // K = 2: t_1 = 4 is on the gap: snapped to its end (bin 12).
  EXPECT_FLOAT_EQ(ComputePartitions({PartitionScheme::AdaptiveLog, 2}, 1, 16, h, 0, 0).positions[1], 12.0f);
  // K = 4: t = 2, 4, 6 -> bins 2, (gap) 12, 14; |2 - 4| = 2 is not < M/2K = 1, so split 1 stays.
  std::vector<float> u = ComputePartitions({PartitionScheme::AdaptiveLog, 4}, 1, 16, h, 0, 0).positions;
  EXPECT_FLOAT_EQ(u[1], 2.0f);
  EXPECT_FLOAT_EQ(u[2], 12.0f);
  EXPECT_FLOAT_EQ(u[3], 14.0f);
  // K = 3: t = 8/3 and 16/3, both 4/3 from the gap's measure 4, exactly half a share (2|8 - 12| =
  // 8 is not < M = 8): neither snaps; they sit in occupied bins 2 (acc 2) and 13 (acc 5).
  u = ComputePartitions({PartitionScheme::AdaptiveLog, 3}, 1, 16, h, 0, 0).positions;
  EXPECT_FLOAT_EQ(u[1], 2.0f + 2.0f / 3.0f);
  EXPECT_FLOAT_EQ(u[2], 13.0f + 1.0f / 3.0f);
  // A threshold turns sparse bins into gap.
  h[8] = 1;
  EXPECT_FLOAT_EQ(ComputePartitions({PartitionScheme::AdaptiveLog, 2, 1}, 1, 16, h, 0, 0).positions[1], 12.0f);
  EXPECT_NE(ComputePartitions({PartitionScheme::AdaptiveLog, 2, 0}, 1, 16, h, 0, 0).positions[1], 12.0f);
}

TEST(SdsmPartitions, KMeansConvergesOnSeparatedClusters) {
  // Two equal clusters at bins 10 and 50 of 64: two centres go one to each.
  std::vector<uint32_t> h(64, 0);
  h[10] = 100, h[50] = 100;
  PartitionResult r = ComputePartitions({PartitionScheme::KMeans, 2}, 1, 64, h, 0, 0);
  ASSERT_EQ(r.centres.size(), 2u);
  EXPECT_FLOAT_EQ(r.centres[0], 10.5f);
  EXPECT_FLOAT_EQ(r.centres[1], 50.5f);
  EXPECT_FLOAT_EQ(r.positions[1], 30.5f);
  // Zero iterations leave the log initialisation: the middles of the log partitions.
  PartitionResult r0 = ComputePartitions({PartitionScheme::KMeans, 2, 0, 0}, 1, 64, h, 0, 0);
  EXPECT_FLOAT_EQ(r0.centres[0], 16.0f);
  EXPECT_FLOAT_EQ(r0.centres[1], 48.0f);
}

TEST(SdsmPartitions, NoSamplesFallBackToLogOverTheCameraRange) {
  std::vector<uint32_t> h(256, 0);
  for (PartitionScheme s : {PartitionScheme::Log, PartitionScheme::AdaptiveLog, PartitionScheme::KMeans}) {
    PartitionResult r = ComputePartitions({s, 3}, INFINITY, 0.0f, h, 0.5f, 200.0f);
    EXPECT_EQ(r.splits.front(), 0.5f);
    EXPECT_EQ(r.splits.back(), 200.0f);
    EXPECT_NEAR(r.splits[1], 0.5f * std::pow(400.0f, 1.0f / 3), 1e-3f);
  }
  EXPECT_EQ(ParsePartitionScheme("kmeans"), PartitionScheme::KMeans);
  EXPECT_THROW(ParsePartitionScheme("pssm"), std::invalid_argument);
  EXPECT_EQ(PartitionOf(5.0f, {1, 2, 4, 8}), 2u);
  EXPECT_EQ(PartitionOf(8.0f, {1, 2, 4, 8}), 2u);
  EXPECT_EQ(PartitionOf(0.5f, {1, 2, 4, 8}), 0u);
}

TEST(SdsmLightFrame, XAxisIsTheCameraDirectionProjectedOntoTheLightPlane) {
  glm::vec3 light = glm::normalize(glm::vec3(-0.4f, -1.0f, -0.3f)), camPos(3, 6, 12), fwd = glm::normalize(glm::vec3(-3, -5, -12));
  glm::mat4 v = MakeLightView(camPos, fwd, {0, 1, 0}, light);
  glm::vec3 x(v[0][0], v[1][0], v[2][0]), y(v[0][1], v[1][1], v[2][1]), z(v[0][2], v[1][2], v[2][2]);
  EXPECT_NEAR(glm::dot(z, -light), 1.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(x, light), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(x, y), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(glm::cross(x, y) - z), 0.0f, 1e-6f);  // right-handed
  glm::vec3 flat = glm::normalize(fwd - glm::dot(fwd, light) * light);
  EXPECT_NEAR(glm::dot(x, flat), 1.0f, 1e-6f);
  EXPECT_NEAR(glm::length(glm::vec3(v * glm::vec4(camPos, 1))), 0.0f, 1e-5f);  // origin at the camera
  // Looking along the light: the camera's up takes over.
  glm::mat4 w = MakeLightView({0, 10, 0}, {0, -1, 0}, {0, 0, -1}, {0, -1, 0});
  EXPECT_NEAR(w[2][0], -1.0f, 1e-6f);  // x = (0, 0, -1)
}

TEST(SdsmLightFrame, LightPositionIsTheSampleSeenThroughTheCamera) {
  scene::Camera cam;
  cam.position = {1, 4, 9};
  cam.target = {0, 0, 0};
  glm::mat4 lv = MakeLightView(cam.position, cam.forward(), cam.up, {0.3f, -1, 0.1f});
  const uint32_t W = 64, H = 40;
  AnalysisFrame f = AnalysisFrame::Make(cam.view(), cam.projection(float(W) / H), lv, W, H);
  EXPECT_NEAR(f.nearZ, cam.nearZ, 1e-6f);
  // Far comes back through A / (B - 1) of the float matrix: B - 1 = n / (f - n) loses digits.
  EXPECT_NEAR(f.farZ, cam.farZ, 2e-4f * cam.farZ);
  glm::mat4 inv = glm::inverse(cam.projection(float(W) / H) * cam.view());
  for (auto [x, y, d] : {std::tuple{3u, 5u, 0.9f}, std::tuple{60u, 39u, 0.999f}, std::tuple{31u, 20u, 0.2f}}) {
    glm::vec4 w = inv * glm::vec4((x + 0.5f) / W * 2 - 1, 1 - (y + 0.5f) / H * 2, d, 1.0f);
    glm::vec3 expect = glm::vec3(lv * glm::vec4(glm::vec3(w) / w.w, 1.0f));
    glm::vec3 got = f.LightPosition(x, y, f.ViewDepth(d));
    EXPECT_NEAR(glm::length(got - expect), 0.0f, 1e-4f * (1 + glm::length(expect)));
  }
  EXPECT_THROW(AnalysisFrame::Make(cam.view(), glm::mat4(1.0f), lv, W, H), std::invalid_argument);
  glm::mat4 reversed = glm::perspectiveRH_ZO(cam.fovY, 1.6f, cam.farZ, cam.nearZ);  // depth 1 at the near plane
  EXPECT_THROW(AnalysisFrame::Make(cam.view(), reversed, lv, W, H), std::invalid_argument);
}

TEST(SdsmLightFrame, OrderedKeysOrderLikeTheFloats) {
  std::vector<float> v = {-std::numeric_limits<float>::infinity(), -1e30f, -2.5f, -1e-30f, -0.0f, 0.0f, 1e-30f, 1.0f, 3.5f, 1e30f,
                          std::numeric_limits<float>::infinity()};
  for (size_t i = 0; i < v.size(); ++i) {
    EXPECT_EQ(std::signbit(FromOrderedKey(OrderedKey(v[i]))), std::signbit(v[i]));
    EXPECT_EQ(FromOrderedKey(OrderedKey(v[i])), v[i]);
    if (i) {
      EXPECT_LT(OrderedKey(v[i - 1]), OrderedKey(v[i])) << v[i - 1] << " < " << v[i];
    }
  }
}

TEST(SdsmLightFrame, ResultsRoundTripAndBoxesBecomeProjections) {
  AnalysisResults r;
  r.zMin = 0.7f, r.zMax = 93.0f, r.samples = 1234, r.partitionCount = 3;
  r.splits = {0.7f, 3.0f, 20.0f, 93.0f};
  r.bounds = {{{-1, -2, -30}, {4, 5, -10}, 7}, {}, {{-0.0f, 2, -3}, {0.0f, 2, 1}, 1}};
  AnalysisResults d = DecodeResults(EncodeResults(r).data());
  EXPECT_EQ(d.zMin, r.zMin);
  EXPECT_EQ(d.samples, r.samples);
  EXPECT_EQ(d.splits, r.splits);
  ASSERT_EQ(d.bounds.size(), 3u);
  EXPECT_EQ(d.bounds[0].min, r.bounds[0].min);
  EXPECT_EQ(d.bounds[0].max, r.bounds[0].max);
  EXPECT_TRUE(d.bounds[1].empty());
  EXPECT_TRUE(std::signbit(d.bounds[2].min.x));
  // The box's corners land on the clip volume's; dilation widens it by that much on each side.
  glm::mat4 p = PartitionProjection(r.bounds[0], 0.0f);
  glm::vec4 lo = p * glm::vec4(-1, -2, -10, 1), hi = p * glm::vec4(4, 5, -30, 1);
  EXPECT_NEAR(lo.x, -1, 1e-5f); EXPECT_NEAR(lo.y, -1, 1e-5f); EXPECT_NEAR(lo.z, 0, 1e-5f);
  EXPECT_NEAR(hi.x, 1, 1e-5f); EXPECT_NEAR(hi.y, 1, 1e-5f); EXPECT_NEAR(hi.z, 1, 1e-5f);
  glm::vec4 dl = PartitionProjection(r.bounds[0], 0.5f) * glm::vec4(-1.5f, -2.5f, -9.5f, 1);
  EXPECT_NEAR(dl.x, -1, 1e-5f); EXPECT_NEAR(dl.y, -1, 1e-5f); EXPECT_NEAR(dl.z, 0, 1e-5f);
}

TEST(SdsmLightFrame, FrustumSliceBoundsContainTheSlice) {
  scene::Camera cam;
  glm::mat4 lv = MakeLightView(cam.position, cam.forward(), cam.up, {-0.4f, -1, -0.3f});
  glm::mat4 proj = cam.projection(1.5f);
  LightBounds b = FrustumSliceBounds(cam.view(), proj, lv, 2.0f, 10.0f);
  glm::mat4 inv = glm::inverse(proj * cam.view());
  for (float nx : {-1.0f, 0.3f, 1.0f})
    for (float ny : {-1.0f, 1.0f})
      for (float vd : {2.0f, 5.0f, 10.0f}) {
        glm::vec4 c = proj * glm::vec4(0, 0, -vd, 1);
        glm::vec4 w = inv * glm::vec4(nx, ny, c.z / c.w, 1);
        glm::vec3 l = glm::vec3(lv * glm::vec4(glm::vec3(w) / w.w, 1));
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(l, b.min - 1e-3f)) && glm::all(glm::lessThanEqual(l, b.max + 1e-3f)));
      }
}

TEST(SdsmHistogramImage, DrawsBarsAndRedSplitLines) {
  const uint32_t N = 256, Wd = 320, Hd = 120;
  std::vector<uint32_t> h(N, 0);
  for (uint32_t b = 0; b < 80; ++b) h[b] = 100 + b;
  for (uint32_t b = 180; b < N; ++b) h[b] = 40;
  const float zMin = 1, zMax = 500;
  PartitionResult r = ComputePartitions({PartitionScheme::AdaptiveLog, 4}, zMin, zMax, h, 0, 0);
  std::vector<uint8_t> img = RenderHistogramImage(h, zMin, zMax, r.splits, Wd, Hd);
  ASSERT_EQ(img.size(), size_t(Wd) * Hd * 4);
  WritePng(TestOutputDir() / "histogram-adaptive-log.png", Wd, Hd, img.data());
  for (size_t i = 1; i + 1 < r.splits.size(); ++i) {
    uint32_t x = HistogramImageColumn(r.splits[i], zMin, zMax, Wd);
    for (uint32_t y : {0u, Hd / 2, Hd - 1}) {
      const uint8_t* p = &img[(size_t(y) * Wd + x) * 4];
      EXPECT_EQ(p[0], 220); EXPECT_EQ(p[1], 30); EXPECT_EQ(p[2], 30);
    }
  }
  // Bars stand from the bottom in occupied columns; the empty middle is background.
  auto blue = [&](uint32_t x, uint32_t y) { return img[(size_t(y) * Wd + x) * 4 + 2] == 160; };
  EXPECT_TRUE(blue(10, Hd - 1));
  EXPECT_FALSE(blue(Wd / 2, Hd - 1));
}

}  // namespace
}  // namespace sp::test
