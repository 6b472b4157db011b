#include "metrics.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

namespace sp::eval {

void Accuracy::add(const Accuracy& o) {
  receiving += o.receiving;
  falseLit += o.falseLit;
  falseShadow += o.falseShadow;
  absErrorSum += o.absErrorSum;
  penumbra += o.penumbra;
  penumbraAbsErrorSum += o.penumbraAbsErrorSum;
  umbra += o.umbra;
  umbraLeaked += o.umbraLeaked;
  umbraVisibilitySum += o.umbraVisibilitySum;
}

namespace {

void Judge(Accuracy& a, float v, float ref) {
  bool lit = v >= kLitThreshold, refLit = ref >= kLitThreshold;
  ++a.receiving;
  if (lit && !refLit) ++a.falseLit;
  if (!lit && refLit) ++a.falseShadow;
  a.absErrorSum += std::abs(double(v) - double(ref));
  if (ref > 0.0f && ref < 1.0f) {
    ++a.penumbra;
    a.penumbraAbsErrorSum += std::abs(double(v) - double(ref));
  }
  if (ref == 0.0f) {
    ++a.umbra;
    if (v > kUmbraLeakThreshold) ++a.umbraLeaked;
    a.umbraVisibilitySum += double(v);
  }
}

}  // namespace

std::vector<float> ReferenceAsFloat(const tech::LabBuffers& lab, const uint8_t* reference) {
  std::vector<float> f(lab.size(), 0.0f);
  for (size_t i = 0; i < f.size(); ++i) f[i] = reference[i] ? 1.0f : 0.0f;
  return f;
}

LabSurfacePoints SurfacePointsOf(const tech::LabBuffers& lab) {
  const size_t n = lab.size();
  LabSurfacePoints p;
  p.position.resize(n);
  p.normal.resize(n);
  p.valid.resize(n);
  for (size_t i = 0; i < n; ++i) {
    glm::vec3 x(lab.position[i]), nrm(lab.normal[i]);
    p.position[i] = x;
    p.normal[i] = nrm;
    bool finite = std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z) && glm::length(nrm) > 0.5f;
    p.valid[i] = lab.receiving(i) && finite ? 1 : 0;
  }
  return p;
}

Accuracy MeasureAccuracy(const tech::LabBuffers& lab, const uint8_t* reference) {
  return MeasureAccuracy(lab, ReferenceAsFloat(lab, reference).data());
}

Accuracy MeasureAccuracy(const tech::LabBuffers& lab, const float* reference) {
  Accuracy a;
  for (size_t i = 0; i < lab.size(); ++i)
    if (lab.receiving(i)) Judge(a, lab.visibility[i], reference[i]);
  return a;
}

Accuracy MeasureRegionAccuracy(const tech::LabBuffers& lab, const float* reference, const scene::Region& region) {
  Accuracy a;
  for (size_t i = 0; i < lab.size(); ++i)
    if (lab.receiving(i) && region.contains(glm::vec3(lab.position[i]))) Judge(a, lab.visibility[i], reference[i]);
  return a;
}

float CubeEdgeGap(const glm::vec3& d) {
  glm::vec3 a = glm::abs(d);
  float ma = std::max({a.x, a.y, a.z});
  // The second largest: the largest of the pairwise minima.
  float second = std::max({std::min(a.x, a.y), std::min(a.y, a.z), std::min(a.x, a.z)});
  return ma > 0.0f ? (ma - second) / ma : 0.0f;
}

SeamAccuracy MeasureSeamAccuracy(const tech::LabBuffers& lab, const uint8_t* reference, const glm::vec3& light, float band) {
  return MeasureSeamAccuracy(lab, ReferenceAsFloat(lab, reference).data(), light, band);
}

SeamAccuracy MeasureSeamAccuracy(const tech::LabBuffers& lab, const float* reference, const glm::vec3& light, float band) {
  if (!(band > 0.0f && band < 1.0f)) throw std::invalid_argument("seam band " + std::to_string(band) + " is outside (0, 1)");
  SeamAccuracy s;
  for (size_t i = 0; i < lab.size(); ++i)
    if (lab.receiving(i))
      Judge(CubeEdgeGap(glm::vec3(lab.position[i]) - light) < band ? s.band : s.elsewhere, lab.visibility[i], reference[i]);
  return s;
}

// --- LogHistogram

LogHistogram::LogHistogram() : bins_(size_t(kMaxExp - kMinExp) * kPerOctave, 0) {}

void LogHistogram::add(double value) {
  if (!(value > 0.0) || !std::isfinite(value)) return;
  double pos = (std::log2(value) - kMinExp) * kPerOctave;
  size_t bin = size_t(std::clamp(pos, 0.0, double(bins_.size() - 1)));
  ++bins_[bin];
  min_ = count_ ? std::min(min_, value) : value;
  max_ = count_ ? std::max(max_, value) : value;
  ++count_;
}

void LogHistogram::add(const LogHistogram& o) {
  if (!o.count_) return;
  for (size_t i = 0; i < bins_.size(); ++i) bins_[i] += o.bins_[i];
  min_ = count_ ? std::min(min_, o.min_) : o.min_;
  max_ = count_ ? std::max(max_, o.max_) : o.max_;
  count_ += o.count_;
}

double LogHistogram::percentile(double p) const {
  if (!count_) return 0.0;
  // The rank sits within a bin: spread that bin's values evenly over its logarithmic width.
  double rank = std::clamp(p, 0.0, 1.0) * double(count_);
  uint64_t before = 0;
  for (size_t i = 0; i < bins_.size(); ++i) {
    if (!bins_[i]) continue;
    if (double(before + bins_[i]) >= rank || i + 1 == bins_.size()) {
      double f = std::clamp((rank - double(before)) / double(bins_[i]), 0.0, 1.0);
      return std::clamp(std::exp2((double(i) + f) / kPerOctave + kMinExp), min_, max_);
    }
    before += bins_[i];
  }
  return 0.0;
}

void AddTexelDensity(const tech::LabBuffers& lab, LogHistogram& h) {
  for (size_t i = 0; i < lab.size(); ++i)
    if (lab.receiving(i) && lab.lookup[i].x >= 0.0f) h.add(lab.lookup[i].w);
}

int CubeFace(const glm::vec3& d) {
  glm::vec3 a = glm::abs(d);
  if (a.z >= a.x && a.z >= a.y) return d.z >= 0 ? 4 : 5;
  if (a.y >= a.x) return d.y >= 0 ? 2 : 3;
  return d.x >= 0 ? 0 : 1;
}

void AddTexelDensityByFace(const tech::LabBuffers& lab, const glm::vec3& light, std::array<LogHistogram, 6>& h) {
  for (size_t i = 0; i < lab.size(); ++i)
    if (lab.receiving(i) && lab.lookup[i].x >= 0.0f) h[size_t(CubeFace(glm::vec3(lab.position[i]) - light))].add(lab.lookup[i].w);
}

// --- Utilization

double MeasureUtilization(const tech::LabBuffers& lab, const std::vector<tech::ShadowLayer>& layers) {
  uint64_t total = 0;
  std::vector<std::vector<bool>> hit(layers.size());
  for (size_t l = 0; l < layers.size(); ++l) {
    hit[l].assign(size_t(layers[l].width) * layers[l].height, false);
    total += hit[l].size();
  }
  if (!total) return 0.0;
  uint64_t used = 0;
  for (size_t i = 0; i < lab.size(); ++i) {
    if (!lab.receiving(i)) continue;
    const glm::vec4& k = lab.lookup[i];
    if (!(k.x >= 0.0f) || !std::isfinite(k.y) || !std::isfinite(k.z)) continue;
    size_t l = size_t(k.x + 0.5f);
    if (l >= layers.size()) continue;
    // Texel i covers [i, i+1); the map's far edge (coordinate == size) belongs to the last texel.
    int64_t w = layers[l].width, h = layers[l].height;
    int64_t x = std::clamp<int64_t>(int64_t(std::floor(k.y)), 0, w - 1);
    int64_t y = std::clamp<int64_t>(int64_t(std::floor(k.z)), 0, h - 1);
    std::vector<bool>::reference bit = hit[l][size_t(y * w + x)];
    if (!bit) {
      bit = true;
      ++used;
    }
  }
  return double(used) / double(total);
}

// --- Flicker

void Flicker::add(const Flicker& o) {
  pixels += o.pixels;
  sum += o.sum;
  unmatched += o.unmatched;
}

Flicker MeasureFlicker(const tech::LabBuffers& now, const tech::LabBuffers& before) {
  Flicker f;
  for (size_t i = 0; i < now.size() && i < before.size(); ++i) {
    if (!now.receiving(i)) continue;
    if (std::memcmp(&now.position[i], &before.position[i], sizeof(glm::vec4)) != 0) {
      ++f.unmatched;
      continue;
    }
    ++f.pixels;
    f.sum += std::abs(double(now.visibility[i]) - double(before.visibility[i]));
  }
  return f;
}

Flicker MeasureReprojectedFlicker(const tech::LabBuffers& prev, const float* prevValue, const tech::LabBuffers& cur,
                                  const float* curValue) {
  Flicker f;
  for (size_t i = 0; i < cur.size(); ++i) {
    if (!cur.receiving(i)) continue;
    glm::vec3 x(cur.position[i]);
    glm::vec4 clip = prev.viewProj * glm::vec4(x, 1.0f);
    if (!(clip.w > 0.0f)) continue;
    // D3D conventions: NDC +y is the top row; pixel (0, 0) is the top-left.
    float px = (clip.x / clip.w * 0.5f + 0.5f) * float(prev.width);
    float py = (0.5f - clip.y / clip.w * 0.5f) * float(prev.height);
    if (!(px >= 0.0f && py >= 0.0f && px < float(prev.width) && py < float(prev.height))) continue;
    size_t j = size_t(py) * prev.width + size_t(px);
    if (!prev.receiving(j)) continue;
    float expected = glm::length(x - prev.cameraPosition);
    float found = glm::length(glm::vec3(prev.position[j]) - prev.cameraPosition);
    if (std::abs(found - expected) > kReprojectionTolerance * expected) continue;
    ++f.pixels;
    f.sum += std::abs(double(curValue[i]) - double(prevValue[j]));
  }
  return f;
}

}  // namespace sp::eval
