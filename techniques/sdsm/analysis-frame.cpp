#include "sdsm/analysis-frame.h"

#include <cmath>
#include <cstring>
#include <glm/ext/matrix_clip_space.hpp>
#include <limits>
#include <stdexcept>

namespace sp::tech::sdsm {
namespace {

uint32_t Bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}
float FromBits(uint32_t u) {
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

}  // namespace

glm::mat4 MakeLightView(const glm::vec3& cameraPosition, const glm::vec3& cameraForward, const glm::vec3& cameraUp,
                        const glm::vec3& lightDirection) {
  glm::vec3 l = glm::normalize(lightDirection);
  glm::vec3 z = -l;
  auto flatten = [&](glm::vec3 v) { return v - glm::dot(v, l) * l; };
  glm::vec3 x = flatten(glm::normalize(cameraForward));
  if (glm::length(x) < 1e-4f) x = flatten(glm::normalize(cameraUp));
  if (glm::length(x) < 1e-4f) x = flatten(std::abs(l.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0));
  x = glm::normalize(x);
  glm::vec3 y = glm::cross(z, x);
  glm::mat4 v(1.0f);
  for (int i = 0; i < 3; ++i) {
    v[i][0] = x[i];
    v[i][1] = y[i];
    v[i][2] = z[i];
  }
  v[3] = glm::vec4(-glm::dot(x, cameraPosition), -glm::dot(y, cameraPosition), -glm::dot(z, cameraPosition), 1.0f);
  return v;
}

uint32_t OrderedKey(float f) {
  uint32_t u = Bits(f);
  return (u & 0x80000000u) ? ~u : (u | 0x80000000u);
}

float FromOrderedKey(uint32_t k) { return FromBits((k & 0x80000000u) ? (k & 0x7fffffffu) : ~k); }

AnalysisFrame AnalysisFrame::Make(const glm::mat4& cameraView, const glm::mat4& P, const glm::mat4& lightView, uint32_t width,
                                  uint32_t height) {
  // glm is column-major: P[column][row]. A perspective projection has w = -z_view.
  if (P[2][3] != -1.0f || P[3][3] != 0.0f || P[0][3] != 0.0f || P[1][3] != 0.0f)
    throw std::invalid_argument("AnalysisFrame: the camera projection must be a right-handed perspective projection");
  // The passes take depth 1.0 for sky: a reversed-Z projection (depth 1 at the near plane) would
  // analyse the sky and drop the nearest pixels.
  if (P[2][2] >= 0.0f) throw std::invalid_argument("AnalysisFrame: reversed-Z projections are not supported (sky must be depth 1.0)");
  if (width == 0 || height == 0) throw std::invalid_argument("AnalysisFrame: empty depth buffer");
  AnalysisFrame f;
  f.width = width;
  f.height = height;
  // d = (P22 z + P32) / -z with vd = -z  =>  vd = -P32 / (-P22 - d).
  f.depthA = -P[3][2];
  f.depthB = -P[2][2];
  f.nearZ = float(double(f.depthA) / double(f.depthB));
  f.farZ = float(double(f.depthA) / (double(f.depthB) - 1.0));
  f.ndcScale = glm::vec2(2.0f / float(width), -2.0f / float(height));
  f.ndcOffset = glm::vec2(-1.0f, 1.0f);
  // ndc.x = (P00 x + P20 z) / -z  =>  x / vd = ndc.x / P00 + P20 / P00 (and likewise for y).
  f.rayScale = glm::vec2(1.0f / P[0][0], 1.0f / P[1][1]);
  f.rayOffset = glm::vec2(P[2][0] / P[0][0], P[2][1] / P[1][1]);
  glm::mat4 lightFromView = lightView * glm::inverse(cameraView);
  f.lightRayX = glm::vec3(lightFromView[0]);
  f.lightRayY = glm::vec3(lightFromView[1]);
  f.lightRayZ = -glm::vec3(lightFromView[2]);
  f.lightOrigin = glm::vec3(lightFromView[3]);
  f.lightView = lightView;
  return f;
}

float AnalysisFrame::ViewDepth(float d) const { return depthA / (depthB - d); }

glm::vec3 AnalysisFrame::LightPosition(uint32_t x, uint32_t y, float z) const {
  float ndcX = (float(x) + 0.5f) * ndcScale.x + ndcOffset.x;
  float ndcY = (float(y) + 0.5f) * ndcScale.y + ndcOffset.y;
  float rx = ndcX * rayScale.x + rayOffset.x;
  float ry = ndcY * rayScale.y + rayOffset.y;
  glm::vec3 p;
  for (int i = 0; i < 3; ++i) {
    float l = lightRayX[i] * rx + lightRayY[i] * ry + lightRayZ[i];
    p[i] = lightOrigin[i] + l * z;
  }
  return p;
}

AnalysisResults DecodeResults(const uint32_t* w) {
  AnalysisResults r;
  r.zMin = FromBits(w[kWordMin]);
  r.zMax = FromBits(w[kWordMax]);
  r.samples = w[kWordSamples];
  r.partitionCount = std::min(w[kWordPartitions], kMaxPartitions);
  for (uint32_t i = 0; i <= r.partitionCount && r.partitionCount; ++i) r.splits.push_back(FromBits(w[kWordSplits + i]));
  for (uint32_t p = 0; p < r.partitionCount; ++p) {
    const uint32_t* b = w + kWordBounds + p * 8;
    LightBounds lb;
    lb.samples = b[3];
    if (lb.samples) {
      lb.min = glm::vec3(FromOrderedKey(b[0]), FromOrderedKey(b[1]), FromOrderedKey(b[2]));
      lb.max = glm::vec3(FromOrderedKey(b[4]), FromOrderedKey(b[5]), FromOrderedKey(b[6]));
    }
    r.bounds.push_back(lb);
  }
  return r;
}

std::vector<uint32_t> EncodeResults(const AnalysisResults& r) {
  std::vector<uint32_t> w(kResultWords, 0);
  w[kWordMin] = Bits(r.zMin);
  w[kWordMax] = Bits(r.zMax);
  w[kWordSamples] = r.samples;
  w[kWordPartitions] = r.partitionCount;
  for (size_t i = 0; i < r.splits.size() && i <= kMaxPartitions; ++i) w[kWordSplits + i] = Bits(r.splits[i]);
  for (uint32_t p = 0; p < kMaxPartitions; ++p) {
    uint32_t* b = &w[kWordBounds + p * 8];
    const LightBounds* lb = p < r.bounds.size() ? &r.bounds[p] : nullptr;
    bool has = lb && !lb->empty();
    for (int a = 0; a < 3; ++a) {
      b[a] = has ? OrderedKey(lb->min[a]) : 0xffffffffu;
      b[4 + a] = has ? OrderedKey(lb->max[a]) : 0u;
    }
    b[3] = has ? lb->samples : 0u;
  }
  return w;
}

glm::mat4 PartitionProjection(const LightBounds& b, float dilation) {
  glm::vec3 lo = b.min - dilation, hi = b.max + dilation;
  // Degenerate boxes (a single sample, a flat receiver facing the light) still need a volume.
  for (int a = 0; a < 3; ++a) {
    float pad = std::max(1e-4f, 1e-6f * std::max(std::abs(lo[a]), std::abs(hi[a])));
    if (hi[a] - lo[a] < pad) lo[a] -= pad, hi[a] += pad;
  }
  // Looking down -z: the near plane (depth 0) is at z = hi.z, the far plane at z = lo.z.
  return glm::orthoRH_ZO(lo.x, hi.x, lo.y, hi.y, -hi.z, -lo.z);
}

LightBounds FrustumSliceBounds(const glm::mat4& cameraView, const glm::mat4& P, const glm::mat4& lightView, float zNear, float zFar) {
  glm::mat4 lightFromView = lightView * glm::inverse(cameraView);
  LightBounds b;
  b.min = glm::vec3(std::numeric_limits<float>::max());
  b.max = glm::vec3(-std::numeric_limits<float>::max());
  for (float vd : {zNear, zFar})
    for (float sx : {-1.0f, 1.0f})
      for (float sy : {-1.0f, 1.0f}) {
        glm::vec3 view(vd * (sx + P[2][0]) / P[0][0], vd * (sy + P[2][1]) / P[1][1], -vd);
        glm::vec3 l = glm::vec3(lightFromView * glm::vec4(view, 1.0f));
        b.min = glm::min(b.min, l);
        b.max = glm::max(b.max, l);
      }
  b.samples = 1;  // stands for "some receiver may be here"
  return b;
}

}  // namespace sp::tech::sdsm
