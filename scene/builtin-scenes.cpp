// Built-in procedural scenes. Each models no more than its point needs.
#include <glm/ext/matrix_transform.hpp>
#include <stdexcept>

#include "scene.h"

namespace sp::scene {
namespace {

glm::mat4 Place(glm::vec3 pos, glm::vec3 scale, float yawDegrees = 0.0f) {
  glm::mat4 m = glm::translate(glm::mat4(1.0f), pos);
  m = glm::rotate(m, glm::radians(yawDegrees), glm::vec3(0, 1, 0));
  return glm::scale(m, scale);
}

// Ground, columns and boxes: long shadows from the columns, contact shadows under the boxes and
// the thin slab, self-shadowing on the stacked boxes and the sphere.
Scene MakeDefault() {
  Scene s;
  s.name = "default";
  uint32_t plane = s.addMesh(MakePlane(8));
  uint32_t box = s.addMesh(MakeBox());
  uint32_t column = s.addMesh(MakeCylinder(24));
  uint32_t sphere = s.addMesh(MakeSphere(24, 16));

  s.addInstance(plane, Place({0, 0, 0}, {40, 1, 40}), {0.72f, 0.70f, 0.66f});
  const glm::vec3 stone(0.78f, 0.74f, 0.68f);
  for (int i = 0; i < 4; ++i) s.addInstance(column, Place({-6.0f + 4.0f * i, 0, -4.0f}, {0.9f, 6.0f + i, 0.9f}), stone);
  s.addInstance(box, Place({-3.0f, 0.75f, 1.5f}, {1.5f, 1.5f, 1.5f}, 20.0f), {0.80f, 0.35f, 0.25f});
  s.addInstance(box, Place({-3.0f, 2.0f, 1.5f}, {1.0f, 1.0f, 1.0f}, 50.0f), {0.85f, 0.60f, 0.25f});
  s.addInstance(box, Place({2.5f, 1.0f, 2.0f}, {3.0f, 2.0f, 1.0f}, -15.0f), {0.30f, 0.45f, 0.75f});
  s.addInstance(box, Place({0.0f, 0.05f, 4.5f}, {4.0f, 0.1f, 0.6f}, 5.0f), {0.35f, 0.65f, 0.40f});  // thin slab
  s.addInstance(sphere, Place({5.5f, 1.2f, -0.5f}, {2.4f, 2.4f, 2.4f}), {0.70f, 0.70f, 0.75f});
  s.addInstance(box, Place({6.0f, 3.0f, -5.0f}, {1.0f, 6.0f, 1.0f}), stone);

  s.camera.position = {-4.0f, 7.0f, 14.0f};
  s.camera.target = {1.0f, 1.0f, 0.0f};
  s.camera.nearZ = 0.5f;
  s.camera.farZ = 100.0f;
  s.light.direction = glm::normalize(glm::vec3(-0.55f, -0.65f, -0.5f));
  s.finalize();
  return s;
}

struct Entry {
  const char* name;
  Scene (*make)();
};

const Entry kScenes[] = {
    {"default", MakeDefault},
};

}  // namespace

std::vector<std::string> BuiltinSceneNames() {
  std::vector<std::string> names;
  for (const Entry& e : kScenes) names.push_back(e.name);
  return names;
}

Scene MakeBuiltinScene(const std::string& name) {
  for (const Entry& e : kScenes)
    if (name == e.name) return e.make();
  std::string list;
  for (const Entry& e : kScenes) list += (list.empty() ? "" : ", ") + std::string(e.name);
  throw std::invalid_argument("unknown scene '" + name + "' (built-in scenes: " + list + ")");
}

}  // namespace sp::scene
