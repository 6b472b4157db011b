// The scene model shared by the renderer, the techniques and (later) the reference ray tracer:
// meshes with positions and normals, instances with transforms and world bounds, a camera and a
// light. Right-handed, +y up, as glTF; clip-space depth in [0, 1] as D3D.
#pragma once
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace sp::scene {

struct Bounds {
  glm::vec3 min{1e30f};
  glm::vec3 max{-1e30f};

  bool empty() const { return min.x > max.x; }
  void extend(const glm::vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  void extend(const Bounds& b) {
    if (!b.empty()) extend(b.min), extend(b.max);
  }
  glm::vec3 center() const { return (min + max) * 0.5f; }
  glm::vec3 extent() const { return max - min; }
  Bounds transformed(const glm::mat4& m) const;  // bounds of the 8 transformed corners
  void corners(glm::vec3 out[8]) const;
};

struct Vertex {
  glm::vec3 position;
  glm::vec3 normal;
};
static_assert(sizeof(Vertex) == 24, "Vertex is uploaded as is");

struct Mesh {
  std::string name;
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;  // triangle list
  Bounds bounds;                  // object space

  size_t triangleCount() const { return indices.size() / 3; }
  void computeBounds();
};

struct Instance {
  uint32_t mesh = 0;
  glm::mat4 transform{1.0f};
  glm::vec3 albedo{0.7f};
  Bounds worldBounds;  // filled by Scene::finalize()
};

struct Camera {
  glm::vec3 position{0, 5, 10};
  glm::vec3 target{0, 0, 0};
  glm::vec3 up{0, 1, 0};
  float fovY = glm::radians(60.0f);
  float nearZ = 0.1f;
  float farZ = 200.0f;

  glm::mat4 view() const;
  glm::mat4 projection(float aspect) const;  // right-handed, depth 0..1
  glm::vec3 forward() const { return glm::normalize(target - position); }
};

struct DirectionalLight {
  glm::vec3 direction{-0.4f, -1.0f, -0.3f};  // the way the light travels
  glm::vec3 color{1.0f, 0.96f, 0.9f};
  float ambient = 0.18f;

  glm::vec3 towardsLight() const { return -glm::normalize(direction); }
};

struct Scene {
  std::string name;
  std::vector<Mesh> meshes;
  std::vector<Instance> instances;
  Camera camera;
  DirectionalLight light;
  Bounds bounds;  // world space, filled by finalize()

  uint32_t addMesh(Mesh mesh);
  void addInstance(uint32_t mesh, const glm::mat4& transform, const glm::vec3& albedo);
  // Computes mesh and world bounds; call after building.
  void finalize();
  size_t triangleCount() const;
};

// Built-in procedural scenes. Throws std::invalid_argument listing the names for unknown ones.
Scene MakeBuiltinScene(const std::string& name);
std::vector<std::string> BuiltinSceneNames();

// Primitive meshes (unit sized, centred at the origin unless stated).
Mesh MakeBox();                                        // [-0.5, 0.5]^3
Mesh MakeCylinder(uint32_t segments);                  // radius 0.5, y in [0, 1]
Mesh MakePlane(uint32_t subdivisions);                 // xz in [-0.5, 0.5], y = 0, facing +y
Mesh MakeSphere(uint32_t segments, uint32_t rings);    // radius 0.5

}  // namespace sp::scene
