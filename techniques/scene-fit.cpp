#include "scene-fit.h"

#include <cmath>
#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>

namespace sp::tech {

OrthoFit FitOrthoToBounds(const scene::Bounds& bounds, const glm::vec3& direction) {
  glm::vec3 dir = glm::normalize(direction);
  glm::vec3 center = bounds.center();
  float radius = glm::length(bounds.extent()) * 0.5f;
  glm::vec3 up = std::abs(dir.y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
  glm::mat4 view = glm::lookAtRH(center - dir * radius, center, up);
  scene::Bounds ls = bounds.transformed(view);
  // Right-handed view space looks down -z: near = -max.z, far = -min.z.
  glm::mat4 proj = glm::orthoRH_ZO(ls.min.x, ls.max.x, ls.min.y, ls.max.y, -ls.max.z, -ls.min.z);
  return {proj * view, -ls.max.z, -ls.min.z, glm::vec2(ls.max.x - ls.min.x, ls.max.y - ls.min.y)};
}

}  // namespace sp::tech
