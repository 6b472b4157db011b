// Shared pieces of the procedural scenes: a portable random generator, placement, meshes with
// shared vertices, budget-driven receivers and scene finishing. Internal to sp_scene.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <sp/scene/scene.h>

namespace sp::scene::proc {

// splitmix64: the same sequence on every compiler and standard library (the <random>
// distributions are not specified bit for bit, so they would make scenes differ across builds).
class Rng {
 public:
  explicit Rng(uint64_t seed) : state_(seed) {}
  uint64_t next();
  float uniform();  // [0, 1)
  float uniform(float lo, float hi) { return lo + (hi - lo) * uniform(); }
  int range(int lo, int hi);  // [lo, hi]

 private:
  uint64_t state_;
};

// Translate * yaw about +y * scale. The lit pass transforms normals by the world matrix itself,
// so non-uniform scales are only used where they keep normals right: on meshes whose normals are
// axis-aligned (boxes, planes) or with equal x and z scale (cylinders).
glm::mat4 Place(const glm::vec3& pos, const glm::vec3& scale, float yawDegrees = 0.0f);

// [-0.5, 0.5]^3 with each face split into a grid (cells along x, y, z); vertices shared within a
// face, flat normals, closed (adjacent faces split their common edge identically).
Mesh MakeGridBox(glm::ivec3 cells, const std::string& name = "grid-box");
inline Mesh MakeGridBox(int cells, const std::string& name = "grid-box") { return MakeGridBox(glm::ivec3(cells), name); }
// xz in [-0.5, 0.5], y = 0, facing +y, cellsX x cellsZ quads over shared vertices.
Mesh MakeGridPlane(int cellsX, int cellsZ);

// Appends `src` transformed by `m` (normals by the inverse transpose; winding kept for
// orientation-preserving `m`, which is all the builders use).
void AppendMesh(Mesh& dst, const Mesh& src, const glm::mat4& m);

// A chair-like frame standing on y = 0 with its seat centred over the origin: thin legs, a thin
// seat and a back; one closed mesh per tessellation level (boxes split into `cells` per edge).
Mesh MakeChair(int cells);
// A table with a thin top at 0.75 m and four legs, standing on y = 0.
Mesh MakeTable(int cells, glm::vec2 top);
// A 2 x 2.2 x 0.4 m open shelf (two sides, five boards) standing on y = 0, centred on x and z.
Mesh MakeShelf(int cells);
// Appends `box` (MakeGridBox) scaled to `size` and centred at `center`: furniture from boxes.
void AddBoxPart(Mesh& dst, const Mesh& box, glm::vec3 center, glm::vec3 size);

// A closed room's four walls and ceiling (slabs `t` thick outside the inside box lo..hi; the walls
// overlap at the corners so no light leaks there): five instances of one "wall" grid box split
// finely enough to spend about `triangles`. The floor is the scene's, under the walls.
void AddRoomShell(Scene& s, const glm::vec3& lo, const glm::vec3& hi, float t, const glm::vec3& albedo, uint64_t triangles);

// A flat receiver at y = center.y facing +y covering size.x by size.y (x, z), as tiles x tiles
// instances of one subdivided grid, with about `triangles` triangles (at least 2 per tile):
// the filler that lets a scene meet a triangle budget without changing its shape.
// Returns the triangles added.
uint64_t AddTiledFloor(Scene& s, const glm::vec3& center, const glm::vec2& size, uint64_t triangles, const glm::vec3& albedo,
                       int maxTilesPerSide = 8);

// A heightfield over [x0, x0 + tilesX * tileSize] x [z0, z0 + tilesZ * tileSize], one mesh per
// tile (so per-instance culling works), `cells` quads per tile side, world-space vertices with
// normals from the height function's gradient. Vertices on tile edges are computed from global
// grid indices, so neighbouring tiles meet without cracks. Returns the triangles added.
uint64_t AddTerrain(Scene& s, float x0, float z0, float tileSize, int tilesX, int tilesZ, int cells,
                    const std::function<float(float, float)>& height, const glm::vec3& albedo);

// Round meshes stop refining here (a 256-segment sphere has 65k triangles); budgets beyond go to
// instanced parts.
constexpr int kMaxSegments = 256;

// The largest n >= lo (<= hi) with triangles(n) <= budget, else lo: picks a tessellation level.
int LevelForBudget(int lo, int hi, uint64_t budget, const std::function<uint64_t(int)>& triangles);

// Instance triangles per mesh, for spending budgets.
inline uint64_t Tris(const Scene& s, uint32_t mesh) { return s.meshes[mesh].triangleCount(); }

// What is left of `budget` after the triangles placed so far (at least 2): the floor's share.
uint64_t Remainder(const Scene& s, uint64_t budget);

// A path through explicit keys with the scene camera's lens.
CameraPath MakePath(const std::string& name, const Camera& lens, std::vector<CameraKey> keys);
// A yaw about the camera position from `fromDegrees` to `toDegrees` (positive turns left), keys
// every 1.25 degrees so the spline stays on the circle.
CameraPath YawPath(const std::string& name, const Camera& camera, float fromDegrees, float toDegrees);

// finalize() plus the standard camera paths followed by the scene's own.
void FinishScene(Scene& s, std::vector<CameraPath> extraPaths = {});

// The builders: `budget` is the instanced-triangle count to aim at, 0 for the natural size.
Scene MakeDefaultScene(uint64_t budget);
Scene MakeTerrainCity(uint64_t budget);
Scene MakeCanyonCity(uint64_t budget);
Scene MakeDuelingFrusta(uint64_t budget);
Scene MakeGrazingLight(uint64_t budget);
Scene MakeContact(uint64_t budget);
Scene MakeOverlappingOccluders(uint64_t budget);
Scene MakeStackedPlanks(uint64_t budget);
Scene MakeSinglePlank(uint64_t budget);
Scene MakeDistantOccluder(uint64_t budget);
Scene MakePointLightRoom(uint64_t budget);
Scene MakeCubeSeam(uint64_t budget);
Scene MakeParaboloidCoarse(uint64_t budget);
Scene MakeParaboloidFine(uint64_t budget);
Scene MakeFurnishedRoom(uint64_t budget);
Scene MakeStreet(uint64_t budget);
Scene MakeLattice(uint64_t budget);

}  // namespace sp::scene::proc
