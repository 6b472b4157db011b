#include "sdsm/sdsm-technique-fit.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace sp::tech::sdsm {
namespace {

float FromBits(uint32_t u) {
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

// The smallest power of two >= x on the float's bits (as fit.hlsl's CeilPow2): exact.
float CeilPow2(float x) {
  uint32_t u;
  std::memcpy(&u, &x, 4);
  return FromBits((u + 0x007fffffu) & 0xff800000u);
}

}  // namespace

FrustumRays MakeFrustumRays(const glm::mat4& lightView, const glm::mat4& cameraView, const glm::mat4& P) {
  glm::mat4 lightFromView = lightView * glm::inverse(cameraView);
  FrustumRays r;
  r.origin = glm::vec3(lightFromView[3]);
  for (int i = 0; i < 4; ++i) {
    float sx = (i & 1) ? 1.0f : -1.0f, sy = (i & 2) ? 1.0f : -1.0f;
    r.corner[i] = glm::vec3(lightFromView * glm::vec4((sx + P[2][0]) / P[0][0], (sy + P[2][1]) / P[1][1], -1.0f, 0.0f));
  }
  return r;
}

LightBounds SliceBounds(const FrustumRays& rays, float z0, float z1) {
  LightBounds b;
  b.min = glm::vec3(1e30f);
  b.max = glm::vec3(-1e30f);
  for (int i = 0; i < 8; ++i) {
    float z = i < 4 ? z0 : z1;
    glm::vec3 q;
    for (int a = 0; a < 3; ++a) q[a] = rays.origin[a] + rays.corner[i & 3][a] * z;
    b.min = glm::min(b.min, q);
    b.max = glm::max(b.max, q);
  }
  b.samples = 1;
  return b;
}

bool PartitionFit::MayCast(const scene::Bounds& b) const {
  if (empty) return false;
  return b.max.x >= min.x && b.max.y >= min.y && b.min.x <= max.x && b.min.y <= max.y && b.max.z >= min.z;
}

PartitionFit FitPartition(const LightBounds& bounds, float splitNear, float splitFar, const glm::mat4& lightView, const FitParams& p) {
  PartitionFit f;
  f.splitNear = splitNear;
  f.splitFar = splitFar;
  if (bounds.empty()) return f;
  f.empty = false;
  const float N = float(p.resolution);
  glm::vec3 lo = bounds.min - p.dilation, hi = bounds.max + p.dilation;
  glm::vec2 size = glm::max(glm::vec2(hi) - glm::vec2(lo), glm::vec2(1e-3f));
  glm::vec2 centre = (glm::vec2(lo) + glm::vec2(hi)) * 0.5f;
  float pad = float(p.padTexels);
  if (p.blurWorld > 0.0f) pad += std::min(std::ceil(p.blurWorld * N / std::max(size.x, size.y)), float(p.blurMaxTexels));
  size = size * (N / (N - 2.0f * pad));
  if (p.quantize) {
    // One texel to spare: snapping moves the centre by up to half a texel.
    glm::vec2 s = size * (N / (N - 1.0f));
    size = glm::vec2(CeilPow2(s.x), CeilPow2(s.y));
    glm::vec2 t = size / N, g(p.gridOrigin);
    centre = g + glm::floor((centre - g) / t + 0.5f) * t;
  }
  lo.x = centre.x - size.x * 0.5f;
  lo.y = centre.y - size.y * 0.5f;
  hi.x = centre.x + size.x * 0.5f;
  hi.y = centre.y + size.y * 0.5f;
  float texel = std::max(size.x, size.y) / N;
  float zPad = pad * texel + 1e-4f * (std::abs(lo.z) + std::abs(hi.z)) + 1e-4f;
  lo.z = lo.z - zPad;
  hi.z = hi.z + zPad;
  hi.z = std::max(hi.z, p.casterTop);

  glm::vec3 extent = hi - lo;
  f.min = lo;
  f.max = hi;
  f.texelWorld = texel;
  f.padTexels = pad;
  f.scale = glm::vec3(1.0f / extent.x, -1.0f / extent.y, -1.0f / extent.z);
  f.offset = glm::vec3(-lo.x * f.scale.x, hi.y / extent.y, hi.z / extent.z);
  // Light view -> clip: x = 2u - 1, y = 1 - 2v, z = depth (glm: m[column][row]).
  glm::mat4 clip(0.0f);
  for (int c = 0; c < 4; ++c) {
    clip[c][0] = lightView[c][0] * (2.0f * f.scale.x);
    clip[c][1] = lightView[c][1] * (-2.0f * f.scale.y);
    clip[c][2] = lightView[c][2] * f.scale.z;
  }
  clip[3][0] += 2.0f * f.offset.x - 1.0f;
  clip[3][1] += 1.0f - 2.0f * f.offset.y;
  clip[3][2] += f.offset.z;
  clip[3][3] = 1.0f;
  f.viewProj = clip;
  return f;
}

CsmShadowConstants MakeConstants(const std::vector<PartitionFit>& fits, const glm::mat4& lightView, const glm::vec3& cameraForward,
                                 const glm::vec4& settings, uint32_t resolution, const glm::vec4& pcss) {
  CsmShadowConstants k{};
  const float N = float(resolution);
  k.lightView = lightView;
  for (size_t c = 0; c < fits.size() && c < 8; ++c) {
    const PartitionFit& f = fits[c];
    k.region[c] = glm::vec4(0.0f, 0.0f, 1.0f, 1.0f);
    k.cascade[c] = glm::vec4(f.splitNear, f.splitFar, f.empty ? 0.0f : f.texelWorld, float(c));
    if (f.empty) {
      // Nothing inside: map selection's test fails, a lookup lands beyond the far plane (lit).
      k.toMapScale[c] = glm::vec4(0.0f);
      k.toMapOffset[c] = glm::vec4(-1.0f, -1.0f, 2.0f, 0.0f);
    } else {
      k.toMapScale[c] = glm::vec4(f.scale, f.padTexels / N);
      k.toMapOffset[c] = glm::vec4(f.offset, 0.0f);
    }
  }
  k.cameraForward = glm::vec4(cameraForward, float(fits.size()));
  k.settings = settings;
  k.mapInfo = glm::vec4(1.0f / N, 1.0f / N, 0.0f, N);
  k.pcss = pcss;
  return k;
}

std::vector<PartitionFit> DecodeFitBuffer(const std::vector<uint32_t>& words, uint32_t partitions) {
  std::vector<PartitionFit> fits;
  if (words.size() < kFitBytes / 4) return fits;
  CsmShadowConstants k;
  std::memcpy(&k, words.data() + kFitConstantsOffset / 4, sizeof(k));
  const float N = k.mapInfo.w;
  for (uint32_t p = 0; p < partitions && p < kMaxPartitions; ++p) {
    PartitionFit f;
    const uint32_t* b = words.data() + kWordBounds + p * 8;
    f.empty = b[3] == 0;
    f.splitNear = k.cascade[p].x;
    f.splitFar = k.cascade[p].y;
    if (!f.empty) {
      f.min = glm::vec3(FromOrderedKey(b[0]), FromOrderedKey(b[1]), FromOrderedKey(b[2]));
      f.max = glm::vec3(FromOrderedKey(b[4]), FromOrderedKey(b[5]), FromOrderedKey(b[6]));
      f.texelWorld = k.cascade[p].z;
      f.padTexels = k.toMapScale[p].w * N;
      f.scale = glm::vec3(k.toMapScale[p]);
      f.offset = glm::vec3(k.toMapOffset[p]);
      const uint32_t* m = words.data() + (kFitMatricesOffset + p * 64) / 4;
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) f.viewProj[c][r] = FromBits(m[r * 4 + c]);
    }
    fits.push_back(f);
  }
  return fits;
}

std::vector<float> DecodeFitBlurRadii(const std::vector<uint32_t>& words, uint32_t partitions) {
  std::vector<float> radii;
  if (words.size() < kFitBytes / 4) return radii;
  for (uint32_t p = 0; p < partitions && p < kMaxPartitions; ++p) radii.push_back(FromBits(words[kFitBlurOffset / 4 + p]));
  return radii;
}

std::vector<uint8_t> RenderLightSpaceImage(const std::vector<glm::vec3>& samples, const std::vector<PartitionFit>& fits, uint32_t w,
                                           uint32_t h) {
  static const uint8_t kPalette[8][3] = {{228, 26, 28},  {55, 126, 184}, {77, 175, 74},  {152, 78, 163},
                                         {255, 127, 0}, {166, 86, 40},  {247, 129, 191}, {90, 90, 90}};
  std::vector<uint8_t> img(size_t(w) * h * 4, 255);
  glm::vec2 lo(1e30f), hi(-1e30f);
  for (const glm::vec3& s : samples) lo = glm::min(lo, glm::vec2(s)), hi = glm::max(hi, glm::vec2(s));
  for (const PartitionFit& f : fits)
    if (!f.empty) lo = glm::min(lo, glm::vec2(f.min)), hi = glm::max(hi, glm::vec2(f.max));
  if (lo.x > hi.x) return img;
  // One scale for both axes (the picture keeps light-space proportions), 4% margin.
  glm::vec2 centre = (lo + hi) * 0.5f;
  float span = std::max((hi.x - lo.x) / float(w), (hi.y - lo.y) / float(h)) * 1.08f;
  span = std::max(span, 1e-6f);
  auto toPixel = [&](glm::vec2 p) {
    glm::vec2 q = (p - centre) / span;
    return glm::ivec2(int(std::floor(q.x + w * 0.5f)), int(std::floor(h * 0.5f - q.y)));
  };
  auto put = [&](glm::ivec2 q, const uint8_t* c, float alpha) {
    if (q.x < 0 || q.y < 0 || q.x >= int(w) || q.y >= int(h)) return;
    uint8_t* d = &img[(size_t(q.y) * w + q.x) * 4];
    for (int i = 0; i < 3; ++i) d[i] = uint8_t(d[i] * (1.0f - alpha) + c[i] * alpha);
  };
  for (const glm::vec3& s : samples) put(toPixel(glm::vec2(s)), kPalette[uint32_t(s.z) % 8], 0.7f);
  for (size_t p = 0; p < fits.size(); ++p) {
    if (fits[p].empty) continue;
    glm::ivec2 a = toPixel(glm::vec2(fits[p].min)), b = toPixel(glm::vec2(fits[p].max));
    const uint8_t* c = kPalette[p % 8];
    for (int x = std::min(a.x, b.x); x <= std::max(a.x, b.x); ++x) put({x, a.y}, c, 1.0f), put({x, b.y}, c, 1.0f);
    for (int y = std::min(a.y, b.y); y <= std::max(a.y, b.y); ++y) put({a.x, y}, c, 1.0f), put({b.x, y}, c, 1.0f);
  }
  return img;
}

}  // namespace sp::tech::sdsm
