// Depth bias: DepthBias, SlopeScaledDepthBias and DepthBiasClamp on D16, D24S8 and D32_FLOAT,
// against the D3D11 formula (functional spec, "Depth Bias"):
//   UNORM: Bias = DepthBias * 1/(2^n - 1) + SlopeScaledDepthBias * MaxDepthSlope
//   float: Bias = DepthBias * 2^(exponent(max z of the primitive) - 23) + SlopeScaledDepthBias * MaxDepthSlope
//   clamp: DepthBiasClamp > 0 -> min(Bias, clamp); < 0 -> max(Bias, clamp); 0 -> none
//   then depth is clamped to the viewport's [MinDepth, MaxDepth] and converted to the format.
// Allowed error: 1 LSB (UNORM) or 1 ulp (float), plus, for UNORM, the float32 rounding of
// z + Bias that D3D11 itself performs (the rasterizer works in float32): in [0.5, 1) one float
// ulp is one D24 LSB, so D24 may be 2 LSB off there; for D16 the extra is negligible.
#include <algorithm>

#include "probe-helpers.h"

namespace sp::conformance {
namespace {

const char* kGroup = "Depth bias";
constexpr uint32_t W = 32, H = 16;

struct BiasCase {
  double z0, gx;        // depth plane in NDC: z = z0 + gx * x (slopes along x only: Vulkan allows
                        // |grad| or max(|dx|,|dy|) for MaxDepthSlope, D3D uses the max; they agree
                        // when one partial derivative is 0)
  int32_t bias;
  float slope, clamp;
};

// Largest deviation from the D3D11 result over all pixels, in LSB or ulp, relative to the
// allowed error at that depth (the result is the error of the pixel that comes closest to its
// allowance; *allowed receives that pixel's allowance).
double Deviation(Device& device, FORMAT fmt, const BiasCase& c, std::string* where, double* allowed) {
  // A triangle covering the viewport, with vertices at NDC x in {-1, 3}.
  std::vector<DepthVertex> v = {{-1, -1, float(c.z0 - c.gx)}, {-1, 3, float(c.z0 - c.gx)}, {3, -1, float(c.z0 + 3 * c.gx)}};
  RASTERIZER_DESC rd;
  rd.CullMode = CULL_NONE;
  rd.DepthBias = c.bias;
  rd.SlopeScaledDepthBias = c.slope;
  rd.DepthBiasClamp = c.clamp;
  std::vector<double> got = DrawDepth(device, fmt, W, H, v, PRIMITIVE_TOPOLOGY_TRIANGLELIST, rd);

  uint32_t bits = UnormBits(fmt);
  double maxZ = std::max({double(v[0].z), double(v[1].z), double(v[2].z)});
  double unit = bits ? 1.0 / double((1u << bits) - 1) : std::ldexp(1.0, std::ilogb(float(maxZ)) - 23);
  double maxSlope = std::abs(c.gx) * 2.0 / W;
  double bias = c.bias * unit + double(c.slope) * maxSlope;
  if (c.clamp > 0) bias = std::min(bias, double(c.clamp));
  if (c.clamp < 0) bias = std::max(bias, double(c.clamp));
  double worst = 0, worstMargin = -1e30;
  *allowed = 1.0;
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      double ndcX = (x + 0.5) / W * 2 - 1;
      double z = std::clamp(c.z0 + c.gx * ndcX + bias, 0.0, 1.0);
      double expected = bits ? QuantizeUnorm(z, bits) : double(float(z));
      double err = bits ? std::abs(got[y * W + x] - expected) : std::abs(got[y * W + x] - expected) / FloatUlp(expected);
      // One LSB, plus one where a float32 ulp of z reaches half an LSB (the sum's rounding can
      // then move the quantized value): D24 at z >= 0.25, never D16.
      double tol = bits ? (FloatUlp(z) * double((1u << bits) - 1) >= 0.5 ? 2.0 : 1.0) : 1.0;
      if (err - tol > worstMargin) {
        worstMargin = err - tol;
        worst = err;
        *allowed = tol;
        *where = "pixel (" + std::to_string(x) + "," + std::to_string(y) + "): got " + std::to_string(got[y * W + x]) + ", D3D11 " +
                 std::to_string(expected);
      }
    }
  return worst;
}

Result RunCases(Device& device, FORMAT fmt, const std::vector<BiasCase>& cases) {
  if (!(device.CheckFormatSupport(fmt) & FORMAT_SUPPORT_DEPTH_STENCIL)) return Unsupported(std::string(FormatName(fmt)) + " is not a depth format on this device");
  double worst = 0, worstMargin = -1e30, worstAllowed = 1.0;
  std::string detail;
  for (const BiasCase& c : cases) {
    std::string where;
    double allowed;
    double e = Deviation(device, fmt, c, &where, &allowed);
    if (e - allowed > worstMargin) {
      worstMargin = e - allowed;
      worst = e;
      worstAllowed = allowed;
      detail = "z0=" + std::to_string(c.z0) + " DepthBias=" + std::to_string(c.bias) + " slope=" + std::to_string(c.slope) +
               " clamp=" + std::to_string(c.clamp) + " at " + where;
    }
  }
  return Within(worst, worstAllowed, UnormBits(fmt) ? "LSB" : "ulp", detail);
}

const std::vector<BiasCase> kConstant = {
    {0.30, 0, 0, 0, 0},    {0.30, 0, 37, 0, 0},    {0.30, 0, -37, 0, 0},   {0.55, 0, 1000, 0, 0},
    {0.80, 0, -1000, 0, 0}, {0.80, 0, 1, 0, 0},     {0.0001, 0, -100000, 0, 0}, {0.9999, 0, 100000, 0, 0}};
const std::vector<BiasCase> kSlope = {
    {0.60, 0.05, 0, 1.0f, 0}, {0.60, 0.05, 0, 2.5f, 0}, {0.70, -0.04, 0, 1.5f, 0}, {0.60, 0.05, 50, -1.5f, 0}, {0.60, 0.05, 0, 0.0f, 0}};
const std::vector<BiasCase> kClamp = {
    {0.60, 0, 100000, 0, 0.0005f}, {0.60, 0.05, 0, 4.0f, 0.001f}, {0.60, 0, -100000, 0, -0.0005f}, {0.60, 0, 100000, 0, 0.0f}};

}  // namespace

SP_PROBE(kGroup, "D16: constant bias, positive/negative/zero, several depths", "DepthBias moves D16 depth by DepthBias LSB, clamped to [0,1]") {
  return RunCases(device, FORMAT_D16_UNORM, kConstant);
}
SP_PROBE(kGroup, "D24S8: constant bias, positive/negative/zero, several depths", "DepthBias moves D24 depth by DepthBias LSB, clamped to [0,1]") {
  return RunCases(device, FORMAT_D24_UNORM_S8_UINT, kConstant);
}
SP_PROBE(kGroup, "D32F: constant bias, positive/negative/zero, several depths", "DepthBias moves D32F depth by DepthBias * 2^(e-23)") {
  // Keep every vertex in one binade so exponent(max z) is that of z0.
  std::vector<BiasCase> cases = {{0.30, 0, 0, 0, 0}, {0.30, 0, 37, 0, 0}, {0.30, 0, -37, 0, 0}, {0.55, 0, 1000, 0, 0}, {0.80, 0, -1000, 0, 0}, {0.80, 0, 1, 0, 0}};
  return RunCases(device, FORMAT_D32_FLOAT, cases);
}
SP_PROBE(kGroup, "D16: slope-scaled bias", "SlopeScaledDepthBias * max(|dz/dx|,|dz/dy|) is added") { return RunCases(device, FORMAT_D16_UNORM, kSlope); }
SP_PROBE(kGroup, "D24S8: slope-scaled bias", "SlopeScaledDepthBias * max(|dz/dx|,|dz/dy|) is added") { return RunCases(device, FORMAT_D24_UNORM_S8_UINT, kSlope); }
SP_PROBE(kGroup, "D32F: slope-scaled bias", "SlopeScaledDepthBias * max(|dz/dx|,|dz/dy|) is added") { return RunCases(device, FORMAT_D32_FLOAT, kSlope); }
SP_PROBE(kGroup, "D16: DepthBiasClamp positive, negative, zero", "the bias is clamped by DepthBiasClamp's sign rule") { return RunCases(device, FORMAT_D16_UNORM, kClamp); }
SP_PROBE(kGroup, "D24S8: DepthBiasClamp positive, negative, zero", "the bias is clamped by DepthBiasClamp's sign rule") { return RunCases(device, FORMAT_D24_UNORM_S8_UINT, kClamp); }
SP_PROBE(kGroup, "D32F: DepthBiasClamp positive, negative, zero", "the bias is clamped by DepthBiasClamp's sign rule") { return RunCases(device, FORMAT_D32_FLOAT, kClamp); }

SP_PROBE(kGroup, "no bias on lines and points", "D3D11 applies depth bias to triangles only") {
  RASTERIZER_DESC rd;
  rd.CullMode = CULL_NONE;
  rd.DepthBias = 100000;
  rd.SlopeScaledDepthBias = 4.0f;
  double worst = 0;
  for (PRIMITIVE_TOPOLOGY t : {PRIMITIVE_TOPOLOGY_LINELIST, PRIMITIVE_TOPOLOGY_POINTLIST}) {
    // A horizontal line through row 8 and a point at pixel (5, 3), both at depth 0.5.
    std::vector<DepthVertex> v = t == PRIMITIVE_TOPOLOGY_LINELIST ? std::vector<DepthVertex>{{-1, 0.0f - 1.0f / H, 0.5f}, {1, 0.0f - 1.0f / H, 0.5f}}
                                                                  : std::vector<DepthVertex>{{(5.5f / W) * 2 - 1, 1 - (3.5f / H) * 2, 0.5f}};
    std::vector<double> got = DrawDepth(device, FORMAT_D32_FLOAT, W, H, v, t, rd);
    int drawn = 0;
    for (double d : got) {
      if (d == 1.0) continue;
      ++drawn;
      worst = std::max(worst, std::abs(d - 0.5) / FloatUlp(0.5));
    }
    if (!drawn) return Fail(std::string(t == PRIMITIVE_TOPOLOGY_LINELIST ? "the line" : "the point") + " drew no pixel");
  }
  return Within(worst, 0.0, "ulp", "biased depth written by a line or point");
}

SP_PROBE(kGroup, "calibration measured the driver's unit", "the device measured a plausible constant-bias unit for D16, D24 and D32F at creation") {
  const DeviceInfo& i = device.Info();
  std::string detail = "scales D16 " + std::to_string(i.depthBiasScaleD16) + ", D24 " + std::to_string(i.depthBiasScaleD24) + ", D32 " +
                       std::to_string(i.depthBiasScaleD32);
  for (float s : {i.depthBiasScaleD16, i.depthBiasScaleD24, i.depthBiasScaleD32})
    if (!(s > 0.01f && s < 100.0f)) return Fail("implausible calibration: " + detail);
  // The scaled bias must reproduce exactly one LSB per unit (the other probes check the formula
  // at large values; this one at the smallest).
  std::string where;
  BiasCase one{0.4, 0, 1, 0, 0};  // 0.4 * (2^n - 1) is not a rounding tie for n = 16, 24
  double worst = 0, allowed;
  for (FORMAT f : {FORMAT_D16_UNORM, FORMAT_D24_UNORM_S8_UINT}) worst = std::max(worst, Deviation(device, f, one, &where, &allowed));
  Result r = Within(worst, 0.0, "LSB", "DepthBias = 1 " + where);
  r.detail = r.status == Status::Pass ? detail : r.detail + "; " + detail;
  return r;
}

}  // namespace sp::conformance
