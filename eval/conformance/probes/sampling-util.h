// Shared pieces of the "Sampling" probes: running a table of sample cases through a compute or a
// pixel shader, making textures with known contents, and D3D11's texture addressing and
// filtering on the CPU (D3D11.3 functional spec, 7.18 "Texture Sampling"), which the probes
// compare against.
//
// Tolerances come from D3D11's filtering precision: texel coordinates are converted with at least
// D3D11_SUBTEXEL_FRACTIONAL_BIT_COUNT = 8 fractional bits and the LOD with at least
// D3D11_MIP_LOD_FRACTIONAL_BIT_COUNT = 8, truncation allowed (WARP truncates). A weight may thus
// be off by up to 1/256, and each linearly filtered axis (u, v, mip) may move the result by
// 1/256 of the difference between the values it blends. On top of that the filter runs in float32:
// kFloatSlack allows a few roundings of values of magnitude <= 1.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "probe-helpers.h"

namespace sp::conformance::sampling {

inline const char* kGroup = "Sampling";

using Float4 = std::array<float, 4>;

// One row of the case table the shaders read from t15 (`struct Case { float4 a; float4 b; }`):
// what a, b mean is up to each probe's shader (uv, reference, LOD, which variant to run...).
struct Case {
  Float4 a{}, b{};
};

// Eight float32 roundings of values in [0, 1] (2^-23 each): a bilinear or trilinear blend is a
// handful of multiply-adds.
constexpr double kFloatSlack = 8.0 / 8388608.0;
// One 8-bit step of a weight (D3D11_SUBTEXEL_FRACTIONAL_BIT_COUNT, D3D11_MIP_LOD_FRACTIONAL_BIT_COUNT).
constexpr double kWeightStep = 1.0 / 256.0;

// Runs `body` for every case in a compute shader and returns one float4 per case. `body` is HLSL
// defining `float4 Probe(Case k, uint index)`; the prologue declares Case, `cases` (t15) and the
// output. Resources and samplers the body declares are bound from slot 0 in the order given.
std::vector<Float4> RunCompute(Device& device, const std::string& body, const std::string& name, const std::vector<Case>& cases,
                               const std::vector<ShaderResourceView*>& srvs, const std::vector<SamplerState*>& samplers);

// Runs `body` in a pixel shader: every case gets one 2x2 quad of a float4 render target and the
// body defines `float4 Probe(Case k, float2 sub)`, where sub is the pixel's position in its quad
// ((0,0) top-left, (1,0), (0,1), (1,1)). Texture coordinates computed as `base + sub * step` have
// the exact derivatives (step.x, 0) and (0, step.y); the result of the top-left pixel is returned.
std::vector<Float4> RunPixel(Device& device, const std::string& body, const std::string& name, const std::vector<Case>& cases,
                             const std::vector<ShaderResourceView*>& srvs, const std::vector<SamplerState*>& samplers);

// A sampler with the given filter and address modes; everything else is D3D11's default.
Ref<SamplerState> MakeSampler(Device& device, FILTER filter, TEXTURE_ADDRESS_MODE u, TEXTURE_ADDRESS_MODE v);
Ref<SamplerState> MakeSampler(Device& device, const SAMPLER_DESC& desc);

// A texture of 32-bit float texels (R32_FLOAT or R32G32B32A32_FLOAT by `components`) with the
// given mip levels, level 0 first; each level holds width(l) * height(l) * components floats.
Ref<Texture2D> MakeFloatTexture(Device& device, uint32_t w, uint32_t h, uint32_t components, const std::vector<std::vector<float>>& levels);

// An R32_TYPELESS depth texture (BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE) holding `depths`,
// row by row, and its R32_FLOAT view. `rendered`: written by drawing with SV_Depth into its
// D32_FLOAT view; otherwise uploaded through a staging texture and CopyResource.
struct DepthTexture {
  Ref<Texture2D> texture;
  Ref<ShaderResourceView> srv;
};
DepthTexture MakeDepthTexture(Device& device, uint32_t w, uint32_t h, const std::vector<float>& depths, bool rendered);

// One channel of a mip chain on the CPU.
struct MipChain {
  uint32_t width = 0, height = 0;
  std::vector<std::vector<float>> levels;  // levels[l][y * width(l) + x]
  uint32_t Width(uint32_t l) const { return std::max(1u, width >> l); }
  uint32_t Height(uint32_t l) const { return std::max(1u, height >> l); }
  uint32_t Levels() const { return uint32_t(levels.size()); }
  float At(uint32_t l, uint32_t x, uint32_t y) const { return levels[l][y * Width(l) + x]; }
};

// D3D11 addressing of an integer texel index in [0, size); returns -1 for BORDER outside.
int AddressTexel(TEXTURE_ADDRESS_MODE mode, int i, int size);

// The expected result of a D3D11 filter and how far a conformant implementation may be from it.
struct Expected {
  double value = 0;
  double tol = 0;
};

struct SamplerModel {
  bool linear = true;  // min/mag filter (the probes use the same for both)
  TEXTURE_ADDRESS_MODE u = TEXTURE_ADDRESS_CLAMP, v = TEXTURE_ADDRESS_CLAMP;
  double border = 0;  // the border colour's component for this channel
};

// Point or bilinear sample of one level at normalized (u, v), texel offsets (ox, oy) applied in
// texel space before addressing, as D3D11 does for aoffimmi.
Expected SampleLevelCpu(const MipChain& img, uint32_t level, double u, double v, const SamplerModel& s, int ox = 0, int oy = 0);

// Sample at a LOD (already biased and clamped to [MinLOD, MaxLOD] by the caller): clamped to the
// chain, then the nearest level (mipLinear false) or a blend of the two around it.
Expected SampleLodCpu(const MipChain& img, double lod, bool mipLinear, double u, double v, const SamplerModel& s, int ox = 0, int oy = 0);

// Collects the cases of a probe: reports the largest error when all are within their
// tolerances, else the case furthest beyond its tolerance and how many failed.
class Worst {
 public:
  void Add(double got, const Expected& e, const std::string& where);
  void AddError(double err, double tol, const std::string& where);  // for errors the probe computed itself
  Result Finish(const std::string& unit) const;

 private:
  double err_ = -1, tol_ = 0;
  std::string where_;
  double failErr_ = 0, failTol_ = 0, margin_ = -std::numeric_limits<double>::infinity();
  std::string failWhere_;
  int failures_ = 0;
};

std::string Fmt(double v);  // shortest round-trip form of a double, for details
std::string AddressName(TEXTURE_ADDRESS_MODE m);

}  // namespace sp::conformance::sampling
