// Perspective shadow-map warps, CPU side (techniques/warps/warp-fit.h): containment of the body
// of interest and its casters for every warp over the whole range of light angles, the analytic
// texel densities on a ground plane, the TSM focus line, and continuity at the fallback.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <string>

#include "warps/warp-fit.h"

namespace sp::test {
namespace {

using namespace tech::warps;

const Warp kWarps[] = {Warp::None, Warp::Psm, Warp::Lispsm, Warp::Tsm};
const char* Name(Warp w) { return w == Warp::None ? "none" : w == Warp::Psm ? "psm" : w == Warp::Lispsm ? "lispsm" : "tsm"; }

// A 400 m field with casters up to 20 m.
scene::Bounds Field() {
  scene::Bounds b;
  b.extend(glm::vec3(-200, 0, -200));
  b.extend(glm::vec3(200, 20, 200));
  return b;
}

scene::Camera Cam(glm::vec3 pos, glm::vec3 target) {
  scene::Camera c;
  c.position = pos;
  c.target = target;
  c.fovY = glm::radians(60.0f);
  c.nearZ = 0.5f;
  c.farZ = 300.0f;
  return c;
}

// The light travelling at `gammaDeg` from the camera's view direction, turned about the view axis
// by `azimuthDeg` (0: the light comes from above the camera's up side).
glm::vec3 LightAt(const scene::Camera& c, float gammaDeg, float azimuthDeg) {
  glm::vec3 f = c.forward();
  glm::vec3 r = glm::normalize(glm::cross(f, c.up)), u = glm::cross(r, f);
  float az = glm::radians(azimuthDeg), g = glm::radians(gammaDeg);
  glm::vec3 side = -(u * std::cos(az) + r * std::sin(az));  // travelling away from the up side
  return glm::normalize(f * std::cos(g) + side * std::sin(g));
}

bool AllFinite(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

// Distance along `dir` from p to where it leaves the box (p inside).
float ExitDistance(const glm::vec3& p, const glm::vec3& dir, const scene::Bounds& b) {
  float t = 1e30f;
  for (int a = 0; a < 3; ++a) {
    if (dir[a] > 1e-6f) t = std::min(t, (b.max[a] - p[a]) / dir[a]);
    if (dir[a] < -1e-6f) t = std::min(t, (b.min[a] - p[a]) / dir[a]);
  }
  return std::max(t, 0.0f);
}

bool Inside(const glm::vec3& b, const scene::Bounds& box, float eps) {
  return glm::all(glm::greaterThanEqual(b, box.min - eps)) && glm::all(glm::lessThanEqual(b, box.max + eps));
}

// Every point of B maps inside the map; points of B moved towards the light while inside the
// caster bounds keep their texel and land at a depth in [0, depth of B's point]; beyond the caster
// bounds they land in front of the near plane or inside it, never behind B.
void ExpectContained(const WarpInput& in, const WarpFit& fit, const std::string& what) {
  const float R = 1024.0f, eps = 1e-3f;
  ASSERT_TRUE(AllFinite(fit.viewProj)) << what;
  ASSERT_TRUE(std::isfinite(fit.gamma) && std::isfinite(fit.blend)) << what;
  for (int i = 0; i < 4; ++i) ASSERT_TRUE(std::isfinite(fit.linearDepth[i])) << what;
  for (const glm::vec2& c : fit.trapezoid) ASSERT_TRUE(std::isfinite(c.x) && std::isfinite(c.y)) << what;
  glm::vec3 L = glm::normalize(in.lightDirection);
  for (const glm::vec3& b : in.body) {
    glm::vec4 clip = fit.viewProj * glm::vec4(b, 1.0f);
    ASSERT_GT(clip.w, 0.0f) << what;
    glm::vec3 t = ToTexel(fit, b, R);
    ASSERT_TRUE(std::isfinite(t.x) && std::isfinite(t.y) && std::isfinite(t.z)) << what;
    EXPECT_GE(t.x / R, -eps) << what;
    EXPECT_LE(t.x / R, 1 + eps) << what;
    EXPECT_GE(t.y / R, -eps) << what;
    EXPECT_LE(t.y / R, 1 + eps) << what;
    EXPECT_GE(t.z, -eps) << what;
    EXPECT_LE(t.z, 1 + eps) << what;
    float lin = LinearDepth(fit, b);
    EXPECT_GE(lin, -eps) << what;
    EXPECT_LE(lin, 1 + eps) << what;
    if (!Inside(b, in.casters, 1e-3f)) continue;
    float exit = ExitDistance(b, -L, in.casters);
    for (float s : {0.3f, 0.7f, 1.0f}) {
      glm::vec3 c = b - L * (exit * s);
      glm::vec3 tc = ToTexel(fit, c, R);
      EXPECT_NEAR(tc.x, t.x, 0.05f) << what << " caster keeps its texel";
      EXPECT_NEAR(tc.y, t.y, 0.05f) << what << " caster keeps its texel";
      EXPECT_GE(tc.z, -eps) << what << " caster between B and the light";
      EXPECT_LE(tc.z, t.z + eps) << what << " caster nearer the light than B";
      EXPECT_GE(LinearDepth(fit, c), -eps) << what;
    }
    // Beyond the caster bounds: still nearer the light, possibly in front of the near plane.
    glm::vec3 far = b - L * (exit + 50.0f);
    glm::vec4 fc = fit.viewProj * glm::vec4(far, 1.0f);
    EXPECT_GT(fc.w, 0.0f) << what;
    EXPECT_LE(fc.z / fc.w, t.z + eps) << what;
  }
}

TEST(WarpFit, BodyAndCastersInsideTheMapForEveryWarpAndLightAngle) {
  const scene::Bounds field = Field();
  const scene::Camera cams[] = {
      Cam({10, 12, 60}, {0, 0, 0}),          // looking down across the field
      Cam({0, 2, 0}, {0, 2, -10}),           // horizontal, near the ground
      Cam({-50, 15, -30}, {30, 40, 20}),     // looking up and sideways
      Cam({0, 18, 0}, {5, 0, -4}),           // steeply down
  };
  int fits = 0, fellBack = 0;
  for (const scene::Camera& cam : cams)
    for (float az : {0.0f, 35.0f, 90.0f, 200.0f})
      for (int g = 0; g <= 180; g += (g < 3 || g > 176) ? 1 : 4) {
        glm::vec3 L = LightAt(cam, float(g), az);
        WarpInput in = MakeWarpInput(cam, 16.0f / 9.0f, L, field, cam.nearZ, 150.0f);
        ASSERT_FALSE(in.body.empty());
        for (Warp w : kWarps) {
          WarpFit fit = FitWarp(in, w);
          ExpectContained(in, fit, std::string(Name(w)) + " gamma " + std::to_string(g) + " azimuth " + std::to_string(az));
          EXPECT_NEAR(fit.gamma, float(g), 0.05f);
          ++fits;
          fellBack += fit.fellBack;
          if (w != Warp::None && (g == 0 || g == 180) && w != Warp::Lispsm) {
            EXPECT_TRUE(fit.fellBack) << Name(w) << " at gamma " << g;
          }
        }
        if (HasFatalFailure()) return;
      }
  RecordProperty("fits", fits);
  RecordProperty("fellBack", fellBack);
}

// Exactly parallel and anti-parallel light, the light along the camera's up vector too: finite,
// contained, and the uniform map (LiSPSM's sin(gamma) rounds to ~1e-8 there: within a hair of it).
TEST(WarpFit, ParallelAndOppositeLightFallBackToTheUniformMap) {
  const scene::Bounds field = Field();
  scene::Camera cam = Cam({0, 10, 0}, {0, 0, 0.0f});
  cam.target = {0, 0, 0};
  cam.up = {0, 0, -1};
  for (scene::Camera c : {cam, Cam({10, 12, 60}, {0, 0, 0})})
    for (float sign : {1.0f, -1.0f}) {
      glm::vec3 L = sign * c.forward();
      WarpInput in = MakeWarpInput(c, 1.5f, L, field, c.nearZ, 150.0f);
      WarpFit uniform = FitWarp(in, Warp::None);
      for (Warp w : kWarps) {
        WarpFit fit = FitWarp(in, w);
        ExpectContained(in, fit, Name(w));
        for (const glm::vec3& b : in.body) {
          glm::vec3 a = ToTexel(fit, b, 1024), u = ToTexel(uniform, b, 1024);
          EXPECT_NEAR(a.x, u.x, 0.01f) << Name(w);
          EXPECT_NEAR(a.y, u.y, 0.01f) << Name(w);
        }
      }
    }
}

// Ground plane, camera at eye height looking along it, light straight down (gamma = 90 degrees),
// B = the whole slice [z_n, z_f] = [1, 100] (the scene bounds hold it). Along the view, light-view
// Y is the view depth z, so with t = z - z_n and d = z_f - z_n:
//   uniform  v = t / d                                 dv/dz constant, du/dx constant
//   LiSPSM   v ~ t / (1 + k t), u ~ x / (1 + k t)      dv/dz ~ 1 / (1 + k t)^2, du/dx ~ 1 / (1 + k t)
//            k = 1 / n_opt, n_opt = z_n + sqrt(z_n z_f) (the paper's formula, sin 90 = 1), so
//            (1 + k d) = (n + d) / n = sqrt(z_f) (sqrt(z_f) + sqrt(z_n)) / (sqrt(z_n) (sqrt(z_n) + sqrt(z_f)))
//            = sqrt(z_f / z_n): near/far density z_f / z_n along v, sqrt(z_f / z_n) along u (the
//            paper's point: texel density falls as 1/z, like the screen's).
//   PSM      post-projective z of a camera with near z_n (slide-back 0: nothing is behind it) and
//            far at infinity, v ~ 1 - z_n / z, u ~ x / z: near/far (z_f / z_n)^2 along v, z_f / z_n
//            along u (PSM's over-sampling of the near field).
// Tolerance: densities are central differences over +-h, h = z / 100; for v = A + B / (z + c) or
// t / (1 + k t) the relative truncation error h^2 v''' / (6 v') is at most (h / z)^2 = 1e-4. The
// fit's slack scales both ends alike (it cancels in the ratio). Float rounding of the clip
// position is about 1e-6 of the map (4e-3 texels at 4096) against differences of at least 0.8
// texels (PSM's far end): under 0.5 %. So 2 % holds with room and still tells these laws apart.
struct Ground {
  scene::Camera cam = Cam({0, 2, 0}, {0, 2, -1});
  WarpInput in;
  Ground() {
    cam.nearZ = 1.0f;
    scene::Bounds big;
    big.extend(glm::vec3(-1000, -100, -1000));
    big.extend(glm::vec3(1000, 100, 1000));
    in = MakeWarpInput(cam, 1.0f, glm::vec3(0, -1, 0), big, 1.0f, 100.0f);
  }
  // Texels per metre along the view (v) and across it (u) at view depth z on the ground.
  glm::vec2 Density(const WarpFit& fit, float z) const {
    glm::vec3 p(0, 0, -z);
    return {TexelsPerUnit(fit, p, {1, 0, 0}, 4096, z / 100), TexelsPerUnit(fit, p, {0, 0, -1}, 4096, z / 100)};
  }
};

TEST(WarpDensity, UniformIsConstantAlongTheView) {
  Ground g;
  ASSERT_EQ(g.in.body.size(), 8u);
  WarpFit fit = FitWarp(g.in, Warp::None);
  EXPECT_NEAR(fit.gamma, 90.0f, 1e-3f);
  glm::vec2 near = g.Density(fit, 1), mid = g.Density(fit, 30), far = g.Density(fit, 100);
  EXPECT_NEAR(near.y / far.y, 1.0f, 0.02f);
  EXPECT_NEAR(mid.y / far.y, 1.0f, 0.02f);
  EXPECT_NEAR(near.x / far.x, 1.0f, 0.02f);
}

TEST(WarpDensity, LispsmAtNoptFollowsThePapersPrediction) {
  Ground g;
  WarpFit fit = FitWarp(g.in, Warp::Lispsm);
  EXPECT_FALSE(fit.fellBack);
  EXPECT_NEAR(fit.blend, 1.0f, 1e-6f);
  EXPECT_NEAR(fit.n, 1.0f + std::sqrt(100.0f), 1e-3f);  // z_n + sqrt(z_n z_f)
  // A perspective map: w grows along the warp axis, 1 + d / n times from near to far.
  glm::vec4 wn = fit.viewProj * glm::vec4(0, 0, -1, 1), wf = fit.viewProj * glm::vec4(0, 0, -100, 1);
  EXPECT_NEAR(wf.w / wn.w, 1.0f + 99.0f / fit.n, 1e-3f);
  glm::vec2 near = g.Density(fit, 1), far = g.Density(fit, 100);
  EXPECT_NEAR((near.y / far.y) / 100.0f, 1.0f, 0.02f) << near.y << " " << far.y;
  EXPECT_NEAR((near.x / far.x) / 10.0f, 1.0f, 0.02f) << near.x << " " << far.x;
  // In between it follows the same law: density along v at z relative to far = ((n + d) / (n + t))^2.
  const double n = 1.0 + 10.0, d = 99.0;
  for (float z : {5.0f, 20.0f, 60.0f}) {
    double expect = std::pow((n + d) / (n + z - 1.0), 2.0);
    EXPECT_NEAR(g.Density(fit, z).y / far.y / expect, 1.0, 0.02) << z;
  }
  // Scaling n: twice n_opt warps less (ratio ((n + d) / n)^2 with n = 2 n_opt).
  WarpParams p;
  p.lispsmScale = 2.0f;
  WarpFit weaker = FitWarp(g.in, Warp::Lispsm, p);
  double n2 = 2.0 * n, expect2 = std::pow((n2 + d) / n2, 2.0);
  EXPECT_NEAR(g.Density(weaker, 1).y / g.Density(weaker, 100).y / expect2, 1.0, 0.02);
}

TEST(WarpDensity, PsmOverSamplesTheNearField) {
  Ground g;
  WarpParams least;
  least.psmSlideBack = 0.0f;
  WarpFit fit = FitWarp(g.in, Warp::Psm, least);
  EXPECT_FALSE(fit.fellBack);
  EXPECT_NEAR(fit.slideBack, 0.0f, 1e-5f);
  glm::vec2 near = g.Density(fit, 1), far = g.Density(fit, 100);
  EXPECT_NEAR((near.y / far.y) / 1e4f, 1.0f, 0.02f) << near.y << " " << far.y;
  EXPECT_NEAR((near.x / far.x) / 100.0f, 1.0f, 0.02f) << near.x << " " << far.x;
  // A slide-back s replaces z by z + s: (z_f + s) / (z_n + s) squared.
  WarpParams p;
  p.psmSlideBack = 10.0f / 99.0f;  // s = 10 m
  WarpFit slid = FitWarp(g.in, Warp::Psm, p);
  EXPECT_NEAR(slid.slideBack, 10.0f, 1e-3f);
  double expect = std::pow(110.0 / 11.0, 2.0);
  EXPECT_NEAR(g.Density(slid, 1).y / g.Density(slid, 100).y / expect, 1.0, 0.02);
}

// The trapezoid's definition: the focus line (view depth z_n + 0.5 (z_f - z_n) on the axis) at
// v = 0.8, the top line (B's near side) at v = 0, the base at v = 1; the apex distance is the
// paper's eta; the trapezoid is narrower at the top and its sides meet at the apex.
TEST(WarpTsm, FocusLineMapsToEightyPercentOfTheMap) {
  Ground g;
  for (float focus : {0.8f, 0.9f, 0.7f}) {
    WarpParams p;
    p.tsmFocus = focus;
    WarpFit fit = FitWarp(g.in, Warp::Tsm, p);
    EXPECT_FALSE(fit.fellBack);
    EXPECT_TRUE(fit.preferLinearDepth);
    float zFocus = 1.0f + 0.5f * 99.0f;
    EXPECT_NEAR(ToTexel(fit, glm::vec3(0, 2, -zFocus), 1).y, focus, 1e-3f);
    EXPECT_NEAR(ToTexel(fit, glm::vec3(0, 0, -1), 1).y, 0.0f, 1e-3f);
    EXPECT_NEAR(ToTexel(fit, glm::vec3(0, 0, -100), 1).y, 1.0f, 1e-3f);
    // eta from the paper's formula, in its [-1, 1] terms: xi_p = 1 - 2 focus, lambda = 99,
    // delta' = 49.5 (focus line at view depth 50.5, top line at 1).
    double lambda = 99.0, delta = 49.5, xp = 1.0 - 2.0 * focus;
    double eta = lambda * delta * (1.0 + xp) / (lambda - 2.0 * delta - lambda * xp);
    EXPECT_NEAR(fit.n / eta, 1.0, 1e-4) << focus;
    // Light-view x/y: +y along the view; top edge (near) shorter than the base, and the sides
    // meet at the apex q on the centre line (x = 0), eta before the top line.
    float top = glm::distance(fit.trapezoid[0], fit.trapezoid[1]), base = glm::distance(fit.trapezoid[3], fit.trapezoid[2]);
    EXPECT_LT(top, base * 0.9f);
    glm::vec2 a = fit.trapezoid[0], da = fit.trapezoid[3] - a, b = fit.trapezoid[1], db = fit.trapezoid[2] - b;
    float t = ((b.x - a.x) * db.y - (b.y - a.y) * db.x) / (da.x * db.y - da.y * db.x);
    glm::vec2 q = a + da * t;
    EXPECT_NEAR(q.x, 0.0f, 1e-3f * float(eta));
    EXPECT_NEAR(q.y, 1.0f - float(eta), 2e-3f * float(eta));
    // Top line at B's near side (y = z_n), base at its far side; the fit's slack of 1e-4 of the
    // map is stretched by the warp towards the base.
    EXPECT_NEAR(fit.trapezoid[0].y, 1.0f, 0.05f);
    EXPECT_NEAR(fit.trapezoid[3].y, 100.0f, 0.5f);
    // The linear depth is the light-space one: ground points at any distance share it.
    EXPECT_NEAR(LinearDepth(fit, glm::vec3(0, 0, -3)), LinearDepth(fit, glm::vec3(0, 0, -90)), 1e-5f);
  }
  // A focus at or below the focus line's own place needs no warp: the uniform map.
  WarpParams none;
  none.tsmFocus = 0.0f;
  WarpFit flat = FitWarp(g.in, Warp::Tsm, none);
  EXPECT_TRUE(flat.fellBack);
}

// Parameters that switch the warp off give the uniform map: LiSPSM n = +inf, PSM slide-back
// +inf, TSM focus 0; and large finite values come close to it.
TEST(WarpFit, SwitchedOffWarpsEqualTheUniformFit) {
  const scene::Bounds field = Field();
  scene::Camera cam = Cam({10, 12, 60}, {0, 0, 0});
  for (float g : {30.0f, 90.0f, 140.0f}) {
    WarpInput in = MakeWarpInput(cam, 1.5f, LightAt(cam, g, 20.0f), field, cam.nearZ, 150.0f);
    WarpFit uniform = FitWarp(in, Warp::None);
    WarpParams off;
    off.lispsmScale = INFINITY;
    off.psmSlideBack = INFINITY;
    off.tsmFocus = 0.0f;
    for (Warp w : {Warp::Psm, Warp::Lispsm, Warp::Tsm}) {
      WarpFit fit = FitWarp(in, w, off);
      EXPECT_TRUE(fit.fellBack) << Name(w);
      EXPECT_EQ(fit.blend, 0.0f);
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_EQ(fit.viewProj[c][r], uniform.viewProj[c][r]) << Name(w);
    }
    WarpParams weak;
    weak.lispsmScale = 1e5f;
    weak.psmSlideBack = 1e4f;
    for (Warp w : {Warp::Psm, Warp::Lispsm}) {
      WarpFit fit = FitWarp(in, w, weak);
      float worst = 0;
      for (const glm::vec3& b : in.body) worst = std::max(worst, glm::distance(glm::vec2(ToTexel(fit, b, 1024)), glm::vec2(ToTexel(uniform, b, 1024))));
      EXPECT_LT(worst, 1.0f) << Name(w) << " gamma " << g;
    }
  }
}

// The light turns away from the view axis through the fallback band (PSM and TSM fade between 5
// and 20 degrees from it, PSM also where its light camera degenerates, LiSPSM weakens with
// sin(gamma)), the camera fixed, in steps of 0.05 degrees. A pop is a change concentrated at one
// light direction: it survives refining the step. So every step that moves B's texels by more
// than a quarter texel is cut into 8 sub-steps, and no sub-step may carry more than 35 % of the
// step's change (a smooth change puts about 1/8 in each). And no step moves a texel by more than
// 32 (3 % of the map): a warp magnifies the near field, so its texels there move several times
// as far as the uniform map's (about 1 to 6 texels per step here, following B's silhouette).
std::vector<glm::vec2> Texels(const WarpInput& base, const scene::Camera& cam, Warp w, float g, float azimuth) {
  WarpInput in = base;
  in.lightDirection = LightAt(cam, g, azimuth);
  WarpFit fit = FitWarp(in, w);
  std::vector<glm::vec2> out;
  for (const glm::vec3& b : in.body) out.push_back(glm::vec2(ToTexel(fit, b, 1024.0f)));
  return out;
}

float MaxMove(const std::vector<glm::vec2>& a, const std::vector<glm::vec2>& b) {
  float m = 0;
  for (size_t i = 0; i < a.size(); ++i) m = std::max(m, glm::distance(a[i], b[i]));
  return m;
}

TEST(WarpContinuity, NoPopThroughTheFallbackBand) {
  const scene::Bounds field = Field();
  for (const scene::Camera& cam : {Cam({10, 12, 60}, {0, 0, 0}), Cam({0, 2, 0}, {0, 2, -10})}) {
    WarpInput base = MakeWarpInput(cam, 1.5f, glm::vec3(0, -1, 0), field, cam.nearZ, 150.0f);
    for (float azimuth : {0.0f, 60.0f})
      for (float start : {0.5f, 140.0f}) {
        const float step = 0.05f;
        float uniformWorst = 0;
        for (float g = start; g < start + 39.5f; g += step)
          uniformWorst = std::max(uniformWorst, MaxMove(Texels(base, cam, Warp::None, g, azimuth), Texels(base, cam, Warp::None, g + step, azimuth)));
        for (Warp w : {Warp::Psm, Warp::Lispsm, Warp::Tsm}) {
          float worst = 0, worstAt = 0, worstShare = 0, shareAt = 0;
          for (float g = start; g < start + 39.5f; g += step) {
            std::vector<glm::vec2> a = Texels(base, cam, w, g, azimuth), b = Texels(base, cam, w, g + step, azimuth);
            float move = MaxMove(a, b);
            if (move > worst) worst = move, worstAt = g;
            if (move < 0.25f) continue;
            float sub = 0;
            std::vector<glm::vec2> prev = a;
            for (int i = 1; i <= 8; ++i) {
              std::vector<glm::vec2> next = i == 8 ? b : Texels(base, cam, w, g + step * float(i) / 8.0f, azimuth);
              sub = std::max(sub, MaxMove(prev, next));
              prev = next;
            }
            if (sub / move > worstShare) worstShare = sub / move, shareAt = g;
          }
          std::string what = std::string(Name(w)) + " azimuth " + std::to_string(azimuth) + " from " + std::to_string(start);
          EXPECT_LT(worst, 32.0f) << what << ": worst step at gamma " << worstAt;
          EXPECT_LT(worstShare, 0.35f) << what << ": at gamma " << shareAt;
          std::printf("%-40s uniform %.2f  worst %.2f at %.2f  sub-step share %.2f at %.2f\n", what.c_str(), uniformWorst, worst, worstAt, worstShare, shareAt);
        }
      }
  }
}

// Caster culling (MayCastInto) is conservative: a box with any point that lands in the map
// (w > 0, inside the square, depth <= 1, i.e. what the rasterizer would write and a lookup of B
// could read) is kept. Boxes of 1 to 30 m scattered over and beyond the field, every warp, four
// light angles and cascade-sized bodies; the points tried are a 5x5x5 grid over each box. And it
// culls: most boxes far from the body are dropped.
TEST(WarpCulling, KeepsEveryBoxThatReachesTheMapAndDropsMostOthers) {
  const scene::Camera cam = Cam({10, 12, 60}, {0, 0, 0});
  uint32_t seed = 12345;
  auto next = [&] {
    seed = seed * 1664525u + 1013904223u;
    return float(seed >> 8) / 16777216.0f;
  };
  int kept = 0, culled = 0;
  for (float g : {30.0f, 90.0f, 135.0f, 170.0f})
    for (float d1 : {20.0f, 150.0f})
      for (Warp w : kWarps) {
        WarpInput in = MakeWarpInput(cam, 16.0f / 9.0f, LightAt(cam, g, 20.0f), Field(), cam.nearZ, d1);
        WarpFit fit = FitWarp(in, w);
        for (int k = 0; k < 200; ++k) {
          glm::vec3 c(next() * 600 - 300, next() * 40 - 10, next() * 600 - 300), half(next() * 15 + 0.5f, next() * 15 + 0.5f, next() * 15 + 0.5f);
          scene::Bounds box;
          box.extend(c - half);
          box.extend(c + half);
          bool reaches = false;
          for (int i = 0; i <= 4 && !reaches; ++i)
            for (int j = 0; j <= 4 && !reaches; ++j)
              for (int l = 0; l <= 4 && !reaches; ++l) {
                glm::vec3 p = box.min + (box.max - box.min) * glm::vec3(i, j, l) / 4.0f;
                glm::vec4 q = fit.viewProj * glm::vec4(p, 1.0f);
                reaches = q.w > 0 && std::abs(q.x) <= q.w && std::abs(q.y) <= q.w && LinearDepth(fit, p) <= 1.0f;
              }
          bool may = MayCastInto(fit, box);
          if (reaches) {
            EXPECT_TRUE(may) << Name(w) << " gamma " << g << " d1 " << d1 << " box " << k;
          }
          (may ? kept : culled) += 1;
        }
      }
  RecordProperty("kept", kept);
  RecordProperty("culled", culled);
  EXPECT_GT(culled, kept) << "most of the boxes scattered over 600 m miss a body of 20 or 150 m";
}

}  // namespace
}  // namespace sp::test
