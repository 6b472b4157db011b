// The local-light scenes show what they exist for, checked geometrically from the light: the
// furnished room has furniture on (at least) five sides of its lamp and legs on the floor, the
// street keeps most of its lamps out of the camera's view, and every face of the lattice light's
// shadow cube sees bars. No GPU needed.
#include <gtest/gtest.h>

#include <array>
#include <set>
#include <string>

#include "cube/cube-faces.h"
#include "scene-rays.h"
#include <sp/scene/scene.h>
#include <sp/tech/technique.h>

namespace sp::test {
namespace {

using scene::Instance;
using scene::Scene;

// The room shells and floors are "wall" and "floor-tile" meshes; everything else is furniture.
bool IsShell(const Scene& s, const Instance& i) {
  const std::string& n = s.meshes[i.mesh].name;
  return n == "wall" || n == "floor-tile";
}

// The nearest triangle along a ray within `range` (boxes first to skip most instances): its t,
// or `range` with `hit` null when nothing is nearer.
float FirstHit(const Scene& s, const glm::vec3& origin, const glm::vec3& dir, float range, const Instance** hit) {
  float best = range;
  *hit = nullptr;
  for (const Instance& inst : s.instances) {
    float box = RayHit(s, inst, origin, dir);
    if (box < 0.0f || box >= best) continue;
    float t = RayMesh(s, inst, origin, dir);
    if (t >= 0.0f && t < best) best = t, *hit = &inst;
  }
  return best;
}

// For each D3D11 cube face of a light at `light`: the fraction of a grid x grid fan of rays through
// the face whose first hit (by triangles, within `range`) is an instance `counts` accepts.
template <class Pred>
std::array<double, 6> FaceHitFractions(const Scene& s, const glm::vec3& light, float range, int grid, Pred counts) {
  std::array<double, 6> out{};
  for (int f = 0; f < 6; ++f) {
    tech::cube::FaceAxes ax = tech::cube::Face(f);
    int hits = 0;
    for (int j = 0; j < grid; ++j)
      for (int i = 0; i < grid; ++i) {
        float sc = (i + 0.5f) / grid * 2 - 1, tc = (j + 0.5f) / grid * 2 - 1;
        const Instance* first = nullptr;
        FirstHit(s, light, glm::normalize(ax.major + sc * ax.s + tc * ax.t), range, &first);
        hits += first && counts(*first);
      }
    out[f] = double(hits) / double(grid * grid);
  }
  return out;
}

TEST(ProceduralSceneProperties, FurnishedRoomHasFurnitureOnFiveSidesOfItsLamp) {
  Scene s = scene::MakeBuiltinScene("furnished-room");
  ASSERT_EQ(s.pointLights.size(), 1u);
  const scene::PointLight& L = s.pointLights[0];
  EXPECT_LT(std::max({s.light.color.r, s.light.color.g, s.light.color.b}), 0.1f);
  for (const Instance& i : s.instances) {
    EXPECT_FALSE(Inside(s, i, L.position));
    EXPECT_FALSE(Inside(s, i, s.camera.position));
  }
  // What each face of the light's cube sees first, along 24 x 24 rays: furniture on >= 5 faces
  // (at least 2 % of a face's rays), and the room closed (every ray meets something in range).
  std::array<double, 6> furniture = FaceHitFractions(s, L.position, L.range, 24, [&](const Instance& i) { return !IsShell(s, i); });
  std::array<double, 6> anything = FaceHitFractions(s, L.position, L.range, 24, [](const Instance&) { return true; });
  int faces = 0;
  for (int f = 0; f < 6; ++f) {
    faces += furniture[f] >= 0.02;
    EXPECT_EQ(anything[f], 1.0) << "face " << f;
    std::printf("furnished-room face %d: %.1f %% of rays meet furniture first\n", f, 100.0 * furniture[f]);
  }
  EXPECT_GE(faces, 5);
  // Contact shadows: furniture standing on the floor on legs (table, chairs, sideboard, sofa).
  int resting = 0;
  for (const Instance& i : s.instances)
    resting += !IsShell(s, i) && std::abs(i.worldBounds.min.y) < 1e-3f;
  EXPECT_GE(resting, 8);
}

TEST(ProceduralSceneProperties, StreetKeepsMostLampsOutOfView) {
  Scene s = scene::MakeBuiltinScene("street");
  const size_t n = s.pointLights.size();
  EXPECT_GE(n, 12u);
  EXPECT_LE(n, size_t(tech::kMaxLocalLights));
  for (const scene::PointLight& l : s.pointLights) {
    EXPECT_GT(l.range, 0.0f);
    EXPECT_LE(l.range, 10.0f);  // small lamps: each lights its own stretch of street
    // Under its lamp head (within 10 cm above), over the open street (the floor 4.5 m below).
    const Instance* hit = nullptr;
    EXPECT_LT(FirstHit(s, l.position, {0, 1, 0}, l.range, &hit), 0.1f);
    EXPECT_NEAR(FirstHit(s, l.position, {0, -1, 0}, l.range, &hit), l.position.y, 1e-3f);
    ASSERT_TRUE(hit);
    EXPECT_EQ(s.meshes[hit->mesh].name, "floor-tile");
  }
  // Lamps whose range sphere meets the camera frustum (the six planes of clip = P V p, D3D depth
  // 0..w), at the start of the "walk" and along it: well below N everywhere.
  auto visible = [&](const scene::Camera& cam) {
    glm::mat4 m = glm::transpose(cam.projection(16.0f / 9.0f) * cam.view());
    const glm::vec4 planes[6] = {m[3] + m[0], m[3] - m[0], m[3] + m[1], m[3] - m[1], m[2], m[3] - m[2]};
    size_t count = 0;
    for (const scene::PointLight& l : s.pointLights) {
      bool in = true;
      for (const glm::vec4& p : planes) in &= glm::dot(glm::vec3(p), l.position) + p.w > -l.range * glm::length(glm::vec3(p));
      count += in;
    }
    return count;
  };
  size_t atStart = visible(s.camera);
  std::printf("street: %zu lamps, %zu meet the camera frustum at the start\n", n, atStart);
  EXPECT_GE(atStart, 1u);
  EXPECT_LE(atStart * 2, n);
  const scene::CameraPath& walk = s.cameraPath("walk");
  EXPECT_EQ(walk.at(0.0).position, s.camera.position);
  EXPECT_GT(glm::length(walk.at(1.0).position - walk.at(0.0).position), 100.0f);
  for (int k = 0; k <= 8; ++k) EXPECT_LE(visible(walk.at(k / 8.0)) * 2, n) << "t = " << k / 8.0;
}

TEST(ProceduralSceneProperties, LatticeBusiesEveryCubeFace) {
  Scene s = scene::MakeBuiltinScene("lattice");
  ASSERT_EQ(s.pointLights.size(), 1u);
  const scene::PointLight& L = s.pointLights[0];
  for (const Instance& i : s.instances) {
    EXPECT_FALSE(Inside(s, i, L.position));
    EXPECT_FALSE(Inside(s, i, s.camera.position));
  }
  // Bars first on a good part of every face's rays: each face's shadow is a grid.
  std::array<double, 6> bars = FaceHitFractions(s, L.position, L.range, 48, [&](const Instance& i) { return s.meshes[i.mesh].name == "bar"; });
  for (int f = 0; f < 6; ++f) {
    std::printf("lattice face %d: %.1f %% of rays meet a bar first\n", f, 100.0 * bars[f]);
    EXPECT_GE(bars[f], 0.15) << "face " << f;
    EXPECT_LE(bars[f], 0.6) << "face " << f << ": light must get through the cage";
  }
}

}  // namespace
}  // namespace sp::test
