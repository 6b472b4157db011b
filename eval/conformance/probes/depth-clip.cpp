// DepthClipEnable: TRUE clips geometry beyond the near and far planes; FALSE keeps it and clamps
// its depth to the viewport's [MinDepth, MaxDepth] (the "pancaking" of shadow casters behind the
// light's near plane). Expected coverage and depth come from the plane equation per pixel.
#include <algorithm>

#include "probe-helpers.h"

namespace sp::conformance {
namespace {

const char* kGroup = "Depth clip";
constexpr uint32_t W = 32, H = 8;
constexpr float kClear = 0.25f;  // drawn pixels are never 0.25 in these cases

// Depth plane z = a + b * ndcX across the viewport, from -0.5 at the left to 1.5 at the right.
struct Plane {
  double a = 0.5, b = 1.0;
  double at(uint32_t x) const { return a + b * ((x + 0.5) / W * 2 - 1); }
};

Result Check(Device& device, bool clipEnable, float minDepth, float maxDepth) {
  Plane p;
  std::vector<DepthVertex> v = {{-1, -1, float(p.a - p.b)}, {-1, 3, float(p.a - p.b)}, {3, -1, float(p.a + 3 * p.b)}};
  RASTERIZER_DESC rd;
  rd.CullMode = CULL_NONE;
  rd.DepthClipEnable = clipEnable;
  VIEWPORT vp{0, 0, float(W), float(H), minDepth, maxDepth};
  std::vector<double> got = DrawDepth(device, FORMAT_D32_FLOAT, W, H, v, PRIMITIVE_TOPOLOGY_TRIANGLELIST, rd, kClear, &vp);
  int wrong = 0;
  double worst = 0;
  std::string detail;
  for (uint32_t x = 0; x < W; ++x) {
    double z = p.at(x);  // NDC depth before the viewport transform
    // Pixels whose centre lies within half a pixel of a clip boundary may go either way.
    double dzPerPixel = p.b * 2.0 / W;
    if (std::abs(z) < dzPerPixel || std::abs(z - 1.0) < dzPerPixel) continue;
    bool inside = z >= 0.0 && z <= 1.0;
    double windowZ = minDepth + z * (maxDepth - minDepth);
    double expected = clipEnable ? (inside ? windowZ : kClear) : std::clamp(windowZ, double(minDepth), double(maxDepth));
    for (uint32_t y = 0; y < H; ++y) {
      double g = got[y * W + x];
      bool drawn = g != kClear;
      bool shouldDraw = expected != kClear;
      if (drawn != shouldDraw) {
        if (++wrong == 1) detail = "column " + std::to_string(x) + " (z=" + std::to_string(z) + "): " + (drawn ? "drawn, D3D11 clips it" : "clipped, D3D11 draws it");
        continue;
      }
      if (drawn) {
        double e = std::abs(g - double(float(expected))) / FloatUlp(expected);
        if (e > worst) {
          worst = e;
          if (e > 2) detail = "column " + std::to_string(x) + ": depth " + std::to_string(g) + ", D3D11 " + std::to_string(expected);
        }
      }
    }
  }
  if (wrong) return Fail(std::to_string(wrong) + " pixels with the wrong coverage; first: " + detail, wrong, "pixels", 0);
  return Within(worst, 2.0, "ulp", detail);
}

}  // namespace

SP_PROBE(kGroup, "DepthClipEnable = TRUE clips beyond near and far", "geometry with z < 0 or z > 1 is not drawn") { return Check(device, true, 0.0f, 1.0f); }
SP_PROBE(kGroup, "DepthClipEnable = FALSE keeps and clamps depth", "geometry beyond near/far is drawn with depth clamped to [0, 1]") {
  return Check(device, false, 0.0f, 1.0f);
}
SP_PROBE(kGroup, "DepthClipEnable = FALSE clamps to the viewport depth range", "with MinDepth 0.2, MaxDepth 0.6 depth is clamped to [0.2, 0.6]") {
  return Check(device, false, 0.2f, 0.6f);
}
SP_PROBE(kGroup, "DepthClipEnable = TRUE with a viewport depth range", "clipping happens in NDC; the range only maps [0,1] to [MinDepth, MaxDepth]") {
  return Check(device, true, 0.2f, 0.6f);
}

}  // namespace sp::conformance
