// Close-range scenes: "contact" (thin objects on a floor, for peter-panning), "overlapping-occluders"
// (stacked casters, for filtered-map light bleeding) and "point-light-room" (omni lights in a
// closed room).
#include <algorithm>
#include <cmath>
#include <glm/ext/matrix_transform.hpp>

#include "procedural.h"

namespace sp::scene::proc {

namespace {

// Positions on a circle about the camera's target: a slow orbit that keeps the subject framed.
CameraPath OrbitPath(const std::string& name, const Camera& camera, float degrees) {
  std::vector<CameraKey> keys;
  int steps = std::max(2, int(std::ceil(std::abs(degrees) / 1.25f)) + 1);
  glm::vec3 arm = camera.position - camera.target;
  for (int i = 0; i < steps; ++i) {
    float t = float(i) / float(steps - 1);
    glm::mat4 r = glm::rotate(glm::mat4(1.0f), glm::radians(degrees * t), glm::vec3(0, 1, 0));
    keys.push_back({t, camera.target + glm::vec3(r * glm::vec4(arm, 0.0f)), camera.target});
  }
  return MakePath(name, camera, std::move(keys));
}

}  // namespace

Scene MakeContact(uint64_t budget) {
  if (!budget) budget = 15'000;
  Scene s;
  s.name = "contact";
  Rng rng(0xc0417ac7ull);

  // Objects from 1 mm to 2 cm thick lying on the floor (their undersides exactly at y = 0) and a
  // chair on thin legs: any offset that pushes the shadow away from the caster shows as a gap.
  int k = LevelForBudget(1, 128, budget * 15 / 100, [](int c) { return uint64_t(15) * 12 * c * c; });
  uint32_t box = s.addMesh(MakeGridBox(k, "thin-box"));
  s.addInstance(box, Place({-0.45f, 0.01f, 0.25f}, {0.8f, 0.02f, 0.5f}, 15.0f), {0.62f, 0.45f, 0.30f});     // board, 2 cm
  s.addInstance(box, Place({0.35f, 0.0005f, 0.40f}, {0.297f, 0.001f, 0.21f}, -20.0f), {0.92f, 0.92f, 0.90f});  // paper, 1 mm
  s.addInstance(box, Place({0.25f, 0.0045f, -0.20f}, {0.075f, 0.009f, 0.16f}, 40.0f), {0.15f, 0.15f, 0.17f});  // phone, 9 mm
  s.addInstance(box, Place({-0.10f, 0.0015f, -0.35f}, {0.30f, 0.003f, 0.03f}, -60.0f), {0.80f, 0.75f, 0.30f});  // ruler, 3 mm
  uint32_t chair = s.addMesh(MakeChair(k));
  s.addInstance(chair, Place({-0.75f, 0.0f, -0.75f}, glm::vec3(1.0f), 25.0f), {0.55f, 0.40f, 0.28f});

  // Coins 2.3 mm thick on a 4 cm grid (never overlapping), as many as the budget allows, and a
  // stack of six where each rests on the one below.
  const glm::vec3 coinScale(0.024f, 0.0023f, 0.024f);
  struct Coin {
    glm::vec2 pos;
    float key;
  };
  std::vector<Coin> coins;
  for (int j = 0; j < 30; ++j)
    for (int i = 0; i < 30; ++i) {
      glm::vec2 p(0.02f + 0.04f * i + rng.uniform(-0.007f, 0.007f), -1.18f + 0.04f * j + rng.uniform(-0.007f, 0.007f));
      float key = rng.uniform();
      if (glm::distance(p, glm::vec2(0.25f, -0.20f)) > 0.12f) coins.push_back({p, key});  // clear of the phone
    }
  std::stable_sort(coins.begin(), coins.end(), [](const Coin& a, const Coin& b) { return a.key < b.key; });
  const uint64_t coinBudget = budget * 35 / 100;
  int seg = LevelForBudget(12, kMaxSegments, coinBudget / coins.size(), [](int g) { return uint64_t(4 * g); });
  uint32_t coin = s.addMesh(MakeCylinder(uint32_t(seg)));
  const glm::vec3 brass(0.78f, 0.62f, 0.30f);
  for (int i = 0; i < 6; ++i) s.addInstance(coin, Place({0.75f, coinScale.y * i, 0.25f}, coinScale), brass);
  uint64_t coinTris = 0;
  for (const Coin& c : coins) {
    if (coinTris >= coinBudget) break;
    s.addInstance(coin, Place({c.pos.x, 0.0f, c.pos.y}, coinScale), brass * rng.uniform(0.9f, 1.1f));
    coinTris += Tris(s, coin);
  }

  AddTiledFloor(s, {0.0f, 0.0f, 0.0f}, {6.0f, 6.0f}, Remainder(s, budget), {0.70f, 0.68f, 0.64f});

  s.camera.position = {0.9f, 0.75f, 1.3f};
  s.camera.target = {-0.05f, 0.05f, -0.25f};
  s.camera.fovY = glm::radians(50.0f);
  s.camera.nearZ = 0.02f;
  s.camera.farZ = 20.0f;
  // 37 degrees up: shadows as long again as the objects are thick, attached only if bias allows.
  s.light.direction = glm::normalize(glm::vec3(-0.7f, -0.6f, -0.4f));
  FinishScene(s, {OrbitPath("orbit", s.camera, 40.0f)});
  return s;
}

Scene MakeOverlappingOccluders(uint64_t budget) {
  if (!budget) budget = 12'000;
  Scene s;
  s.name = "overlapping-occluders";

  // Two stacks over one receiver: three offset plates, and four bars crossing at different
  // heights. Where several casters at different depths cover a receiver, variance and
  // exponential-variance maps see a wide depth distribution and leak light.
  int k = LevelForBudget(1, 256, budget * 3 / 10, [](int c) { return uint64_t(8) * 12 * c * c; });
  uint32_t box = s.addMesh(MakeGridBox(k, "plate"));
  for (int i = 0; i < 3; ++i)
    s.addInstance(box, Place({-2.0f + 0.6f * (i - 1), 0.8f * (i + 1), 0.3f * (i - 1)}, {2.4f, 0.04f, 2.4f}),
                  glm::vec3(0.80f, 0.35f, 0.25f) + glm::vec3(0.0f, 0.15f, 0.2f) * float(i));
  const float barYaw[4] = {0.0f, 90.0f, 45.0f, -45.0f};
  for (int i = 0; i < 4; ++i) s.addInstance(box, Place({2.2f, 0.7f * (i + 1), 0.3f}, {3.0f, 0.05f, 0.5f}, barYaw[i]), {0.30f, 0.45f, 0.75f});
  // Receivers of their own inside the shadowed regions.
  s.addInstance(box, Place({-2.2f, 0.4f, 0.4f}, glm::vec3(0.8f), 15.0f), {0.85f, 0.60f, 0.25f});
  int seg = LevelForBudget(16, kMaxSegments, budget * 15 / 100, [](int g) { return uint64_t(g) * (g - 2); });
  uint32_t sphere = s.addMesh(MakeSphere(uint32_t(seg), uint32_t(seg / 2)));
  s.addInstance(sphere, Place({2.4f, 0.5f, -0.9f}, glm::vec3(1.0f)), {0.70f, 0.70f, 0.75f});

  AddTiledFloor(s, {0.0f, 0.0f, 0.0f}, {16.0f, 16.0f}, Remainder(s, budget), {0.72f, 0.70f, 0.66f});

  s.camera.position = {5.5f, 4.2f, 7.5f};
  s.camera.target = {0.0f, 0.6f, 0.0f};
  s.camera.nearZ = 0.1f;
  s.camera.farZ = 60.0f;
  s.light.direction = glm::normalize(glm::vec3(0.25f, -1.0f, 0.12f));
  FinishScene(s, {OrbitPath("orbit", s.camera, 40.0f)});
  return s;
}

namespace {

// The sun's angular diameter the planks' regions are laid out for: part 5b/5c of
// eval/experiments/techniques-v.sh run these scenes with --light-size 3.
constexpr float kPlankSunDegrees = 3.0f;

// Regions of the floor (y = 0) where PCSS's one average blocker depth can go wrong, the same in
// both plank scenes so that their pixels are the same ones (the camera is below the high plank,
// which is never on screen). A blocker edge at height h casts its hard edge on the floor at
// h * (dx, dz) / -dy from it (d the light's direction) and a penumbra about
// h * (tan(t + a) - tan(t - a)) wide across it, t the light's tilt from the vertical in the plane
// across the edge and a the sun's angular radius: 0.03 m for the low plank, 0.16 m for the high
// one at 3 degrees.
// In the low plank's shadow (both long edges with 0.1 m of floor beyond them and its umbra
// between):
//  "under-high-penumbra": where the high plank's penumbra crosses it (1.15 times its half width
//    plus 1 cm for the plank's thickness either side of its hard edges): the area light's
//    visibility is the two planks' together there, PCSS's blocker search finds both, and its one
//    average blocker depth is wrong for each;
//  "beside-high-penumbra": strips 0.1 m wide just outside that: the area light's visibility is the
//    low plank's alone, as in single-plank, but a blocker search reaching further than the high
//    plank's penumbra (PCSS searches the penumbra of a blocker on the light's near plane, up to
//    pcss_max_kernel / 2 texels) still mixes the high plank's depth into the average;
//  "far": the same band 0.5 m or more from the high plank's penumbra, which no search reaches.
std::vector<Region> PlankRegions(const glm::vec3& light, const glm::vec3& lowCentre, const glm::vec3& lowSize,
                                 const glm::vec3& highCentre, const glm::vec3& highSize) {
  glm::vec2 slope(light.x / -light.y, light.z / -light.y);  // floor offset per metre of height
  glm::vec2 low = glm::vec2(lowCentre.x, lowCentre.z) + slope * lowCentre.y;
  glm::vec2 high = glm::vec2(highCentre.x, highCentre.z) + slope * highCentre.y;
  float a = glm::radians(0.5f * kPlankSunDegrees), t = std::atan(slope.x);
  float highHalfPenumbra = 0.5f * highCentre.y * (std::tan(t + a) - std::tan(t - a));
  float gap = 1.15f * highHalfPenumbra + 0.01f, strip = 0.1f, beyond = 0.1f;
  float z0 = low.y - 0.5f * lowSize.z - beyond, z1 = low.y + 0.5f * lowSize.z + beyond;
  float left = high.x - 0.5f * highSize.x - gap, right = high.x + 0.5f * highSize.x + gap;
  auto band = [&](float x0, float x1) {
    Bounds b;
    b.extend({x0, -0.01f, z0});
    b.extend({x1, 0.01f, z1});
    return b;
  };
  float far = right + 0.5f;
  return {Region{"under-high-penumbra", {band(left, left + 2.0f * gap), band(right - 2.0f * gap, right)}},
          Region{"beside-high-penumbra", {band(left - strip, left), band(right, right + strip)}},
          Region{"far", {band(far, far + 2.0f * strip)}}};
}

// A low plank 0.6 m over a floor and, with `high`, a second plank 3 m up crossing over it, under a
// near-overhead sun: PCSS's blocker search around the low plank's penumbra also finds the high
// plank, and its one average blocker depth widens the low plank's penumbra (issue 15's known
// failure); "single-plank" is the low plank alone, where the average is right.
Scene MakePlanks(uint64_t budget, bool high) {
  if (!budget) budget = 8'000;
  Scene s;
  s.name = high ? "stacked-planks" : "single-plank";
  int k = LevelForBudget(1, 128, budget * 2 / 10, [](int c) { return uint64_t(2) * 12 * c * c; });
  uint32_t box = s.addMesh(MakeGridBox(k, "plank"));
  s.light.direction = glm::normalize(glm::vec3(0.2f, -1.0f, 0.15f));
  const glm::vec3 lowCentre(0.0f, 0.6f, 0.0f), lowSize(3.0f, 0.04f, 0.4f);
  const glm::vec3 highCentre(-0.48f, 3.0f, -0.36f), highSize(0.5f, 0.04f, 3.0f);
  s.addInstance(box, Place(lowCentre, lowSize), {0.62f, 0.45f, 0.30f});
  // Over the low plank so that its shadow on the floor (offset by 3 m along the light) crosses the
  // low plank's shadow at right angles.
  if (high) s.addInstance(box, Place(highCentre, highSize), {0.45f, 0.50f, 0.62f});
  s.regions = PlankRegions(s.light.direction, lowCentre, lowSize, highCentre, highSize);
  AddTiledFloor(s, {0.0f, 0.0f, 0.0f}, {8.0f, 8.0f}, Remainder(s, budget), {0.72f, 0.70f, 0.66f});
  s.camera.position = {1.2f, 1.6f, 1.9f};
  s.camera.target = {0.1f, 0.0f, 0.1f};
  s.camera.fovY = glm::radians(45.0f);
  s.camera.nearZ = 0.05f;
  s.camera.farZ = 30.0f;
  FinishScene(s, {OrbitPath("orbit", s.camera, 20.0f)});
  return s;
}

}  // namespace

Scene MakeStackedPlanks(uint64_t budget) { return MakePlanks(budget, true); }
Scene MakeSinglePlank(uint64_t budget) { return MakePlanks(budget, false); }

Scene MakePointLightRoom(uint64_t budget) {
  if (!budget) budget = 20'000;
  Scene s;
  s.name = "point-light-room";

  // A closed 12 x 3.6 x 9 m room (inside), walls and ceiling 25 cm thick, so no light enters or
  // leaves: what the camera sees is lit by the point lights alone. Omni-shadow techniques use
  // Scene::pointLights; the directional light is kept only so directional techniques still run,
  // and is dim (and blocked by the ceiling anyway).
  const glm::vec3 lo(-6.0f, 0.0f, -4.5f), hi(6.0f, 3.6f, 4.5f);
  const float t = 0.25f;
  const glm::vec3 plaster(0.80f, 0.78f, 0.74f);
  glm::vec3 size = hi - lo, mid = (hi + lo) * 0.5f;
  AddRoomShell(s, lo, hi, t, plaster, budget / 4);

  // Furniture: legs, shelves and table tops throw the many small, overlapping omni shadows.
  const int boxesInFurniture = 10 + 7 + 4 + 8 * 11;  // two tables, a shelf, a cabinet and crates, eight chairs
  int k = LevelForBudget(1, 128, budget * 35 / 100, [&](int c) { return uint64_t(boxesInFurniture) * 12 * c * c; });
  uint32_t table = s.addMesh(MakeTable(k, {1.6f, 0.9f}));
  uint32_t chair = s.addMesh(MakeChair(k));
  uint32_t shelf = s.addMesh(MakeShelf(k));
  uint32_t box = s.addMesh(MakeGridBox(k, "box"));

  const glm::vec3 wood(0.60f, 0.44f, 0.30f), dark(0.35f, 0.30f, 0.28f);
  const glm::vec3 tables[2] = {{-2.0f, 0.0f, 1.2f}, {2.0f, 0.0f, -2.6f}};
  const float tableYaw[2] = {10.0f, -5.0f};
  for (int i = 0; i < 2; ++i) {
    s.addInstance(table, Place(tables[i], glm::vec3(1.0f), tableYaw[i]), wood);
    for (int c = 0; c < 4; ++c) {
      float side = c < 2 ? -1.0f : 1.0f, along = c % 2 ? 0.4f : -0.4f;
      glm::vec3 local(along, 0.0f, side * 0.75f);
      glm::vec3 p = tables[i] + glm::vec3(glm::rotate(glm::mat4(1.0f), glm::radians(tableYaw[i]), glm::vec3(0, 1, 0)) * glm::vec4(local, 0.0f));
      s.addInstance(chair, Place(p, glm::vec3(1.0f), tableYaw[i] + (side < 0 ? 0.0f : 180.0f) + 7.0f * c), dark);
    }
  }
  s.addInstance(shelf, Place({-3.5f, 0.0f, lo.z + 0.22f}, glm::vec3(1.0f)), wood);
  s.addInstance(box, Place({4.6f, 0.45f, -3.9f}, {1.0f, 0.9f, 0.6f}), {0.55f, 0.58f, 0.62f});
  s.addInstance(box, Place({-5.2f, 0.3f, 3.7f}, glm::vec3(0.6f), 8.0f), {0.62f, 0.50f, 0.36f});
  s.addInstance(box, Place({-5.2f, 0.9f, 3.7f}, glm::vec3(0.6f), -14.0f), {0.66f, 0.52f, 0.37f});
  s.addInstance(box, Place({-4.5f, 0.3f, 3.9f}, glm::vec3(0.6f), 30.0f), {0.60f, 0.48f, 0.35f});

  int seg = LevelForBudget(16, kMaxSegments, budget / 10, [](int g) { return uint64_t(4 * 4 * g); });
  uint32_t column = s.addMesh(MakeCylinder(uint32_t(seg)));
  for (float x : {-4.0f, 0.0f})
    for (float z : {-1.6f, 1.6f}) s.addInstance(column, Place({x, 0.0f, z}, {0.4f, size.y, 0.4f}), plaster);

  // The floor runs under the walls so the room has no gap at their feet.
  AddTiledFloor(s, {mid.x, 0.0f, mid.z}, {size.x + 2 * t, size.z + 2 * t}, Remainder(s, budget), {0.55f, 0.50f, 0.45f});

  s.pointLights.push_back({{-2.0f, 2.9f, -0.6f}, {4.0f, 3.4f, 2.6f}, 12.0f});
  s.pointLights.push_back({{3.2f, 1.5f, 2.2f}, {1.2f, 1.6f, 2.4f}, 7.0f});
  s.light.direction = glm::normalize(glm::vec3(0.1f, -1.0f, 0.05f));
  s.light.color = glm::vec3(0.04f);
  s.light.ambient = 0.06f;

  s.camera.position = {5.3f, 1.7f, 3.9f};
  s.camera.target = {-2.0f, 0.9f, -1.5f};
  s.camera.fovY = glm::radians(70.0f);
  s.camera.nearZ = 0.05f;
  s.camera.farZ = 30.0f;

  // "walk": along the front wall and round towards the shelf, passing between the two lights.
  std::vector<CameraKey> keys = {{0.0f, s.camera.position, s.camera.target},
                                 {0.5f, {1.0f, 1.7f, 3.7f}, glm::vec3(1.0f, 1.7f, 3.7f) + glm::vec3(-3.0f, -0.6f, -5.4f)},
                                 {1.0f, {-3.6f, 1.6f, 3.4f}, glm::vec3(-3.6f, 1.2f, -4.0f)}};
  FinishScene(s, {MakePath("walk", s.camera, std::move(keys))});
  return s;
}

}  // namespace sp::scene::proc
