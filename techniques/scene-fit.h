// The orthographic light frustum around a whole scene, shared by the techniques that cover the
// scene with one map (basic, asm's level 0).
#pragma once
#include <glm/glm.hpp>
#include <sp/scene/scene.h>

namespace sp::tech {

struct OrthoFit {
  glm::mat4 viewProj;
  float nearZ, farZ;  // world units along the light direction, from the view's origin
  glm::vec2 extent;   // the frustum's width and height in world units
};

// The box's light-space bounds, tight in x, y and depth.
OrthoFit FitOrthoToBounds(const scene::Bounds& bounds, const glm::vec3& direction);

}  // namespace sp::tech
