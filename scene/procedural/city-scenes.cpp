// The two cities: "terrain-city" (a long view over rolling ground to the horizon, the case cascaded
// shadow maps exist for) and "canyon-city" (narrow streets between tall buildings, where most of
// what the camera sees is occluded in light space).
#include <algorithm>
#include <cmath>

#include "procedural.h"

namespace sp::scene::proc {

namespace {

// Gentle rolling ground that rises slowly with distance, so the far blocks stay in view over the
// crests instead of hiding behind them. Slopes stay under about 8%.
float CityHeight(float x, float z) {
  float rise = 0.012f * std::max(0.0f, -z - 150.0f);
  return 4.0f * std::sin(x / 170.0f + 0.3f) * std::cos(z / 230.0f) + 3.0f * std::sin((x + z) / 410.0f) +
         1.5f * std::sin(z / 97.0f - x / 140.0f) + rise;
}

glm::vec3 Facade(Rng& rng) {
  const glm::vec3 tones[] = {{0.72f, 0.70f, 0.66f}, {0.66f, 0.52f, 0.42f}, {0.58f, 0.60f, 0.64f}, {0.80f, 0.77f, 0.70f}, {0.50f, 0.47f, 0.45f}};
  glm::vec3 c = tones[rng.range(0, 4)];
  return c * rng.uniform(0.88f, 1.08f);
}

struct Lot {
  glm::vec2 center;
  glm::vec2 size;
  float base, top;      // the footprint sunk into the terrain, the roof
  float tierScale = 0;  // > 0: a set-back upper block
  float tierHeight = 0;
  glm::vec3 color;
  float key;  // lots are built in increasing key order until the budget is spent
};

}  // namespace

Scene MakeTerrainCity(uint64_t budget) {
  if (!budget) budget = 80'000;
  Scene s;
  s.name = "terrain-city";
  Rng rng(0x7e22a1c17ull);

  const glm::vec2 eye(0.0f, 90.0f);
  const float eyeHeight = 6.0f;
  // Blocks of 3x3 lots either side of a 40 m avenue along -z, 64 m apart, from behind the camera
  // to about 1.9 km ahead.
  std::vector<Lot> lots;
  const float lotPitch = 52.0f / 3.0f;
  for (int row = -2; row < 30; ++row)
    for (int side : {-1, 1})
      for (int col = 0; col < 6; ++col) {
        glm::vec2 block(float(side) * (52.0f + 64.0f * col), 14.0f - 64.0f * row);
        for (int j = -1; j <= 1; ++j)
          for (int i = -1; i <= 1; ++i) {
            Lot l;
            l.size = {rng.uniform(10.0f, 15.0f), rng.uniform(10.0f, 15.0f)};
            glm::vec2 slack = (glm::vec2(lotPitch) - l.size) * 0.5f;
            l.center = block + glm::vec2(i, j) * lotPitch + glm::vec2(rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f)) * slack;
            float u = rng.uniform();
            float height = rng.uniform() < 0.04f ? 70.0f + 70.0f * u : 8.0f + 42.0f * u * u * u;
            float lowest = 1e9f, highest = -1e9f;
            for (int c = 0; c < 5; ++c) {
              glm::vec2 p = l.center + (c == 4 ? glm::vec2(0.0f) : glm::vec2(c & 1 ? 0.5f : -0.5f, c & 2 ? 0.5f : -0.5f) * l.size);
              lowest = std::min(lowest, CityHeight(p.x, p.y));
              highest = std::max(highest, CityHeight(p.x, p.y));
            }
            // Sunk below the lowest corner: the triangulated ground deviates from the height
            // function by up to a few decimetres at coarse tessellations.
            l.base = lowest - 1.5f;
            l.top = highest + height;
            if (height > 25.0f && rng.uniform() < 0.6f) {
              l.tierScale = rng.uniform(0.55f, 0.8f);
              l.tierHeight = height * rng.uniform(0.15f, 0.4f);
            }
            l.color = Facade(rng);
            // Near lots first, so small budgets keep the foreground dense and thin out the distance.
            l.key = rng.uniform() * (1.0f + glm::distance(l.center, eye) / 500.0f);
            lots.push_back(l);
          }
      }
  std::stable_sort(lots.begin(), lots.end(), [](const Lot& a, const Lot& b) { return a.key < b.key; });

  const uint64_t buildingBudget = budget * 7 / 10;
  size_t blocksAvailable = 0;
  for (const Lot& l : lots) blocksAvailable += l.tierScale > 0 ? 2 : 1;
  // The coarsest tessellation at which every lot together reaches the budget; then lots in key order.
  int cells = 1;
  while (blocksAvailable * 12ull * cells * cells < buildingBudget && cells < 256) ++cells;
  uint32_t box = s.addMesh(MakeGridBox(cells, "building"));
  uint64_t used = 0;
  for (const Lot& l : lots) {
    if (used >= buildingBudget) break;
    s.addInstance(box, Place({l.center.x, (l.base + l.top) * 0.5f, l.center.y}, {l.size.x, l.top - l.base, l.size.y}), l.color);
    used += Tris(s, box);
    if (l.tierScale > 0) {
      glm::vec2 ts = l.size * l.tierScale;
      s.addInstance(box, Place({l.center.x, l.top + l.tierHeight * 0.5f, l.center.y}, {ts.x, l.tierHeight, ts.y}), l.color * 0.95f);
      used += Tris(s, box);
    }
  }

  // Terrain from x = -400 to 400 and z = -1900 to 200 in 100 m tiles, with what is left.
  const int tilesX = 8, tilesZ = 21;
  uint64_t rest = budget > used ? budget - used : 0;
  int terrainCells = std::max(2, int(std::lround(std::sqrt(double(rest) / (2.0 * tilesX * tilesZ)))));
  AddTerrain(s, -400.0f, -1900.0f, 100.0f, tilesX, tilesZ, terrainCells, CityHeight, {0.50f, 0.52f, 0.44f});

  glm::vec3 cam(eye.x, CityHeight(eye.x, eye.y) + eyeHeight, eye.y);
  glm::vec3 look(0.0f, -14.0f, -400.0f);  // 2 degrees down the avenue
  s.camera.position = cam;
  s.camera.target = cam + look;
  s.camera.fovY = glm::radians(55.0f);
  s.camera.nearZ = 0.5f;
  s.camera.farZ = 2000.0f;
  // Late-afternoon sun from behind the camera's left: long shadows across the avenue.
  s.light.direction = glm::normalize(glm::vec3(0.62f, -0.42f, -0.38f));

  // "drive": 200 m down the avenue at a constant height above the ground, the motion cascades
  // must follow without their splits swimming.
  std::vector<CameraKey> keys;
  for (int i = 0; i <= 8; ++i) {
    float z = eye.y - 25.0f * i;
    glm::vec3 p(eye.x, CityHeight(eye.x, z) + eyeHeight, z);
    keys.push_back({float(i) / 8.0f, p, p + look});
  }
  FinishScene(s, {MakePath("drive", s.camera, std::move(keys))});
  return s;
}

Scene MakeCanyonCity(uint64_t budget) {
  if (!budget) budget = 40'000;
  Scene s;
  s.name = "canyon-city";
  Rng rng(0xca2701c1ull);

  // 7x7 blocks of 36 m separated by 10 m streets; each block holds four 17.5 m towers 36-110 m
  // tall, so every street is at least 3.6 times deeper than it is wide.
  const float pitch = 46.0f, tower = 17.5f, street = 10.0f;
  struct Tower {
    glm::vec2 center;
    glm::vec2 streetSide;  // the two faces towards streets
    float height;
    glm::vec3 color;
  };
  std::vector<Tower> towers;
  for (int bz = -3; bz <= 3; ++bz)
    for (int bx = -3; bx <= 3; ++bx)
      for (int j : {-1, 1})
        for (int i : {-1, 1}) {
          Tower t;
          t.center = glm::vec2(bx * pitch, bz * pitch) + glm::vec2(i, j) * (tower * 0.5f + 0.5f);
          t.streetSide = glm::vec2(i, j);
          float u = rng.uniform();
          t.height = 36.0f + 74.0f * u * u;
          // Along the camera's street (x = 18..28) the sun-side towers are the low ones and the
          // far side the tall ones, so the sun reaches the upper half of the far wall, striped by
          // the ledges' shadows, while the street and lower walls stay in shadow.
          if (t.center.y > -2 * pitch) {
            if (bx == 0 && i == 1) t.height = 36.0f + 19.0f * u;
            if (bx == 1 && i == -1) t.height = 60.0f + 50.0f * u;
          }
          t.color = Facade(rng);
          towers.push_back(t);
        }

  // Ledges every 8 m on the street faces: thin casters high up that stripe the walls below.
  struct Ledge {
    glm::vec3 center, size;
    glm::vec3 color;
    float key;
  };
  std::vector<Ledge> ledges;
  for (const Tower& t : towers)
    for (int axis = 0; axis < 2; ++axis)
      for (float y = 8.0f; y < t.height - 4.0f; y += 8.0f) {
        Ledge l;
        float out = tower * 0.5f + 0.3f;
        l.center = axis == 0 ? glm::vec3(t.center.x + t.streetSide.x * out, y, t.center.y) : glm::vec3(t.center.x, y, t.center.y + t.streetSide.y * out);
        l.size = axis == 0 ? glm::vec3(0.6f, 0.3f, tower - 1.0f) : glm::vec3(tower - 1.0f, 0.3f, 0.6f);
        l.color = t.color * 0.85f;
        l.key = rng.uniform();
        ledges.push_back(l);
      }
  std::stable_sort(ledges.begin(), ledges.end(), [](const Ledge& a, const Ledge& b) { return a.key < b.key; });

  int cells = LevelForBudget(1, 256, budget * 4 / 10, [&](int k) { return uint64_t(towers.size()) * 12 * k * k; });
  uint32_t towerMesh = s.addMesh(MakeGridBox(cells, "tower"));
  for (const Tower& t : towers) s.addInstance(towerMesh, Place({t.center.x, t.height * 0.5f, t.center.y}, {tower, t.height, tower}), t.color);

  const uint64_t ledgeBudget = budget * 3 / 10;
  int ledgeCells = 1;
  while (ledges.size() * 12ull * ledgeCells * ledgeCells < ledgeBudget && ledgeCells < 64) ++ledgeCells;
  uint32_t ledgeMesh = s.addMesh(MakeGridBox(ledgeCells, "ledge"));
  uint64_t ledgeTris = 0;
  for (const Ledge& l : ledges) {
    if (ledgeTris >= ledgeBudget) break;
    s.addInstance(ledgeMesh, Place(l.center, l.size), l.color);
    ledgeTris += Tris(s, ledgeMesh);
  }

  uint64_t used = s.triangleCount();
  const float extent = 7 * pitch + 2 * street;
  AddTiledFloor(s, {0, 0, 0}, {extent, extent}, budget > used + 2 ? budget - used : 2, {0.45f, 0.45f, 0.47f});

  // At eye height in the middle of the north-south street between block columns 0 and 1,
  // looking along it and 15 degrees up at the canyon walls.
  glm::vec3 cam(pitch * 0.5f, 1.7f, 2 * pitch + 8.0f);
  s.camera.position = cam;
  s.camera.target = cam + glm::vec3(0.0f, 25.5f, -95.0f);
  s.camera.nearZ = 0.2f;
  s.camera.farZ = 600.0f;
  // The sun 68 degrees up, across the street from the left and slightly behind.
  s.light.direction = glm::normalize(glm::vec3(0.36f, -0.927f, -0.108f));

  // "walk": 40 m along the street at eye height, through a crossing (shadow, sun, shadow).
  glm::vec3 look = s.camera.target - cam;
  glm::vec3 end = cam + glm::vec3(0.0f, 0.0f, -40.0f);
  FinishScene(s, {MakePath("walk", s.camera, {{0.0f, cam, cam + look}, {1.0f, end, end + look}})});
  return s;
}

}  // namespace sp::scene::proc
