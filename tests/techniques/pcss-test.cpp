// PCSS (filter=pcss, shaders-hlsl/common/shadow-pcss.hlsli) in basic, csm and sdsm (the sun,
// orthographic maps) and spot (perspective map): a thin plank at a known height over a floor, its straight edge
// above x = 0, the camera under the plank looking down. Across the edge the lab's visibility must
// ramp from 0 to 1 over the penumbra the light's size gives by geometry (computed here on the
// CPU), centred on the edge's shadow; 1 past it, 0 in the umbra; twice the light, twice the ramp.
//
// The ramp's width: PCSS filters with a box of the penumbra's width w over texel-sized cells, and
// the map holds the edge as a step, so visibility is exactly linear over w: the 10 % and 90 %
// crossings lie 0.8 w apart and w = (x90 - x10) / 0.8. Tolerance 2 %, from: the plank is 0.02
// thick and the map holds only its top, so PCSS uses h = 2.02 where the geometric penumbra runs
// from the bottom edge's umbra boundary to the top edge's lit one (h between 2.0 and 2.02: 0.5 %
// sun, 1 % spot against the mid-height value used here); the depth bias moves the blocker depth by
// a few 1e-5 of the range; the crossings are interpolated linearly between pixels of an exactly
// linear ramp, except where a crossing falls in the pixel where the ramp meets 0 or 1 (never:
// 10 % and 90 % lie several pixels inside). No Poisson noise and no kernel quantisation (the box
// takes any real width). Position of the ramp's centre: within a texel plus a pixel of x = 0
// (the edge snaps to a texel boundary in the map).
#include <cstdio>
#include <glm/ext/matrix_transform.hpp>
#include <glm/gtc/constants.hpp>

#include "backend-test.h"
#include "technique-renderer.h"
#include "cross-backend.h"
#include "reference.h"
#include <sp/tech/renderer.h>

namespace sp::test {
namespace {

constexpr float kPlankBottom = 2.0f, kPlankTop = 2.02f, kPlankHeight = 0.5f * (kPlankBottom + kPlankTop);
constexpr float kSpotHeight = 4.0f, kSpotOuterDegrees = 30.0f;
constexpr uint32_t kSize = 128, kResolution = 512;

// Floor [-3, 3]^2 at y = 0; plank x in [-3, 0], z in [-2.5, 2.5], y in [2, 2.02]. Camera at
// `cameraHeight` over x = cameraX, under the plank or beside it, looking straight down, image
// x = world x. `point`: a point light there (range 10) besides the sun.
scene::Scene PlankScene(bool spot, float cameraHeight = 1.0f, const glm::vec3* point = nullptr, float cameraX = 0.0f) {
  scene::Scene s;
  s.name = spot ? "pcss-plank-spot" : "pcss-plank";
  uint32_t plane = s.addMesh(scene::MakePlane(1));
  uint32_t box = s.addMesh(scene::MakeBox());
  s.addInstance(plane, glm::scale(glm::mat4(1.0f), glm::vec3(6, 1, 6)), glm::vec3(0.8f));
  glm::mat4 plank = glm::translate(glm::mat4(1.0f), glm::vec3(-1.5f, kPlankHeight, 0.0f));
  s.addInstance(box, glm::scale(plank, glm::vec3(3.0f, kPlankTop - kPlankBottom, 5.0f)), glm::vec3(0.8f));
  s.camera.position = {cameraX, cameraHeight, 0.001f};
  s.camera.target = {cameraX, 0.0f, 0.0f};
  s.camera.up = {0.0f, 0.0f, -1.0f};
  s.camera.fovY = glm::radians(50.0f);
  s.camera.nearZ = 0.1f;
  s.camera.farZ = 10.0f;
  s.light.direction = {0.0f, -1.0f, 0.0f};
  s.light.ambient = 0.2f;
  if (spot) {
    scene::SpotLight l;
    l.position = {0.0f, kSpotHeight, 0.0f};
    l.direction = {0.0f, -1.0f, 0.0f};
    l.range = 10.0f;
    l.innerConeAngle = glm::radians(kSpotOuterDegrees - 5.0f);
    l.outerConeAngle = glm::radians(kSpotOuterDegrees);
    s.spotLights.push_back(l);
  }
  if (point) {
    scene::PointLight l;
    l.position = *point;
    l.range = 10.0f;
    s.pointLights.push_back(l);
  }
  s.finalize();
  return s;
}

// Geometric penumbra widths on the floor (world units) for the plank's mid height.
double SunPenumbra(double degrees) { return kPlankHeight * 2.0 * std::tan(0.5 * glm::radians(degrees)); }
// A light disc or sphere of `radius` at `height` above the edge: similar triangles.
double LocalPenumbra(double radius, double height) { return 2.0 * radius * kPlankHeight / (height - kPlankHeight); }
double SpotPenumbra(double radius) { return LocalPenumbra(radius, kSpotHeight); }
// One map texel on the floor.
double SunTexel() { return 6.0 / kResolution; }
double SpotTexel() { return kSpotHeight * 2.0 * std::tan(glm::radians(kSpotOuterDegrees)) / kResolution; }

struct Ramp {
  double x10 = 0, x90 = 0;  // mean crossings of visibility 0.1 and 0.9 along the rows
  double width() const { return (x90 - x10) / 0.8; }
  double centre() const { return 0.5 * (x10 + x90); }
  std::vector<std::pair<float, float>> samples;  // (world x, visibility) of the floor pixels measured
};

// The central rows' visibility along x; each crossing interpolated between neighbouring pixels.
Ramp MeasureRamp(const tech::LabBuffers& lab) {
  Ramp r;
  int rows = 0;
  for (uint32_t y = lab.height / 2 - 3; y < lab.height / 2 + 3; ++y) {
    std::vector<std::pair<float, float>> row;
    for (uint32_t x = 0; x < lab.width; ++x) {
      size_t i = size_t(y) * lab.width + x;
      if (lab.drawn(i) && std::abs(lab.position[i].y) < 1e-3f) row.push_back({lab.position[i].x, lab.visibility[i]});
    }
    auto crossing = [&](float level) {
      for (size_t k = 1; k < row.size(); ++k)
        if (row[k - 1].second < level && row[k].second >= level) {
          auto [xa, va] = row[k - 1];
          auto [xb, vb] = row[k];
          return double(xa) + (double(level) - va) / (double(vb) - va) * (double(xb) - xa);
        }
      return std::nan("");
    };
    r.x10 += crossing(0.1f);
    r.x90 += crossing(0.9f);
    r.samples.insert(r.samples.end(), row.begin(), row.end());
    ++rows;
  }
  r.x10 /= rows;
  r.x90 /= rows;
  return r;
}

class PcssTest : public BackendTest {
 protected:
  tech::LabBuffers Render(const std::string& technique, const scene::Scene& s, std::map<std::string, std::string> params) {
    params.emplace("resolution", std::to_string(kResolution));
    params["filter"] = "pcss";
    params.emplace("pcss_max_kernel", "31");
    tech::Renderer r(device(), s, MakeConfiguredTechnique(device(), technique, params), kSize, kSize, LabOptions(true));
    r.RenderFrame(s.camera, s.light, tech::LitPass::Lab);
    return r.ReadLab();
  }

  // The ramp's width and centre against the geometry, and exact 1 and 0 past its ends.
  Ramp ExpectPenumbra(const std::string& what, const tech::LabBuffers& lab, double want, double texel, double cameraHeight = 1.0,
                      double centre = 0.0, double tolerance = 0.02) {
    Ramp r = MeasureRamp(lab);
    std::printf("%s: penumbra %.5f (10-90 %% %.5f), geometry %.5f, ratio %.4f, centre %.5f\n", what.c_str(), r.width(), r.x90 - r.x10, want,
                r.width() / want, r.centre());
    const double pixel = cameraHeight * 2.0 * std::tan(glm::radians(25.0)) / kSize;  // at the floor
    EXPECT_NEAR(r.width(), want, tolerance * want) << what << ": 10-90 % distance " << r.x90 - r.x10;
    EXPECT_NEAR(r.centre(), centre, texel + pixel) << what;
    const double margin = 0.5 * want * (1.0 + tolerance) + 2 * texel + pixel;
    int lit = 0, umbra = 0;
    for (auto [px, v] : r.samples) {
      const double x = px - centre;
      if (x > margin) {
        ++lit;
        EXPECT_GE(v, 1.0f - 1e-6f) << what << " lit floor at x = " << x;
      }
      if (x < -margin) {
        ++umbra;
        EXPECT_LE(v, 1e-6f) << what << " umbra at x = " << x;
      }
    }
    EXPECT_GT(lit, 100) << what;
    EXPECT_GT(umbra, 100) << what;
    return r;
  }
};

TEST_P(PcssTest, SunPenumbraIsTheAngularSizeTimesTheHeight) {
  scene::Scene s = PlankScene(false);
  Ramp small = ExpectPenumbra("basic light_size=4", Render("basic", s, {{"light_size", "4"}}), SunPenumbra(4), SunTexel());
  Ramp large = ExpectPenumbra("basic light_size=8", Render("basic", s, {{"light_size", "8"}}), SunPenumbra(8), SunTexel());
  // Proportional: tan(4) / tan(2) = 2.0024.
  EXPECT_NEAR(large.width() / small.width(), std::tan(glm::radians(4.0)) / std::tan(glm::radians(2.0)), 0.04);
}

TEST_P(PcssTest, SpotPenumbraFollowsSimilarTriangles) {
  scene::Scene s = PlankScene(true);
  Ramp small = ExpectPenumbra("spot light_size=0.05", Render("spot", s, {{"light_size", "0.05"}}), SpotPenumbra(0.05), SpotTexel());
  Ramp large = ExpectPenumbra("spot light_size=0.1", Render("spot", s, {{"light_size", "0.1"}}), SpotPenumbra(0.1), SpotTexel());
  EXPECT_NEAR(large.width() / small.width(), 2.0, 0.04);
}

// cube: a point light over the plank's edge, a sphere of radius light_size; the receiver under it
// reads the -Y face, whose planar depths are the heights, so the penumbra is the spot's similar
// triangles at the light's height: 2 r h / (H - h). Heights 4 and 3.5 (face texels on the floor
// 2 H / 512 = 0.0156 and 0.0137; 0.101 to 0.270: 7 to 17 texels). Tolerance 2 % as above, the
// plank's thickness now 1.2 % at 3.5 (h / (H - h) for h = 2.02 against 2.01).
TEST_P(PcssTest, CubePenumbraFollowsSimilarTriangles) {
  for (float height : {4.0f, 3.5f}) {
    const glm::vec3 light(0.0f, height, 0.0f);
    scene::Scene s = PlankScene(false, 1.0f, &light);
    char what[64];
    std::snprintf(what, sizeof what, "cube height %.1f light_size=", height);
    const double texel = 2.0 * height / kResolution;
    Ramp small = ExpectPenumbra(what + std::string("0.05"), Render("cube", s, {{"light_size", "0.05"}}), LocalPenumbra(0.05, height), texel);
    Ramp large = ExpectPenumbra(what + std::string("0.1"), Render("cube", s, {{"light_size", "0.1"}}), LocalPenumbra(0.1, height), texel);
    EXPECT_NEAR(large.width() / small.width(), 2.0, 0.04) << what;
  }
}

// The cube's face edge: the light at (-1.99, 4, 0) puts the plank's shadow edge (its top corner,
// the silhouette from the side) at x = 1.99 h / (4 - h) = 2.030 on the floor, seen at 45 degrees:
// the penumbra straddles the -Y face (left half) and the +X face (right half); the search and the
// box step across the edge in direction space (cube/pcss.hlsli). On -Y the plank's top and the
// floor are perpendicular to the axis: the width is 2 r h / (H - h) as overhead (2 %, measured
// 1.0 %). On +X both are tilted 45 degrees to the axis: the blockers' planar depths fall across the
// search region (radius 0.24 at planar depth 4: up to 6 % nearer at its far side, about half that
// on average, and (dR - dB) / dB grows twice as fast), and the face's vertical box projects onto
// the floor stretched by X / 4 <= 1.035; together up to 10 % wider on that half, 5 % on the whole
// ramp: tolerance 8 %. Measured 1.051 x. A seam shows as a jump between neighbouring pixels: no
// step may exceed twice the mean step of the ideal ramp (pixel / width).
TEST_P(PcssTest, CubePenumbraAcrossAFaceEdge) {
  const glm::vec3 light(-1.99f, 4.0f, 0.0f);
  const double edge = -light.x * kPlankTop / (light.y - kPlankTop);
  const double want = 2.0 * 0.1 * kPlankTop / (light.y - kPlankTop);
  scene::Scene s = PlankScene(false, 1.0f, &light, float(edge));
  Ramp r = ExpectPenumbra("cube across the -Y/+X edge light_size=0.1", Render("cube", s, {{"light_size", "0.1"}}), want, 2.0 * 4.0 / kResolution,
                          1.0, edge, 0.08);
  const double pixel = 2.0 * std::tan(glm::radians(25.0)) / kSize;
  double largest = 0.0;
  for (size_t k = 1; k < r.samples.size(); ++k)
    if (r.samples[k].first > r.samples[k - 1].first) largest = std::max(largest, double(std::abs(r.samples[k].second - r.samples[k - 1].second)));
  std::printf("cube across the face edge: largest step %.4f, ideal %.4f\n", largest, pixel / want);
  EXPECT_LE(largest, 2.0 * pixel / want);
}

// csm: each cascade is its own orthographic map with its own world texel size, which the fit
// makes from the view and the resolution: the penumbra must not change with either. The camera
// at 0.4 sees 0.37 of floor; the cascade covering it is about 0.41 wide, 0.0026 per texel at 160
// and 0.0016 at 256 (texel bound for the centre and margins: 0.005); 1.2 degrees is a 0.042
// penumbra: 14.5 pixels, 16 and 26 texels (under pcss_max_kernel, 31).
TEST_P(PcssTest, CsmPenumbraDoesNotDependOnTheCascadeFit) {
  const float height = 0.4f;
  scene::Scene s = PlankScene(false, height);
  for (auto [cascades, resolution] : {std::pair{"1", "160"}, {"3", "160"}, {"3", "256"}}) {
    std::string what = std::string("csm cascades=") + cascades + " resolution=" + resolution + " light_size=1.2";
    tech::LabBuffers lab = Render("csm", s, {{"light_size", "1.2"}, {"cascades", cascades}, {"resolution", resolution}});
    ExpectPenumbra(what, lab, SunPenumbra(1.2), 0.005, height);
  }
}

// sdsm: the partitions are fitted to the analysed samples, each with its own texel size (oblong:
// the tight box of the visible floor), written by fit.hlsl (cull=gpu) or the CPU (readback); the
// lighting derives each partition's texel size per axis and its depth range from the partition's
// own scale and offset, and with pcss the boxes reach up to the scene's top so the plank is not
// pancaked onto the floor's box. The camera looks down the floor at 27 degrees, so the view depth
// runs from 0.77 to 3.9 and the partitions' boxes differ in size (about 0.005 to 0.013 per texel at
// 160 .. 256); the central rows (at 1.34, pixels 0.0098 wide) lie on the split between the first
// two of 2 or 3 partitions, so both partitions' scales are measured. 4 degrees is a 0.140
// penumbra: 14 pixels, 11 to 28 texels (under pcss_max_kernel, 31).
TEST_P(PcssTest, SdsmPenumbraDoesNotDependOnThePartitions) {
  scene::Scene s = PlankScene(false);
  s.camera.position = {0.0f, 0.6f, 0.9f};
  s.camera.target = {0.0f, 0.0f, -0.3f};
  s.camera.up = {0.0f, 1.0f, 0.0f};
  const double distance = glm::length(s.camera.target - s.camera.position);
  const std::map<std::string, std::string> layouts[] = {
      {{"cascades", "1"}, {"resolution", "256"}},
      {{"cascades", "3"}, {"resolution", "256"}},
      {{"cascades", "3"}, {"resolution", "160"}, {"cull", "readback"}},
      {{"cascades", "2"}, {"resolution", "256"}, {"tight", "0"}},
      {{"cascades", "3"}, {"resolution", "256"}, {"accel", "hpsm"}},
  };
  for (std::map<std::string, std::string> p : layouts) {
    std::string what = "sdsm";
    for (const auto& [k, v] : p) what += " " + k + "=" + v;
    p["light_size"] = "4";
    ExpectPenumbra(what, Render("sdsm", s, p), SunPenumbra(4), 0.015, distance);
  }
}

// A penumbra wider than pcss_max_kernel is clamped to it: 4 degrees wants 12 texels, 5 gives 5.
TEST_P(PcssTest, MaxKernelClampsThePenumbra) {
  scene::Scene s = PlankScene(false);
  Ramp r = MeasureRamp(Render("basic", s, {{"light_size", "4"}, {"pcss_max_kernel", "5"}}));
  EXPECT_NEAR(r.width(), 5 * SunTexel(), 0.04 * 5 * SunTexel());
}

// PCSS against the ray-traced area light (eval/reference with ReferenceLight::size) on the same
// floor pixels. Under a disc light a straight edge gives the circular-segment profile
//   v(u) = 1/2 + (u sqrt(1 - u^2) + asin u) / pi,  u = x / R,  R the penumbra's half-width,
// PCSS's box the linear ramp 1/2 + u/2 of the same width: the two agree past the penumbra
// (exactly 0 and 1), cross 1/2 at the same x, and inside it differ by the shapes' mean gap, which
// is computed here (0.0378). Tolerance 0.008: a 2 % error in the width (the plank's thickness,
// above) moves the gap by 0.005, the reference's sampling error is 0.4 % RMS; a penumbra off by
// a factor 1.25 either way would miss it (0.056 wider, 0.030 narrower).
double SegmentVsLinearGap() {
  const int n = 20000;
  double sum = 0.0;
  for (int k = 0; k < n; ++k) {
    double u = -1.0 + 2.0 * (k + 0.5) / n;
    sum += std::abs((u * std::sqrt(1.0 - u * u) + std::asin(u)) / glm::pi<double>() - 0.5 * u);
  }
  return sum / n;
}

void ExpectMatchesTheAreaLight(const std::string& what, const tech::LabBuffers& lab, const scene::Scene& s, const eval::ReferenceLight& light,
                               double width, double texel) {
  std::vector<glm::vec3> pos(lab.size()), nrm(lab.size());
  std::vector<uint8_t> valid(lab.size());
  for (size_t i = 0; i < lab.size(); ++i) {
    pos[i] = glm::vec3(lab.position[i]);
    nrm[i] = glm::vec3(lab.normal[i]);
    valid[i] = lab.drawn(i) && std::abs(lab.position[i].y) < 1e-3f;  // the floor
  }
  std::vector<float> ref(lab.size(), 0.0f);
  eval::ReferenceTracer(s).Visibility(pos.data(), nrm.data(), valid.data(), lab.size(), light, ref.data());
  // The central rows, as MeasureRamp reads them.
  double gap = 0.0, outside = 0.0, refHalf = 0.0, pcssHalf = 0.0;
  int inside = 0, past = 0, rows = 0;
  for (uint32_t y = lab.height / 2 - 3; y < lab.height / 2 + 3; ++y, ++rows) {
    float prevX = 0, prevRef = -1, prevPcss = -1;
    for (uint32_t x = 0; x < lab.width; ++x) {
      size_t i = size_t(y) * lab.width + x;
      if (!valid[i]) continue;
      float px = lab.position[i].x;
      if (std::abs(px) < 0.5 * width) {
        gap += std::abs(lab.visibility[i] - ref[i]);
        ++inside;
      } else if (std::abs(px) > 0.5 * width + texel) {
        outside = std::max(outside, double(std::abs(lab.visibility[i] - ref[i])));
        ++past;
      }
      // Where each crosses 1/2, interpolated between neighbouring pixels.
      if (prevRef >= 0 && prevRef < 0.5f && ref[i] >= 0.5f) refHalf += prevX + (0.5 - prevRef) / (ref[i] - prevRef) * (px - prevX);
      if (prevPcss >= 0 && prevPcss < 0.5f && lab.visibility[i] >= 0.5f)
        pcssHalf += prevX + (0.5 - prevPcss) / (lab.visibility[i] - prevPcss) * (px - prevX);
      prevX = px, prevRef = ref[i], prevPcss = lab.visibility[i];
    }
  }
  gap /= std::max(inside, 1);
  const double want = SegmentVsLinearGap();
  std::printf("%s: mean |pcss - area-light reference| over the penumbra %.4f (%d pixels; a disc against a box of the same width: %.4f), "
              "largest past it %.2g, 1/2 crossings %.5f / %.5f\n",
              what.c_str(), gap, inside, want, outside, pcssHalf / rows, refHalf / rows);
  EXPECT_GT(inside, 60) << what;
  EXPECT_GT(past, 200) << what;
  EXPECT_NEAR(gap, want, 0.008) << what;
  // Past the penumbra (and a texel for the map's edge position): full light and umbra on both
  // sides, up to the float rounding of the box's weights (PCSS divides their sum by w^2).
  EXPECT_LE(outside, 1e-5) << what;
  const double pixel = 2.0 * std::tan(glm::radians(25.0)) / kSize;
  EXPECT_NEAR(pcssHalf / rows, refHalf / rows, texel + pixel) << what;
}

TEST_P(PcssTest, SunAndSpotPenumbraeMatchTheRayTracedAreaLight) {
  scene::Scene sun = PlankScene(false);
  sun.light.angularDiameterDegrees = 4.0f;
  ExpectMatchesTheAreaLight("basic light_size=4", Render("basic", sun, {{"light_size", "4"}}), sun, eval::ReferenceLight::FromScene(sun.light),
                            SunPenumbra(4), SunTexel());
  scene::Scene spot = PlankScene(true);
  const scene::SpotLight& l = spot.spotLights[0];
  ExpectMatchesTheAreaLight("spot light_size=0.1", Render("spot", spot, {{"light_size", "0.1"}}), spot,
                            eval::ReferenceLight::MakeSpot(l.position, l.direction, std::cos(l.outerConeAngle), 0.1f), SpotPenumbra(0.1),
                            SpotTexel());
}

// The cube's point light as a sphere of radius 0.1 against the reference's sphere light: from the
// edge 1.99 away its silhouette is a disc of radius 0.1 / sqrt(1 - (0.1 / 1.99)^2) = 1.0013 x 0.1,
// so the same gap and tolerance as the spot's disc apply.
TEST_P(PcssTest, CubePenumbraMatchesTheRayTracedSphereLight) {
  const glm::vec3 light(0.0f, kSpotHeight, 0.0f);
  scene::Scene s = PlankScene(false, 1.0f, &light);
  ExpectMatchesTheAreaLight("cube light_size=0.1", Render("cube", s, {{"light_size", "0.1"}}), s, eval::ReferenceLight::MakePoint(light, 0.1f),
                            SpotPenumbra(0.1), 2.0 * kSpotHeight / kResolution);
}

SP_INSTANTIATE_BACKEND_TESTS(PcssTest);

// Bad values are refused by name before any rendering: these run on the null backend too.
class PcssValidationTest : public BackendTest {};

TEST_P(PcssValidationTest, OutOfRangeParametersAreNamed) {
  const std::pair<std::string, std::map<std::string, std::string>> cases[] = {
      {"light_size", {{"filter", "pcss"}, {"light_size", "0"}}},
      {"light_size", {{"filter", "pcss"}, {"light_size", "45"}}},
      {"pcss_search", {{"filter", "pcss"}, {"pcss_search", "1"}}},
      {"pcss_max_kernel", {{"filter", "pcss"}, {"pcss_max_kernel", "40"}}},
      {"kernel", {{"filter", "box"}, {"kernel", "17"}}},
      {"kernel", {{"filter", "gauss"}, {"kernel", "31"}}},
  };
  for (const std::string technique : {"basic", "spot", "csm", "sdsm", "cube"})
    for (const auto& [name, params] : cases) {
      const bool local = technique == "spot" || technique == "cube";
      if (local && name == "light_size" && params.at("light_size") == "45") continue;  // a radius: 45 is valid
      if (technique == "cube" && params.at("filter") == "gathercmp") continue;        // not a cube filter
      ExpectConfigureRefused(device(), technique, params, name + "=");
    }
  // Combinations without a PCSS path, refused naming the parameter and why.
  const std::tuple<std::string, std::map<std::string, std::string>, std::string> refused[] = {
      {"cube", {{"filter", "pcss"}, {"storage", "radial"}}, "storage=depth"},
      {"psm", {{"filter", "pcss"}}, "texel size is not uniform"},
      {"tsm", {{"filter", "pcss"}}, "texel size is not uniform"},
      {"vsdct", {{"filter", "pcss"}}, "filter=pcss is not offered"},
      {"paraboloid", {{"filter", "pcss"}}, "filter"},
  };
  for (const auto& [technique, params, why] : refused) {
    ExpectConfigureRefused(device(), technique, params, why);
  }
  // gathercmp takes 31.
  EXPECT_NO_THROW(MakeConfiguredTechnique(device(), "basic", {{"filter", "gathercmp"}, {"kernel", "31"}}));
}

SP_INSTANTIATE_VALIDATION_TESTS(PcssValidationTest);

// Mesa's one rasterizer and sampler under both backends and the toolchain's fixed arithmetic (as
// for the other filters, shadow-filter-test.cpp): the PCSS images must be identical, the cube's
// across a face edge included.
TEST(PcssCrossBackend, PlankRendersIdenticallyOnBothBackends) {
  const glm::vec3 point(-1.99f, 4.0f, 0.0f);  // over a face edge, as CubePenumbraAcrossAFaceEdge
  for (std::string technique : {"basic", "spot", "cube"}) {
    const bool spot = technique == "spot";
    scene::Scene s = PlankScene(spot, 1.0f, technique == "cube" ? &point : nullptr, technique == "cube" ? 2.0f : 0.0f);
    CrossBackendFrame f = RenderOnBothBackends(technique, {{"filter", "pcss"}, {"resolution", "512"}, {"light_size", technique == "basic" ? "8" : "0.1"}}, s, 96, 96);
    size_t differing = CompareImages("pcss-" + technique, 96, 96, f.images[0].data(), f.images[1].data(), 0);
    if (f.mesa) EXPECT_EQ(differing, 0u) << technique;
    else EXPECT_LT(differing, size_t(96 * 96 / 200)) << technique;
  }
}

}  // namespace
}  // namespace sp::test
