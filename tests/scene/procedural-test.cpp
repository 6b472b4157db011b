// Procedural scenes: every built-in scene builds, is well formed (finite bounds, unit normals,
// closed meshes counter-clockwise from outside), meets triangle targets, is deterministic, has the
// standard camera paths moving slowly and continuously, and shows the property it exists for,
// checked geometrically. No GPU needed.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <set>
#include <tuple>

#include <sp/scene/scene.h>

#include "scene-rays.h"

namespace sp::test {
namespace {

using scene::Bounds;
using scene::Camera;
using scene::CameraPath;
using scene::Instance;
using scene::Mesh;
using scene::Scene;

const std::vector<std::string> kNames = {"default",          "terrain-city",          "canyon-city",      "dueling-frusta",  "grazing-light",
                                         "contact",          "overlapping-occluders", "distant-occluder", "point-light-room",
                                         "cube-seam",        "paraboloid-coarse",     "paraboloid-fine",  "furnished-room",
                                         "street",           "lattice",               "stacked-planks",   "single-plank"};

bool Finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

float Diagonal(const Bounds& b) { return glm::length(b.extent()); }

// Counter-clockwise seen from outside: after welding vertices by position, a closed mesh has every
// directed edge matched by its reverse, and its signed volume is positive.
struct Topology {
  bool closed = false;
  double volume = 0.0;
};

Topology Analyse(const Mesh& m) {
  double quantum = 1e-6 * std::max(1.0, double(glm::length(m.bounds.extent())));
  std::map<std::tuple<int64_t, int64_t, int64_t>, uint32_t> weld;
  std::vector<uint32_t> id(m.vertices.size());
  for (size_t i = 0; i < m.vertices.size(); ++i) {
    glm::dvec3 p = glm::dvec3(m.vertices[i].position) / quantum;
    auto key = std::make_tuple(std::llround(p.x), std::llround(p.y), std::llround(p.z));
    id[i] = weld.emplace(key, uint32_t(weld.size())).first->second;
  }
  std::map<std::pair<uint32_t, uint32_t>, int> edges;
  Topology t;
  for (size_t i = 0; i + 2 < m.indices.size(); i += 3) {
    uint32_t v[3] = {id[m.indices[i]], id[m.indices[i + 1]], id[m.indices[i + 2]]};
    for (int e = 0; e < 3; ++e) edges[{v[e], v[(e + 1) % 3]}]++;
    glm::dvec3 a(m.vertices[m.indices[i]].position), b(m.vertices[m.indices[i + 1]].position), c(m.vertices[m.indices[i + 2]].position);
    t.volume += glm::dot(a, glm::cross(b, c)) / 6.0;
  }
  t.closed = true;
  for (const auto& [e, n] : edges) {
    auto r = edges.find({e.second, e.first});
    if (r == edges.end() || r->second != n) {
      t.closed = false;
      break;
    }
  }
  return t;
}

bool SameScene(const Scene& a, const Scene& b) {
  auto bytesEqual = [](const auto& x, const auto& y) { return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(x[0])) == 0; };
  if (a.name != b.name || a.meshes.size() != b.meshes.size() || a.instances.size() != b.instances.size()) return false;
  for (size_t i = 0; i < a.meshes.size(); ++i)
    if (!bytesEqual(a.meshes[i].vertices, b.meshes[i].vertices) || a.meshes[i].indices != b.meshes[i].indices) return false;
  for (size_t i = 0; i < a.instances.size(); ++i) {
    const Instance &x = a.instances[i], &y = b.instances[i];
    if (x.mesh != y.mesh || x.transform != y.transform || x.albedo != y.albedo) return false;
  }
  if (a.camera.position != b.camera.position || a.camera.target != b.camera.target || a.camera.fovY != b.camera.fovY ||
      a.camera.nearZ != b.camera.nearZ || a.camera.farZ != b.camera.farZ)
    return false;
  if (a.light.direction != b.light.direction || a.light.color != b.light.color || a.light.ambient != b.light.ambient) return false;
  if (a.pointLights.size() != b.pointLights.size()) return false;
  for (size_t i = 0; i < a.pointLights.size(); ++i)
    if (a.pointLights[i].position != b.pointLights[i].position || a.pointLights[i].color != b.pointLights[i].color ||
        a.pointLights[i].range != b.pointLights[i].range)
      return false;
  if (a.spotLights.size() != b.spotLights.size()) return false;
  for (size_t i = 0; i < a.spotLights.size(); ++i)
    if (a.spotLights[i].position != b.spotLights[i].position || a.spotLights[i].direction != b.spotLights[i].direction ||
        a.spotLights[i].color != b.spotLights[i].color || a.spotLights[i].range != b.spotLights[i].range ||
        a.spotLights[i].innerConeAngle != b.spotLights[i].innerConeAngle || a.spotLights[i].outerConeAngle != b.spotLights[i].outerConeAngle)
      return false;
  if (a.cameraPaths.size() != b.cameraPaths.size()) return false;
  for (size_t i = 0; i < a.cameraPaths.size(); ++i) {
    const CameraPath &p = a.cameraPaths[i], &q = b.cameraPaths[i];
    if (p.name != q.name || p.keys.size() != q.keys.size()) return false;
    for (size_t k = 0; k < p.keys.size(); ++k)
      if (p.keys[k].time != q.keys[k].time || p.keys[k].position != q.keys[k].position || p.keys[k].target != q.keys[k].target) return false;
  }
  return true;
}

size_t MeshBytes(const Scene& s) {
  size_t n = 0;
  for (const Mesh& m : s.meshes) n += m.vertices.size() * sizeof(scene::Vertex) + m.indices.size() * sizeof(uint32_t);
  return n;
}

// atan2 of |cross| and dot: acos loses the small angles between consecutive frames.
double AngleDegrees(const glm::vec3& a, const glm::vec3& b) {
  glm::dvec3 x = glm::normalize(glm::dvec3(a)), y = glm::normalize(glm::dvec3(b));
  return glm::degrees(std::atan2(glm::length(glm::cross(x, y)), glm::dot(x, y)));
}

// --- The list and the model

TEST(ProceduralScenes, AllNamesAreListedAndLoadable) {
  EXPECT_EQ(scene::BuiltinSceneNames(), kNames);
  for (const std::string& n : kNames) EXPECT_EQ(scene::LoadScene(n).name, n);
  EXPECT_THROW(scene::MakeBuiltinScene("no-such-scene"), std::invalid_argument);
}

TEST(ProceduralScenes, EverySceneIsWellFormed) {
  for (const std::string& name : kNames) {
    SCOPED_TRACE(name);
    Scene s = scene::MakeBuiltinScene(name);
    ASSERT_FALSE(s.instances.empty());
    ASSERT_FALSE(s.bounds.empty());
    EXPECT_TRUE(Finite(s.bounds.min) && Finite(s.bounds.max));
    if (name != "default") {
      EXPECT_GE(s.triangleCount(), 5'000u);
      EXPECT_LE(s.triangleCount(), 200'000u);
    }
    for (const Instance& i : s.instances) {
      ASSERT_LT(i.mesh, s.meshes.size());
      ASSERT_FALSE(i.worldBounds.empty());
      ASSERT_TRUE(Finite(i.worldBounds.min) && Finite(i.worldBounds.max));
      EXPECT_TRUE(glm::all(glm::greaterThanEqual(i.albedo, glm::vec3(0.0f))) && glm::all(glm::lessThanEqual(i.albedo, glm::vec3(1.0f))));
    }
    int closed = 0;
    for (const Mesh& m : s.meshes) {
      SCOPED_TRACE(m.name);
      ASSERT_EQ(m.indices.size() % 3, 0u);
      for (uint32_t i : m.indices) ASSERT_LT(i, m.vertices.size());
      for (const scene::Vertex& v : m.vertices) {
        ASSERT_TRUE(Finite(v.position));
        ASSERT_NEAR(glm::length(v.normal), 1.0f, 1e-4f);
      }
      // Every triangle faces the way its vertex normals say (outwards, as glTF winds them).
      float scale = std::max(1e-3f, glm::length(m.bounds.extent()));
      for (size_t i = 0; i < m.indices.size(); i += 3) {
        const scene::Vertex &a = m.vertices[m.indices[i]], &b = m.vertices[m.indices[i + 1]], &c = m.vertices[m.indices[i + 2]];
        glm::vec3 g = glm::cross(b.position - a.position, c.position - a.position);
        if (glm::length(g) < 1e-9f * scale * scale) continue;
        ASSERT_GT(glm::dot(g, a.normal + b.normal + c.normal), 0.0f) << "triangle " << i / 3;
      }
      Topology t = Analyse(m);
      if (t.closed) {
        ++closed;
        EXPECT_GT(t.volume, 0.0);
      }
    }
    EXPECT_GT(closed, 0);
  }
}

// The lit pass transforms normals by the world matrix (not its inverse transpose); instances are
// placed so that gives the right normals.
TEST(ProceduralScenes, InstanceTransformsKeepNormalsRight) {
  for (const std::string& name : kNames) {
    SCOPED_TRACE(name);
    Scene s = scene::MakeBuiltinScene(name);
    for (const Instance& inst : s.instances) {
      glm::mat3 m(inst.transform), nm = glm::transpose(glm::inverse(m));
      const Mesh& mesh = s.meshes[inst.mesh];
      size_t stride = std::max<size_t>(1, mesh.vertices.size() / 64);
      for (size_t v = 0; v < mesh.vertices.size(); v += stride) {
        glm::vec3 n = mesh.vertices[v].normal;
        ASSERT_GT(glm::dot(glm::normalize(m * n), glm::normalize(nm * n)), 0.999f) << mesh.name;
      }
    }
  }
}

TEST(ProceduralScenes, DefaultSceneIsUnchanged) {
  Scene s = scene::MakeBuiltinScene("default");
  ASSERT_EQ(s.meshes.size(), 4u);
  ASSERT_EQ(s.instances.size(), 11u);
  EXPECT_EQ(s.meshes[0].name, "plane");
  EXPECT_EQ(s.triangleCount(), 128u + 4 * 96 + 5 * 12 + 720);
  EXPECT_EQ(s.camera.position, glm::vec3(-4.0f, 7.0f, 14.0f));
  EXPECT_EQ(s.camera.target, glm::vec3(1.0f, 1.0f, 0.0f));
  EXPECT_EQ(s.camera.farZ, 100.0f);
  EXPECT_EQ(s.light.direction, glm::normalize(glm::vec3(-0.55f, -0.65f, -0.5f)));
  EXPECT_TRUE(s.pointLights.empty());
}

// --- Size

TEST(ProceduralScenes, TriangleTargetsAreMetWithinThirtyPercent) {
  const uint64_t targets[] = {10'000, 30'000, 100'000, 300'000, 1'000'000, 2'500'000};
  std::printf("%-22s %9s %9s %9s %10s %9s %9s\n", "scene", "natural", "1e4", "2.5e6", "instances", "MiB", "ms@2.5e6");
  for (const std::string& name : kNames) {
    SCOPED_TRACE(name);
    size_t counts[6];
    double ms = 0;
    size_t bytes = 0, instances = 0;
    for (int i = 0; i < 6; ++i) {
      auto t0 = std::chrono::steady_clock::now();
      Scene s = scene::MakeBuiltinScene(name, {targets[i]});
      double elapsed = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      counts[i] = s.triangleCount();
      EXPECT_NEAR(double(counts[i]) / double(targets[i]), 1.0, 0.3) << "target " << targets[i] << " gave " << counts[i];
      if (i == 5) {
        ms = elapsed;
        bytes = MeshBytes(s);
        instances = s.instances.size();
        // Instancing keeps the stored meshes far below the instanced count (72 bytes a triangle
        // if nothing were shared), and the build fast.
        EXPECT_LT(bytes, size_t(32) << 20);
        EXPECT_LT(elapsed, 5000.0);
        EXPECT_LT(instances, 20'000u);
      }
    }
    std::printf("%-22s %9zu %9zu %9zu %10zu %9.1f %9.0f\n", name.c_str(), scene::MakeBuiltinScene(name).triangleCount(), counts[0], counts[5],
                instances, double(bytes) / (1 << 20), ms);
  }
}

TEST(ProceduralScenes, OptionsAndLimits) {
  for (const std::string& name : kNames) {
    SCOPED_TRACE(name);
    EXPECT_TRUE(SameScene(scene::MakeBuiltinScene(name), scene::MakeBuiltinScene(name, scene::SceneOptions{})));
  }
  EXPECT_NEAR(double(scene::LoadScene("canyon-city", {200'000}).triangleCount()) / 200'000.0, 1.0, 0.3);
  EXPECT_THROW(scene::LoadScene("some/file.gltf", {100'000}), std::invalid_argument);
  EXPECT_THROW(scene::MakeBuiltinScene("contact", {scene::kMaxTargetTriangles + 1}), std::invalid_argument);
}

TEST(ProceduralScenes, BuildsAreDeterministic) {
  for (const std::string& name : kNames) {
    SCOPED_TRACE(name);
    EXPECT_TRUE(SameScene(scene::MakeBuiltinScene(name), scene::MakeBuiltinScene(name)));
    EXPECT_TRUE(SameScene(scene::MakeBuiltinScene(name, {150'000}), scene::MakeBuiltinScene(name, {150'000})));
  }
}

// --- Camera paths

TEST(ProceduralCameraPaths, EverySceneHasTheStandardPathsStartingAtItsCamera) {
  for (const std::string& name : kNames) {
    SCOPED_TRACE(name);
    Scene s = scene::MakeBuiltinScene(name);
    for (const char* p : {"slow-pan", "rotate", "dolly"}) {
      const CameraPath& path = s.cameraPath(p);
      Camera c0 = path.at(0.0);
      EXPECT_EQ(c0.position, s.camera.position) << p;
      EXPECT_LT(glm::length(c0.target - s.camera.target), 1e-3f * glm::length(s.camera.target - s.camera.position)) << p;
    }
    for (const CameraPath& path : s.cameraPaths) {
      SCOPED_TRACE(path.name);
      ASSERT_GE(path.keys.size(), 2u);
      EXPECT_EQ(path.keys.front().time, 0.0f);
      EXPECT_EQ(path.keys.back().time, 1.0f);
      Camera a = path.at(0.0), b = path.at(1.0);
      EXPECT_EQ(a.position, path.keys.front().position);
      EXPECT_EQ(a.target, path.keys.front().target);
      EXPECT_EQ(b.position, path.keys.back().position);
      EXPECT_EQ(b.target, path.keys.back().target);
      EXPECT_EQ(path.at(-1.0).position, a.position);
      EXPECT_EQ(path.at(2.0).position, b.position);
      EXPECT_EQ(b.fovY, s.camera.fovY);
      EXPECT_EQ(b.nearZ, s.camera.nearZ);
      EXPECT_EQ(b.farZ, s.camera.farZ);
    }
    EXPECT_THROW(s.cameraPath("no-such-path"), std::invalid_argument);
  }
}

TEST(ProceduralCameraPaths, MotionIsSlowAndContinuous) {
  for (const std::string& name : kNames) {
    SCOPED_TRACE(name);
    Scene s = scene::MakeBuiltinScene(name);
    const float diag = Diagonal(s.bounds);
    for (const CameraPath& path : s.cameraPaths) {
      SCOPED_TRACE(path.name);
      // At 60 frames over the path: small steps.
      for (int i = 0; i < 60; ++i) {
        Camera a = path.at(i / 60.0), b = path.at((i + 1) / 60.0);
        EXPECT_LE(glm::distance(a.position, b.position), 0.02f * diag);
        EXPECT_LE(AngleDegrees(a.forward(), b.forward()), 2.0);
      }
      // At 600 samples: neither position nor direction jumps, and speed changes gradually.
      const int n = 600;
      std::vector<float> speed, turn;
      for (int i = 0; i < n; ++i) {
        Camera a = path.at(double(i) / n), b = path.at(double(i + 1) / n);
        speed.push_back(glm::distance(a.position, b.position));
        turn.push_back(float(AngleDegrees(a.forward(), b.forward())));
      }
      float maxSpeed = *std::max_element(speed.begin(), speed.end()), maxTurn = *std::max_element(turn.begin(), turn.end());
      for (int i = 1; i < n; ++i) {
        ASSERT_LE(std::abs(speed[i] - speed[i - 1]), 0.05f * maxSpeed + 1e-6f * diag) << "at " << i;
        ASSERT_LE(std::abs(turn[i] - turn[i - 1]), 0.05f * maxTurn + 1e-3f) << "at " << i;
      }
      EXPECT_GT(maxSpeed + maxTurn, 0.0f);
    }
    // slow-pan: sideways, a fraction of a shadow texel (2048^2 over the scene) per 1/60.
    const CameraPath& pan = s.cameraPath("slow-pan");
    const float texel = diag / 2048.0f;
    glm::vec3 forward = s.camera.forward();
    for (int i = 0; i < 60; ++i) {
      Camera a = pan.at(i / 60.0), b = pan.at((i + 1) / 60.0);
      float step = glm::distance(a.position, b.position);
      EXPECT_LE(step, 0.15f * texel);
      EXPECT_GE(step, 0.05f * texel);
      EXPECT_LT(std::abs(glm::dot(glm::normalize(b.position - a.position), forward)), 1e-3f);
      EXPECT_LT(AngleDegrees(a.forward(), forward), 1e-2);
    }
    // rotate: a yaw in place; dolly: straight ahead.
    const CameraPath& rotate = s.cameraPath("rotate");
    EXPECT_EQ(rotate.at(0.5).position, s.camera.position);
    auto flat = [](glm::vec3 v) { return glm::vec3(v.x, 0.0f, v.z); };
    EXPECT_NEAR(AngleDegrees(flat(rotate.at(0.0).forward()), flat(rotate.at(1.0).forward())), 20.0, 0.1);
    EXPECT_GT(glm::cross(rotate.at(0.0).forward(), rotate.at(1.0).forward()).y, 0.0f);  // to the left
    const CameraPath& dolly = s.cameraPath("dolly");
    glm::vec3 move = dolly.at(1.0).position - dolly.at(0.0).position;
    EXPECT_GT(glm::dot(glm::normalize(move), forward), 0.999f);
  }
}

TEST(ProceduralCameraPaths, StandardPathsForScenesWithoutTheirOwn) {
  Scene s;
  s.addInstance(s.addMesh(scene::MakeBox()), glm::mat4(1.0f), glm::vec3(0.5f));
  s.finalize();
  std::vector<CameraPath> paths = scene::CameraPathsFor(s);
  ASSERT_EQ(paths.size(), 3u);
  EXPECT_EQ(paths[0].name, "slow-pan");
  EXPECT_EQ(paths[1].name, "rotate");
  EXPECT_EQ(paths[2].name, "dolly");
  // A spline through keys on a circle stays on it.
  for (int i = 0; i <= 100; ++i) {
    Camera c = paths[1].at(i / 100.0);
    EXPECT_NEAR(glm::length(c.target - c.position) / glm::length(s.camera.target - s.camera.position), 1.0f, 5e-5f);
  }
}

// --- What each scene is for

TEST(ProceduralSceneProperties, DuelingFrustaLooksIntoTheLight) {
  Scene s = scene::MakeBuiltinScene("dueling-frusta");
  EXPECT_LT(glm::dot(s.camera.forward(), glm::normalize(s.light.direction)), -0.9f);
  EXPECT_LT(glm::normalize(s.light.direction).y, -0.1f);  // still a sun above the ground
}

TEST(ProceduralSceneProperties, GrazingLightSkimsTheFloorAndTheWall) {
  Scene s = scene::MakeBuiltinScene("grazing-light");
  glm::vec3 d = glm::normalize(s.light.direction);
  double toFloor = glm::degrees(std::asin(std::abs(double(d.y))));
  EXPECT_LT(toFloor, 6.0);
  EXPECT_GT(toFloor, 0.5);
  // A large vertical receiver facing +z, long and tall, possibly in sections.
  Bounds wall;
  for (const Instance& i : s.instances) {
    glm::vec3 e = i.worldBounds.extent();
    if (e.x > 5.0f && e.y > 5.0f && e.z < 1.0f) wall.extend(i.worldBounds);
  }
  ASSERT_FALSE(wall.empty());
  EXPECT_GT(wall.extent().x, 30.0f);
  EXPECT_LT(wall.extent().z, 1.0f);
  double toWall = glm::degrees(std::asin(std::abs(double(d.z))));
  EXPECT_LT(toWall, 6.0);
  EXPECT_LT(d.z, 0.0f);  // onto its front face
}

TEST(ProceduralSceneProperties, TerrainCityIsLongAndDeep) {
  Scene s = scene::MakeBuiltinScene("terrain-city");
  EXPECT_GT(s.camera.farZ / s.camera.nearZ, 1000.0f);
  glm::vec3 f = s.camera.forward();
  glm::vec3 c[8];
  s.bounds.corners(c);
  float lo = 1e30f, hi = -1e30f;
  for (const glm::vec3& p : c) lo = std::min(lo, glm::dot(p - s.camera.position, f)), hi = std::max(hi, glm::dot(p - s.camera.position, f));
  EXPECT_GT(hi - lo, 1000.0f);
  // Buildings all the way: some beyond 1.5 km ahead, inside the far plane.
  float farthest = 0.0f;
  for (const Instance& i : s.instances)
    if (i.worldBounds.extent().y > 5.0f && i.worldBounds.extent().x < 50.0f)
      farthest = std::max(farthest, glm::dot(i.worldBounds.center() - s.camera.position, f));
  EXPECT_GT(farthest, 1500.0f);
  EXPECT_LT(farthest, s.camera.farZ);
  // The ground rolls gently: metres of relief, no steep slopes.
  float ylo = 1e30f, yhi = -1e30f;
  for (const Mesh& m : s.meshes) {
    if (m.name != "terrain") continue;
    for (const scene::Vertex& v : m.vertices) {
      ylo = std::min(ylo, v.position.y), yhi = std::max(yhi, v.position.y);
      ASSERT_GT(v.normal.y, 0.95f);
    }
  }
  EXPECT_GT(yhi - ylo, 2.0f);
  // Near the ground: the camera is less than 10 m above the terrain below it.
  float below = Cast(s, s.camera.position, {0, -1, 0});
  EXPECT_GT(below, 0.0f);
  EXPECT_LT(below, 10.0f);
}

TEST(ProceduralSceneProperties, CanyonCityStreetsAreDeepAndNarrow) {
  Scene s = scene::MakeBuiltinScene("canyon-city");
  EXPECT_LT(s.camera.position.y, 2.5f);  // street level
  glm::vec3 f = s.camera.forward();
  glm::vec3 side = glm::normalize(glm::cross(glm::vec3(f.x, 0.0f, f.z), glm::vec3(0, 1, 0)));
  const Instance *left = nullptr, *right = nullptr;
  float tl = Cast(s, s.camera.position, -side, &left), tr = Cast(s, s.camera.position, side, &right);
  ASSERT_GT(tl, 0.0f);
  ASSERT_GT(tr, 0.0f);
  float width = tl + tr;
  EXPECT_GT(width, 4.0f);
  EXPECT_GT(left->worldBounds.max.y, 3.0f * width);
  EXPECT_GT(right->worldBounds.max.y, 3.0f * width);
  // Down the street, buildings on both sides all along the first 60 m.
  for (float ahead = 0.0f; ahead < 60.0f; ahead += 5.0f) {
    glm::vec3 p = s.camera.position + glm::normalize(glm::vec3(f.x, 0.0f, f.z)) * ahead;
    const Instance *l = nullptr, *r = nullptr;
    float a = Cast(s, p, -side, &l), b = Cast(s, p, side, &r);
    if (a < 0.0f || b < 0.0f) continue;  // a crossing
    EXPECT_GT(std::min(l->worldBounds.max.y, r->worldBounds.max.y), 3.0f * (a + b)) << ahead;
  }
}

TEST(ProceduralSceneProperties, OverlappingOccludersStackThreeCastersInLightSpace) {
  Scene s = scene::MakeBuiltinScene("overlapping-occluders");
  glm::vec3 d = glm::normalize(s.light.direction);
  glm::vec3 u = glm::normalize(glm::cross(d, glm::vec3(0, 0, 1))), v = glm::cross(u, d);
  // Rays along the light over the whole scene; count distinct casters (at least 20 cm apart along
  // the ray) above the floor.
  int best = 0;
  glm::vec3 c = s.bounds.center();
  float r = Diagonal(s.bounds) * 0.5f;
  for (int j = 0; j <= 200; ++j)
    for (int i = 0; i <= 200; ++i) {
      glm::vec3 origin = c - d * (2 * r) + u * (r * (i / 100.0f - 1.0f)) + v * (r * (j / 100.0f - 1.0f));
      std::vector<float> hits;
      for (const Instance& inst : s.instances) {
        if (inst.worldBounds.extent().y < 1e-4f) continue;  // the receiver
        float t = RayHit(s, inst, origin, d);
        if (t >= 0.0f) hits.push_back(t);
      }
      std::sort(hits.begin(), hits.end());
      int distinct = hits.empty() ? 0 : 1;
      for (size_t k = 1; k < hits.size(); ++k) distinct += hits[k] - hits[k - 1] > 0.2f;
      best = std::max(best, distinct);
    }
  EXPECT_GE(best, 3);
}

TEST(ProceduralSceneProperties, DistantOccluderLeavesAnEmptyDepthRange) {
  Scene s = scene::MakeBuiltinScene("distant-occluder");
  glm::mat4 view = s.camera.view(), proj = s.camera.projection(16.0f / 9.0f);
  // View-depth intervals of the instances in the frustum; the largest gap in their union.
  std::vector<std::pair<float, float>> spans;
  int farVisible = 0;
  for (const Instance& i : s.instances) {
    glm::vec3 c[8];
    i.worldBounds.corners(c);
    float lo = 1e30f, hi = -1e30f;
    for (const glm::vec3& p : c) {
      float z = -(view * glm::vec4(p, 1.0f)).z;
      lo = std::min(lo, z), hi = std::max(hi, z);
    }
    lo = std::max(lo, s.camera.nearZ), hi = std::min(hi, s.camera.farZ);
    if (lo > hi) continue;
    spans.push_back({lo, hi});
    glm::vec4 clip = proj * view * glm::vec4(i.worldBounds.center(), 1.0f);
    if (clip.w > 500.0f && std::abs(clip.x) < clip.w && std::abs(clip.y) < clip.w) ++farVisible;
  }
  std::sort(spans.begin(), spans.end());
  float reach = spans.front().second, gap = 0.0f, lo = spans.front().first, hi = 0.0f;
  for (const auto& [a, b] : spans) {
    gap = std::max(gap, a - reach);
    reach = std::max(reach, b);
    hi = std::max(hi, b);
  }
  EXPECT_GT(gap / (hi - lo), 0.6f) << "largest empty depth interval " << gap << " of " << lo << ".." << hi;
  EXPECT_GT(farVisible, 0);
}

TEST(ProceduralSceneProperties, ContactHasThinObjectsRestingOnTheFloor) {
  Scene s = scene::MakeBuiltinScene("contact");
  float floorY = s.bounds.min.y;
  int thin = 0, coins = 0;
  for (const Instance& i : s.instances) {
    glm::vec3 e = i.worldBounds.extent();
    if (e.y > 1e-5f && e.y < 0.05f && std::abs(i.worldBounds.min.y - floorY) < 0.001f) {
      ++thin;
      coins += e.y < 0.005f && e.x < 0.03f;
    }
  }
  EXPECT_GE(thin, 5);
  EXPECT_GE(coins, 3);
  // A chair-like frame standing on the floor: a seat above 0.4 m over open space (a horizontal
  // ray at ankle height through the middle passes between the legs).
  bool chair = false;
  for (const Instance& i : s.instances) {
    if (i.worldBounds.extent().y < 0.5f || std::abs(i.worldBounds.min.y - floorY) > 0.001f) continue;
    glm::vec3 c = i.worldBounds.center();
    float seat = RayMesh(s, i, {c.x, 2.0f, c.z}, {0, -1, 0});
    bool open = RayMesh(s, i, {c.x - 5.0f, floorY + 0.1f, c.z}, {1, 0, 0}) < 0.0f;
    chair |= seat > 0.0f && 2.0f - seat > floorY + 0.4f && open;
  }
  EXPECT_TRUE(chair);
}

TEST(ProceduralSceneProperties, PointLightRoomIsClosedAroundItsLights) {
  Scene s = scene::MakeBuiltinScene("point-light-room");
  ASSERT_FALSE(s.pointLights.empty());
  EXPECT_LT(std::max({s.light.color.r, s.light.color.g, s.light.color.b}), 0.1f);
  for (const glm::vec3& p : {s.pointLights[0].position, s.pointLights.back().position, s.camera.position}) {
    EXPECT_TRUE(glm::all(glm::greaterThan(p, s.bounds.min)) && glm::all(glm::lessThan(p, s.bounds.max)));
    for (const Instance& i : s.instances) EXPECT_FALSE(Inside(s, i, p));
    // Enclosed: every direction meets something within the light's range.
    for (int x = -1; x <= 1; ++x)
      for (int y = -1; y <= 1; ++y)
        for (int z = -1; z <= 1; ++z) {
          if (!x && !y && !z) continue;
          float t = Cast(s, p, glm::normalize(glm::vec3(x, y, z)));
          EXPECT_GE(t, 0.0f);
          EXPECT_LT(t, s.pointLights[0].range);
        }
  }
  for (const scene::PointLight& l : s.pointLights) EXPECT_GT(l.range, 0.0f);
}


// The seam scene: every occluder floats between the light and the floor and spans a cube-map face
// edge as seen from the point light (its box's corners select at least two faces), so each shadow
// crosses a seam; one bar lies in the -Y/+X edge plane, its shadow along the seam.
TEST(ProceduralSceneProperties, CubeSeamOccludersStraddleCubeFaceEdges) {
  Scene s = scene::MakeBuiltinScene("cube-seam");
  ASSERT_EQ(s.pointLights.size(), 1u);
  const glm::vec3 L = s.pointLights[0].position;
  auto face = [](glm::vec3 d) {  // D3D11's cube face of a direction (ties to z, then y)
    glm::vec3 a = glm::abs(d);
    if (a.z >= a.x && a.z >= a.y) return d.z >= 0 ? 4 : 5;
    if (a.y >= a.x) return d.y >= 0 ? 2 : 3;
    return d.x >= 0 ? 0 : 1;
  };
  int occluders = 0, onEdgePlane = 0;
  for (const Instance& i : s.instances) {
    if (i.worldBounds.min.y < 0.05f || i.worldBounds.max.y > L.y) continue;  // floor tiles and walls
    ++occluders;
    glm::vec3 corners[8];
    i.worldBounds.corners(corners);
    std::set<int> faces;
    for (const glm::vec3& c : corners) faces.insert(face(c - L));
    EXPECT_GE(faces.size(), 2u) << "occluder at " << i.worldBounds.center().x << "," << i.worldBounds.center().y << "," << i.worldBounds.center().z;
    glm::vec3 d = i.worldBounds.center() - L;
    onEdgePlane += std::abs(std::abs(d.x) - std::abs(d.y)) < 1e-4f && i.worldBounds.extent().z > 1.0f;
  }
  EXPECT_GE(occluders, 5);
  EXPECT_EQ(onEdgePlane, 1);
  for (const Instance& i : s.instances) EXPECT_FALSE(Inside(s, i, L));
}

}  // namespace
}  // namespace sp::test

namespace sp::test {
namespace {

// The paraboloid pair: the same room, boxes, light and camera, differing only in triangle size:
// the coarse room's surfaces are two triangles a face (its walls' triangles are over 4 m long),
// the fine room's are split into triangles under 0.5 m; the light is enclosed and inside nothing.
TEST(ProceduralSceneProperties, ParaboloidScenesDifferOnlyInTessellation) {
  Scene coarse = scene::MakeBuiltinScene("paraboloid-coarse"), fine = scene::MakeBuiltinScene("paraboloid-fine");
  ASSERT_EQ(coarse.pointLights.size(), 1u);
  ASSERT_EQ(fine.pointLights.size(), 1u);
  EXPECT_EQ(coarse.pointLights[0].position, fine.pointLights[0].position);
  EXPECT_EQ(coarse.camera.position, fine.camera.position);
  // The room: what lies above the ground the budget filler adds outside it.
  auto room = [](const Scene& s) {
    std::vector<const Instance*> r;
    for (const Instance& i : s.instances)
      if (i.worldBounds.max.y > -0.25f) r.push_back(&i);
    return r;
  };
  std::vector<const Instance*> rc = room(coarse), rf = room(fine);
  ASSERT_EQ(rc.size(), rf.size());
  ASSERT_EQ(rc.size(), 12u);
  auto longestEdge = [](const Scene& s, const Instance& i) {
    const Mesh& m = s.meshes[i.mesh];
    float longest = 0.0f;
    for (size_t t = 0; t < m.indices.size(); t += 3)
      for (int e = 0; e < 3; ++e) {
        glm::vec3 a(i.transform * glm::vec4(m.vertices[m.indices[t + e]].position, 1.0f));
        glm::vec3 b(i.transform * glm::vec4(m.vertices[m.indices[t + (e + 1) % 3]].position, 1.0f));
        longest = std::max(longest, glm::distance(a, b));
      }
    return longest;
  };
  float coarseLongest = 0.0f, fineLongest = 0.0f;
  for (size_t k = 0; k < rc.size(); ++k) {
    EXPECT_LT(glm::distance(rc[k]->worldBounds.min, rf[k]->worldBounds.min), 1e-4f);
    EXPECT_LT(glm::distance(rc[k]->worldBounds.max, rf[k]->worldBounds.max), 1e-4f);
    EXPECT_EQ(rc[k]->albedo, rf[k]->albedo);
    EXPECT_EQ(coarse.meshes[rc[k]->mesh].triangleCount(), k < 6 ? 2u : 12u);
    coarseLongest = std::max(coarseLongest, longestEdge(coarse, *rc[k]));
    fineLongest = std::max(fineLongest, longestEdge(fine, *rf[k]));
  }
  EXPECT_GT(coarseLongest, 4.0f);
  EXPECT_LT(fineLongest, 0.5f);
  const glm::vec3 L = coarse.pointLights[0].position;
  for (const Scene* s : {&coarse, &fine}) {
    for (const Instance& i : s->instances) EXPECT_FALSE(Inside(*s, i, L));
    for (int x = -1; x <= 1; ++x)
      for (int y = -1; y <= 1; ++y)
        for (int z = -1; z <= 1; ++z) {
          if (!x && !y && !z) continue;
          float t = Cast(*s, L, glm::normalize(glm::vec3(x, y, z)));
          EXPECT_GE(t, 0.0f);
          EXPECT_LT(t, s->pointLights[0].range);
        }
  }
}

}  // namespace
}  // namespace sp::test
