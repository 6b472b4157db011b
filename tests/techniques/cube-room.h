// The point-light test room of the cube technique's tests: a closed box room (inward-facing floor,
// ceiling and walls) with a point light off its centre and small spheres around the light, one in
// the direction of each cube face (off the face's axis, so a mirrored or swapped face moves its
// shadow) and one on the +X/-Y face edge; and the exact shadows on the room's surfaces computed on
// the CPU (segment against sphere).
#pragma once
#include <algorithm>
#include <cmath>
#include <glm/ext/matrix_transform.hpp>
#include <array>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "backend-test.h"
#include "cube/cube-faces.h"
#include <sp/scene/scene.h>
#include <sp/tech/renderer.h>

namespace sp::test {

struct CubeRoom {
  struct Sphere {
    glm::vec3 center;
    float radius;
  };
  scene::Scene scene;
  std::vector<Sphere> spheres;
  glm::vec3 light, lo{-5, 0, -5}, hi{5, 6, 5};
  static constexpr uint32_t kSegments = 48, kRings = 24;
  size_t edgeSphere = 0;  // the sphere on the +X/-Y face edge
};

// withSpheres=false: the bare room (nothing casts a shadow).
inline CubeRoom MakeCubeRoom(bool withSpheres = true) {
  CubeRoom r;
  scene::Scene& s = r.scene;
  s.name = "cube-room";
  uint32_t plane = s.addMesh(scene::MakePlane(2));
  const glm::vec3 size = r.hi - r.lo, mid = (r.hi + r.lo) * 0.5f;
  auto place = [&](glm::vec3 at, float angle, glm::vec3 axis, glm::vec3 scale) {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), at);
    if (angle != 0) m = glm::rotate(m, glm::radians(angle), axis);
    s.addInstance(plane, glm::scale(m, scale), glm::vec3(0.8f));
  };
  // MakePlane faces +y; each surface is rotated to face into the room.
  place({mid.x, r.lo.y, mid.z}, 0, {1, 0, 0}, {size.x, 1, size.z});     // floor, +y
  place({mid.x, r.hi.y, mid.z}, 180, {1, 0, 0}, {size.x, 1, size.z});   // ceiling, -y
  place({r.lo.x, mid.y, mid.z}, -90, {0, 0, 1}, {size.y, 1, size.z});   // wall x = lo, +x
  place({r.hi.x, mid.y, mid.z}, 90, {0, 0, 1}, {size.y, 1, size.z});    // wall x = hi, -x
  place({mid.x, mid.y, r.lo.z}, 90, {1, 0, 0}, {size.x, 1, size.y});    // wall z = lo, +z
  place({mid.x, mid.y, r.hi.z}, -90, {1, 0, 0}, {size.x, 1, size.y});   // wall z = hi, -z

  r.light = {0.4f, 2.6f, -0.3f};
  const glm::vec3 offsets[] = {{1.6f, 0.35f, -0.25f}, {-1.5f, -0.3f, 0.4f}, {0.3f, 1.4f, 0.2f},
                               {-0.35f, -1.5f, 0.3f}, {0.25f, -0.3f, 1.5f}, {-0.3f, 0.25f, -1.6f}};
  if (withSpheres) {
    for (const glm::vec3& o : offsets) r.spheres.push_back({r.light + o, 0.35f});
    r.edgeSphere = r.spheres.size();
    r.spheres.push_back({r.light + glm::normalize(glm::vec3(1.0f, -1.0f, 0.3f)) * 1.8f, 0.3f});
  }
  uint32_t sphere = s.addMesh(scene::MakeSphere(CubeRoom::kSegments, CubeRoom::kRings));
  for (const CubeRoom::Sphere& sp : r.spheres)
    s.addInstance(sphere, glm::scale(glm::translate(glm::mat4(1.0f), sp.center), glm::vec3(2 * sp.radius)), glm::vec3(0.5f));

  s.light.color = glm::vec3(0.0f);  // only the point light shades
  s.light.ambient = 0.05f;
  s.pointLights.push_back({r.light, {5.0f, 5.0f, 5.0f}, 16.0f});
  s.camera.fovY = glm::radians(90.0f);
  s.camera.nearZ = 0.05f;
  s.camera.farZ = 30.0f;
  s.camera.position = {-3.0f, 4.0f, 4.0f};
  s.camera.target = {3.0f, 0.2f, 0.0f};
  s.finalize();
  return r;
}

// Per pixel of a camera's view: -1 not a room surface (sphere or outside), 0 lit, 1 in a sphere's
// shadow, 2 undecided (the segment to the light passes between a tessellated sphere's inscribed and
// circumscribed spheres). `surface` gets the world point, `occluder` the sphere index (or -1).
struct RoomPixel {
  int code = -1;
  glm::vec3 surface{0.0f}, normal{0.0f};
  int occluder = -1;
};

inline std::vector<RoomPixel> AnalyticRoom(const CubeRoom& r, const scene::Camera& cam, uint32_t w, uint32_t h) {
  glm::mat4 inv = glm::inverse(cam.projection(float(w) / h) * cam.view());
  // A polygonal sphere lies between its circumscribed sphere and cos(pi / rings) of it (rings <= segments / 2).
  const double inner = std::cos(glm::pi<double>() / CubeRoom::kRings) - 1e-3, outer = 1.0 + 1e-3;
  std::vector<RoomPixel> out(size_t(w) * h);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      glm::vec4 a = inv * glm::vec4((x + 0.5f) / w * 2 - 1, 1 - (y + 0.5f) / h * 2, 0.0f, 1.0f);
      glm::vec4 b = inv * glm::vec4((x + 0.5f) / w * 2 - 1, 1 - (y + 0.5f) / h * 2, 1.0f, 1.0f);
      glm::dvec3 o = glm::dvec3(glm::vec3(a) / a.w), d = glm::normalize(glm::dvec3(glm::vec3(b) / b.w) - o);
      // Leaving the box from inside: the nearest wall along the ray.
      double tWall = 1e30;
      glm::vec3 n(0.0f);
      for (int k = 0; k < 3; ++k) {
        if (std::abs(d[k]) < 1e-12) continue;
        double t = ((d[k] > 0 ? r.hi[k] : r.lo[k]) - o[k]) / d[k];
        if (t < tWall) tWall = t, n = glm::vec3(0.0f), n[k] = d[k] > 0 ? -1.0f : 1.0f;
      }
      bool blocked = false;
      for (const CubeRoom::Sphere& s : r.spheres) {
        glm::dvec3 oc = o - glm::dvec3(s.center);
        double bq = glm::dot(oc, d), c = glm::dot(oc, oc) - double(s.radius) * s.radius * outer * outer;
        if (bq * bq - c >= 0 && -bq - std::sqrt(bq * bq - c) < tWall) blocked = true;
      }
      RoomPixel& px = out[size_t(y) * w + x];
      if (blocked) continue;
      glm::dvec3 p = o + d * tWall;
      px.surface = glm::vec3(p);
      px.normal = n;
      px.code = 0;
      glm::dvec3 L(r.light);
      for (size_t i = 0; i < r.spheres.size(); ++i) {
        glm::dvec3 c(r.spheres[i].center), seg = L - p;
        double t = std::clamp(glm::dot(c - p, seg) / glm::dot(seg, seg), 0.0, 1.0);
        double dist = glm::length(p + seg * t - c) / r.spheres[i].radius;
        if (dist < inner) {
          px.code = 1, px.occluder = int(i);
          break;
        }
        if (dist <= outer) px.code = 2;
      }
    }
  return out;
}

// Three cameras that together see all six faces' shadows and the edge sphere's on both sides of
// its edge: floor with the -X and -Z walls; ceiling with +X and +Z; the scene's camera on the
// floor around the +X/-Y edge and the +X wall.
inline std::vector<scene::Camera> RoomCameras(const CubeRoom& room) {
  std::vector<scene::Camera> cams(3, room.scene.camera);
  cams[0].position = {4.2f, 5.5f, 4.2f}, cams[0].target = {-1.5f, 0.5f, -1.5f};
  cams[1].position = {-4.2f, 0.6f, -4.2f}, cams[1].target = {1.5f, 4.0f, 1.5f};
  return cams;
}

inline int EncodeSrgb8(double v) {
  v = std::clamp(v, 0.0, 1.0);
  return int(std::lround((v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055) * 255.0));
}

// The room scene's one local light (its point light, or its spot light when it has one) at a
// surface point, as common/local-lights.hlsli shades it (green channel, before albedo).
inline double RoomLocalLight(const scene::Scene& s, glm::vec3 p, glm::vec3 n) {
  glm::vec3 pos = s.spotLights.empty() ? s.pointLights[0].position : s.spotLights[0].position;
  float range = s.spotLights.empty() ? s.pointLights[0].range : s.spotLights[0].range;
  float color = s.spotLights.empty() ? s.pointLights[0].color.g : s.spotLights[0].color.g;
  glm::dvec3 v = glm::dvec3(pos) - glm::dvec3(p);
  double d = glm::length(v), q = d / range;
  double cone = 1.0;
  if (!s.spotLights.empty()) {
    const scene::SpotLight& l = s.spotLights[0];
    double cd = glm::dot(glm::normalize(glm::dvec3(l.direction)), -v / d);
    double ci = std::cos(double(l.innerConeAngle)), co = std::cos(double(l.outerConeAngle));
    double t = std::clamp((cd - co) / std::max(1e-3, ci - co), 0.0, 1.0);
    cone = t * t;
  }
  return color * std::clamp(1 - q * q * q * q, 0.0, 1.0) / (d * d) * std::max(0.0, glm::dot(glm::dvec3(n), v) / d) * cone;
}

// Whether a room-surface point lies within `reachTexels` face texels (at `resolution`) of a second
// wall: a kernel that wide reaches the other wall there, which stands in front of the receiver's
// plane, and darkens the concave corner as any filter of that width does.
inline bool WithinKernelOfACorner(const CubeRoom& room, const RoomPixel& e, float reachTexels, float resolution) {
  glm::vec3 d = glm::abs(e.surface - room.light);
  float footprint = 2.0f * reachTexels * 2.0f * std::max({d.x, d.y, d.z}) / resolution;
  for (int k = 0; k < 3; ++k)
    if (e.normal[k] == 0.0f && std::min(e.surface[k] - room.lo[k], room.hi[k] - e.surface[k]) < footprint) return true;
  return false;
}

// Pixels checked, wrong and in shadow, and shadow pixels per cube face (of the direction from the
// light) in all, and of the edge sphere's shadow.
struct RoomCheck {
  int checked = 0, wrong = 0, shadowed = 0;
  std::array<int, 6> shadowPerFace{}, edgeShadowPerFace{};
  void add(const RoomCheck& o) {
    checked += o.checked, wrong += o.wrong, shadowed += o.shadowed;
    for (int f = 0; f < 6; ++f) shadowPerFace[f] += o.shadowPerFace[f], edgeShadowPerFace[f] += o.edgeShadowPerFace[f];
  }
};

// Compares a rendered RGBA8 image of the room with the analytic shadows: every room-surface pixel
// at least `band` pixels away from a change of the expected answer (texel grid, 2x2 PCF; a wider
// kernel's penumbra needs more), not within `cornerReachTexels` of a second wall (at face size
// `resolution`; WithinKernelOfACorner) and lit
// enough to tell lit from shadowed (16 sRGB levels) must be classified as the CPU says. Reports
// the first failures and writes the image under TestOutputDir() when any pixel is wrong.
inline RoomCheck CheckRoomImage(const CubeRoom& room, const scene::Camera& cam, const std::vector<uint8_t>& img, uint32_t W, uint32_t H, int band = 1,
                                float cornerReachTexels = 0.0f, float resolution = 512.0f) {
  RoomCheck c;
  std::vector<RoomPixel> expected = AnalyticRoom(room, cam, W, H);
  for (uint32_t y = band; y + band < H; ++y)
    for (uint32_t x = band; x + band < W; ++x) {
      const RoomPixel& e = expected[y * W + x];
      if (e.code != 0 && e.code != 1) continue;
      bool nearEdge = false;
      for (int dy = -band; dy <= band; ++dy)
        for (int dx = -band; dx <= band; ++dx) nearEdge |= expected[(y + dy) * W + (x + dx)].code != e.code;
      if (nearEdge || (cornerReachTexels > 0 && WithinKernelOfACorner(room, e, cornerReachTexels, resolution))) continue;
      int lit = EncodeSrgb8(0.8 * (room.scene.light.ambient + RoomLocalLight(room.scene, e.surface, e.normal)));
      int dark = EncodeSrgb8(0.8 * room.scene.light.ambient);
      if (lit - dark < 16) continue;
      int got = img[(y * W + x) * 4 + 1];
      int shadow = std::abs(got - dark) < std::abs(got - lit) ? 1 : 0;
      ++c.checked;
      c.shadowed += e.code;
      int face = tech::cube::FaceOf(e.surface - room.light);
      if (e.code == 1) ++c.shadowPerFace[face];
      if (e.code == 1 && e.occluder == int(room.edgeSphere)) ++c.edgeShadowPerFace[face];
      if (shadow != e.code && ++c.wrong <= 5)
        ADD_FAILURE() << "camera at " << cam.position.x << "," << cam.position.y << "," << cam.position.z << " pixel " << x << "," << y << " (face " << face
                      << "): got " << got << ", expected " << (e.code ? "shadow " : "lit ") << (e.code ? dark : lit);
    }
  if (c.wrong) WritePng(TestOutputDir() / ("room-" + std::to_string(int(cam.position.x * 10)) + ".png"), W, H, img.data());
  return c;
}

// Renders the room with `r` (W x H) from the three RoomCameras and checks every pixel away from
// shadow edges (CheckRoomImage; `cornerReachTexels` at face size `resolution`): none wrong, and
// enough of them in shadow on every face and on both sides of the edge sphere's +X/-Y edge for
// that to mean something.
inline RoomCheck ExpectExactRoomShadows(tech::Renderer& r, const CubeRoom& room, uint32_t W, uint32_t H, float cornerReachTexels, float resolution) {
  RoomCheck total;
  for (const scene::Camera& cam : RoomCameras(room)) {
    r.RenderFrame(cam, room.scene.light);
    total.add(CheckRoomImage(room, cam, r.ReadColor(), W, H, 1, cornerReachTexels, resolution));
  }
  EXPECT_EQ(total.wrong, 0) << "of " << total.checked << " pixels checked";
  EXPECT_GT(total.checked, 20000);
  EXPECT_GT(total.shadowed, 2000);
  for (int f = 0; f < 6; ++f) EXPECT_GT(total.shadowPerFace[f], 40) << "shadow pixels checked on face " << f;
  EXPECT_GT(total.edgeShadowPerFace[0], 20);
  EXPECT_GT(total.edgeShadowPerFace[3], 20);
  return total;
}

// A point-light technique (cube, paraboloid) refuses a light the room lacks and a near plane beyond
// the light's range with errors naming the scene and the parameter. `render` configures the
// technique with the given parameters and renders one frame of `room`.
template <class Render>
void ExpectBadPointLightChoicesRefused(const CubeRoom& room, Render render) {
  try {
    render(std::map<std::string, std::string>{{"light", "1"}});
    ADD_FAILURE() << "expected an error for a light the scene does not have";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(room.scene.name), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("1 point light"), std::string::npos) << e.what();
  }
  try {
    render(std::map<std::string, std::string>{{"near", "20"}});
    ADD_FAILURE() << "expected an error for near beyond the light's range";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("near"), std::string::npos) << e.what();
  }
}

// A floor under a point light, seen from above: the camera frustum reaches above the light, but
// nothing there receives a shadow, so a technique culling faces against visible receivers renders
// 5 faces (not +Y) where it renders 6 without culling, and the same picture. `make(scene, w, h,
// cull)` builds the technique's renderer with cull_faces=cull.
template <class MakeRenderer>
void ExpectTheFaceWithoutReceiversSkipped(MakeRenderer make) {
  scene::Scene s;
  s.name = "floor-under-a-light";
  s.addInstance(s.addMesh(scene::MakePlane(2)), glm::scale(glm::mat4(1.0f), glm::vec3(10.0f, 1.0f, 10.0f)), glm::vec3(0.8f));
  s.addInstance(s.addMesh(scene::MakeSphere(24, 12)), glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 1.0f, 0.0f)), glm::vec3(0.5f));
  s.light.color = glm::vec3(0.0f);
  s.light.ambient = 0.05f;
  s.pointLights.push_back({{0.0f, 2.0f, 0.0f}, {5.0f, 5.0f, 5.0f}, 16.0f});
  s.camera.position = {0.0f, 12.0f, 8.0f};
  s.camera.target = {0.0f, 0.0f, 0.0f};
  s.finalize();
  const uint32_t W = 96, H = 72;
  std::vector<uint8_t> img[2];
  uint32_t faces[2] = {};
  for (int cull = 0; cull < 2; ++cull) {
    auto r = make(s, W, H, cull);
    r->RenderFrame(s.camera, s.light);
    img[cull] = r->ReadColor();
    faces[cull] = r->technique().Stats().layersRendered;
  }
  EXPECT_EQ(faces[0], 6u);
  EXPECT_EQ(faces[1], 5u) << "only the +Y face (nothing above the light) may be skipped";
  EXPECT_EQ(CompareImages("cull-receivers", W, H, img[0].data(), img[1].data(), 0), 0u);
}

}  // namespace sp::test
