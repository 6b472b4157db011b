// The seam metric (eval::MeasureSeamAccuracy): the classification of directions by their distance
// from the nearest cube-face edge against D3D11's face table, a synthetic frame whose errors lie
// only in the seam band (or only outside it), and the bench on `cube-seam` with `cube` on both
// backends. And the reference picture of a judged local light, which must show what the
// technique's picture shows where the technique is right.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <string>

#include "../techniques/cube-room.h"
#include "bench-both-backends.h"
#include "bench.h"
#include "cube/cube-faces.h"
#include "metrics.h"
#include <sp/rhi/rhi.h>

namespace sp::test {
namespace {

TEST(SeamMetric, EdgeGapIsTheDistanceFromTheFaceEdgeInFaceCoordinates) {
  // A direction at face coordinates (s, t) of face f, scaled: its gap is 1 - max(|s|, |t|).
  for (int f = 0; f < 6; ++f) {
    tech::cube::FaceAxes ax = tech::cube::Face(f);
    for (float s : {-1.0f, -0.97f, -0.5f, 0.0f, 0.3f, 0.996f, 1.0f}) {
      for (float t : {-0.999f, -0.2f, 0.0f, 0.75f, 1.0f}) {
        glm::vec3 d = 2.5f * (ax.major + s * ax.s + t * ax.t);
        EXPECT_NEAR(eval::CubeEdgeGap(d), 1.0f - std::max(std::abs(s), std::abs(t)), 1e-5f) << "face " << f << " s " << s << " t " << t;
        if (std::max(std::abs(s), std::abs(t)) < 1.0f) {
          EXPECT_EQ(tech::cube::FaceOf(d), f);
        }
      }
    }
  }
  EXPECT_FLOAT_EQ(eval::CubeEdgeGap({1, 1, 1}), 0.0f);    // a corner
  EXPECT_FLOAT_EQ(eval::CubeEdgeGap({0, -3, 0}), 1.0f);   // a face's axis
  EXPECT_FLOAT_EQ(eval::CubeEdgeGap({-2, 0, 2}), 0.0f);   // the -X/+Z edge
  EXPECT_FLOAT_EQ(eval::SeamBandFor(512), 2.0f / 512.0f); // one texel on each side
}

// A 192 x 192 view straight down on a floor 2 m under a point light, [-6, 6]^2: every pixel
// judged, the reference lit everywhere. The floor holds the -Y face and parts of the four side
// faces, so it crosses -Y's four edges (x or z = +-2) and the side faces' diagonal edges.
struct FloorFrame {
  tech::LabBuffers lab;
  std::vector<uint8_t> reference;
  glm::vec3 light{0.0f, 2.0f, 0.0f};
  std::vector<bool> inBand;
  size_t bandPixels = 0;
};

FloorFrame MakeFloorFrame(float band) {
  FloorFrame f;
  const uint32_t n = 192;
  tech::LabBuffers& b = f.lab;
  b.width = b.height = n;
  b.normal.assign(b.size(), glm::vec4(0, 1, 0, 1));
  b.visibility.assign(b.size(), 1.0f);
  b.lookup.assign(b.size(), glm::vec4(-1, 0, 0, 0));
  b.color.assign(b.size() * 4, 128);
  b.albedo.assign(b.size() * 4, 200);
  f.reference.assign(b.size(), 1);
  for (uint32_t y = 0; y < n; ++y)
    for (uint32_t x = 0; x < n; ++x) {
      glm::vec3 p(-6.0f + 12.0f * (x + 0.5f) / n, 0.0f, -6.0f + 12.0f * (y + 0.5f) / n);
      b.position.push_back(glm::vec4(p, 1.0f));
      // Independently of CubeEdgeGap: the two largest of |x|, |y|, |z| by sorting.
      glm::vec3 d = glm::abs(p - f.light);
      float v[3] = {d.x, d.y, d.z};
      std::sort(v, v + 3);
      bool in = (v[2] - v[1]) / v[2] < band;
      f.inBand.push_back(in);
      f.bandPixels += in;
    }
  return f;
}

TEST(SeamMetric, ErrorsAlongTheSeamsCountInTheBandAndErrorsElsewhereOutsideIt) {
  const float band = eval::SeamBandFor(64);  // a coarse 64-texel face, so the band is a few pixels wide
  FloorFrame f = MakeFloorFrame(band);
  const size_t total = f.lab.size();
  ASSERT_GT(f.bandPixels, 500u);
  ASSERT_LT(f.bandPixels, total / 4);

  // Every other band pixel shadowed against a lit reference: a seam artifact.
  size_t wrong = 0, k = 0;
  for (size_t i = 0; i < total; ++i)
    if (f.inBand[i] && k++ % 2 == 0) f.lab.visibility[i] = 0.0f, ++wrong;
  eval::SeamAccuracy s = eval::MeasureSeamAccuracy(f.lab, f.reference.data(), f.light, band);
  EXPECT_EQ(s.band.receiving, f.bandPixels);
  EXPECT_EQ(s.elsewhere.receiving, total - f.bandPixels);
  EXPECT_EQ(s.band.falseShadow, wrong);
  EXPECT_NEAR(s.band.misclassifiedPct(), 50.0, 0.5);
  EXPECT_EQ(s.elsewhere.misclassifiedPct(), 0.0);

  // The reverse: the same number of errors, all away from the seams (false lit this time).
  FloorFrame g = MakeFloorFrame(band);
  for (size_t i = 0; i < total; ++i) g.reference[i] = 0, g.lab.visibility[i] = 0.0f;
  k = 0;
  for (size_t i = 0; i < total && k < wrong; ++i)
    if (!g.inBand[i] && i % 3 == 0) g.lab.visibility[i] = 1.0f, ++k;
  eval::SeamAccuracy r = eval::MeasureSeamAccuracy(g.lab, g.reference.data(), g.light, band);
  EXPECT_EQ(r.band.misclassifiedPct(), 0.0);
  EXPECT_EQ(r.elsewhere.falseLit, wrong);
  EXPECT_GT(r.elsewhere.misclassifiedPct(), 0.5);

  EXPECT_THROW(eval::MeasureSeamAccuracy(g.lab, g.reference.data(), g.light, 0.0f), std::invalid_argument);
  EXPECT_THROW(eval::MeasureSeamAccuracy(g.lab, g.reference.data(), g.light, 1.5f), std::invalid_argument);
}

// Texels per pixel per face: each pixel's density set to its face's number (+1) is found again
// under that face, by D3D11's face selection; the floor under the light never sees +Y.
TEST(SeamMetric, TexelDensityIsSplitByTheCubeFaceOfTheDirection) {
  for (int f = 0; f < 6; ++f) {
    tech::cube::FaceAxes ax = tech::cube::Face(f);
    for (glm::vec2 st : {glm::vec2(0.0f), glm::vec2(0.9f, -0.4f), glm::vec2(-0.99f, 0.99f)})
      EXPECT_EQ(eval::CubeFace(ax.major + st.x * ax.s + st.y * ax.t), f);
  }
  EXPECT_EQ(eval::CubeFace({1, 1, 1}), tech::cube::FaceOf({1, 1, 1}));
  EXPECT_EQ(eval::CubeFace({-1, -1, 0.5f}), tech::cube::FaceOf({-1, -1, 0.5f}));
  FloorFrame fr = MakeFloorFrame(0.01f);
  for (size_t i = 0; i < fr.lab.size(); ++i)
    fr.lab.lookup[i] = glm::vec4(0, 0, 0, float(tech::cube::FaceOf(glm::vec3(fr.lab.position[i]) - fr.light) + 1));
  std::array<eval::LogHistogram, 6> h;
  eval::AddTexelDensityByFace(fr.lab, fr.light, h);
  for (int f = 0; f < 6; ++f) {
    SCOPED_TRACE(eval::kCubeFaceNames[f]);
    if (f == 2) {
      EXPECT_EQ(h[f].count(), 0u);
      continue;
    }
    EXPECT_GT(h[f].count(), 1000u);
    EXPECT_DOUBLE_EQ(h[f].percentile(0.5), double(f + 1));
  }
}

// The seam scene: `cube` at its default 512 texels per face, 256 x 144. The band is one texel on
// each side of the edges; no seam error means the band is misclassified no more than the shadow
// edges elsewhere are.
TEST(SeamBench, CubeOnCubeSeamIsMeasuredInAndOutsideTheSeamBandAlikeOnBothBackends) {
  scene::Scene s = scene::MakeBuiltinScene("cube-seam");
  std::array<bench::RunResult, 2> r = BenchOnBothBackends(s, "cube", {}, 256, 144);
  ExpectSameAccuracyOnMesa(r, "cube-seam");
  EXPECT_FLOAT_EQ(r[0].seamBand, 2.0f / 512.0f);
  EXPECT_EQ(r[0].seam.band.receiving + r[0].seam.elsewhere.receiving, r[0].accuracy.receiving);
  EXPECT_GT(r[0].seam.band.receiving, 150u) << "the camera must see the floor along the seams";
  nlohmann::json j = bench::RunToJson(r[0], {});
  EXPECT_EQ(j["checks"]["seam_pixels"], r[0].seam.band.receiving);
  EXPECT_EQ(j["checks"]["off_seam_pixels"], r[0].seam.elsewhere.receiving);
  EXPECT_TRUE(j["metrics"].contains("seam_misclassified_pct") && j["metrics"].contains("off_seam_misclassified_pct"));
  // The camera sees the floor (-Y) and the two walls (+X, +Z) lit by the light.
  for (int f : {0, 3, 4}) EXPECT_GT(r[0].texelsPerPixelMedianByFace[f], 0.5) << eval::kCubeFaceNames[f];
  EXPECT_EQ(j["metrics"]["texels_per_pixel_median_by_face"]["-Y"], r[0].texelsPerPixelMedianByFace[3]);
  std::printf("cube-seam 256x144: seam band %.3f %% of %llu px, elsewhere %.3f %% of %llu px (Vulkan); %.3f %% / %.3f %% (GL)\n",
              r[0].seam.band.misclassifiedPct(), (unsigned long long)r[0].seam.band.receiving, r[0].seam.elsewhere.misclassifiedPct(),
              (unsigned long long)r[0].seam.elsewhere.receiving, r[1].seam.band.misclassifiedPct(), r[1].seam.elsewhere.misclassifiedPct());
  // No more wrong band pixels than the rate elsewhere (shadow edges under the 2x2 filter) predicts
  // with room for chance: three times the expectation, or two pixels where that is below one.
  const eval::SeamAccuracy& seam = r[0].seam;
  double expected = seam.band.receiving * seam.elsewhere.misclassifiedPct() / 100.0;
  EXPECT_LE(double(seam.band.falseLit + seam.band.falseShadow), std::max(2.0, 3.0 * expected)) << "expected " << expected;
  bool mesa = r[0].device.find("llvmpipe") != std::string::npos && r[1].device.find("llvmpipe") != std::string::npos;
  if (mesa) {
    EXPECT_EQ(r[0].seam.band.receiving, r[1].seam.band.receiving);
    EXPECT_EQ(r[0].seam.band.falseLit, r[1].seam.band.falseLit);
    EXPECT_EQ(r[0].seam.band.falseShadow, r[1].seam.band.falseShadow);
    EXPECT_EQ(r[0].seam.elsewhere.falseLit, r[1].seam.elsewhere.falseLit);
    EXPECT_EQ(r[0].seam.elsewhere.falseShadow, r[1].seam.elsewhere.falseShadow);
    EXPECT_EQ(r[0].texelsPerPixelMedianByFace, r[1].texelsPerPixelMedianByFace);
  }
}

// The reference picture of a judged point light shades that light with the reference's
// visibility: on the cube test room (one point light, the directional light off) it matches the
// technique's own picture except on shadow edges; the directional-only picture does not.
TEST(ReferencePicture, JudgedPointLightPictureMatchesTheTechniquesPicture) {
  CubeRoom room = MakeCubeRoom();
  for (const bench::RunResult& r : BenchOnBothBackends(room.scene, "cube", {}, 160, 90)) {
    SCOPED_TRACE(r.backend);
    const tech::LabBuffers& f = r.firstFrame;
    ASSERT_EQ(r.judgedLocalLight, 0);
    auto differing = [&](const std::vector<uint8_t>& pic) {
      size_t n = 0;
      for (size_t i = 0; i < f.size(); ++i) {
        int m = 0;
        for (int c = 0; c < 3; ++c) m = std::max(m, std::abs(int(pic[i * 4 + c]) - int(f.color[i * 4 + c])));
        n += m > 3;  // beyond the GPU's float and sRGB rounding
      }
      return 100.0 * double(n) / double(f.size());
    };
    double local = differing(eval::ReferenceImage(f, r.firstReference.data(), r.light, tech::LocalLightsOf(room.scene), 0));
    double directional = differing(eval::ReferenceImage(f, r.firstReference.data(), r.light));
    std::printf("%s: reference picture differs from the technique's in %.2f %% of pixels (directional-only picture: %.2f %%)\n",
                r.backend.c_str(), local, directional);
    EXPECT_LT(local, 1.5);
    EXPECT_GT(directional, 50.0);
    EXPECT_EQ(bench::ReferenceImageName(0), "reference-light0.png");
  }
}

}  // namespace
}  // namespace sp::test
