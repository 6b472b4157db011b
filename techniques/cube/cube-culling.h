// Conservative culling for omnidirectional shadow maps (King: "skip faces whose frustum does not
// meet the view frustum or any visible receiver, cull casters per face"), shared by the point-light
// techniques and their tests. Every test answers "may meet": a false "yes" costs a draw, a false
// "no" would lose a shadow, so each is a separating-plane test that only says "no" when one plane
// has all of the other shape's corners outside it.
#pragma once
#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <vector>

#include <sp/scene/scene.h>

#include "cube/cube-faces.h"

namespace sp::tech::cube {

// Whether all `n` clip-space points lie outside one of the six planes of the D3D clip volume
// (-w <= x, y <= w, 0 <= z <= w), x and y widened by `widen` (1 = exact).
inline bool AllOutsideOnePlane(const glm::vec4* c, int n, float widen = 1.0f) {
  auto all = [&](auto outside) {
    for (int i = 0; i < n; ++i)
      if (!outside(c[i])) return false;
    return true;
  };
  return all([&](const glm::vec4& p) { return p.x > widen * p.w; }) || all([&](const glm::vec4& p) { return p.x < -widen * p.w; }) ||
         all([&](const glm::vec4& p) { return p.y > widen * p.w; }) || all([&](const glm::vec4& p) { return p.y < -widen * p.w; }) ||
         all([](const glm::vec4& p) { return p.z < 0; }) || all([](const glm::vec4& p) { return p.z > p.w; });
}

// A world box may be inside the frustum of `viewProj` (exact for the box's planes test: each
// clip plane is linear in the world point).
inline bool BoxMayMeetFrustum(const glm::mat4& viewProj, const scene::Bounds& b, float widen = 1.0f) {
  glm::vec3 corners[8];
  b.corners(corners);
  glm::vec4 c[8];
  for (int i = 0; i < 8; ++i) c[i] = viewProj * glm::vec4(corners[i], 1.0f);
  return !AllOutsideOnePlane(c, 8, widen);
}

// Face f's frustum (near to range), widened by `widen` in x and y, against the camera frustum
// (`camera` = proj * view): separated when the camera frustum's 8 corners lie outside one plane of
// the face's, or the face pyramid's 5 corners (light, far corners) outside one of the camera's.
inline bool FaceMayMeetCamera(int f, const glm::vec3& light, float nearZ, float range, float widen, const glm::mat4& camera) {
  glm::mat4 face = FaceViewProj(f, light, nearZ, range);
  glm::mat4 inv = glm::inverse(camera);
  glm::vec4 cam[8];
  for (int i = 0; i < 8; ++i) {
    glm::vec4 p = inv * glm::vec4(i & 1 ? 1.0f : -1.0f, i & 2 ? 1.0f : -1.0f, i & 4 ? 1.0f : 0.0f, 1.0f);
    cam[i] = face * (p / p.w);
  }
  // The camera's corners may lie behind the light (w < 0 in the face's clip space): the z < 0
  // plane test still holds for them, the x/y tests compare against a negative w and say "inside".
  if (AllOutsideOnePlane(cam, 8, widen)) return false;
  FaceAxes ax = Face(f);
  glm::vec4 pyr[5] = {camera * glm::vec4(light, 1.0f)};
  for (int i = 0; i < 4; ++i) {
    glm::vec3 d = ax.major + widen * ((i & 1 ? 1.0f : -1.0f) * ax.s + (i & 2 ? 1.0f : -1.0f) * ax.t);
    pyr[i + 1] = camera * glm::vec4(light + range * d, 1.0f);
  }
  return !AllOutsideOnePlane(pyr, 5);
}

// The visible receivers: the instances whose boxes may meet the camera frustum.
inline std::vector<uint32_t> VisibleInstances(const scene::Scene& s, const glm::mat4& camera) {
  std::vector<uint32_t> visible;
  for (uint32_t i = 0; i < s.instances.size(); ++i)
    if (BoxMayMeetFrustum(camera, s.instances[i].worldBounds)) visible.push_back(i);
  return visible;
}

// Whether face f of a light must be rendered: its frustum, widened by `widen` (the lookup's reach
// past the face's edge), may meet the camera frustum and the box of a visible receiver (King:
// "skip faces whose frustum does not meet the view frustum or any visible receiver").
inline bool FaceNeeded(int f, const glm::vec3& light, float nearZ, float range, float widen, const glm::mat4& camera, const scene::Scene& s,
                       const std::vector<uint32_t>& visible) {
  if (!FaceMayMeetCamera(f, light, nearZ, range, widen, camera)) return false;
  glm::mat4 face = FaceViewProj(f, light, nearZ, range);
  for (uint32_t v : visible)
    if (BoxMayMeetFrustum(face, s.instances[v].worldBounds, widen)) return true;
  return false;
}

// King's budget: a light's face resolution from its size on screen. The radius in pixels of the
// light's range sphere (the screen's half height, at most 1e9, when the camera is inside it)...
inline float ScreenRadius(const glm::vec3& light, float range, const glm::vec3& cameraPosition, const glm::mat4& cameraProj, uint32_t screenHeight) {
  float d = glm::length(light - cameraPosition);
  if (d <= range * 1.0001f) return 1e9f;
  float tanHalf = range / std::sqrt(d * d - range * range);
  return std::min(1e9f, tanHalf * cameraProj[1][1] * 0.5f * float(screenHeight));
}

// ...and the face resolution: a face spans the sphere's diameter (2 radius pixels) at its far end,
// so that many texels give `texelsPerPixel` there (more nearer the light), rounded up to a power
// of two and clamped to [minResolution, maxResolution].
inline uint32_t ScreenSizedResolution(float screenRadius, float texelsPerPixel, uint32_t minResolution, uint32_t maxResolution) {
  float wanted = std::min(2.0f * screenRadius * texelsPerPixel, float(maxResolution));
  uint32_t r = 1;
  while (float(r) < wanted && r < (1u << 30)) r <<= 1;
  return std::clamp(r, minResolution, maxResolution);
}

}  // namespace sp::tech::cube
