// Scenes about local lights: "cube-seam" (shadows on cube-map face edges), "furnished-room" (a
// lamp with furniture on every side), "street" (a row of small lamps, most far or off screen) and
// "lattice" (a point light in a cage: every cube face busy).
#include <algorithm>
#include <glm/ext/matrix_transform.hpp>

#include "procedural.h"

namespace sp::scene::proc {

Scene MakeCubeSeam(uint64_t budget) {
  if (!budget) budget = 15'000;
  Scene s;
  s.name = "cube-seam";
  // A point light 2.4 m above a floor, and occluders placed on the edges between the faces of its
  // shadow cube (directions where two of |x|, |y|, |z| are equal, as seen from the light), so
  // their shadows fall across the seams: a bar lying in the -Y/+X edge plane (its shadow runs
  // along the seam, the line x = 2.4 on the floor), spheres centred on the -Y/+X and -Y/-Z edges,
  // a block on the corner where -Y, +X and +Z meet, and a bar across the -Y/+Z edge. Two walls
  // catch the +X and +Z faces' shadows.
  const glm::vec3 light(0.0f, 2.4f, 0.0f);
  int k = LevelForBudget(1, 64, budget / 4, [](int c) { return uint64_t(6) * 12 * c * c; });
  uint32_t box = s.addMesh(MakeGridBox(k, "block"));
  int seg = LevelForBudget(16, kMaxSegments, budget / 4, [](int g) { return uint64_t(2) * g * g; });
  uint32_t sphere = s.addMesh(MakeSphere(uint32_t(seg), uint32_t(seg / 2)));
  const glm::vec3 grey(0.62f, 0.60f, 0.58f), red(0.70f, 0.36f, 0.30f), blue(0.34f, 0.42f, 0.66f);

  // On the -Y/+X edge plane (x = -(y - 2.4), any z): a bar along z, and a sphere.
  s.addInstance(box, Place({1.2f, 1.2f, -0.6f}, {0.12f, 0.12f, 1.8f}), red);
  glm::vec3 a = light + glm::normalize(glm::vec3(1.0f, -1.0f, 0.9f)) * 1.5f;
  s.addInstance(sphere, Place(a, glm::vec3(0.5f)), blue);
  // On the -Y/-Z edge: a sphere.
  glm::vec3 b = light + glm::normalize(glm::vec3(-0.5f, -1.0f, -1.0f)) * 1.5f;
  s.addInstance(sphere, Place(b, glm::vec3(0.6f)), blue);
  // On the corner of -Y, +X and +Z: a block; across the -Y/+Z edge: a bar along x.
  s.addInstance(box, Place(light + glm::vec3(0.95f, -0.95f, 0.95f), glm::vec3(0.3f), 20.0f), grey);
  s.addInstance(box, Place({-0.9f, 1.3f, 1.1f}, {1.2f, 0.1f, 0.1f}), red);

  // Walls (0.2 m slabs, 3 m high) beyond the +X and +Z faces' floor edge.
  uint32_t slab = s.addMesh(MakeGridBox(k, "wall"));
  const glm::vec3 plaster(0.80f, 0.78f, 0.74f);
  s.addInstance(slab, Place({4.6f, 1.5f, 0.0f}, {0.2f, 3.0f, 9.4f}), plaster);
  s.addInstance(slab, Place({-0.1f, 1.5f, 4.6f}, {9.2f, 3.0f, 0.2f}), plaster);

  uint64_t used = s.triangleCount();
  AddTiledFloor(s, {0.0f, 0.0f, 0.0f}, {9.4f, 9.4f}, budget > used + 2 ? budget - used : 2, {0.66f, 0.64f, 0.60f});

  s.pointLights.push_back({light, {3.2f, 3.0f, 2.7f}, 10.0f});
  // The directional light is kept only so directional techniques run; dim.
  s.light.direction = glm::normalize(glm::vec3(0.1f, -1.0f, 0.05f));
  s.light.color = glm::vec3(0.04f);
  s.light.ambient = 0.06f;
  s.camera.position = {-1.8f, 5.2f, -2.6f};
  s.camera.target = {1.6f, 0.0f, 1.2f};
  s.camera.fovY = glm::radians(65.0f);
  s.camera.nearZ = 0.05f;
  s.camera.farZ = 30.0f;
  FinishScene(s);
  return s;
}

namespace {

// The night-time directional light of the local-light scenes: kept only so directional
// techniques run, too dim to matter next to the lamps.
void DimSun(Scene& s) {
  s.light.direction = glm::normalize(glm::vec3(0.1f, -1.0f, 0.05f));
  s.light.color = glm::vec3(0.04f);
  s.light.ambient = 0.06f;
}

// Legs or wheels: four parts of `size` centred at (+-at.x, at.y, +-at.z).
void AddFourParts(Mesh& m, const Mesh& box, glm::vec3 at, glm::vec3 size) {
  for (float x : {-at.x, at.x})
    for (float z : {-at.z, at.z}) AddBoxPart(m, box, {x, at.y, z}, size);
}

// A three-seat sofa 2.1 x 0.85 x 0.9 m (back towards -z) on four short legs, standing on y = 0.
Mesh MakeSofa(int cells) {
  Mesh box = MakeGridBox(cells);
  Mesh m;
  m.name = "sofa";
  AddFourParts(m, box, {0.98f, 0.05f, 0.38f}, {0.06f, 0.1f, 0.06f});
  AddBoxPart(m, box, {0.0f, 0.27f, 0.0f}, {2.1f, 0.34f, 0.9f});          // seat
  AddBoxPart(m, box, {0.0f, 0.62f, -0.36f}, {2.1f, 0.46f, 0.18f});       // back
  for (float x : {-0.97f, 0.97f}) AddBoxPart(m, box, {x, 0.55f, 0.05f}, {0.16f, 0.22f, 0.8f});  // arms
  return m;
}

// A sideboard 1.6 x 0.9 x 0.45 m on four 15 cm legs: a contact shadow under a raised body.
Mesh MakeSideboard(int cells) {
  Mesh box = MakeGridBox(cells);
  Mesh m;
  m.name = "sideboard";
  AddFourParts(m, box, {0.74f, 0.075f, 0.18f}, {0.05f, 0.15f, 0.05f});
  AddBoxPart(m, box, {0.0f, 0.525f, 0.0f}, {1.6f, 0.75f, 0.45f});
  return m;
}

// A parked car: body 1.8 x 0.7 x 4.2 m on four wheels (boxes), a cabin on top; nose towards +z.
Mesh MakeCar(int cells) {
  Mesh box = MakeGridBox(cells);
  Mesh m;
  m.name = "car";
  AddFourParts(m, box, {0.78f, 0.31f, 1.35f}, {0.22f, 0.62f, 0.62f});
  AddBoxPart(m, box, {0.0f, 0.7f, 0.0f}, {1.8f, 0.7f, 4.2f});
  AddBoxPart(m, box, {0.0f, 1.32f, -0.3f}, {1.6f, 0.55f, 2.2f});
  return m;
}

// A street lamp's post, arm and head, for a light at (0, 4.5, 0): the post stands 0.7 m to the
// side (+x), the head's underside 5 cm above the light, so the lamp shades the sky.
Mesh MakeLampPost(int cells) {
  Mesh box = MakeGridBox(cells);
  Mesh m;
  m.name = "lamp-post";
  AddBoxPart(m, box, {0.7f, 2.35f, 0.0f}, {0.14f, 4.7f, 0.14f});
  AddBoxPart(m, box, {0.35f, 4.65f, 0.0f}, {0.7f, 0.08f, 0.08f});
  AddBoxPart(m, box, {0.0f, 4.61f, 0.0f}, {0.5f, 0.12f, 0.3f});
  return m;
}

}  // namespace

Scene MakeFurnishedRoom(uint64_t budget) {
  if (!budget) budget = 20'000;
  Scene s;
  s.name = "furnished-room";
  // A closed 7 x 2.8 x 6 m room (inside) with a pendant lamp 1.5 m above the floor over a dining
  // table: chairs and the table below it (contact shadows of legs, long shadows of the chair backs
  // on the floor and walls), the lamp's shade above it, a shelf, a sideboard, a sofa and a wardrobe
  // on the four sides at heights within 45 degrees of the light's horizon, so every face of its
  // shadow cube but none by accident sees furniture.
  const glm::vec3 lo(-3.5f, 0.0f, -3.0f), hi(3.5f, 2.8f, 3.0f);
  AddRoomShell(s, lo, hi, 0.2f, {0.82f, 0.80f, 0.74f}, budget / 4);

  const int boxesInFurniture = 5 + 4 * 11 + 7 + 11 + 5 + 6 + 2;  // table, four chairs, shelf, sofa, sideboard, wardrobe, shade and cord
  int k = LevelForBudget(1, 128, budget * 35 / 100, [&](int c) { return uint64_t(boxesInFurniture) * 12 * c * c; });
  uint32_t table = s.addMesh(MakeTable(k, {1.6f, 0.9f}));
  uint32_t chair = s.addMesh(MakeChair(k));
  uint32_t box = s.addMesh(MakeGridBox(k, "box"));
  const glm::vec3 wood(0.60f, 0.44f, 0.30f), dark(0.35f, 0.30f, 0.28f), fabric(0.42f, 0.50f, 0.58f);
  const glm::vec3 light(0.1f, 1.5f, -0.05f);
  s.addInstance(table, Place({0.0f, 0.0f, 0.0f}, glm::vec3(1.0f), 4.0f), wood);
  for (int c = 0; c < 4; ++c) {
    float side = c < 2 ? -1.0f : 1.0f, along = c % 2 ? 0.42f : -0.42f;
    s.addInstance(chair, Place({along, 0.0f, side * 0.78f}, glm::vec3(1.0f), (side < 0 ? 0.0f : 180.0f) + 6.0f * c - 9.0f), dark);
  }
  // The shade: a 34 cm square 20 cm above the bulb, hung from the ceiling by a cord; its shadow
  // covers the middle of the ceiling (the +Y face within 0.85 of its centre) and leaves a lit ring.
  s.addInstance(box, Place(light + glm::vec3(0.0f, 0.2f, 0.0f), {0.34f, 0.02f, 0.34f}), {0.90f, 0.86f, 0.70f});
  s.addInstance(box, Place(light + glm::vec3(0.0f, 0.21f + 0.5f * (hi.y - light.y - 0.21f), 0.0f), {0.015f, hi.y - light.y - 0.21f, 0.015f}), dark);
  s.addInstance(s.addMesh(MakeShelf(k)), Place({lo.x + 0.22f, 0.0f, -0.6f}, glm::vec3(1.0f), 90.0f), wood);
  s.addInstance(s.addMesh(MakeSofa(k)), Place({-0.4f, 0.0f, hi.z - 0.5f}, glm::vec3(1.0f), 180.0f), fabric);
  s.addInstance(s.addMesh(MakeSideboard(k)), Place({hi.x - 0.25f, 0.0f, 0.5f}, glm::vec3(1.0f), -90.0f), wood * 0.8f);
  // A wardrobe against the -z wall, raised on a plinth gap (its body 5 cm over the floor).
  s.addInstance(box, Place({0.9f, 1.0f, lo.z + 0.32f}, {1.2f, 1.9f, 0.6f}), {0.55f, 0.52f, 0.48f});
  for (float x : {0.35f, 1.45f}) s.addInstance(box, Place({x, 0.025f, lo.z + 0.32f}, {0.06f, 0.05f, 0.5f}), dark);

  glm::vec3 size = hi - lo, mid = (hi + lo) * 0.5f;
  AddTiledFloor(s, {mid.x, 0.0f, mid.z}, {size.x + 0.4f, size.z + 0.4f}, Remainder(s, budget), {0.58f, 0.50f, 0.42f});

  s.pointLights.push_back({light, {3.0f, 2.6f, 2.0f}, 8.0f});
  DimSun(s);
  s.camera.position = {3.0f, 1.65f, 2.5f};
  s.camera.target = {-1.2f, 0.7f, -1.2f};
  s.camera.fovY = glm::radians(70.0f);
  s.camera.nearZ = 0.05f;
  s.camera.farZ = 20.0f;
  // "walk": from the corner along the sofa to the shelf side, the lamp always in view.
  std::vector<CameraKey> keys = {{0.0f, s.camera.position, s.camera.target},
                                 {0.5f, {0.6f, 1.6f, 2.4f}, {-0.4f, 0.8f, -1.5f}},
                                 {1.0f, {-2.2f, 1.6f, 2.3f}, {-0.5f, 0.8f, -1.5f}}};
  FinishScene(s, {MakePath("walk", s.camera, std::move(keys))});
  return s;
}

Scene MakeStreet(uint64_t budget) {
  if (!budget) budget = 30'000;
  Scene s;
  s.name = "street";
  // A 200 m street at night: 16 lamps 4.5 m high, 12 m apart, alternating sides, each reaching
  // 9 m; terraces of buildings on both sides, cars parked along the kerbs, bollards. The camera
  // looks down the street with a 60 m far plane, so at any time most lamps are behind it or
  // beyond its far plane: what per-light culling of shadow work is for.
  const int lamps = 16;
  const float length = 200.0f, spacing = 12.0f;
  Rng rng(0x57ee7ull);
  int k = LevelForBudget(1, 64, budget / 4, [](int c) { return uint64_t(40) * 12 * c * c; });
  uint32_t block = s.addMesh(MakeGridBox(k, "building"));
  for (float side : {-1.0f, 1.0f}) {
    float z = -10.0f;
    while (z < length + 10.0f) {
      float w = rng.uniform(10.0f, 18.0f), h = rng.uniform(8.0f, 20.0f), d = rng.uniform(8.0f, 12.0f);
      float gap = rng.uniform() < 0.3f ? 4.0f : 0.0f;  // side streets let the lamps light further
      s.addInstance(block, Place({side * (7.0f + d * 0.5f), h * 0.5f, z + w * 0.5f}, {d, h, w}),
                    glm::vec3(rng.uniform(0.45f, 0.7f), rng.uniform(0.42f, 0.6f), rng.uniform(0.4f, 0.55f)));
      z += w + gap;
    }
  }
  int kc = LevelForBudget(1, 64, budget / 4, [&](int c) { return uint64_t(24 * 6 + lamps * 3) * 12 * c * c; });
  uint32_t car = s.addMesh(MakeCar(kc));
  for (float side : {-1.0f, 1.0f})
    for (float z = 4.0f; z < length - 4.0f; z += rng.uniform(6.0f, 12.0f))
      if (rng.uniform() < 0.75f)
        s.addInstance(car, Place({side * 3.1f, 0.0f, z}, glm::vec3(1.0f), side > 0 ? 0.0f : 180.0f),
                      glm::vec3(rng.uniform(0.2f, 0.8f), rng.uniform(0.2f, 0.6f), rng.uniform(0.2f, 0.6f)));
  uint32_t post = s.addMesh(MakeLampPost(kc));
  int seg = LevelForBudget(12, kMaxSegments, budget / 10, [](int g) { return uint64_t(4 * 40 * g); });
  uint32_t bollard = s.addMesh(MakeCylinder(uint32_t(seg)));
  for (int i = 0; i < lamps; ++i) {
    float side = i % 2 ? 1.0f : -1.0f;
    glm::vec3 at(side * 5.2f, 4.5f, 6.0f + spacing * float(i));
    // The post model stands at +x of its light; on the -x side it is turned round.
    s.addInstance(post, Place({at.x, 0.0f, at.z}, glm::vec3(1.0f), side > 0 ? 0.0f : 180.0f), {0.25f, 0.27f, 0.3f});
    s.pointLights.push_back({at, {5.0f, 4.2f, 3.0f}, 9.0f});
  }
  for (float side : {-1.0f, 1.0f})
    for (float z = 9.0f; z < length; z += 9.5f) s.addInstance(bollard, Place({side * 4.6f, 0.0f, z}, {0.2f, 0.9f, 0.2f}), {0.3f, 0.3f, 0.32f});

  AddTiledFloor(s, {0.0f, 0.0f, length * 0.5f}, {40.0f, length + 40.0f}, Remainder(s, budget), {0.32f, 0.32f, 0.34f});

  DimSun(s);
  s.camera.position = {0.8f, 1.7f, -6.0f};
  s.camera.target = {0.0f, 1.5f, 30.0f};
  s.camera.fovY = glm::radians(60.0f);
  s.camera.nearZ = 0.1f;
  s.camera.farZ = 60.0f;
  // "walk": 150 m down the middle of the street at walking height.
  std::vector<CameraKey> keys = {{0.0f, s.camera.position, s.camera.target}, {1.0f, {0.0f, 1.7f, 144.0f}, {-0.8f, 1.5f, 180.0f}}};
  FinishScene(s, {MakePath("walk", s.camera, std::move(keys))});
  return s;
}

Scene MakeLattice(uint64_t budget) {
  if (!budget) budget = 15'000;
  Scene s;
  s.name = "lattice";
  // A point light at the centre of a 1 m cubic cage of 2.5 cm bars 20 cm apart, on a stand in a
  // closed 8 x 4 x 8 m room: every face of the light's shadow cube sees bars, so every face's
  // shadow is a grid on the floor, the ceiling or a wall, magnified about 6 times, and the bars on
  // the cage's edges lie in the cube's face-edge planes.
  const glm::vec3 lo(-4.0f, 0.0f, -4.0f), hi(4.0f, 4.0f, 4.0f);
  AddRoomShell(s, lo, hi, 0.2f, {0.82f, 0.80f, 0.76f}, budget / 4);

  const glm::vec3 light(0.0f, 1.6f, 0.0f);
  const float half = 0.5f, bar = 0.025f;
  const int steps = 5;  // grid lines per side: 6 at -0.5, -0.3, ..., 0.5
  int k = LevelForBudget(1, 64, budget / 3, [](int c) { return uint64_t(60) * 12 * c * c; });
  uint32_t rod = s.addMesh(MakeGridBox(k, "bar"));
  const glm::vec3 metal(0.45f, 0.45f, 0.48f);
  // Rods along each axis a at the grid points (u, v) on the boundary of the cage's cross-section.
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i <= steps; ++i)
      for (int j = 0; j <= steps; ++j) {
        if (i != 0 && i != steps && j != 0 && j != steps) continue;
        glm::vec3 c = light, sz(bar);
        c[(a + 1) % 3] += -half + 2.0f * half * float(i) / float(steps);
        c[(a + 2) % 3] += -half + 2.0f * half * float(j) / float(steps);
        sz[a] = 2.0f * half + bar;
        s.addInstance(rod, Place(c, sz), metal);
      }
  int seg = LevelForBudget(12, kMaxSegments, budget / 20, [](int g) { return uint64_t(4 * g); });
  s.addInstance(s.addMesh(MakeCylinder(uint32_t(seg))), Place({0.0f, 0.0f, 0.0f}, {0.06f, light.y - half - bar * 0.5f, 0.06f}), metal);

  glm::vec3 size = hi - lo, mid = (hi + lo) * 0.5f;
  AddTiledFloor(s, {mid.x, 0.0f, mid.z}, {size.x + 0.4f, size.z + 0.4f}, Remainder(s, budget), {0.62f, 0.60f, 0.56f});

  s.pointLights.push_back({light, {4.0f, 3.8f, 3.4f}, 10.0f});
  DimSun(s);
  s.camera.position = {3.3f, 2.4f, 3.4f};
  s.camera.target = {-1.0f, 1.2f, -1.6f};
  s.camera.fovY = glm::radians(75.0f);
  s.camera.nearZ = 0.05f;
  s.camera.farZ = 20.0f;
  // "look-around": a 60 degree turn to the left from the corner, across two walls' grids.
  FinishScene(s, {YawPath("look-around", s.camera, 0.0f, 60.0f)});
  return s;
}

}  // namespace sp::scene::proc
