// The viewer's overlay pictures (overlay.h).
#include "overlay.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sp::viewer {
namespace {

// Hues far apart in order, so neighbouring cascades never look alike: red, green, blue, yellow,
// magenta, cyan, orange, violet.
constexpr std::array<uint8_t, 3> kLayerTints[kLayerTintCount] = {{230, 40, 40},  {40, 200, 40},  {50, 90, 240}, {230, 220, 40},
                                                                  {220, 50, 220}, {40, 210, 220}, {250, 140, 20}, {140, 70, 220}};
constexpr const char* kNames[] = {"none", "layers", "density", "error", "shadowmap"};

}  // namespace

const char* OverlayName(Overlay o) { return kNames[int(o)]; }

bool ParseOverlay(const std::string& name, Overlay* out) {
  for (int i = 0; i < 5; ++i)
    if (name == kNames[i]) {
      *out = Overlay(i);
      return true;
    }
  return false;
}

std::array<uint8_t, 3> LayerTint(int layer) { return kLayerTints[size_t(std::max(layer, 0)) % kLayerTintCount]; }

int LayerOf(const tech::LabBuffers& lab, size_t i) {
  if (!lab.drawn(i)) return -1;
  float l = lab.lookup[i].x;
  return l < 0.0f ? -1 : int(std::lround(l));
}

std::vector<uint8_t> ComposeLayerColours(const tech::LabBuffers& lab) {
  std::vector<uint8_t> out(lab.color);
  for (size_t i = 0; i < lab.size(); ++i) {
    uint8_t* p = &out[i * 4];
    p[3] = 255;
    int k = LayerOf(lab, i);
    if (k < 0) continue;
    std::array<uint8_t, 3> t = LayerTint(k);
    for (int c = 0; c < 3; ++c) p[c] = uint8_t((unsigned(p[c]) + t[size_t(c)]) / 2);
  }
  return out;
}

std::vector<uint8_t> TileShadowMap(const MapImage& map, uint32_t width, uint32_t height) {
  std::vector<uint8_t> out(size_t(width) * height * 4, 0);
  for (size_t i = 3; i < out.size(); i += 4) out[i] = 255;
  if (!map.layers || !map.width || !map.height || map.values.size() != size_t(map.width) * map.height * map.layers) return out;
  const uint32_t cols = uint32_t(std::ceil(std::sqrt(double(map.layers))));
  const uint32_t rows = (map.layers + cols - 1) / cols;
  const double cellW = double(width) / cols, cellH = double(height) / rows;
  const double scale = std::min(cellW / map.width, cellH / map.height);  // output pixels per texel
  const uint32_t tileW = uint32_t(map.width * scale), tileH = uint32_t(map.height * scale);
  const size_t slice = size_t(map.width) * map.height;
  for (uint32_t l = 0; l < map.layers; ++l) {
    const float* v = &map.values[l * slice];
    // "Nothing drawn": depth 1, or a moment map's largest value (what depth 1 becomes).
    float top = 1.0f;
    if (!map.depth) {
      top = std::numeric_limits<float>::lowest();
      for (size_t i = 0; i < slice; ++i)
        if (std::isfinite(v[i])) top = std::max(top, v[i]);
    }
    float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
    for (size_t i = 0; i < slice; ++i)
      if (std::isfinite(v[i]) && v[i] < top) lo = std::min(lo, v[i]), hi = std::max(hi, v[i]);
    // ESM's and EVSM's exp(c z) span orders of magnitude: shown on a log scale.
    const bool logScale = !map.depth && lo > 0.0f && hi > 100.0f * lo;
    auto f = [&](double x) { return logScale ? std::log(x) : x; };
    const uint32_t x0 = uint32_t((l % cols) * cellW), y0 = uint32_t((l / cols) * cellH);
    for (uint32_t y = 0; y < tileH && y0 + y < height; ++y)
      for (uint32_t x = 0; x < tileW && x0 + x < width; ++x) {
        uint32_t tx = std::min(map.width - 1, uint32_t(x / scale)), ty = std::min(map.height - 1, uint32_t(y / scale));
        float d = v[size_t(ty) * map.width + tx];
        uint8_t g = 255;
        if (!std::isfinite(d)) g = 0;
        else if (d < top) g = uint8_t(std::lround(hi > lo ? 255.0 * (f(d) - f(lo)) / (f(hi) - f(lo)) : 0.0));
        uint8_t* p = &out[(size_t(y0 + y) * width + x0 + x) * 4];
        p[0] = p[1] = p[2] = g;
      }
  }
  return out;
}

}  // namespace sp::viewer
