// Dual-paraboloid geometry shared by the paraboloid technique and its tests (Brabec, Annen and
// Seidel, "Shadow Mapping for Hemispherical and Omnidirectional Light Sources"; King, "Shadow
// Mapping Algorithms"). The shaders (shaders-hlsl/paraboloid/) compute the same on the GPU.
//
// A light frame (right r, up u, axis a) around the light; hemisphere 0 ("front") holds the
// directions with dot(n, a) >= 0, hemisphere 1 the others, seen through the frame with a negated
// (a mirror image: the shadow pass draws both sides anyway). For a unit direction n in a
// hemisphere's frame, (x, y, z):
//   map NDC = (x, y) / (1 + z)         (the unit disk; z = 0, the seam, is its rim)
//   depth   = (|d| - near) / (range - near)   (linear distance, the same on both hemispheres)
// and texture uv = (ndc.x / 2 + 1/2, 1/2 - ndc.y / 2) (D3D: NDC +y is row 0, where v = 0).
#pragma once
#include <cmath>
#include <glm/glm.hpp>

namespace sp::tech::paraboloid {

// World -> hemisphere frame for a light at `position`, axis 0 = x, 1 = y, 2 = z. The rows of the
// rotation are (r, u, a) with a the axis, negated for hemisphere 1.
inline glm::mat4 HemisphereView(int axis, int hemisphere, const glm::vec3& position) {
  glm::vec3 a(0.0f), r(0.0f), u(0.0f);
  a[axis] = 1.0f;
  r[(axis + 1) % 3] = 1.0f;
  u[(axis + 2) % 3] = 1.0f;
  if (hemisphere == 1) a = -a;
  glm::mat4 m(1.0f);
  for (int c = 0; c < 3; ++c) m[c] = glm::vec4(r[c], u[c], a[c], 0.0f);
  m[3] = glm::vec4(-glm::dot(r, position), -glm::dot(u, position), -glm::dot(a, position), 1.0f);
  return m;
}

// The hemisphere a light-relative direction falls in (the seam, dot = 0, goes to the front).
inline int HemisphereOf(int axis, const glm::vec3& d) { return d[axis] >= 0.0f ? 0 : 1; }

// Map NDC of a direction given in a hemisphere's frame (any length).
inline glm::vec2 Ndc(const glm::vec3& frameDir) {
  glm::vec3 n = glm::normalize(frameDir);
  return glm::vec2(n.x, n.y) / (1.0f + n.z);
}

// The direction (unit, hemisphere frame) a map NDC point stands for: the inverse of Ndc.
inline glm::vec3 Direction(const glm::vec2& ndc) {
  float q = glm::dot(ndc, ndc);
  return glm::vec3(2.0f * ndc.x, 2.0f * ndc.y, 1.0f - q) / (1.0f + q);
}

inline float Depth(float distance, float nearZ, float range) { return (distance - nearZ) / (range - nearZ); }

// The frame z below which the shadow pass discards (interpolated per pixel): the rim is drawn
// `texels` texels beyond the unit disk, so the 2x2 filter of a receiver just inside the seam
// reads written texels. A point at NDC radius s has z = (1 - s^2) / (1 + s^2).
inline float DiscardZ(uint32_t resolution, float texels) {
  float s = 1.0f + 2.0f * texels / float(resolution);
  return (1.0f - s * s) / (1.0f + s * s);
}

}  // namespace sp::tech::paraboloid
