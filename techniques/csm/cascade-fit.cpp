#include "cascade-fit.h"

#include <algorithm>
#include <cmath>
#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <stdexcept>

namespace sp::tech::csm {

namespace {

// Rounds up to a power of 2^(1/8): sizes taken from continuously moving quantities change in
// rare 9% steps instead of every frame.
const float kLadderStep = 1.0905077f;  // 2^(1/8)
float Ladder(float x) {
  x = std::max(x, 1e-6f);
  return std::exp2(std::ceil(std::log2(x) * 8.0f) / 8.0f);
}

struct CameraBasis {
  glm::vec3 forward, right, up;
};

CameraBasis BasisOf(const scene::Camera& c) {
  CameraBasis b;
  b.forward = c.forward();
  b.right = glm::normalize(glm::cross(b.forward, c.up));
  b.up = glm::cross(b.right, b.forward);
  return b;
}

// The smallest sphere around the slice between view depths d0 and d1 depends on these and the
// lens only, so its radius stays bit for bit the same however the camera moves.
void SliceSphere(const scene::Camera& camera, float aspect, float d0, float d1, glm::vec3* center, float* radius) {
  float ty = std::tan(camera.fovY * 0.5f), tx = ty * aspect;
  float t2 = tx * tx + ty * ty;
  // Centre on the axis, equidistant from the near and far corners; past d1 the far rectangle's
  // circumcircle alone decides.
  float z = std::min(0.5f * (d0 + d1) * (1.0f + t2), d1);
  *radius = std::max(std::sqrt((z - d0) * (z - d0) + d0 * d0 * t2), std::sqrt((d1 - z) * (d1 - z) + d1 * d1 * t2));
  *center = camera.position + camera.forward() * z;
}

// Padding of a cascade whose texels, before its share of padWorld is added, are `texel` wide.
// More padding only widens the texels, so padWorld covers fewer of the final texels than of these:
// rounding up here is enough for the cascade as fitted.
uint32_t CascadePad(const FitSettings& s, float texel) {
  if (!(s.padWorld > 0.0f) || !(texel > 0.0f)) return s.padTexels;
  return s.padTexels + uint32_t(std::min(std::ceil(s.padWorld / texel), float(s.padWorldMaxTexels)));
}

std::string Trim(const std::string& s) {
  size_t a = s.find_first_not_of(" \t"), b = s.find_last_not_of(" \t");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

}  // namespace

SplitScheme ParseSplitScheme(const std::string& name) {
  if (name == "uniform") return SplitScheme::Uniform;
  if (name == "log") return SplitScheme::Log;
  if (name == "pssm") return SplitScheme::Pssm;
  if (name == "manual") return SplitScheme::Manual;
  throw std::invalid_argument("split=" + name + " is not valid; split takes uniform|log|pssm|manual");
}

std::vector<float> ParseManualSplits(const std::string& text, int cascades) {
  auto bad = [&](const std::string& why) {
    throw std::invalid_argument("splits=" + text + " is not valid: " + why + "; with cascades=" + std::to_string(cascades) +
                                " splits takes " + std::to_string(cascades - 1) +
                                " increasing fractions of the view range in (0, 1), separated by commas or colons (e.g. 0.05,0.15,0.4)");
  };
  std::vector<float> out;
  if (!Trim(text).empty()) {
    size_t start = 0;
    while (true) {
      size_t comma = text.find_first_of(",:", start);
      std::string item = Trim(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
      size_t used = 0;
      float v = 0;
      try {
        v = std::stof(item, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (item.empty() || used != item.size()) bad("'" + item + "' is not a number");
      if (!(v > 0.0f && v < 1.0f)) bad(item + " is not in (0, 1)");
      if (!out.empty() && v <= out.back()) bad("the fractions must increase");
      out.push_back(v);
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
  }
  if (int(out.size()) != cascades - 1) bad(std::to_string(out.size()) + " given");
  return out;
}

std::vector<float> SplitDistances(SplitScheme scheme, int cascades, float n, float f, float lambda, const std::vector<float>& manual) {
  if (cascades < 1) throw std::invalid_argument("SplitDistances: cascades must be at least 1");
  if (!(n > 0.0f && f > n)) throw std::invalid_argument("SplitDistances: needs 0 < near < far");
  if (scheme == SplitScheme::Manual && int(manual.size()) != cascades - 1)
    throw std::invalid_argument("SplitDistances: manual splits need cascades - 1 fractions");
  std::vector<float> d(cascades + 1);
  for (int i = 0; i <= cascades; ++i) {
    double s = double(i) / cascades;
    double uni = n + (double(f) - n) * s;
    double lg = n * std::pow(double(f) / n, s);
    switch (scheme) {
      case SplitScheme::Uniform: d[i] = float(uni); break;
      case SplitScheme::Log: d[i] = float(lg); break;
      case SplitScheme::Pssm: d[i] = float(lambda * lg + (1.0 - lambda) * uni); break;
      case SplitScheme::Manual:
        d[i] = i == 0 ? n : i == cascades ? f : float(n + (double(f) - n) * manual[i - 1]);
        break;
    }
  }
  // Exact ends, whatever the rounding of pow.
  d.front() = n;
  d.back() = f;
  return d;
}

glm::vec3 CascadeFit::texel(const glm::vec3& world, uint32_t resolution) const {
  glm::vec4 p = viewProj * glm::vec4(world, 1.0f);
  glm::vec3 c = glm::vec3(p) / p.w;
  return {(c.x * 0.5f + 0.5f) * float(resolution), (0.5f - c.y * 0.5f) * float(resolution), c.z};
}

glm::mat4 SharedLightView(const scene::Bounds& bounds, const glm::vec3& direction) {
  glm::vec3 dir = glm::normalize(direction);
  glm::vec3 center = bounds.empty() ? glm::vec3(0.0f) : bounds.center();
  float radius = bounds.empty() ? 1.0f : std::max(glm::length(bounds.extent()) * 0.5f, 1e-3f);
  glm::vec3 up = std::abs(dir.y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
  return glm::lookAtRH(center - dir * radius, center, up);
}

float ClippedFar(const scene::Camera& camera, const scene::Bounds& bounds, bool stabilize) {
  if (bounds.empty()) return camera.farZ;
  float reach;
  if (stabilize) {
    reach = Ladder(glm::distance(camera.position, bounds.center()) + glm::length(bounds.extent()) * 0.5f);
  } else {
    glm::vec3 c[8];
    bounds.corners(c);
    glm::vec3 fwd = camera.forward();
    reach = -1e30f;
    for (const glm::vec3& p : c) reach = std::max(reach, glm::dot(p - camera.position, fwd));
  }
  // A scene wholly behind the camera still gets a valid (if useless) range.
  return std::max(std::min(camera.farZ, reach), camera.nearZ * 1.01f + 1e-4f);
}

void SliceCorners(const scene::Camera& camera, float aspect, float d0, float d1, glm::vec3 out[8]) {
  CameraBasis b = BasisOf(camera);
  float ty = std::tan(camera.fovY * 0.5f), tx = ty * aspect;
  for (int i = 0; i < 8; ++i) {
    float d = i & 4 ? d1 : d0;
    out[i] = camera.position + b.forward * d + b.right * (i & 1 ? d * tx : -d * tx) + b.up * (i & 2 ? d * ty : -d * ty);
  }
}

std::vector<glm::vec3> SliceBoxIntersection(const glm::vec3 corners[8], const scene::Bounds& box) {
  std::vector<glm::vec3> out;
  if (box.empty()) return out;
  // The intersection of two convex solids is the hull of: each one's corners inside the other, and
  // each one's edges crossing the other's faces.
  glm::vec3 centroid(0.0f);
  for (int i = 0; i < 8; ++i) centroid += corners[i] * 0.125f;
  struct Plane {
    glm::vec3 n;
    float d;
  };
  Plane planes[6];
  int np = 0;
  for (int bit : {1, 2, 4})
    for (int side : {0, 1}) {
      int idx[4], k = 0;
      for (int i = 0; i < 8; ++i)
        if (((i & bit) != 0) == (side != 0)) idx[k++] = i;
      glm::vec3 a = corners[idx[0]], b = corners[idx[1]], c = corners[idx[3]];
      glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
      if (glm::dot(n, centroid - a) < 0) n = -n;
      planes[np++] = {n, -glm::dot(n, a)};
    }
  float scale = glm::length(box.extent());
  for (int i = 0; i < 8; ++i) scale = std::max(scale, glm::length(corners[i] - centroid));
  const float eps = 1e-5f * scale;
  auto inSlice = [&](const glm::vec3& p) {
    for (const Plane& pl : planes)
      if (glm::dot(pl.n, p) + pl.d < -eps) return false;
    return true;
  };
  auto inBox = [&](const glm::vec3& p) {
    return glm::all(glm::greaterThanEqual(p, box.min - eps)) && glm::all(glm::lessThanEqual(p, box.max + eps));
  };
  glm::vec3 bc[8];
  box.corners(bc);
  for (int i = 0; i < 8; ++i) {
    if (inBox(corners[i])) out.push_back(corners[i]);
    if (inSlice(bc[i])) out.push_back(bc[i]);
  }
  for (int i = 0; i < 8; ++i)
    for (int bit : {1, 2, 4}) {
      if (i & bit) continue;
      // Slice edge against the box's six faces.
      glm::vec3 p0 = corners[i], p1 = corners[i | bit];
      for (int a = 0; a < 3; ++a) {
        float den = p1[a] - p0[a];
        if (std::abs(den) < 1e-12f) continue;
        for (float v : {box.min[a], box.max[a]}) {
          float t = (v - p0[a]) / den;
          if (t < 0.0f || t > 1.0f) continue;
          glm::vec3 p = p0 + (p1 - p0) * t;
          if (inBox(p)) out.push_back(p);
        }
      }
      // Box edge against the slice's six planes.
      glm::vec3 q0 = bc[i], q1 = bc[i | bit];
      for (const Plane& pl : planes) {
        float s0 = glm::dot(pl.n, q0) + pl.d, s1 = glm::dot(pl.n, q1) + pl.d;
        if ((s0 < 0) == (s1 < 0) || s0 == s1) continue;
        glm::vec3 p = q0 + (q1 - q0) * (s0 / (s0 - s1));
        if (inSlice(p)) out.push_back(p);
      }
    }
  return out;
}

namespace {

// What a cascade must show: the part of its slice inside the scene (focus=receivers), or the
// whole slice; its rectangle and depth range in the light view.
struct Receivers {
  bool wholeSlice = true;  // the points are the slice's corners
  bool none = false;       // focus=receivers, and the slice misses the scene
  glm::vec2 min{1e30f}, max{-1e30f};
  float zNear = 1e30f, zFar = -1e30f;
};

Receivers FindReceivers(const glm::vec3 corners[8], const scene::Bounds& bounds, const glm::mat4& lightView, bool focus) {
  Receivers r;
  std::vector<glm::vec3> points(corners, corners + 8);
  if (focus) {
    bool inside = true;
    for (int i = 0; i < 8; ++i) inside &= glm::all(glm::greaterThanEqual(corners[i], bounds.min)) && glm::all(glm::lessThanEqual(corners[i], bounds.max));
    if (!inside) {
      std::vector<glm::vec3> cut = SliceBoxIntersection(corners, bounds);
      // A slice that misses the scene falls back to the slice itself (nothing there reads it).
      r.none = cut.empty();
      if (!r.none) points = std::move(cut), r.wholeSlice = false;
    }
  }
  for (const glm::vec3& p : points) {
    glm::vec3 l = glm::vec3(lightView * glm::vec4(p, 1.0f));
    r.min = glm::min(r.min, glm::vec2(l));
    r.max = glm::max(r.max, glm::vec2(l));
    r.zNear = std::min(r.zNear, -l.z);
    r.zFar = std::max(r.zFar, -l.z);
  }
  return r;
}

// Stabilized x/y: the side of the square and its centre (light view), before padding.
void StableSquare(const scene::Camera& camera, float aspect, const glm::mat4& lightView, const Receivers& r, bool focus,
                  const CascadeFit& c, const CascadeFit* previous, float* size, glm::vec2* mid) {
  glm::vec3 center;
  float radius;
  SliceSphere(camera, aspect, c.sliceNear, c.sliceFar, &center, &radius);
  *size = 2.0f * radius;
  *mid = glm::vec2(lightView * glm::vec4(center, 1.0f));
  if (!focus || r.none || r.wholeSlice) return;
  // Part of the slice lies outside the scene: a square around the receivers. Its size moves with
  // the camera, so it is kept on the ladder and, while it still fits, at last frame's value
  // (hysteresis): it changes rarely, and in whole steps.
  float need = std::max(r.max.x - r.min.x, r.max.y - r.min.y);
  float target = std::min(*size, Ladder(need));
  float kept = previous && previous->sliceNear == c.sliceNear && previous->sliceFar == c.sliceFar ? previous->fitSize : 0.0f;
  float chosen = kept >= need && kept <= *size && kept <= target * kLadderStep * kLadderStep ? kept : target;
  if (chosen < *size) *size = chosen, *mid = (r.min + r.max) * 0.5f;
}

// focus=receivers: the nearest distance of what can shadow the receivers, i.e. what lies between
// them and the light within their rectangle widened by `widen` (the filter's reach), taking only
// the part of each instance's bounds inside that prism (a ground plane's bounds reach far towards
// the light, its part above the receivers does not). Nearer geometry elsewhere is pancaked.
float CasterNear(const scene::Scene& scene, const std::vector<scene::Bounds>& casters, const glm::mat4& lightView, const scene::Bounds& sceneLs,
                 const Receivers& r, const CascadeFit& c, glm::vec2 widen) {
  CascadeFit reach = c;
  reach.min = glm::max(c.min, r.min - widen);
  reach.max = glm::min(c.max, r.max + widen);
  reach.zFar = r.zFar;
  glm::mat4 toWorld = glm::inverse(lightView);
  glm::vec3 prism[8];
  for (int k = 0; k < 8; ++k) {
    glm::vec3 l(k & 1 ? reach.max.x : reach.min.x, k & 2 ? reach.max.y : reach.min.y, k & 4 ? sceneLs.min.z - 1.0f : sceneLs.max.z + 1.0f);
    prism[k] = glm::vec3(toWorld * glm::vec4(l, 1.0f));
  }
  float zNear = r.zNear;
  for (size_t k = 0; k < casters.size(); ++k) {
    if (!MayCastInto(reach, casters[k]) || -casters[k].max.z >= zNear) continue;
    for (const glm::vec3& p : SliceBoxIntersection(prism, scene.instances[k].worldBounds))
      zNear = std::min(zNear, -glm::vec3(lightView * glm::vec4(p, 1.0f)).z);
  }
  return zNear;
}

// farToRegion: the farthest distance of anything inside the region's prism (its whole x/y, the
// padding included), from the part of each instance's bounds inside it, as CasterNear does for
// the near side; at least `zFar`.
float RegionFar(const scene::Scene& scene, const std::vector<scene::Bounds>& casters, const glm::mat4& lightView, const scene::Bounds& sceneLs,
                const CascadeFit& c, float zFar) {
  CascadeFit prismFit = c;
  prismFit.zFar = 1e30f;
  glm::mat4 toWorld = glm::inverse(lightView);
  glm::vec3 prism[8];
  for (int k = 0; k < 8; ++k) {
    glm::vec3 l(k & 1 ? c.max.x : c.min.x, k & 2 ? c.max.y : c.min.y, k & 4 ? sceneLs.min.z - 1.0f : sceneLs.max.z + 1.0f);
    prism[k] = glm::vec3(toWorld * glm::vec4(l, 1.0f));
  }
  for (size_t k = 0; k < casters.size(); ++k) {
    if (!MayCastInto(prismFit, casters[k]) || -casters[k].min.z <= zFar) continue;
    for (const glm::vec3& p : SliceBoxIntersection(prism, scene.instances[k].worldBounds))
      zFar = std::max(zFar, -glm::vec3(lightView * glm::vec4(p, 1.0f)).z);
  }
  return zFar;
}

}  // namespace

CascadeSet FitCascades(const scene::Scene& scene, const scene::Camera& camera, float aspect, const glm::vec3& lightDirection,
                       const FitSettings& s, const CascadeSet* previous) {
  CascadeSet set;
  set.lightView = SharedLightView(scene.bounds, lightDirection);
  set.nearZ = camera.nearZ;
  set.farZ = ClippedFar(camera, scene.bounds, s.stabilize);
  set.splits = SplitDistances(s.split, s.cascades, set.nearZ, set.farZ, s.lambda, s.manualFractions);
  const scene::Bounds sceneLs = scene.bounds.transformed(set.lightView);

  std::vector<scene::Bounds> casters;
  if (s.focusReceivers) {
    casters.reserve(scene.instances.size());
    for (const scene::Instance& inst : scene.instances) casters.push_back(inst.worldBounds.transformed(set.lightView));
  }
  const float n = float(s.resolution);

  for (int i = 0; i < s.cascades; ++i) {
    CascadeFit c;
    c.splitNear = set.splits[i];
    c.splitFar = set.splits[i + 1];
    c.sliceFar = c.splitFar;
    if (s.fitToScene) {
      c.sliceNear = set.nearZ;
    } else {
      // Cover the previous cascade's blend band too, so both are valid where they are mixed.
      c.sliceNear = i > 0 ? c.splitNear - s.blend * (set.splits[i] - set.splits[i - 1]) : c.splitNear;
    }
    glm::vec3 corners[8];
    SliceCorners(camera, aspect, c.sliceNear, c.sliceFar, corners);
    Receivers r = FindReceivers(corners, scene.bounds, set.lightView, s.focusReceivers);
    c.noReceivers = r.none;

    glm::vec2 texel;
    const float basePad = float(s.padTexels);
    float pad;
    if (s.stabilize) {
      const CascadeFit* last = previous && i < int(previous->cascades.size()) ? &previous->cascades[i] : nullptr;
      float size;
      glm::vec2 mid;
      StableSquare(camera, aspect, set.lightView, r, s.focusReceivers, c, last, &size, &mid);
      c.fitSize = size;
      // One texel more than the padding needs: snapping moves the square by up to one.
      c.padTexels = CascadePad(s, size / std::max(n - 2.0f * basePad - 1.0f, 1.0f));
      pad = float(c.padTexels);
      float t = size / std::max(n - 2.0f * pad - 1.0f, 1.0f);
      texel = glm::vec2(t);
      c.min = (glm::floor((mid - size * 0.5f) / t) - pad) * t;
    } else {
      glm::vec2 extent = glm::max(r.max - r.min, glm::vec2(1e-4f));
      glm::vec2 t0 = extent / std::max(n - 2.0f * basePad, 1.0f);
      c.padTexels = CascadePad(s, std::max(t0.x, t0.y));
      pad = float(c.padTexels);
      texel = extent / std::max(n - 2.0f * pad, 1.0f);
      c.min = r.min - pad * texel;
    }
    c.max = c.min + n * texel;
    c.texelWorld = std::max(texel.x, texel.y);

    if (s.focusReceivers && !r.none) {
      c.zFar = r.zFar;
      c.zNear = CasterNear(scene, casters, set.lightView, sceneLs, r, c, (pad + 1.0f) * texel);
      if (s.farToRegion) c.zFar = RegionFar(scene, casters, set.lightView, sceneLs, c, c.zFar);
    } else {
      c.zNear = -sceneLs.max.z;
      c.zFar = -sceneLs.min.z;
    }
    // A little slack so receivers on the bounds do not land exactly on depth 1.
    float margin = std::max(c.zFar - c.zNear, 1e-3f) * 1e-3f;
    c.zNear -= margin;
    c.zFar += margin;
    if (s.stabilize) {
      // Depth too on a fixed grid (1/256 of the scene's depth), so small motions leave the depth
      // mapping, and with it every comparison, unchanged.
      float q = std::max(sceneLs.max.z - sceneLs.min.z, 1e-3f) / 256.0f;
      c.zNear = std::floor(c.zNear / q) * q;
      c.zFar = std::ceil(c.zFar / q) * q;
    }
    c.proj = glm::orthoRH_ZO(c.min.x, c.max.x, c.min.y, c.max.y, c.zNear, c.zFar);
    c.viewProj = c.proj * set.lightView;
    set.cascades.push_back(c);
  }
  return set;
}

bool MayCastInto(const CascadeFit& c, const scene::Bounds& b) {
  if (b.empty()) return false;
  if (b.max.x < c.min.x || b.min.x > c.max.x || b.max.y < c.min.y || b.min.y > c.max.y) return false;
  return -b.max.z <= c.zFar;
}

}  // namespace sp::tech::csm
