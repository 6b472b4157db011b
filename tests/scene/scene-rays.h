// Rays against a scene's instances for the scene property tests (CPU, no acceleration: the
// scenes are small): against an instance's oriented box (its mesh bounds under its transform) or
// its triangles.
#pragma once
#include <algorithm>
#include <cmath>

#include <sp/scene/scene.h>

namespace sp::test {

// Ray against an instance's oriented box (its mesh bounds under its transform); t along the world
// ray, or -1 when missed.
inline float RayHit(const scene::Scene& s, const scene::Instance& inst, const glm::vec3& origin, const glm::vec3& dir) {
  glm::mat4 inv = glm::inverse(inst.transform);
  glm::vec3 o(inv * glm::vec4(origin, 1.0f)), d(inv * glm::vec4(dir, 0.0f));
  const scene::Bounds& b = s.meshes[inst.mesh].bounds;
  float t0 = 0.0f, t1 = 1e30f;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-12f) {
      if (o[a] < b.min[a] || o[a] > b.max[a]) return -1.0f;
      continue;
    }
    float ta = (b.min[a] - o[a]) / d[a], tb = (b.max[a] - o[a]) / d[a];
    t0 = std::max(t0, std::min(ta, tb));
    t1 = std::min(t1, std::max(ta, tb));
  }
  return t0 <= t1 ? t0 : -1.0f;
}

// Ray against an instance's triangles (Moller-Trumbore in object space); nearest t or -1.
inline float RayMesh(const scene::Scene& s, const scene::Instance& inst, const glm::vec3& origin, const glm::vec3& dir) {
  glm::mat4 inv = glm::inverse(inst.transform);
  glm::vec3 o(inv * glm::vec4(origin, 1.0f)), d(inv * glm::vec4(dir, 0.0f));
  const scene::Mesh& m = s.meshes[inst.mesh];
  float best = -1.0f;
  for (size_t i = 0; i < m.indices.size(); i += 3) {
    glm::vec3 a = m.vertices[m.indices[i]].position, e1 = m.vertices[m.indices[i + 1]].position - a, e2 = m.vertices[m.indices[i + 2]].position - a;
    glm::vec3 p = glm::cross(d, e2);
    float det = glm::dot(e1, p);
    if (std::abs(det) < 1e-12f) continue;
    glm::vec3 q = o - a;
    float u = glm::dot(q, p) / det;
    glm::vec3 r = glm::cross(q, e1);
    float v = glm::dot(d, r) / det, t = glm::dot(e2, r) / det;
    if (u >= 0.0f && v >= 0.0f && u + v <= 1.0f && t >= 0.0f && (best < 0.0f || t < best)) best = t;
  }
  return best;
}

inline bool Inside(const scene::Scene& s, const scene::Instance& inst, const glm::vec3& p) {
  glm::vec3 o(glm::inverse(inst.transform) * glm::vec4(p, 1.0f));
  const scene::Bounds& b = s.meshes[inst.mesh].bounds;
  return glm::all(glm::greaterThan(o, b.min)) && glm::all(glm::lessThan(o, b.max));
}

// The nearest hit of a ray over all instances (-1 when none).
inline float Cast(const scene::Scene& s, const glm::vec3& origin, const glm::vec3& dir, const scene::Instance** hit = nullptr) {
  float best = -1.0f;
  for (const scene::Instance& i : s.instances) {
    float t = RayHit(s, i, origin, dir);
    if (t >= 0.0f && (best < 0.0f || t < best)) {
      best = t;
      if (hit) *hit = &i;
    }
  }
  return best;
}

}  // namespace sp::test
