#include <algorithm>
#include <cmath>
#include <glm/ext/matrix_transform.hpp>

#include "procedural.h"

namespace sp::scene::proc {

uint64_t Rng::next() {
  uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

float Rng::uniform() { return float(next() >> 40) * (1.0f / 16777216.0f); }

int Rng::range(int lo, int hi) { return lo + int(next() % uint64_t(hi - lo + 1)); }

glm::mat4 Place(const glm::vec3& pos, const glm::vec3& scale, float yawDegrees) {
  glm::mat4 m = glm::translate(glm::mat4(1.0f), pos);
  m = glm::rotate(m, glm::radians(yawDegrees), glm::vec3(0, 1, 0));
  return glm::scale(m, scale);
}

Mesh MakeGridBox(glm::ivec3 cells, const std::string& name) {
  Mesh m;
  m.name = name;
  cells = glm::max(cells, glm::ivec3(1));
  for (int a = 0; a < 3; ++a) {
    int u = (a + 1) % 3, v = (a + 2) % 3;  // cross(e_u, e_v) = e_a
    int nu = cells[u], nv = cells[v];
    for (float s : {-1.0f, 1.0f}) {
      glm::vec3 n(0.0f);
      n[a] = s;
      uint32_t base = uint32_t(m.vertices.size());
      for (int j = 0; j <= nv; ++j)
        for (int i = 0; i <= nu; ++i) {
          glm::vec3 p;
          p[a] = 0.5f * s;
          // The same expression on every face, so shared edges have identical vertices.
          p[u] = float(i) / float(nu) - 0.5f;
          p[v] = float(j) / float(nv) - 0.5f;
          m.vertices.push_back({p, n});
        }
      auto at = [&](int i, int j) { return base + uint32_t(j * (nu + 1) + i); };
      for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
          uint32_t q[4] = {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)};
          // Counter-clockwise around +e_a; the face on the negative side runs the other way.
          if (s > 0)
            m.indices.insert(m.indices.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
          else
            m.indices.insert(m.indices.end(), {q[0], q[2], q[1], q[0], q[3], q[2]});
        }
    }
  }
  m.computeBounds();
  return m;
}

Mesh MakeGridPlane(int cellsX, int cellsZ) {
  Mesh m;
  m.name = "grid-plane";
  cellsX = std::max(cellsX, 1);
  cellsZ = std::max(cellsZ, 1);
  for (int j = 0; j <= cellsZ; ++j)
    for (int i = 0; i <= cellsX; ++i)
      m.vertices.push_back({{float(i) / float(cellsX) - 0.5f, 0.0f, float(j) / float(cellsZ) - 0.5f}, {0, 1, 0}});
  auto at = [&](int i, int j) { return uint32_t(j * (cellsX + 1) + i); };
  for (int j = 0; j < cellsZ; ++j)
    for (int i = 0; i < cellsX; ++i)
      // (x0,z0) -> (x0,z1) -> (x1,z1) turns counter-clockwise seen from +y.
      m.indices.insert(m.indices.end(), {at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i + 1, j)});
  m.computeBounds();
  return m;
}

void AppendMesh(Mesh& dst, const Mesh& src, const glm::mat4& m) {
  uint32_t base = uint32_t(dst.vertices.size());
  glm::mat3 nm = glm::transpose(glm::inverse(glm::mat3(m)));
  for (const Vertex& v : src.vertices) dst.vertices.push_back({glm::vec3(m * glm::vec4(v.position, 1.0f)), glm::normalize(nm * v.normal)});
  bool flip = glm::determinant(glm::mat3(m)) < 0.0f;
  for (size_t i = 0; i < src.indices.size(); i += 3) {
    dst.indices.push_back(base + src.indices[i]);
    dst.indices.push_back(base + src.indices[i + (flip ? 2 : 1)]);
    dst.indices.push_back(base + src.indices[i + (flip ? 1 : 2)]);
  }
}

void AddBoxPart(Mesh& dst, const Mesh& box, glm::vec3 center, glm::vec3 size) {
  AppendMesh(dst, box, glm::scale(glm::translate(glm::mat4(1.0f), center), size));
}

void AddRoomShell(Scene& s, const glm::vec3& lo, const glm::vec3& hi, float t, const glm::vec3& albedo, uint64_t triangles) {
  int n = LevelForBudget(1, 512, triangles, [](int c) { return uint64_t(5) * 12 * c * c; });
  uint32_t slab = s.addMesh(MakeGridBox(n, "wall"));
  glm::vec3 size = hi - lo, mid = (hi + lo) * 0.5f;
  s.addInstance(slab, Place({lo.x - t * 0.5f, mid.y, mid.z}, {t, size.y, size.z + 2 * t}), albedo);
  s.addInstance(slab, Place({hi.x + t * 0.5f, mid.y, mid.z}, {t, size.y, size.z + 2 * t}), albedo);
  s.addInstance(slab, Place({mid.x, mid.y, lo.z - t * 0.5f}, {size.x, size.y, t}), albedo);
  s.addInstance(slab, Place({mid.x, mid.y, hi.z + t * 0.5f}, {size.x, size.y, t}), albedo);
  s.addInstance(slab, Place({mid.x, hi.y + t * 0.5f, mid.z}, {size.x + 2 * t, t, size.z + 2 * t}), albedo * 0.95f);
}

uint64_t Remainder(const Scene& s, uint64_t budget) {
  uint64_t used = s.triangleCount();
  return budget > used + 2 ? budget - used : 2;
}

Mesh MakeShelf(int cells) {
  Mesh part = MakeGridBox(cells);
  Mesh m;
  m.name = "shelf";
  AddBoxPart(m, part, {-0.98f, 1.1f, 0.0f}, {0.04f, 2.2f, 0.4f});
  AddBoxPart(m, part, {0.98f, 1.1f, 0.0f}, {0.04f, 2.2f, 0.4f});
  for (int i = 0; i < 5; ++i) AddBoxPart(m, part, {0.0f, 0.05f + 0.52f * i, 0.0f}, {1.92f, 0.03f, 0.38f});
  return m;
}

Mesh MakeChair(int cells) {
  Mesh box = MakeGridBox(cells);
  Mesh m;
  m.name = "chair";
  const float leg = 0.03f, half = 0.195f, seatY = 0.45f, seatT = 0.025f;
  for (float x : {-half, half})
    for (float z : {-half, half}) AddBoxPart(m, box, {x, seatY * 0.5f, z}, {leg, seatY, leg});
  AddBoxPart(m, box, {0.0f, seatY + seatT * 0.5f, 0.0f}, {0.44f, seatT, 0.44f});
  const float backBase = seatY + seatT, backH = 0.45f;
  for (float x : {-half, half}) AddBoxPart(m, box, {x, backBase + backH * 0.5f, -half}, {leg, backH, leg});
  for (float y : {backBase + 0.18f, backBase + backH - 0.04f}) AddBoxPart(m, box, {0.0f, y, -half}, {2 * half - leg, 0.06f, 0.02f});
  m.computeBounds();
  return m;
}

Mesh MakeTable(int cells, glm::vec2 top) {
  Mesh box = MakeGridBox(cells);
  Mesh m;
  m.name = "table";
  const float topY = 0.75f, topT = 0.04f, leg = 0.06f, legH = topY - topT * 0.5f;
  AddBoxPart(m, box, {0.0f, topY, 0.0f}, {top.x, topT, top.y});
  for (float sx : {-1.0f, 1.0f})
    for (float sz : {-1.0f, 1.0f})
      AddBoxPart(m, box, {sx * (top.x * 0.5f - 0.08f), legH * 0.5f, sz * (top.y * 0.5f - 0.08f)}, {leg, legH, leg});
  m.computeBounds();
  return m;
}

uint64_t AddTiledFloor(Scene& s, const glm::vec3& center, const glm::vec2& size, uint64_t triangles, const glm::vec3& albedo,
                       int maxTilesPerSide) {
  // Enough tiles for per-instance culling to matter, but at least a 2x2 grid of cells each.
  int tiles = std::clamp(int(std::sqrt(double(triangles) / 8.0)), 1, std::max(1, maxTilesPerSide));
  double perTile = double(triangles) / (2.0 * tiles * tiles);
  double aspect = size.x / size.y;
  int cx = std::max(1, int(std::lround(std::sqrt(perTile * aspect))));
  int cz = std::max(1, int(std::lround(perTile / cx)));
  Mesh tile = MakeGridPlane(cx, cz);
  tile.name = "floor-tile";
  uint32_t mesh = s.addMesh(std::move(tile));
  glm::vec2 step = size / float(tiles);
  for (int j = 0; j < tiles; ++j)
    for (int i = 0; i < tiles; ++i) {
      glm::vec3 c = center + glm::vec3(-0.5f * size.x + (i + 0.5f) * step.x, 0.0f, -0.5f * size.y + (j + 0.5f) * step.y);
      s.addInstance(mesh, Place(c, {step.x, 1.0f, step.y}), albedo);
    }
  return uint64_t(tiles) * tiles * 2 * cx * cz;
}

uint64_t AddTerrain(Scene& s, float x0, float z0, float tileSize, int tilesX, int tilesZ, int cells,
                    const std::function<float(float, float)>& height, const glm::vec3& albedo) {
  cells = std::max(cells, 1);
  const float step = tileSize / float(cells), e = 0.5f;
  uint64_t added = 0;
  for (int tz = 0; tz < tilesZ; ++tz)
    for (int tx = 0; tx < tilesX; ++tx) {
      Mesh m;
      m.name = "terrain";
      for (int j = 0; j <= cells; ++j)
        for (int i = 0; i <= cells; ++i) {
          float x = x0 + float(tx * cells + i) * step, z = z0 + float(tz * cells + j) * step;
          glm::vec3 n(-(height(x + e, z) - height(x - e, z)) / (2 * e), 1.0f, -(height(x, z + e) - height(x, z - e)) / (2 * e));
          m.vertices.push_back({{x, height(x, z), z}, glm::normalize(n)});
        }
      auto at = [&](int i, int j) { return uint32_t(j * (cells + 1) + i); };
      for (int j = 0; j < cells; ++j)
        for (int i = 0; i < cells; ++i)
          m.indices.insert(m.indices.end(), {at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i + 1, j)});
      added += m.triangleCount();
      s.addInstance(s.addMesh(std::move(m)), glm::mat4(1.0f), albedo);
    }
  return added;
}

int LevelForBudget(int lo, int hi, uint64_t budget, const std::function<uint64_t(int)>& triangles) {
  int n = lo;
  while (n < hi && triangles(n + 1) <= budget) ++n;
  return n;
}

CameraPath MakePath(const std::string& name, const Camera& lens, std::vector<CameraKey> keys) {
  CameraPath p;
  p.name = name;
  p.lens = lens;
  p.keys = std::move(keys);
  return p;
}

CameraPath YawPath(const std::string& name, const Camera& camera, float fromDegrees, float toDegrees) {
  int steps = std::max(2, int(std::ceil(std::abs(toDegrees - fromDegrees) / 1.25f)) + 1);
  std::vector<CameraKey> keys;
  glm::vec3 look = camera.target - camera.position;
  for (int i = 0; i < steps; ++i) {
    float t = float(i) / float(steps - 1);
    float a = glm::radians(fromDegrees + (toDegrees - fromDegrees) * t);
    glm::vec3 d = glm::vec3(glm::rotate(glm::mat4(1.0f), a, glm::vec3(0, 1, 0)) * glm::vec4(look, 0.0f));
    keys.push_back({t, camera.position, camera.position + d});
  }
  return MakePath(name, camera, std::move(keys));
}

void FinishScene(Scene& s, std::vector<CameraPath> extraPaths) {
  s.finalize();
  s.cameraPaths = StandardCameraPaths(s.camera, s.bounds);
  for (CameraPath& p : extraPaths) s.cameraPaths.push_back(std::move(p));
}

}  // namespace sp::scene::proc
