// Cascaded shadow maps, CPU side (techniques/csm/cascade-fit.h): split schemes against their
// formulas, parameter validation, frustum fitting, focusing, culling and stabilization.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/ext/matrix_transform.hpp>

#include "csm/cascade-fit.h"
#include "csm/csm-technique.h"

namespace sp::test {
namespace {

using namespace tech::csm;

// A large, slightly uneven field of boxes on a 400 m plane; the camera looks across part of it.
scene::Scene Field(float size = 400.0f) {
  scene::Scene s;
  s.name = "field";
  uint32_t plane = s.addMesh(scene::MakePlane(1));
  uint32_t box = s.addMesh(scene::MakeBox());
  s.addInstance(plane, glm::scale(glm::mat4(1.0f), glm::vec3(size, 1, size)), glm::vec3(0.7f));
  for (int z = -5; z <= 5; ++z)
    for (int x = -5; x <= 5; ++x) {
      glm::vec3 p(x * size / 12, 2.0f + float((x * 7 + z * 3 + 100) % 5), z * size / 12);
      s.addInstance(box, glm::scale(glm::translate(glm::mat4(1.0f), p), glm::vec3(4, 2 * p.y, 4)), glm::vec3(0.7f));
    }
  s.camera.position = {10.0f, 12.0f, 60.0f};
  s.camera.target = {0.0f, 0.0f, 0.0f};
  s.camera.fovY = glm::radians(60.0f);
  s.camera.nearZ = 0.5f;
  s.camera.farZ = 300.0f;
  s.light.direction = glm::normalize(glm::vec3(0.4f, -1.0f, 0.3f));
  s.finalize();
  return s;
}

float Frac(float x) { return x - std::floor(x); }
// Distance between two fractions on the unit circle (0.999 and 0.001 are close).
float FracDistance(float a, float b) {
  float d = std::abs(Frac(a) - Frac(b));
  return std::min(d, 1.0f - d);
}

// --- Splits

TEST(CsmSplits, UniformLogAndPssmFollowTheirFormulas) {
  const float n = 0.5f, f = 500.0f;
  const int N = 4;
  std::vector<float> uni = SplitDistances(SplitScheme::Uniform, N, n, f, 0.0f);
  std::vector<float> lg = SplitDistances(SplitScheme::Log, N, n, f, 0.0f);
  std::vector<float> pssm = SplitDistances(SplitScheme::Pssm, N, n, f, 0.3f);
  ASSERT_EQ(uni.size(), size_t(N + 1));
  for (int i = 0; i <= N; ++i) {
    double s = double(i) / N;
    double u = n + (f - n) * s, l = n * std::pow(f / n, s);
    EXPECT_NEAR(uni[i], u, 1e-4 * u) << i;
    EXPECT_NEAR(lg[i], l, 1e-4 * l) << i;
    EXPECT_NEAR(pssm[i], 0.3 * l + 0.7 * u, 1e-4 * u) << i;
  }
  EXPECT_EQ(uni.front(), n);
  EXPECT_EQ(lg.back(), f);
  // lambda 0 and 1 are the uniform and logarithmic schemes.
  std::vector<float> p0 = SplitDistances(SplitScheme::Pssm, N, n, f, 0.0f), p1 = SplitDistances(SplitScheme::Pssm, N, n, f, 1.0f);
  for (int i = 0; i <= N; ++i) {
    EXPECT_FLOAT_EQ(p0[i], uni[i]);
    EXPECT_FLOAT_EQ(p1[i], lg[i]);
  }
  // One cascade covers the whole range whatever the scheme.
  EXPECT_EQ(SplitDistances(SplitScheme::Log, 1, n, f, 0.5f), (std::vector<float>{n, f}));
}

TEST(CsmSplits, ManualFractionsAreOfTheViewRange) {
  std::vector<float> fr = ParseManualSplits("0.05, 0.15,0.4", 4);
  ASSERT_EQ(fr, (std::vector<float>{0.05f, 0.15f, 0.4f}));
  EXPECT_EQ(ParseManualSplits("0.05:0.15:0.4", 4), fr);  // bench sweeps split --param values at commas
  std::vector<float> d = SplitDistances(SplitScheme::Manual, 4, 1.0f, 101.0f, 0.0f, fr);
  EXPECT_FLOAT_EQ(d[0], 1.0f);
  EXPECT_FLOAT_EQ(d[1], 6.0f);
  EXPECT_FLOAT_EQ(d[2], 16.0f);
  EXPECT_FLOAT_EQ(d[3], 41.0f);
  EXPECT_FLOAT_EQ(d[4], 101.0f);
  EXPECT_TRUE(ParseManualSplits("", 1).empty());
}

void ExpectSplitsError(const std::string& text, int cascades, const std::string& why) {
  try {
    ParseManualSplits(text, cascades);
    ADD_FAILURE() << "splits=" << text << " accepted";
  } catch (const std::invalid_argument& e) {
    std::string m = e.what();
    EXPECT_NE(m.find("splits=" + text), std::string::npos) << m;
    EXPECT_NE(m.find(why), std::string::npos) << m;
  }
}

TEST(CsmSplits, BadManualListsThrowNamingTheParameter) {
  ExpectSplitsError("0.1,0.2", 4, "2 given");
  ExpectSplitsError("0.3,0.2,0.5", 4, "must increase");
  ExpectSplitsError("0.1,0.1,0.5", 4, "must increase");
  ExpectSplitsError("0.1,1.5,1.7", 4, "not in (0, 1)");
  ExpectSplitsError("0.1,abc,0.5", 4, "not a number");
  ExpectSplitsError("0.1,,0.5", 4, "not a number");
  ExpectSplitsError("", 3, "0 given");

  // Through the technique's parameters: manual needs the list, the others refuse one.
  std::unique_ptr<tech::Technique> t = tech::CreateTechnique("csm");
  auto settings = [&](const std::map<std::string, std::string>& given) {
    return SettingsFrom(tech::ParamValues::Parse("csm", t->Params(), given));
  };
  EXPECT_EQ(settings({{"split", "manual"}, {"cascades", "3"}, {"splits", "0.1,0.3"}}).fit.manualFractions.size(), 2u);
  EXPECT_THROW(settings({{"split", "manual"}}), std::invalid_argument);
  try {
    settings({{"split", "log"}, {"splits", "0.1,0.2,0.3"}});
    ADD_FAILURE() << "splits accepted with split=log";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("splits=0.1,0.2,0.3 is only used with split=manual"), std::string::npos) << e.what();
  }
  // Ranges and choices are ParamValues::Parse's: the message lists what is valid.
  try {
    settings({{"kernel", "4"}});
    ADD_FAILURE();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("kernel takes 3|5|7|9"), std::string::npos) << e.what();
  }
  EXPECT_THROW(settings({{"cascades", "9"}}), std::invalid_argument);
  EXPECT_THROW(settings({{"blend", "0.6"}}), std::invalid_argument);
  EXPECT_THROW(settings({{"filter", "pcf"}}), std::invalid_argument);
}

TEST(CsmSplits, FarIsClippedToTheScene) {
  scene::Scene s = Field();
  scene::Camera cam = s.camera;
  cam.farZ = 1e5f;
  float tight = ClippedFar(cam, s.bounds, false);
  float stable = ClippedFar(cam, s.bounds, true);
  EXPECT_LT(tight, 400.0f);
  EXPECT_GE(stable, tight);
  EXPECT_LT(stable, 600.0f);
  // A nearer camera far plane wins.
  cam.farZ = 50.0f;
  EXPECT_EQ(ClippedFar(cam, s.bounds, false), 50.0f);
}

// --- Fitting

TEST(CsmFit, EverySlicePointProjectsInsideItsCascade) {
  scene::Scene s = Field();
  const float aspect = 16.0f / 9.0f;
  for (bool stabilize : {false, true}) {
    FitSettings fs;
    fs.focusReceivers = false;  // the whole slice, not only its part inside the scene
    fs.stabilize = stabilize;
    fs.resolution = 512;
    fs.padTexels = 3;
    CascadeSet set = FitCascades(s, s.camera, aspect, s.light.direction, fs);
    ASSERT_EQ(set.cascades.size(), 4u);
    for (const CascadeFit& c : set.cascades) {
      glm::vec3 corners[8];
      SliceCorners(s.camera, aspect, c.sliceNear, c.sliceFar, corners);
      // Corners and points between them (a slice is convex: corners bound it).
      for (int i = 0; i < 64; ++i) {
        glm::vec3 w(0.0f);
        float sum = 0.0f;
        for (int k = 0; k < 8; ++k) {
          float weight = i < 8 ? float(k == i) : float(((i * 31 + k * 17) % 7) + 1);
          w += corners[k] * weight;
          sum += weight;
        }
        glm::vec3 t = c.texel(w / sum, fs.resolution);
        // Inside the region, the padding kept clear for the filter.
        EXPECT_GE(t.x, fs.padTexels - 1e-2f) << stabilize;
        EXPECT_GE(t.y, fs.padTexels - 1e-2f) << stabilize;
        EXPECT_LE(t.x, fs.resolution - fs.padTexels + 1e-2f) << stabilize;
        EXPECT_LE(t.y, fs.resolution - fs.padTexels + 1e-2f) << stabilize;
      }
    }
    // Every caster of the scene lies within the depth range (focus=scene: the scene's).
    for (const CascadeFit& c : set.cascades)
      for (const scene::Instance& inst : s.instances) {
        scene::Bounds lb = inst.worldBounds.transformed(set.lightView);
        EXPECT_GE(-lb.max.z, c.zNear);
        EXPECT_LE(-lb.min.z, c.zFar);
      }
  }
}

TEST(CsmFit, FitSceneCascadesShareTheNearPlane) {
  scene::Scene s = Field();
  FitSettings fs;
  fs.fitToScene = true;
  CascadeSet set = FitCascades(s, s.camera, 1.5f, s.light.direction, fs);
  for (size_t i = 0; i < set.cascades.size(); ++i) {
    EXPECT_EQ(set.cascades[i].sliceNear, s.camera.nearZ);
    EXPECT_EQ(set.cascades[i].sliceFar, set.splits[i + 1]);
    if (i) {
      EXPECT_GT(set.cascades[i].texelWorld, set.cascades[i - 1].texelWorld);
    }
  }
}

TEST(CsmFit, BlendingCascadesAlsoCoverThePreviousBlendBand) {
  scene::Scene s = Field();
  FitSettings fs;
  fs.blend = 0.2f;
  CascadeSet set = FitCascades(s, s.camera, 1.5f, s.light.direction, fs);
  for (size_t i = 1; i < set.cascades.size(); ++i)
    EXPECT_NEAR(set.cascades[i].sliceNear, set.splits[i] - 0.2f * (set.splits[i] - set.splits[i - 1]), 1e-3f);
}

TEST(CsmFit, SliceBoxIntersectionIsExactForAContainedAndADisjointBox) {
  scene::Scene s = Field();
  glm::vec3 c[8];
  SliceCorners(s.camera, 1.0f, 5.0f, 20.0f, c);
  scene::Bounds big;
  big.extend(glm::vec3(-1000.0f));
  big.extend(glm::vec3(1000.0f));
  EXPECT_EQ(SliceBoxIntersection(c, big).size(), 8u);  // the slice's corners
  scene::Bounds away;
  away.extend(glm::vec3(500.0f));
  away.extend(glm::vec3(510.0f));
  EXPECT_TRUE(SliceBoxIntersection(c, away).empty());
  // A small box wholly inside the slice: its own corners.
  glm::vec3 mid = (c[0] + c[7]) * 0.5f;
  scene::Bounds small;
  small.extend(mid - 0.5f);
  small.extend(mid + 0.5f);
  std::vector<glm::vec3> pts = SliceBoxIntersection(c, small);
  scene::Bounds got;
  for (const glm::vec3& p : pts) got.extend(p);
  EXPECT_LT(glm::length(got.min - small.min) + glm::length(got.max - small.max), 1e-3f);
}

// Looking from near the scene's corner out over its edge: much of the view is empty, so fitting
// to the receivers shrinks the light frustums and their depth ranges, stabilized or not.
TEST(CsmFit, FocusOnReceiversIsTighterThanTheSceneFit) {
  scene::Scene s = Field();
  scene::Camera cam = s.camera;
  cam.position = {150.0f, 15.0f, 150.0f};
  cam.target = {240.0f, 0.0f, 140.0f};
  for (bool stabilize : {false, true}) {
    FitSettings fs;
    fs.stabilize = stabilize;
    fs.focusReceivers = false;
    CascadeSet wide = FitCascades(s, cam, 1.5f, s.light.direction, fs);
    fs.focusReceivers = true;
    CascadeSet focused = FitCascades(s, cam, 1.5f, s.light.direction, fs);
    double areaWide = 0, areaFocused = 0;
    int withReceivers = 0;
    for (int i = 0; i < 4; ++i) {
      const CascadeFit &w = wide.cascades[i], &f = focused.cascades[i];
      if (f.noReceivers) continue;  // fitted to the slice alone, as focus=scene
      ++withReceivers;
      glm::vec2 ew = w.max - w.min, ef = f.max - f.min;
      areaWide += double(ew.x) * ew.y;
      areaFocused += double(ef.x) * ef.y;
      EXPECT_LE(ef.x * ef.y, ew.x * ew.y * 1.0001f) << "cascade " << i << " stabilize " << stabilize;
      EXPECT_LT(f.zFar - f.zNear, 0.8f * (w.zFar - w.zNear)) << "cascade " << i << " stabilize " << stabilize;
    }
    EXPECT_GE(withReceivers, 3);
    EXPECT_LT(areaFocused, 0.75 * areaWide) << "stabilize " << stabilize;
  }
}

TEST(CsmFit, CullingKeepsOnlyCastersThatReachTheCascade) {
  scene::Scene s = Field();
  FitSettings fs;
  CascadeSet set = FitCascades(s, s.camera, 1.5f, s.light.direction, fs);
  size_t total = s.instances.size(), firstKept = 0;
  for (const scene::Instance& inst : s.instances) firstKept += MayCastInto(set.cascades[0], inst.worldBounds.transformed(set.lightView));
  EXPECT_GE(firstKept, 1u);  // the plane
  EXPECT_LT(firstKept, total / 4) << "the nearest cascade covers a few metres";
  // A caster between the light and the near plane is kept (it is pancaked, and casts); one past
  // the far plane is not.
  const CascadeFit& c = set.cascades[0];
  glm::vec2 mid = (c.min + c.max) * 0.5f;
  scene::Bounds before, beyond;
  before.extend(glm::vec3(mid, -(c.zNear - 50.0f)));
  before.extend(glm::vec3(mid + 0.1f, -(c.zNear - 49.0f)));
  beyond.extend(glm::vec3(mid, -(c.zFar + 1.0f)));
  beyond.extend(glm::vec3(mid + 0.1f, -(c.zFar + 2.0f)));
  EXPECT_TRUE(MayCastInto(c, before));
  EXPECT_FALSE(MayCastInto(c, beyond));
}

// --- Stabilization

struct CascadeSnapshot {
  glm::vec2 size;
  glm::vec2 originTexel;  // texel coordinates of the world origin
};

// Fits as the technique does frame after frame, with the previous frame's fit.
std::vector<CascadeSnapshot> Snapshot(const scene::Scene& s, const scene::Camera& cam, const FitSettings& fs, CascadeSet* previous) {
  CascadeSet set = FitCascades(s, cam, 16.0f / 9.0f, s.light.direction, fs, previous->cascades.empty() ? nullptr : previous);
  std::vector<CascadeSnapshot> out;
  for (const CascadeFit& c : set.cascades) out.push_back({c.max - c.min, glm::vec2(c.texel(glm::vec3(0.0f), fs.resolution))});
  *previous = set;
  return out;
}

scene::Camera Moved(scene::Camera cam, int step) {
  // Small sideways and forward moves and a small turn, as a walking camera.
  glm::vec3 shift(0.037f * step, 0.011f * step, -0.023f * step);
  glm::vec3 dir = glm::vec3(glm::rotate(glm::mat4(1.0f), glm::radians(0.35f * step), glm::vec3(0, 1, 0)) * glm::vec4(cam.target - cam.position, 0.0f));
  cam.position += shift;
  cam.target = cam.position + dir;
  return cam;
}

// The camera starts at the top of the scene's bounds, so the nearest slices leave the scene
// (focus=receivers fits them to a square around their receivers) and the farther ones do not.
TEST(CsmStabilize, SmallCameraMotionsMoveTheMapsByWholeTexelsOnly) {
  scene::Scene s = Field();
  std::vector<CascadeSnapshot> bases[2];
  for (bool receivers : {true, false}) {
    FitSettings fs;
    fs.resolution = 1024;
    fs.focusReceivers = receivers;
    CascadeSet previous;
    std::vector<CascadeSnapshot> base = bases[receivers] = Snapshot(s, s.camera, fs, &previous);
    for (int step = 1; step <= 12; ++step) {
      std::vector<CascadeSnapshot> now = Snapshot(s, Moved(s.camera, step), fs, &previous);
      for (size_t c = 0; c < base.size(); ++c) {
        EXPECT_EQ(now[c].size, base[c].size) << "cascade " << c << " step " << step << " receivers " << receivers;
        EXPECT_LT(FracDistance(now[c].originTexel.x, base[c].originTexel.x), 2e-3f) << "cascade " << c << " step " << step;
        EXPECT_LT(FracDistance(now[c].originTexel.y, base[c].originTexel.y), 2e-3f) << "cascade " << c << " step " << step;
      }
    }
  }
  // The receivers' squares are smaller than the slices' spheres: both kinds were exercised.
  EXPECT_LT(bases[1][0].size.x, bases[0][0].size.x);
}

// Without the previous frame (a fresh fit each time) whole slices still keep their sphere.
TEST(CsmStabilize, SlicesInsideTheSceneKeepTheirSizeWithoutHistory) {
  scene::Scene s = Field();
  scene::Camera cam = s.camera;
  // Looking level from inside the bounds, not far enough for the frustum to leave them.
  cam.position.y = 6.0f;
  cam.target = {0.0f, 6.0f, 0.0f};
  cam.farZ = 10.0f;
  FitSettings fs;
  CascadeSet base = FitCascades(s, cam, 1.5f, s.light.direction, fs);
  for (int step = 1; step <= 12; ++step) {
    CascadeSet now = FitCascades(s, Moved(cam, step), 1.5f, s.light.direction, fs);
    for (size_t c = 0; c < base.cascades.size(); ++c) {
      EXPECT_EQ(now.cascades[c].fitSize, base.cascades[c].fitSize) << c;
      EXPECT_FALSE(now.cascades[c].noReceivers);
    }
  }
}

TEST(CsmStabilize, WithoutStabilizationTheMapsShimmer) {
  scene::Scene s = Field();
  FitSettings fs;
  fs.resolution = 1024;
  fs.stabilize = false;
  CascadeSet previous;
  std::vector<CascadeSnapshot> base = Snapshot(s, s.camera, fs, &previous);
  int sizeChanged = 0, subTexelMoves = 0;
  for (int step = 1; step <= 12; ++step) {
    std::vector<CascadeSnapshot> now = Snapshot(s, Moved(s.camera, step), fs, &previous);
    for (size_t c = 0; c < base.size(); ++c) {
      sizeChanged += glm::any(glm::greaterThan(glm::abs(now[c].size - base[c].size), base[c].size * 1e-4f));
      subTexelMoves += FracDistance(now[c].originTexel.x, base[c].originTexel.x) > 1e-2f ||
                       FracDistance(now[c].originTexel.y, base[c].originTexel.y) > 1e-2f;
    }
  }
  EXPECT_GT(sizeChanged, 24);
  EXPECT_GT(subTexelMoves, 24);
}

}  // namespace
}  // namespace sp::test
