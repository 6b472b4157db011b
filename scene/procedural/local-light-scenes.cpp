// Scenes about local lights: "cube-seam" (shadows on cube-map face edges).
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

}  // namespace sp::scene::proc
