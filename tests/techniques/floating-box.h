// The floating-box scene of the technique tests (basic, csm, sdsm): a floor, a box above it,
// the light at 45 degrees, and the box's shadow on the floor computed on the CPU.
#pragma once
#include <algorithm>
#include <cmath>
#include <glm/ext/matrix_transform.hpp>
#include <vector>

#include <sp/scene/scene.h>

namespace sp::test {

// A floor and a box floating above it, the light at 45 degrees. `oblique`: the camera looks
// across the floor, so its view depth (and the cascade) varies over the image; otherwise it looks
// straight down.
inline scene::Scene FloatingBox(bool oblique) {
  scene::Scene s;
  s.name = "floating-box";
  uint32_t plane = s.addMesh(scene::MakePlane(1));
  uint32_t box = s.addMesh(scene::MakeBox());
  s.addInstance(plane, glm::scale(glm::mat4(1.0f), glm::vec3(20, 1, 20)), glm::vec3(0.8f));
  s.addInstance(box, glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(-2.0f, 3.0f, 0.0f)), glm::vec3(2.0f)), glm::vec3(0.8f));
  if (oblique) {
    s.camera.position = {1.0f, 7.0f, 11.0f};
    s.camera.target = {0.0f, 0.0f, -2.0f};
  } else {
    s.camera.position = {0.0f, 16.0f, 0.001f};
    s.camera.target = {0.0f, 0.0f, 0.0f};
    s.camera.up = {0.0f, 0.0f, -1.0f};
  }
  s.camera.fovY = glm::radians(50.0f);
  s.camera.nearZ = 1.0f;
  s.camera.farZ = 40.0f;
  s.light.direction = glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f));
  s.light.ambient = 0.2f;
  s.finalize();
  return s;
}

inline const glm::vec3 kBoxMin(-3.0f, 2.0f, -1.0f), kBoxMax(-1.0f, 4.0f, 1.0f);

// Slab test of a ray against an axis-aligned box; the entry distance or -1.
inline float RayBox(glm::vec3 o, glm::vec3 d, glm::vec3 bmin, glm::vec3 bmax) {
  float t0 = 0.0f, t1 = 1e30f;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-9f) {
      if (o[a] < bmin[a] || o[a] > bmax[a]) return -1.0f;
      continue;
    }
    float ta = (bmin[a] - o[a]) / d[a], tb = (bmax[a] - o[a]) / d[a];
    t0 = std::max(t0, std::min(ta, tb));
    t1 = std::min(t1, std::max(ta, tb));
  }
  return t0 <= t1 ? t0 : -1.0f;
}

// Per pixel: -1 not floor, 0 lit floor, 1 floor in the box's shadow (ray cast on the CPU).
inline std::vector<int> AnalyticFloor(const scene::Scene& s, uint32_t w, uint32_t h) {
  glm::mat4 inv = glm::inverse(s.camera.projection(float(w) / h) * s.camera.view());
  glm::vec3 toLight = s.light.towardsLight();
  std::vector<int> out(w * h, -1);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      glm::vec4 a = inv * glm::vec4((x + 0.5f) / w * 2 - 1, 1 - (y + 0.5f) / h * 2, 0.0f, 1.0f);
      glm::vec4 b = inv * glm::vec4((x + 0.5f) / w * 2 - 1, 1 - (y + 0.5f) / h * 2, 1.0f, 1.0f);
      glm::vec3 o = glm::vec3(a) / a.w, d = glm::normalize(glm::vec3(b) / b.w - o);
      if (d.y >= 0.0f) continue;
      float tFloor = -o.y / d.y;
      float tBox = RayBox(o, d, kBoxMin, kBoxMax);
      if (tBox >= 0 && tBox < tFloor) continue;
      glm::vec3 p = o + d * tFloor;
      if (std::abs(p.x) > 10 || std::abs(p.z) > 10) continue;
      out[y * w + x] = RayBox(p + toLight * 1e-3f, toLight, kBoxMin, kBoxMax) >= 0 ? 1 : 0;
    }
  return out;
}

// Floor pixels whose shadowing differs from the analytic answer, leaving out those within
// `band` pixels of a boundary (where filtering and the texel grid legitimately soften the edge).
struct Comparison {
  int checked = 0, shadow = 0, wrong = 0;
};
inline Comparison CompareWithAnalytic(const std::vector<uint8_t>& img, const std::vector<int>& expected, uint32_t w, uint32_t h, int band) {
  Comparison c;
  for (uint32_t y = band; y < h - band; ++y)
    for (uint32_t x = band; x < w - band; ++x) {
      int e = expected[y * w + x];
      if (e < 0) continue;
      bool nearEdge = false;
      for (int dy = -band; dy <= band; ++dy)
        for (int dx = -band; dx <= band; ++dx) nearEdge |= expected[(y + dy) * w + (x + dx)] != e;
      if (nearEdge) continue;
      // Lit floor: 0.8 * (0.2 + 0.707) = 0.73 linear; shadowed: 0.16. Threshold halfway in sRGB.
      int got = img[(y * w + x) * 4 + 1] < 150 ? 1 : 0;
      ++c.checked;
      c.shadow += e;
      c.wrong += got != e;
    }
  return c;
}

}  // namespace sp::test
