// "paraboloid-coarse" and "paraboloid-fine": one closed room around a point light with box
// occluders, built twice: every wall and box face as two triangles, and the same surfaces split
// into small triangles. Paraboloid shadow maps project per vertex and interpolate linearly in
// between, so their error depends on triangle size; nothing else differs between the two.
#include <glm/ext/matrix_transform.hpp>

#include "procedural.h"

namespace sp::scene::proc {
namespace {

// Room: x in [-4, 4], y in [0, 4], z in [-3, 3].
constexpr glm::vec3 kRoomLo{-4.0f, 0.0f, -3.0f}, kRoomHi{4.0f, 4.0f, 3.0f};
constexpr glm::vec3 kLight{0.3f, 2.2f, -0.2f};

// Triangles of the room and its boxes when walls are split into `wall` cells per side and box
// faces into `box` (6 walls, 6 boxes of 6 faces).
uint64_t RoomTriangles(int wall, int box) { return uint64_t(6) * 2 * wall * wall + uint64_t(6) * 6 * 2 * box * box; }

Scene MakeParaboloidRoom(uint64_t budget, bool fine, const char* name) {
  if (!budget) budget = 40'000;
  Scene s;
  s.name = name;
  // The fine room spends the budget on splitting: walls (8 m) into `wall` cells, boxes (about 1 m)
  // into a third as many, so triangles are of similar size everywhere.
  int wall = 1, box = 1;
  if (fine) {
    wall = LevelForBudget(3, 96, budget, [](int n) { return RoomTriangles(n, (n + 2) / 3); });
    box = (wall + 2) / 3;
  }
  Mesh plane = MakeGridPlane(wall, wall);
  plane.name = fine ? "wall-fine" : "wall";
  uint32_t planeMesh = s.addMesh(std::move(plane));
  uint32_t boxMesh = s.addMesh(MakeGridBox(box, fine ? "block-fine" : "block"));

  // Walls facing into the room (the grid plane faces +y), as in the cube technique's test room.
  const glm::vec3 size = kRoomHi - kRoomLo, mid = (kRoomHi + kRoomLo) * 0.5f;
  const glm::vec3 plaster(0.80f, 0.78f, 0.74f);
  auto wallAt = [&](glm::vec3 at, float angle, glm::vec3 axis, glm::vec3 scale) {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), at);
    if (angle != 0) m = glm::rotate(m, glm::radians(angle), axis);
    s.addInstance(planeMesh, glm::scale(m, scale), plaster);
  };
  wallAt({mid.x, kRoomLo.y, mid.z}, 0, {1, 0, 0}, {size.x, 1, size.z});
  wallAt({mid.x, kRoomHi.y, mid.z}, 180, {1, 0, 0}, {size.x, 1, size.z});
  wallAt({kRoomLo.x, mid.y, mid.z}, -90, {0, 0, 1}, {size.y, 1, size.z});
  wallAt({kRoomHi.x, mid.y, mid.z}, 90, {0, 0, 1}, {size.y, 1, size.z});
  wallAt({mid.x, mid.y, kRoomLo.z}, 90, {1, 0, 0}, {size.x, 1, size.y});
  wallAt({mid.x, mid.y, kRoomHi.z}, -90, {1, 0, 0}, {size.x, 1, size.y});

  // Boxes with long straight edges at various angles to the light: a crate under it, a post
  // crossing the plane through the light (its shadow crosses the seam of a y-axis map), a slab
  // above it (shadow on the ceiling), a long low beam and a floating board (shadows on the floor
  // and walls), a tall block by a wall.
  const glm::vec3 red(0.70f, 0.36f, 0.30f), blue(0.34f, 0.42f, 0.66f), wood(0.62f, 0.50f, 0.36f);
  s.addInstance(boxMesh, Place({-1.6f, 0.5f, 1.0f}, glm::vec3(1.0f), 25.0f), red);
  s.addInstance(boxMesh, Place({1.5f, 2.2f, -0.9f}, {0.25f, 1.6f, 0.25f}, 10.0f), blue);
  s.addInstance(boxMesh, Place({-0.7f, 3.3f, 0.5f}, {1.4f, 0.1f, 1.0f}, -20.0f), wood);
  s.addInstance(boxMesh, Place({0.9f, 0.6f, 1.4f}, {2.6f, 0.2f, 0.3f}, 35.0f), blue);
  s.addInstance(boxMesh, Place({0.5f, 1.1f, -1.8f}, {2.0f, 0.08f, 1.2f}, 5.0f), wood);
  s.addInstance(boxMesh, Place({-3.2f, 1.25f, -1.9f}, {0.8f, 2.5f, 0.8f}, 40.0f), red);

  // The rest of a triangle budget goes to a ground outside the closed room, which neither the
  // camera nor the point light sees: the room keeps its triangles at any size.
  uint64_t used = s.triangleCount();
  AddTiledFloor(s, {0.0f, -0.5f, 0.0f}, {40.0f, 40.0f}, budget > used + 2 ? budget - used : 2, {0.5f, 0.5f, 0.5f});

  s.pointLights.push_back({kLight, {4.0f, 3.8f, 3.4f}, 12.0f});
  // The directional light is kept only so directional techniques run; the ceiling blocks it.
  s.light.direction = glm::normalize(glm::vec3(0.2f, -1.0f, 0.1f));
  s.light.color = glm::vec3(0.04f);
  s.light.ambient = 0.05f;
  s.camera.position = {-3.3f, 3.3f, -2.5f};
  s.camera.target = {1.0f, 0.8f, 1.0f};
  s.camera.fovY = glm::radians(75.0f);
  s.camera.nearZ = 0.05f;
  s.camera.farZ = 30.0f;
  FinishScene(s);
  return s;
}

}  // namespace

Scene MakeParaboloidCoarse(uint64_t budget) { return MakeParaboloidRoom(budget, false, "paraboloid-coarse"); }
Scene MakeParaboloidFine(uint64_t budget) { return MakeParaboloidRoom(budget, true, "paraboloid-fine"); }

}  // namespace sp::scene::proc
