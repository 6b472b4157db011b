// Texel selection and filter weights of Sample, SampleLevel, SampleGrad and SampleBias on a mip
// chain with distinct values per texel and per level, and Load with and without offsets.
//
// D3D11 (functional spec, 7.18 "Texture Sampling"): LOD = log2 of the footprint's longer side in
// texels of level 0 (from explicit gradients or the quad's derivatives) + shader bias + sampler
// MipLODBias, clamped to [MinLOD, MaxLOD] and then to the view's levels. A point mip filter takes
// the nearest level, a linear one blends floor(LOD) and floor(LOD) + 1 by frac(LOD). Within a
// level, point takes texel floor(u * W), linear blends the 2x2 texels around u * W - 0.5. Constant
// offsets move the footprint by whole texels of the level being read.
//
// Gradients are axis-aligned with equal length in both axes and powers of two, so the LOD is an
// exact integer under any of the LOD formulas D3D11 permits; fractional LODs come from
// SampleLevel and SampleBias, which add exact values. Tolerances are those of sampling-util.h:
// 1/256 of the blended difference per linear axis (u, v, mip) plus float rounding.
#include "sampling-util.h"

namespace sp::conformance::sampling {
namespace {

constexpr uint32_t W = 16, H = 16, kLevels = 5;

// Level l holds 0.2 * l + a per-texel pattern in [0, 0.15]: every texel of every level differs
// from its neighbours and every level from the others.
MipChain Chain() {
  MipChain c{W, H, {}};
  for (uint32_t l = 0; l < kLevels; ++l) {
    std::vector<float> v(c.Width(l) * c.Height(l));
    for (uint32_t y = 0; y < c.Height(l); ++y)
      for (uint32_t x = 0; x < c.Width(l); ++x) v[y * c.Width(l) + x] = 0.2f * float(l) + 0.01f * float((x * 7 + y * 3 + l) % 16);
    c.levels.push_back(std::move(v));
  }
  return c;
}

// Positions chosen away from texel boundaries at every level (so point sampling is unambiguous
// whatever the subtexel rounding), plus exact texel centres and points near the edges.
const std::array<float, 2> kUv[] = {{0.3f, 0.55f}, {0.5f, 0.5f}, {0.11f, 0.83f}, {0.78125f, 0.21875f}, {0.97f, 0.04f}, {0.6640625f, 0.4140625f}};

struct Filter {
  FILTER filter;
  const char* name;
};
const Filter kFilters[4] = {{FILTER_MIN_MAG_MIP_LINEAR, "MIN_MAG_MIP_LINEAR"},
                            {FILTER_MIN_MAG_LINEAR_MIP_POINT, "MIN_MAG_LINEAR_MIP_POINT"},
                            {FILTER_MIN_MAG_MIP_POINT, "MIN_MAG_MIP_POINT"},
                            {FILTER_MIN_MAG_POINT_MIP_LINEAR, "MIN_MAG_POINT_MIP_LINEAR"}};

struct Fixture {
  MipChain chain = Chain();
  Ref<Texture2D> texture;
  Ref<ShaderResourceView> srv;
  std::vector<Ref<SamplerState>> keep;
  std::vector<SamplerState*> samplers;  // s0..s3: kFilters, CLAMP
  explicit Fixture(Device& device, TEXTURE_ADDRESS_MODE mode = TEXTURE_ADDRESS_CLAMP) {
    texture = MakeFloatTexture(device, W, H, 1, chain.levels);
    srv = device.CreateShaderResourceView(texture.get());
    for (const Filter& f : kFilters) {
      keep.push_back(MakeSampler(device, f.filter, mode, mode));
      samplers.push_back(keep.back().get());
    }
  }
};

// Checks output component f (sampler kFilters[f]) of every case against the CPU at `lods[i]`.
void CheckAll(Worst& worst, const Fixture& fx, const std::vector<Case>& cases, const std::vector<Float4>& got, const std::vector<double>& lods,
              const std::vector<int>& filters, const std::string& what, TEXTURE_ADDRESS_MODE mode = TEXTURE_ADDRESS_CLAMP, int ox = 0, int oy = 0) {
  for (size_t i = 0; i < cases.size(); ++i)
    for (int f : filters) {
      SamplerModel m;
      m.linear = FilterMinLinear(kFilters[f].filter);
      m.u = m.v = mode;
      Expected e = SampleLodCpu(fx.chain, lods[i], FilterMipLinear(kFilters[f].filter), cases[i].a[0], cases[i].a[1], m, ox, oy);
      worst.Add(got[i][f], e, what + " " + kFilters[f].name + " uv (" + Fmt(cases[i].a[0]) + ", " + Fmt(cases[i].a[1]) + ") LOD " + Fmt(lods[i]));
    }
}

}  // namespace

SP_PROBE(kGroup, "SampleLevel: texel selection, bilinear and trilinear weights at fractional LODs",
         "SampleLevel with point/linear min-mag and mip filters blends the expected texels of the expected levels") {
  Fixture fx(device);
  const double lodList[] = {-0.5, 0, 0.25, 0.7, 1, 1.625, 2.3, 3.75, 4, 6};
  std::vector<Case> cases;
  std::vector<double> lods;
  for (auto& uv : kUv)
    for (double lod : lodList) {
      cases.push_back({{uv[0], uv[1], float(lod), 0}, {}});
      lods.push_back(lod);
    }
  const char* body = R"(
Texture2D<float> tex : register(t0);
SamplerState s0 : register(s0); SamplerState s1 : register(s1); SamplerState s2 : register(s2); SamplerState s3 : register(s3);
float4 Probe(Case k, uint index) {
  return float4(tex.SampleLevel(s0, k.a.xy, k.a.z), tex.SampleLevel(s1, k.a.xy, k.a.z), tex.SampleLevel(s2, k.a.xy, k.a.z), tex.SampleLevel(s3, k.a.xy, k.a.z));
}
)";
  std::vector<Float4> got = RunCompute(device, body, "sampling-samplelevel", cases, {fx.srv.get()}, fx.samplers);
  Worst worst;
  CheckAll(worst, fx, cases, got, lods, {0, 1, 2, 3}, "SampleLevel");
  return worst.Finish("abs");
}

SP_PROBE(kGroup, "SampleGrad: isotropic gradients select the LOD", "ddx = (g/W, 0), ddy = (0, g/H) gives LOD log2(g); g < 1 magnifies level 0") {
  Fixture fx(device);
  // Fractional log2(g) only with the point mip filter: the level is then unambiguous (0.25 from
  // the rounding point) whatever approximation of log2 the hardware uses.
  const double gs[] = {0.5, 1, 2, 4, 8, 16, 32, std::exp2(1.25), std::exp2(2.75)};
  std::vector<Case> cases;
  std::vector<double> lods;
  for (auto& uv : kUv)
    for (double g : gs) {
      cases.push_back({{uv[0], uv[1], float(g / W), float(g / H)}, {}});
      lods.push_back(std::log2(g));
    }
  const char* body = R"(
Texture2D<float> tex : register(t0);
SamplerState s0 : register(s0); SamplerState s1 : register(s1); SamplerState s2 : register(s2); SamplerState s3 : register(s3);
float4 Probe(Case k, uint index) {
  float2 dx = float2(k.a.z, 0), dy = float2(0, k.a.w);
  return float4(tex.SampleGrad(s0, k.a.xy, dx, dy), tex.SampleGrad(s1, k.a.xy, dx, dy), tex.SampleGrad(s2, k.a.xy, dx, dy), tex.SampleGrad(s3, k.a.xy, dx, dy));
}
)";
  std::vector<Float4> got = RunCompute(device, body, "sampling-samplegrad", cases, {fx.srv.get()}, fx.samplers);
  Worst worst;
  std::vector<Case> integral, fractional;
  std::vector<Float4> gotI, gotF;
  std::vector<double> lodI, lodF;
  for (size_t i = 0; i < cases.size(); ++i) {
    bool exact = lods[i] == std::floor(lods[i]);
    (exact ? integral : fractional).push_back(cases[i]);
    (exact ? gotI : gotF).push_back(got[i]);
    (exact ? lodI : lodF).push_back(lods[i]);
  }
  CheckAll(worst, fx, integral, gotI, lodI, {0, 1, 2, 3}, "SampleGrad");
  CheckAll(worst, fx, fractional, gotF, lodF, {1, 2}, "SampleGrad");
  return worst.Finish("abs");
}

SP_PROBE(kGroup, "Sample: quad derivatives select the LOD", "Sample in a pixel shader with uv stepping g/W texels per pixel uses LOD log2(g)") {
  Fixture fx(device);
  const double gs[] = {0.5, 1, 2, 4, 8, 16};
  std::vector<Case> cases;
  std::vector<double> lods;
  for (auto& uv : kUv)
    for (double g : gs) {
      cases.push_back({{uv[0], uv[1], float(g / W), float(g / H)}, {}});
      lods.push_back(std::log2(g));
    }
  const char* body = R"(
Texture2D<float> tex : register(t0);
SamplerState s0 : register(s0); SamplerState s1 : register(s1); SamplerState s2 : register(s2); SamplerState s3 : register(s3);
float4 Probe(Case k, float2 sub) {
  float2 uv = k.a.xy + sub * k.a.zw;
  return float4(tex.Sample(s0, uv), tex.Sample(s1, uv), tex.Sample(s2, uv), tex.Sample(s3, uv));
}
)";
  std::vector<Float4> got = RunPixel(device, body, "sampling-sample", cases, {fx.srv.get()}, fx.samplers);
  Worst worst;
  CheckAll(worst, fx, cases, got, lods, {0, 1, 2, 3}, "Sample");
  return worst.Finish("abs");
}

SP_PROBE(kGroup, "SampleBias: the bias shifts the LOD", "SampleBias adds its bias to the LOD from the derivatives (LOD 1 here), then clamps to the chain") {
  Fixture fx(device);
  const double biases[] = {-4, -1, -0.75, 0, 0.5, 1.25, 2, 2.625, 5};
  std::vector<Case> cases;
  std::vector<double> lods;
  for (auto& uv : kUv)
    for (double b : biases) {
      cases.push_back({{uv[0], uv[1], 2.0f / W, 2.0f / H}, {float(b), 0, 0, 0}});
      lods.push_back(1 + b);
    }
  const char* body = R"(
Texture2D<float> tex : register(t0);
SamplerState s0 : register(s0); SamplerState s1 : register(s1); SamplerState s2 : register(s2); SamplerState s3 : register(s3);
float4 Probe(Case k, float2 sub) {
  float2 uv = k.a.xy + sub * k.a.zw;
  float b = k.b.x;
  return float4(tex.SampleBias(s0, uv, b), tex.SampleBias(s1, uv, b), tex.SampleBias(s2, uv, b), tex.SampleBias(s3, uv, b));
}
)";
  std::vector<Float4> got = RunPixel(device, body, "sampling-samplebias", cases, {fx.srv.get()}, fx.samplers);
  Worst worst;
  CheckAll(worst, fx, cases, got, lods, {0, 1, 2, 3}, "SampleBias");
  return worst.Finish("abs");
}

SP_PROBE(kGroup, "Sample/SampleLevel/SampleGrad/SampleBias with constant offsets (CLAMP, WRAP)",
         "an immediate offset moves the footprint by whole texels of each level read, before addressing") {
  // x: Sample at LOD 0, offset (-2, 3); y: SampleLevel LOD 1.25, (7, -8); z: SampleGrad LOD 2,
  // (-8, 7); w: SampleBias to LOD 1.5, (3, -1). Trilinear sampler in s0.
  const char* body = R"(
Texture2D<float> tex : register(t0);
SamplerState s0 : register(s0);
float4 Probe(Case k, float2 sub) {
  float2 uv = k.a.xy + sub * float2(1.0 / 16, 1.0 / 16);
  float2 uv2 = k.a.xy + sub * float2(2.0 / 16, 2.0 / 16);
  return float4(tex.Sample(s0, uv, int2(-2, 3)), tex.SampleLevel(s0, k.a.xy, 1.25, int2(7, -8)),
                tex.SampleGrad(s0, k.a.xy, float2(4.0 / 16, 0), float2(0, 4.0 / 16), int2(-8, 7)), tex.SampleBias(s0, uv2, 0.5, int2(3, -1)));
}
)";
  struct Call {
    double lod;
    int ox, oy;
    const char* name;
  };
  const Call calls[4] = {{0, -2, 3, "Sample"}, {1.25, 7, -8, "SampleLevel"}, {2, -8, 7, "SampleGrad"}, {1.5, 3, -1, "SampleBias"}};
  Worst worst;
  for (TEXTURE_ADDRESS_MODE mode : {TEXTURE_ADDRESS_CLAMP, TEXTURE_ADDRESS_WRAP}) {
    Fixture fx(device, mode);
    std::vector<Case> cases;
    for (auto& uv : kUv) cases.push_back({{uv[0], uv[1], 0, 0}, {}});
    std::vector<Float4> got = RunPixel(device, body, "sampling-offsets", cases, {fx.srv.get()}, {fx.samplers[0]});
    for (size_t i = 0; i < cases.size(); ++i)
      for (int c = 0; c < 4; ++c) {
        SamplerModel m;
        m.u = m.v = mode;
        Expected e = SampleLodCpu(fx.chain, calls[c].lod, true, cases[i].a[0], cases[i].a[1], m, calls[c].ox, calls[c].oy);
        worst.Add(got[i][c], e,
                  std::string(calls[c].name) + " " + AddressName(mode) + " offset (" + std::to_string(calls[c].ox) + "," + std::to_string(calls[c].oy) +
                      ") uv (" + Fmt(cases[i].a[0]) + ", " + Fmt(cases[i].a[1]) + ")");
      }
  }
  return worst.Finish("abs");
}

SP_PROBE(kGroup, "Load with and without offsets; out of range returns 0",
         "Load(int3(x, y, mip), offset) reads texel (x, y) + offset of the mip exactly; outside the level or past the last mip it returns (0,0,0,0)") {
  constexpr uint32_t LW = 8, LH = 8, LL = 4;
  auto value = [](uint32_t c, uint32_t l, uint32_t x, uint32_t y) { return float(1000 * c + 100 * l + 10 * y + x + 1); };
  std::vector<std::vector<float>> levels;
  for (uint32_t l = 0; l < LL; ++l) {
    uint32_t w = LW >> l, h = LH >> l;
    std::vector<float> v(w * h * 4);
    for (uint32_t y = 0; y < h; ++y)
      for (uint32_t x = 0; x < w; ++x)
        for (uint32_t c = 0; c < 4; ++c) v[(y * w + x) * 4 + c] = value(c, l, x, y);
    levels.push_back(std::move(v));
  }
  Ref<Texture2D> tex = MakeFloatTexture(device, LW, LH, 4, levels);
  Ref<ShaderResourceView> srv = device.CreateShaderResourceView(tex.get());
  const char* body = R"(
Texture2D<float4> tex : register(t0);
float4 Probe(Case k, uint index) {
  int3 p = int3(k.a.xyz);
  switch (uint(k.a.w)) {
    case 0: return tex.Load(p);
    case 1: return tex.Load(p, int2(-3, 2));
    case 2: return tex.Load(p, int2(7, -8));
    default: return tex.Load(p, int2(-8, 7));
  }
}
)";
  const int offsets[4][2] = {{0, 0}, {-3, 2}, {7, -8}, {-8, 7}};
  std::vector<Case> cases;
  for (int mip : {0, 1, 2, 3, 4, 9})
    for (int x : {-1, 0, 3, 7, 8, 12})
      for (int y : {-9, 0, 5, 8})
        for (int o = 0; o < 4; ++o) cases.push_back({{float(x), float(y), float(mip), float(o)}, {}});
  std::vector<Float4> got = RunCompute(device, body, "sampling-load", cases, {srv.get()}, {});
  Worst worst;
  for (size_t i = 0; i < cases.size(); ++i) {
    int x = int(cases[i].a[0]), y = int(cases[i].a[1]), mip = int(cases[i].a[2]), o = int(cases[i].a[3]);
    int tx = x + offsets[o][0], ty = y + offsets[o][1];
    bool inside = mip >= 0 && mip < int(LL) && tx >= 0 && ty >= 0 && tx < int(LW >> mip) && ty < int(LH >> mip);
    for (uint32_t c = 0; c < 4; ++c) {
      double expected = inside ? value(c, uint32_t(mip), uint32_t(tx), uint32_t(ty)) : 0.0;
      worst.Add(got[i][c], {expected, 0.0},
                "Load(" + std::to_string(x) + ", " + std::to_string(y) + ", mip " + std::to_string(mip) + ") offset (" + std::to_string(offsets[o][0]) +
                    "," + std::to_string(offsets[o][1]) + ") ." + "xyzw"[c]);
    }
  }
  return worst.Finish("abs");
}

}  // namespace sp::conformance::sampling
