// The lab's metrics through the whole pipeline (technique, lab lit pass, read-back, reference) on
// scenes whose answers are known in closed form, on both backends with validation on:
//  - a plane under an orthographic light straight down, seen by a camera straight down: every
//    pixel's footprint is the same square, so texels per pixel is footprint / texel size exactly,
//    and utilization is the fraction of the map the view rectangle covers;
//  - a box above the plane under an oblique light: misclassification only on the shadow's edge
//    pixels; with far too much depth bias the shadow vanishes (every shadowed pixel false lit);
//  - a grazing light without bias: acne, false shadow on a large part of the plane, gone with the
//    default bias.
#include <glm/ext/matrix_transform.hpp>

#include "backend-test.h"
#include "metrics.h"
#include "reference.h"

namespace sp::test {
namespace {

constexpr uint32_t W = 160, H = 90;
constexpr float kPlane = 20.0f, kEye = 8.0f;

// A kPlane x kPlane floor at y = 0 and, far outside the view, a unit box that gives the scene
// (and so the basic technique's light frustum) some depth; the camera is kEye above the origin
// looking straight down with a 60 degree vertical field of view.
scene::Scene PlaneScene(const glm::vec3& lightDirection, bool boxAbove) {
  scene::Scene s;
  s.name = "lab-plane";
  uint32_t plane = s.addMesh(scene::MakePlane(1));
  uint32_t box = s.addMesh(scene::MakeBox());
  s.addInstance(plane, glm::scale(glm::mat4(1.0f), glm::vec3(kPlane, 1, kPlane)), glm::vec3(0.8f));
  s.addInstance(box, glm::translate(glm::mat4(1.0f), glm::vec3(9.0f, 0.5f, 9.0f)), glm::vec3(0.8f));
  if (boxAbove) s.addInstance(box, glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(-1.0f, 2.0f, 0.0f)), glm::vec3(2.0f)), glm::vec3(0.8f));
  s.camera.position = {0.0f, kEye, 0.0f};
  s.camera.target = {0.0f, 0.0f, 0.0f};
  s.camera.up = {0.0f, 0.0f, -1.0f};
  s.camera.fovY = glm::radians(60.0f);
  s.camera.nearZ = 1.0f;
  s.camera.farZ = 40.0f;
  s.light.direction = glm::normalize(lightDirection);
  s.finalize();
  return s;
}

class LabAnalyticTest : public BackendTest {
 protected:
  // Renders the scene camera's frame with the lab's lit pass and traces its reference.
  void Render(const scene::Scene& s, const std::map<std::string, std::string>& params) {
    std::unique_ptr<tech::Technique> t = tech::CreateTechnique("basic");
    t->Configure(device(), tech::ParamValues::Parse("basic", t->Params(), params));
    tech::RendererOptions ro;
    ro.lab = true;
    tech::Renderer r(device(), s, std::move(t), W, H, ro);
    r.RenderFrame(s.camera, s.light, tech::LitPass::Lab);
    lab = r.ReadLab();
    layers = r.technique().Layers();
    eval::ReferenceTracer tracer(s);
    eval::LabSurfacePoints p = eval::SurfacePointsOf(lab);
    reference.assign(lab.size(), 0);
    tracer.Visibility(p.position.data(), p.normal.data(), p.valid.data(), p.size(), eval::ReferenceLight::FromScene(s.light), reference.data());
  }

  // Receiving pixels within `radius` pixels of one whose reference value differs.
  std::vector<bool> NearReferenceEdge(int radius) const {
    std::vector<bool> near(lab.size(), false);
    for (int y = 0; y < int(H); ++y)
      for (int x = 0; x < int(W); ++x) {
        size_t i = size_t(y) * W + x;
        if (!lab.receiving(i)) continue;
        for (int dy = -radius; dy <= radius; ++dy)
          for (int dx = -radius; dx <= radius; ++dx) {
            int u = x + dx, v = y + dy;
            if (u < 0 || v < 0 || u >= int(W) || v >= int(H)) continue;
            size_t j = size_t(v) * W + u;
            if (lab.receiving(j) && reference[j] != reference[i]) near[i] = true;
          }
      }
    return near;
  }

  size_t ReferenceShadowed() const {
    size_t n = 0;
    for (size_t i = 0; i < lab.size(); ++i) n += lab.receiving(i) && !reference[i];
    return n;
  }

  tech::LabBuffers lab;
  std::vector<tech::ShadowLayer> layers;
  std::vector<uint8_t> reference;
};

TEST_P(LabAnalyticTest, TexelDensityAndUtilizationOfAPlaneSeenStraightDown) {
  const int resolution = 128;
  scene::Scene s = PlaneScene({0.0f, -1.0f, 0.0f}, false);
  Render(s, {{"resolution", std::to_string(resolution)}});

  // Footprint of a pixel on the plane (square: the projection keeps the aspect) and a texel
  // (the basic technique's map spans the scene's kPlane x kPlane bounds).
  double halfHeight = kEye * std::tan(glm::radians(30.0)), halfWidth = halfHeight * W / H;
  double footprint = 2.0 * halfHeight / H, texel = double(kPlane) / resolution;
  double expected = footprint / texel;  // 0.6569
  eval::LogHistogram h;
  eval::AddTexelDensity(lab, h);
  EXPECT_EQ(h.count(), size_t(W) * H) << "every pixel sees the plane and reads the map";
  EXPECT_NEAR(h.percentile(0.5), expected, expected * 1e-4);
  EXPECT_NEAR(h.percentile(0.05), expected, expected * 1e-4);
  EXPECT_NEAR(h.percentile(0.95), expected, expected * 1e-4);

  // The view is a rectangle centred on the map; with under one texel per pixel every texel it
  // contains holds a pixel centre. Texels wholly inside give the lower bound, texels it touches
  // the upper (which of the map's axes is world x does not matter: the map is square and the
  // rectangle centred).
  ASSERT_LT(expected, 1.0);
  auto span = [&](double half, int* inside, int* touching) {
    double lo = resolution / 2.0 - half / texel, hi = resolution / 2.0 + half / texel;
    *inside = int(std::floor(hi)) - int(std::ceil(lo));
    *touching = int(std::ceil(hi)) - int(std::floor(lo));
  };
  int ix, tx, iy, ty;
  span(halfWidth, &ix, &tx);
  span(halfHeight, &iy, &ty);
  double total = double(resolution) * resolution;
  double u = eval::MeasureUtilization(lab, layers);
  EXPECT_GE(u, ix * iy / total);
  EXPECT_LE(u, tx * ty / total);
  EXPECT_NEAR(u, 4.0 * halfWidth * halfHeight / (double(kPlane) * kPlane), 0.02);
}

TEST_P(LabAnalyticTest, BoxShadowIsWrongOnlyAtItsEdgeAndVanishesWithTooMuchBias) {
  scene::Scene s = PlaneScene({0.5f, -1.0f, 0.2f}, true);
  double footprint = 2.0 * kEye * std::tan(glm::radians(30.0)) / H;
  // Texels much smaller than pixels: the shadow is exact at pixel scale. Texels of 3 pixels: the
  // edge becomes a staircase, wrong within about 1.5 texels of the true edge (a texel of the grid
  // plus the 2x2 filter's reach) and right everywhere else.
  for (int resolution : {1024, 64}) {
    SCOPED_TRACE("resolution " + std::to_string(resolution));
    Render(s, {{"resolution", std::to_string(resolution)}});
    ASSERT_GT(ReferenceShadowed(), size_t(W) * H / 50) << "the view must contain a sizeable shadow";
    eval::Accuracy a = eval::MeasureAccuracy(lab, reference.data());
    double texelPixels = double(kPlane) / resolution / footprint;
    int band = int(std::ceil(1.5 * texelPixels));
    std::vector<bool> edge = NearReferenceEdge(band);
    size_t edgePixels = 0, wrongAwayFromEdge = 0;
    for (size_t i = 0; i < lab.size(); ++i) {
      if (!lab.receiving(i)) continue;
      edgePixels += edge[i];
      bool wrong = (lab.visibility[i] >= eval::kLitThreshold) != (reference[i] != 0);
      if (wrong && !edge[i]) ++wrongAwayFromEdge;
    }
    EXPECT_EQ(wrongAwayFromEdge, 0u) << "misclassified pixels further than " << band << " pixels from the shadow's edge";
    EXPECT_LE(a.misclassifiedPct(), 100.0 * edgePixels / a.receiving);
    if (resolution == 1024) {
      EXPECT_LT(a.misclassifiedPct(), 0.1);
    }
    if (resolution == 64) {
      EXPECT_GT(a.misclassifiedPct(), 0.1) << "a 3-pixel texel grid must show on the edge";
    }
  }

  // Peter-panning taken to the end: a bias larger than the light-space gap between box and floor
  // pushes the box's depth behind the floor, so the whole shadow is lost: false lit = the shadow.
  Render(s, {{"resolution", "1024"}, {"depth_bias", "10000000"}});
  eval::Accuracy biased = eval::MeasureAccuracy(lab, reference.data());
  EXPECT_EQ(biased.falseLit, ReferenceShadowed());
  EXPECT_EQ(biased.falseShadow, 0u);
  EXPECT_GT(biased.falseLitPct(), 1.0);
}

TEST_P(LabAnalyticTest, GrazingLightWithoutBiasGivesAcneAsFalseShadow) {
  // The light 8 degrees above the floor.
  glm::vec3 dir(std::cos(glm::radians(8.0f)), -std::sin(glm::radians(8.0f)), 0.0f);
  scene::Scene s = PlaneScene(dir, false);
  Render(s, {{"resolution", "1024"}, {"depth_bias", "0"}, {"slope_bias", "0"}});
  EXPECT_EQ(ReferenceShadowed(), 0u) << "nothing in view casts a shadow";
  eval::Accuracy acne = eval::MeasureAccuracy(lab, reference.data());
  EXPECT_GT(acne.falseShadowPct(), 10.0);
  EXPECT_EQ(acne.falseLit, 0u);
  Render(s, {{"resolution", "1024"}});
  eval::Accuracy biased = eval::MeasureAccuracy(lab, reference.data());
  EXPECT_LT(biased.falseShadowPct(), 0.1 * acne.falseShadowPct());
}

SP_INSTANTIATE_BACKEND_TESTS(LabAnalyticTest);

}  // namespace
}  // namespace sp::test
