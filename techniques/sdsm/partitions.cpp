#include "sdsm/partitions.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sp::tech::sdsm {
namespace {

constexpr uint32_t kMaxKMeansIterations = 64;  // SDSM_MAX_KMEANS_ITERATIONS

// The adaptive-log rule of partitions.h; integer tests as in the shader.
void AdaptiveLogPositions(const std::vector<uint32_t>& h, uint32_t K, uint32_t threshold, std::vector<float>& u) {
  uint32_t M = 0;
  for (uint32_t c : h) M += c > threshold ? 1u : 0u;
  if (M == 0) return;
  std::vector<uint32_t> snap(K, 0xffffffffu);  // (2 |iM - accK|) << 16 | gap end bin, smallest wins
  uint32_t acc = 0;
  for (uint32_t b = 0; b < h.size(); ++b) {
    if (h[b] <= threshold) continue;
    bool gapEnd = b > 0 && acc > 0 && h[b - 1] <= threshold;
    for (uint32_t i = 1; i < K; ++i) {
      uint32_t target = i * M;
      if (acc * K <= target && target < (acc + 1) * K) u[i] = float(b) + float(target - acc * K) / float(K);
      uint32_t distance2 = 2 * (target > acc * K ? target - acc * K : acc * K - target);
      if (gapEnd && distance2 < M) snap[i] = std::min(snap[i], (distance2 << 16) | b);
    }
    ++acc;
  }
  for (uint32_t i = 1; i < K; ++i)
    if (snap[i] != 0xffffffffu) u[i] = float(snap[i] & 0xffffu);
}

std::vector<float> KMeansCentres(const std::vector<uint32_t>& h, uint32_t K, uint32_t iterations) {
  const uint32_t N = uint32_t(h.size());
  std::vector<float> c(K);
  for (uint32_t k = 0; k < K; ++k) c[k] = (float(k) + 0.5f) * float(N) / float(K);
  std::vector<uint32_t> assign(N);
  for (uint32_t it = 0; it < std::min(iterations, kMaxKMeansIterations); ++it) {
    for (uint32_t b = 0; b < N; ++b) {
      float x = float(b) + 0.5f;
      uint32_t best = 0;
      float bestDistance = std::abs(x - c[0]);
      for (uint32_t k = 1; k < K; ++k) {
        float d = std::abs(x - c[k]);
        if (d < bestDistance) best = k, bestDistance = d;
      }
      assign[b] = best;
    }
    for (uint32_t k = 0; k < K; ++k) {
      float weight = 0.0f, moment = 0.0f;
      for (uint32_t b = 0; b < N; ++b) {
        if (assign[b] != k) continue;
        float w = float(h[b]);
        weight += w;
        moment += w * (float(b) + 0.5f);
      }
      if (weight > 0.0f) c[k] = moment / weight;
    }
  }
  return c;
}

}  // namespace

PartitionScheme ParsePartitionScheme(const std::string& name) {
  if (name == "log") return PartitionScheme::Log;
  if (name == "adaptive-log") return PartitionScheme::AdaptiveLog;
  if (name == "kmeans") return PartitionScheme::KMeans;
  throw std::invalid_argument("unknown partition scheme '" + name + "' (valid: log, adaptive-log, kmeans)");
}

std::string PartitionSchemeName(PartitionScheme scheme) {
  switch (scheme) {
    case PartitionScheme::Log: return "log";
    case PartitionScheme::AdaptiveLog: return "adaptive-log";
    case PartitionScheme::KMeans: return "kmeans";
  }
  return "?";
}

PartitionResult ComputePartitions(const PartitionSettings& s, float zMin, float zMax, const std::vector<uint32_t>& histogram,
                                  float fallbackNear, float fallbackFar) {
  if (histogram.empty()) throw std::invalid_argument("ComputePartitions: empty histogram");
  const uint32_t K = std::clamp(s.count, 1u, kMaxPartitions);
  const uint32_t N = uint32_t(histogram.size());
  bool covered = zMin <= zMax;
  PartitionScheme scheme = covered ? s.scheme : PartitionScheme::Log;
  if (!covered) zMin = fallbackNear, zMax = fallbackFar;

  PartitionResult r;
  r.positions.resize(K + 1);
  for (uint32_t i = 0; i <= K; ++i) r.positions[i] = float(i * N) / float(K);
  if (scheme == PartitionScheme::AdaptiveLog) AdaptiveLogPositions(histogram, K, s.gapThreshold, r.positions);
  if (scheme == PartitionScheme::KMeans) {
    r.centres = KMeansCentres(histogram, K, s.kmeansIterations);
    for (uint32_t i = 1; i < K; ++i) r.positions[i] = (r.centres[i - 1] + r.centres[i]) * 0.5f;
  }
  r.splits.resize(K + 1);
  for (uint32_t i = 0; i <= K; ++i) {
    float z = i == 0 ? zMin : zMax;
    if (i != 0 && i != K) z = std::clamp(DepthAtBinPosition(r.positions[i], zMin, zMax, N), zMin, zMax);
    r.splits[i] = z;
  }
  return r;
}

uint32_t HistogramBin(float z, float zMin, float zMax, uint32_t bins) {
  float lmin = std::log(zMin);
  float range = std::log(zMax) - lmin;
  float scale = range > 0.0f ? float(bins) / range : 0.0f;
  float t = (std::log(z) - lmin) * scale;
  return std::min(uint32_t(std::max(t, 0.0f)), bins - 1);
}

float DepthAtBinPosition(float u, float zMin, float zMax, uint32_t bins) {
  float lmin = std::log(zMin), lmax = std::log(zMax);
  return std::exp(lmin + (lmax - lmin) * (u / float(bins)));
}

uint32_t PartitionOf(float z, const std::vector<float>& splits) {
  uint32_t p = 0;
  for (uint32_t i = 1; i + 1 < splits.size(); ++i) p = z >= splits[i] ? i : p;
  return p;
}

uint32_t HistogramImageColumn(float z, float zMin, float zMax, uint32_t width) {
  float lmin = std::log(zMin), range = std::log(zMax) - lmin;
  float t = range > 0.0f ? (std::log(z) - lmin) / range : 0.0f;
  return std::min(uint32_t(std::max(t, 0.0f) * float(width)), width - 1);
}

std::vector<uint8_t> RenderHistogramImage(const std::vector<uint32_t>& histogram, float zMin, float zMax,
                                          const std::vector<float>& splits, uint32_t width, uint32_t height) {
  std::vector<uint8_t> img(size_t(width) * height * 4);
  auto put = [&](uint32_t x, uint32_t y, uint8_t r, uint8_t g, uint8_t b) {
    uint8_t* p = &img[(size_t(y) * width + x) * 4];
    p[0] = r, p[1] = g, p[2] = b, p[3] = 255;
  };
  // Columns take the bins they cover; a bin wider than a column spreads over several columns.
  const size_t N = histogram.size();
  std::vector<double> column(width, 0.0);
  for (uint32_t x = 0; x < width; ++x) {
    size_t b0 = size_t(x) * N / width, b1 = std::max(b0 + 1, size_t(x + 1) * N / width);
    for (size_t b = b0; b < b1 && b < N; ++b) column[x] = std::max(column[x], std::sqrt(double(histogram[b])));
  }
  double tallest = std::max(1e-9, *std::max_element(column.begin(), column.end()));
  std::vector<uint32_t> partitionOfColumn(width, 0), splitColumns;
  for (size_t i = 1; i + 1 < splits.size(); ++i) splitColumns.push_back(HistogramImageColumn(splits[i], zMin, zMax, width));
  for (uint32_t x = 0; x < width; ++x)
    for (uint32_t c : splitColumns) partitionOfColumn[x] += x >= c ? 1u : 0u;
  for (uint32_t x = 0; x < width; ++x) {
    uint32_t bar = uint32_t(std::lround(column[x] / tallest * (height - 1)));
    bool odd = partitionOfColumn[x] % 2 == 1;
    for (uint32_t y = 0; y < height; ++y) {
      bool filled = height - 1 - y < bar;
      if (filled) put(x, y, 40, 70, 160);
      else if (odd) put(x, y, 228, 232, 240);
      else put(x, y, 248, 248, 248);
    }
  }
  for (uint32_t c : splitColumns)
    for (uint32_t y = 0; y < height; ++y) put(c, y, 220, 30, 30);
  return img;
}

}  // namespace sp::tech::sdsm
