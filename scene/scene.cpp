#include <sp/scene/scene.h>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>

namespace sp::scene {

void Bounds::corners(glm::vec3 out[8]) const {
  for (int i = 0; i < 8; ++i) out[i] = glm::vec3(i & 1 ? max.x : min.x, i & 2 ? max.y : min.y, i & 4 ? max.z : min.z);
}

Bounds Bounds::transformed(const glm::mat4& m) const {
  Bounds b;
  if (empty()) return b;
  glm::vec3 c[8];
  corners(c);
  for (const glm::vec3& p : c) b.extend(glm::vec3(m * glm::vec4(p, 1.0f)));
  return b;
}

void Mesh::computeBounds() {
  bounds = Bounds{};
  for (const Vertex& v : vertices) bounds.extend(v.position);
}

glm::mat4 Camera::view() const { return glm::lookAtRH(position, target, up); }

glm::mat4 Camera::projection(float aspect) const { return glm::perspectiveRH_ZO(fovY, aspect, nearZ, farZ); }

uint32_t Scene::addMesh(Mesh mesh) {
  mesh.computeBounds();
  meshes.push_back(std::move(mesh));
  return uint32_t(meshes.size() - 1);
}

void Scene::addInstance(uint32_t mesh, const glm::mat4& transform, const glm::vec3& albedo) {
  Instance i;
  i.mesh = mesh;
  i.transform = transform;
  i.albedo = albedo;
  instances.push_back(i);
}

void Scene::finalize() {
  bounds = Bounds{};
  for (Mesh& m : meshes) m.computeBounds();
  for (Instance& i : instances) {
    i.worldBounds = meshes[i.mesh].bounds.transformed(i.transform);
    bounds.extend(i.worldBounds);
  }
}

size_t Scene::triangleCount() const {
  size_t n = 0;
  for (const Instance& i : instances) n += meshes[i.mesh].triangleCount();
  return n;
}

}  // namespace sp::scene
