// Scenes whose failure comes from how the view and the light relate: "dueling-frusta" (looking
// into the light), "grazing-light" (light nearly parallel to large receivers) and
// "distant-occluder" (a depth distribution with a wide empty gap).
#include <algorithm>
#include <cmath>
#include <glm/ext/matrix_transform.hpp>

#include "procedural.h"

namespace sp::scene::proc {

namespace {

uint64_t SphereTris(int segments, int rings) { return uint64_t(segments) * (2 * rings - 2); }

}  // namespace

Scene MakeDuelingFrusta(uint64_t budget) {
  if (!budget) budget = 30'000;
  Scene s;
  s.name = "dueling-frusta";
  Rng rng(0xd0e11f0ull);

  // An orchard in front of the camera: trunks with round crowns whose shadows, with the sun ahead
  // and low, stretch back towards the viewer; the shadow map's texels are spread along the
  // light's direction while the view wants them densest near the camera.
  struct Tree {
    glm::vec3 base;
    float trunk, crown;
    glm::vec3 color;
    float key;
  };
  std::vector<Tree> trees;
  for (int row = 0; row < 21; ++row)
    for (int col = 0; col < 10; ++col) {
      Tree t;
      t.base = {-36.0f + 8.0f * col + rng.uniform(-2.5f, 2.5f), 0.0f, -8.0f - 9.0f * row + rng.uniform(-2.5f, 2.5f)};
      t.trunk = rng.uniform(2.5f, 4.0f);
      t.crown = rng.uniform(2.4f, 3.6f);
      t.color = glm::vec3(0.30f, 0.48f, 0.26f) * rng.uniform(0.85f, 1.15f);
      t.key = rng.uniform();
      trees.push_back(t);
    }
  std::stable_sort(trees.begin(), trees.end(), [](const Tree& a, const Tree& b) { return a.key < b.key; });

  const uint64_t treeBudget = budget * 6 / 10;
  auto treeTris = [](int seg) { return uint64_t(4 * seg) + SphereTris(seg, seg / 2); };
  int seg = LevelForBudget(6, kMaxSegments, treeBudget / trees.size(), treeTris);
  uint32_t trunk = s.addMesh(MakeCylinder(uint32_t(seg)));
  uint32_t crown = s.addMesh(MakeSphere(uint32_t(seg), uint32_t(seg / 2)));
  uint64_t used = 0;
  for (const Tree& t : trees) {
    if (used >= treeBudget) break;
    s.addInstance(trunk, Place(t.base, {0.45f, t.trunk + 0.5f, 0.45f}), {0.45f, 0.36f, 0.28f});
    s.addInstance(crown, Place(t.base + glm::vec3(0.0f, t.trunk + t.crown * 0.4f, 0.0f), glm::vec3(t.crown)), t.color);
    used += treeTris(seg);
  }

  // A fence just ahead of the camera: the shadows that land at the viewer's feet, where
  // perspective warping should help most and cannot when the light faces the camera.
  uint32_t post = s.addMesh(MakeGridBox(2, "fence"));
  const glm::vec3 wood(0.55f, 0.42f, 0.30f);
  for (int i = -10; i <= 10; ++i) s.addInstance(post, Place({float(i), 0.55f, -2.0f}, {0.08f, 1.1f, 0.08f}), wood);
  for (float y : {0.5f, 1.0f}) s.addInstance(post, Place({0.0f, y, -2.0f}, {20.2f, 0.06f, 0.04f}), wood);

  used = s.triangleCount();
  AddTiledFloor(s, {0.0f, 0.0f, -90.0f}, {240.0f, 240.0f}, budget > used + 2 ? budget - used : 2, {0.52f, 0.55f, 0.42f});

  s.camera.position = {0.0f, 1.7f, 8.0f};
  s.camera.target = {0.0f, 2.5f, -40.0f};
  s.camera.nearZ = 0.2f;
  s.camera.farZ = 300.0f;
  // The sun 17 degrees up, straight ahead: the light travels back along the view direction.
  s.light.direction = glm::normalize(glm::vec3(0.08f, -0.30f, 0.95f));

  // "turn-to-light": from looking across the light (where warped maps do well) to into it.
  FinishScene(s, {YawPath("turn-to-light", s.camera, 90.0f, 0.0f)});
  return s;
}

Scene MakeGrazingLight(uint64_t budget) {
  if (!budget) budget = 20'000;
  Scene s;
  s.name = "grazing-light";

  // The sun 3 degrees above the floor and 4 degrees off the wall's plane: both large receivers
  // are lit almost edge-on, where a constant depth bias is either too small (acne) or, scaled up
  // by the slope, large enough to detach every shadow.
  const float elevation = glm::radians(3.0f), alongWall = glm::radians(4.0f);
  s.light.direction = glm::normalize(glm::vec3(std::cos(elevation) * std::cos(alongWall), -std::sin(elevation), -std::cos(elevation) * std::sin(alongWall)));

  // A wall 100 m long and 14 m high along z = -30, in ten shared 10 m sections split into cells
  // of about the same shape.
  auto wallCellsX = [](int n) { return std::max(1, int(std::lround(n * 10.0 / 14.0))); };
  auto wallTris = [&](int n) { return uint64_t(10 * 4) * (uint64_t(n) + wallCellsX(n) + uint64_t(wallCellsX(n)) * n); };
  int n = LevelForBudget(1, 1024, budget * 3 / 10, wallTris);
  uint32_t wall = s.addMesh(MakeGridBox(glm::ivec3(wallCellsX(n), n, 1), "wall"));
  for (int i = 0; i < 10; ++i) s.addInstance(wall, Place({-45.0f + 10.0f * i, 7.0f, -30.0f}, {10.0f, 14.0f, 0.6f}), {0.78f, 0.76f, 0.72f});

  // A few casters whose shadows run tens of metres along the floor and the wall.
  int k = LevelForBudget(1, 64, budget / 20, [](int c) { return uint64_t(6) * 12 * c * c; });
  uint32_t box = s.addMesh(MakeGridBox(k, "box"));
  s.addInstance(box, Place({-20.0f, 1.0f, -10.0f}, {2.0f, 2.0f, 2.0f}, 20.0f), {0.80f, 0.35f, 0.25f});
  s.addInstance(box, Place({-8.0f, 1.0f, 6.0f}, {2.0f, 2.0f, 2.0f}, -10.0f), {0.30f, 0.45f, 0.75f});
  s.addInstance(box, Place({-28.0f, 2.0f, -26.0f}, {1.5f, 4.0f, 1.5f}), {0.75f, 0.72f, 0.66f});
  s.addInstance(box, Place({-14.0f, 0.25f, -2.0f}, {0.5f, 0.5f, 8.0f}), {0.35f, 0.65f, 0.40f});
  // A slab tilted 1.5 degrees towards the light: a third grazing angle between the two.
  glm::mat4 ramp = glm::translate(glm::mat4(1.0f), {4.0f, 0.4f, -12.0f});
  ramp = glm::rotate(ramp, glm::radians(1.5f), glm::vec3(0, 0, 1));
  s.addInstance(box, glm::scale(ramp, glm::vec3(14.0f, 0.3f, 6.0f)), {0.70f, 0.66f, 0.58f});
  s.addInstance(box, Place({12.0f, 0.5f, 8.0f}, {1.0f, 1.0f, 1.0f}, 35.0f), {0.85f, 0.60f, 0.25f});
  int seg = LevelForBudget(16, kMaxSegments, budget / 10, [](int g) { return SphereTris(g, g / 2); });
  uint32_t sphere = s.addMesh(MakeSphere(uint32_t(seg), uint32_t(seg / 2)));
  s.addInstance(sphere, Place({-2.0f, 1.5f, -4.0f}, glm::vec3(3.0f)), {0.70f, 0.70f, 0.75f});

  uint64_t used = s.triangleCount();
  AddTiledFloor(s, {0.0f, 0.0f, 0.0f}, {120.0f, 120.0f}, budget > used + 2 ? budget - used : 2, {0.72f, 0.70f, 0.66f});

  s.camera.position = {-32.0f, 9.0f, 22.0f};
  s.camera.target = {6.0f, 0.0f, -22.0f};
  s.camera.nearZ = 0.3f;
  s.camera.farZ = 300.0f;
  FinishScene(s);
  return s;
}

Scene MakeDistantOccluder(uint64_t budget) {
  if (!budget) budget = 25'000;
  Scene s;
  s.name = "distant-occluder";
  Rng rng(0xd157a17ull);

  // A plaza floating in empty space and, 700 m further along the view with nothing in between, a
  // small group of towers on a second platform: a handful of far depth samples beside many near
  // ones. Sample-distribution shadow maps cluster depths (K-means splits one cluster on the gap)
  // and adaptive logarithmic partitions see a wide empty depth range.
  int seg = LevelForBudget(16, kMaxSegments, budget / 4, [](int g) { return uint64_t(5 * 4 * g) + SphereTris(g, g / 2); });
  uint32_t column = s.addMesh(MakeCylinder(uint32_t(seg)));
  uint32_t sphere = s.addMesh(MakeSphere(uint32_t(seg), uint32_t(seg / 2)));
  const glm::vec3 stone(0.78f, 0.74f, 0.68f);
  for (int i = 0; i < 5; ++i) s.addInstance(column, Place({-10.0f + 5.0f * i, 0.0f, -10.0f}, {0.9f, 4.0f + 0.8f * i, 0.9f}), stone);
  s.addInstance(sphere, Place({7.0f, 1.5f, 2.0f}, glm::vec3(3.0f)), {0.70f, 0.70f, 0.75f});

  // Crates scattered over the plaza, as many as the budget allows, away from the camera.
  struct Crate {
    glm::vec3 pos;
    float size, yaw;
    glm::vec3 color;
  };
  std::vector<Crate> crates;
  while (crates.size() < 400) {
    Crate c;
    c.size = rng.uniform(0.4f, 1.2f);
    c.pos = {rng.uniform(-18.0f, 18.0f), c.size * 0.5f, rng.uniform(-18.0f, 14.0f)};
    c.yaw = rng.uniform(0.0f, 90.0f);
    c.color = glm::vec3(0.62f, 0.50f, 0.36f) * rng.uniform(0.8f, 1.15f);
    bool nearColumns = std::abs(c.pos.z + 10.0f) < 1.5f, nearSphere = glm::distance(glm::vec2(c.pos.x, c.pos.z), glm::vec2(7.0f, 2.0f)) < 2.5f;
    if (!nearColumns && !nearSphere) crates.push_back(c);
  }
  const uint64_t crateBudget = budget / 4;
  int k = 1;
  while (crates.size() * 12ull * k * k < crateBudget && k < 128) ++k;
  uint32_t box = s.addMesh(MakeGridBox(k, "crate"));
  uint64_t crateTris = 0;
  for (const Crate& c : crates) {
    if (crateTris >= crateBudget) break;
    s.addInstance(box, Place(c.pos, glm::vec3(c.size), c.yaw), c.color);
    crateTris += Tris(s, box);
  }

  // The far group: 700 m away, a platform and six towers, together a few degrees of the view.
  int farCells = LevelForBudget(1, 64, budget / 10, [](int c) { return uint64_t(7) * 12 * c * c; });
  uint32_t farBox = s.addMesh(MakeGridBox(farCells, "far-block"));
  const float farZ = -700.0f;
  s.addInstance(farBox, Place({0.0f, -2.0f, farZ}, {80.0f, 4.0f, 80.0f}), {0.60f, 0.58f, 0.55f});
  for (int i = 0; i < 6; ++i) {
    float h = 15.0f + 8.0f * float((i * 5) % 6);
    s.addInstance(farBox, Place({-25.0f + 10.0f * i, h * 0.5f, farZ + float((i * 7) % 5 - 2) * 9.0f}, {8.0f, h, 8.0f}, 10.0f * i),
                  {0.74f, 0.71f, 0.66f});
  }

  uint64_t used = s.triangleCount();
  AddTiledFloor(s, {0.0f, 0.0f, 0.0f}, {40.0f, 40.0f}, budget > used + 2 ? budget - used : 2, {0.72f, 0.70f, 0.66f});

  s.camera.position = {0.0f, 5.0f, 22.0f};
  s.camera.target = {0.0f, 0.0f, -700.0f};
  s.camera.nearZ = 0.2f;
  s.camera.farZ = 1000.0f;
  s.light.direction = glm::normalize(glm::vec3(-0.4f, -0.75f, -0.5f));

  // "reveal": the view turns from the plaza alone (the far group off to the side, outside the
  // frustum) to both, so the depth distribution changes abruptly mid-path.
  FinishScene(s, {YawPath("reveal", s.camera, 60.0f, 0.0f)});
  return s;
}

}  // namespace sp::scene::proc
