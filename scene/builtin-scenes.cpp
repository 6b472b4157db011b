// Built-in procedural scenes: the registry, triangle-budget fitting and the "default" scene. The
// scenes built to show where techniques fail are in procedural/.
#include <algorithm>
#include <cmath>
#include <glm/ext/matrix_transform.hpp>
#include <stdexcept>

#include "procedural/procedural.h"
#include <sp/scene/scene.h>

namespace sp::scene {
namespace proc {

// Ground, columns and boxes: long shadows from the columns, contact shadows under the boxes and
// the thin slab, self-shadowing on the stacked boxes and the sphere. At its natural size this is
// the scene the technique tests were written against, unchanged; a triangle budget tessellates
// the round casters more finely and splits the ground into tiles of the same flat shape.
Scene MakeDefaultScene(uint64_t budget) {
  Scene s;
  s.name = "default";
  uint32_t columnSegments = 24, sphereSegments = 24, sphereRings = 16;
  if (budget) {
    // Up to half the budget to the casters; 256 segments at most (these meshes are not shared, the
    // tiled ground is), the ground takes the rest.
    uint64_t casters = budget / 2;
    auto casterTris = [](int seg) { return uint64_t(4 * 4 * seg + seg * (2 * (seg * 2 / 3) - 2) + 6 * 12); };
    columnSegments = sphereSegments = uint32_t(LevelForBudget(24, kMaxSegments, casters, casterTris));
    sphereRings = sphereSegments * 2 / 3;
  }
  uint32_t plane = budget ? 0 : s.addMesh(MakePlane(8));
  uint32_t box = s.addMesh(MakeBox());
  uint32_t column = s.addMesh(MakeCylinder(columnSegments));
  uint32_t sphere = s.addMesh(MakeSphere(sphereSegments, sphereRings));
  const glm::vec3 groundColor(0.72f, 0.70f, 0.66f);
  if (!budget) s.addInstance(plane, Place({0, 0, 0}, {40, 1, 40}), groundColor);

  const glm::vec3 stone(0.78f, 0.74f, 0.68f);
  for (int i = 0; i < 4; ++i) s.addInstance(column, Place({-6.0f + 4.0f * i, 0, -4.0f}, {0.9f, 6.0f + i, 0.9f}), stone);
  s.addInstance(box, Place({-3.0f, 0.75f, 1.5f}, {1.5f, 1.5f, 1.5f}, 20.0f), {0.80f, 0.35f, 0.25f});
  s.addInstance(box, Place({-3.0f, 2.0f, 1.5f}, {1.0f, 1.0f, 1.0f}, 50.0f), {0.85f, 0.60f, 0.25f});
  s.addInstance(box, Place({2.5f, 1.0f, 2.0f}, {3.0f, 2.0f, 1.0f}, -15.0f), {0.30f, 0.45f, 0.75f});
  s.addInstance(box, Place({0.0f, 0.05f, 4.5f}, {4.0f, 0.1f, 0.6f}, 5.0f), {0.35f, 0.65f, 0.40f});  // thin slab
  s.addInstance(sphere, Place({5.5f, 1.2f, -0.5f}, {2.4f, 2.4f, 2.4f}), {0.70f, 0.70f, 0.75f});
  s.addInstance(box, Place({6.0f, 3.0f, -5.0f}, {1.0f, 6.0f, 1.0f}), stone);
  if (budget) {
    uint64_t used = s.triangleCount();
    AddTiledFloor(s, {0, 0, 0}, {40, 40}, budget > used + 2 ? budget - used : 2, groundColor);
  }

  s.camera.position = {-4.0f, 7.0f, 14.0f};
  s.camera.target = {1.0f, 1.0f, 0.0f};
  s.camera.nearZ = 0.5f;
  s.camera.farZ = 100.0f;
  s.light.direction = glm::normalize(glm::vec3(-0.55f, -0.65f, -0.5f));
  FinishScene(s);
  return s;
}

}  // namespace proc

namespace {

struct Entry {
  const char* name;
  Scene (*make)(uint64_t budget);
};

const Entry kScenes[] = {
    {"default", proc::MakeDefaultScene},
    {"terrain-city", proc::MakeTerrainCity},
    {"canyon-city", proc::MakeCanyonCity},
    {"dueling-frusta", proc::MakeDuelingFrusta},
    {"grazing-light", proc::MakeGrazingLight},
    {"contact", proc::MakeContact},
    {"overlapping-occluders", proc::MakeOverlappingOccluders},
    {"distant-occluder", proc::MakeDistantOccluder},
    {"point-light-room", proc::MakePointLightRoom},
    {"cube-seam", proc::MakeCubeSeam},
    {"paraboloid-coarse", proc::MakeParaboloidCoarse},
    {"paraboloid-fine", proc::MakeParaboloidFine},
    {"furnished-room", proc::MakeFurnishedRoom},
    {"street", proc::MakeStreet},
    {"lattice", proc::MakeLattice},
    {"stacked-planks", proc::MakeStackedPlanks},
    {"single-plank", proc::MakeSinglePlank},
};

}  // namespace

std::vector<std::string> BuiltinSceneNames() {
  std::vector<std::string> names;
  for (const Entry& e : kScenes) names.push_back(e.name);
  return names;
}

Scene MakeBuiltinScene(const std::string& name) { return MakeBuiltinScene(name, SceneOptions{}); }

Scene MakeBuiltinScene(const std::string& name, const SceneOptions& options) {
  const Entry* entry = nullptr;
  for (const Entry& e : kScenes)
    if (name == e.name) entry = &e;
  if (!entry) {
    std::string list;
    for (const Entry& e : kScenes) list += (list.empty() ? "" : ", ") + std::string(e.name);
    throw std::invalid_argument("unknown scene '" + name + "' (built-in scenes: " + list + ")");
  }
  const uint64_t target = options.targetTriangles;
  if (target > kMaxTargetTriangles)
    throw std::invalid_argument("scene '" + name + "': targetTriangles " + std::to_string(target) + " is above the limit of " +
                                std::to_string(kMaxTargetTriangles));
  if (target == 0) return entry->make(0);
  // The builders spend their budget closely, but tessellation levels are integers; a rebuild with
  // the budget corrected by the miss absorbs the rounding (each build takes milliseconds).
  uint64_t budget = target;
  Scene s = entry->make(budget);
  for (int i = 0; i < 3; ++i) {
    double ratio = double(target) / double(std::max<size_t>(s.triangleCount(), 1));
    if (std::abs(ratio - 1.0) < 0.05) break;
    budget = std::max<uint64_t>(1, uint64_t(std::llround(double(budget) * ratio)));
    Scene next = entry->make(budget);
    if (std::abs(double(next.triangleCount()) / double(target) - 1.0) >= std::abs(double(s.triangleCount()) / double(target) - 1.0)) break;
    s = std::move(next);
  }
  return s;
}

}  // namespace sp::scene
