// The sampler's LOD controls: MipLODBias and the MinLOD/MaxLOD clamps, on a mip chain whose levels
// are distinct constants (level l = (l + 1) / 8), so the result names the level(s) read. D3D11
// (sample, sample_b, sample_l in the shader model 4 reference; functional spec 7.18.11):
//   LOD = (computed from derivatives, or SampleLevel's LOD) + shader bias + MipLODBias,
//   clamped to [MinLOD, MaxLOD], then to the view's levels; "sample_l honours MIPLODBIAS and
//   MIN/MAXLOD" as sample does.
// A point mip filter reads round(LOD); a linear one blends floor(LOD) and the next level by
// frac(LOD): the tolerance is 1/256 of the difference of the blended levels (8-bit LOD fraction).
// Ties (LOD fraction exactly 0.5 under a point mip filter) are avoided.
//
// Also anisotropic filtering: D3D11 does not define its weights, only that FILTER_ANISOTROPIC
// filters a footprint elongated up to MaxAnisotropy times better than isotropic filtering.
#include "sampling-util.h"

namespace sp::conformance::sampling {
namespace {

constexpr uint32_t W = 16, H = 16, kLevels = 5;

MipChain ConstantLevels() {
  MipChain c{W, H, {}};
  for (uint32_t l = 0; l < kLevels; ++l) c.levels.push_back(std::vector<float>(c.Width(l) * c.Height(l), float(l + 1) / 8.0f));
  return c;
}

struct LodSampler {
  float bias = 0, minLod = -FLT_MAX, maxLod = FLT_MAX;
  bool mipLinear = true;
  std::string Name() const {
    std::string s = mipLinear ? "mip linear" : "mip point";
    if (bias != 0) s += " MipLODBias " + Fmt(bias);
    if (minLod != -FLT_MAX) s += " MinLOD " + Fmt(minLod);
    if (maxLod != FLT_MAX) s += " MaxLOD " + Fmt(maxLod);
    return s;
  }
};

// Runs SampleLevel at each LOD (compute) and Sample with derivatives of 2^g texels per pixel
// (pixel shader, LOD g) through every sampler; the case picks the sampler.
Result Run(Device& device, const std::vector<LodSampler>& ls, const std::vector<double>& levelLods, const std::vector<double>& gradientLods) {
  MipChain chain = ConstantLevels();
  Ref<Texture2D> tex = MakeFloatTexture(device, W, H, 1, chain.levels);
  Ref<ShaderResourceView> srv = device.CreateShaderResourceView(tex.get());
  std::vector<Ref<SamplerState>> keep;
  std::vector<SamplerState*> samplers;
  std::string decl = "Texture2D<float> tex : register(t0);\n";
  std::string level = "float4 Probe(Case k, uint index) {\n  switch (uint(k.b.x)) {\n";
  std::string implicit = "float4 Probe(Case k, float2 sub) {\n  float2 uv = k.a.xy + sub * k.a.zw;\n  switch (uint(k.b.x)) {\n";
  for (size_t i = 0; i < ls.size(); ++i) {
    SAMPLER_DESC d;
    d.Filter = ls[i].mipLinear ? FILTER_MIN_MAG_MIP_LINEAR : FILTER_MIN_MAG_LINEAR_MIP_POINT;
    d.MipLODBias = ls[i].bias;
    d.MinLOD = ls[i].minLod;
    d.MaxLOD = ls[i].maxLod;
    keep.push_back(MakeSampler(device, d));
    samplers.push_back(keep.back().get());
    std::string n = std::to_string(i);
    decl += "SamplerState s" + n + " : register(s" + n + ");\n";
    level += "    case " + n + ": return tex.SampleLevel(s" + n + ", k.a.xy, k.a.z).xxxx;\n";
    implicit += "    case " + n + ": return tex.Sample(s" + n + ", uv).xxxx;\n";
  }
  level += "  }\n  return -1;\n}\n";
  implicit += "  }\n  return -1;\n}\n";

  const float u = 0.3f, v = 0.55f;
  Worst worst;
  auto check = [&](const std::vector<Case>& cases, const std::vector<Float4>& got, const std::vector<double>& lods, const char* how) {
    for (size_t i = 0; i < cases.size(); ++i) {
      const LodSampler& s = ls[size_t(cases[i].b[0])];
      double lod = std::clamp(lods[i] + s.bias, double(s.minLod), double(s.maxLod));
      Expected e = SampleLodCpu(chain, lod, s.mipLinear, u, v, SamplerModel{});
      worst.Add(got[i][0], e, std::string(how) + " LOD " + Fmt(lods[i]) + ", " + s.Name());
    }
  };
  std::vector<Case> cases;
  std::vector<double> lods;
  for (size_t i = 0; i < ls.size(); ++i)
    for (double l : levelLods) {
      cases.push_back({{u, v, float(l), 0}, {float(i), 0, 0, 0}});
      lods.push_back(l);
    }
  check(cases, RunCompute(device, decl + level, "sampling-lod-level", cases, {srv.get()}, samplers), lods, "SampleLevel");
  cases.clear();
  lods.clear();
  for (size_t i = 0; i < ls.size(); ++i)
    for (double g : gradientLods) {
      float step = float(std::exp2(g));
      cases.push_back({{u, v, step / W, step / H}, {float(i), 0, 0, 0}});
      lods.push_back(g);
    }
  check(cases, RunPixel(device, decl + implicit, "sampling-lod-implicit", cases, {srv.get()}, samplers), lods, "Sample");
  return worst.Finish("abs");
}

// A 64 x 64 texture of horizontal (or vertical) stripes four texels wide, 0 and 1, with its box-
// filtered mip chain: levels 0-2 still resolve the stripes, from level 3 on every texel is 0.5.
MipChain Stripes(bool horizontal) {
  constexpr uint32_t S = 64;
  MipChain c{S, S, {std::vector<float>(S * S)}};
  for (uint32_t y = 0; y < S; ++y)
    for (uint32_t x = 0; x < S; ++x) c.levels[0][y * S + x] = float(((horizontal ? y : x) / 4) & 1);
  for (uint32_t l = 1; (S >> l) > 0; ++l) {
    uint32_t n = S >> l;
    std::vector<float> v(n * n);
    for (uint32_t y = 0; y < n; ++y)
      for (uint32_t x = 0; x < n; ++x)
        v[y * n + x] = 0.25f * (c.At(l - 1, 2 * x, 2 * y) + c.At(l - 1, 2 * x + 1, 2 * y) + c.At(l - 1, 2 * x, 2 * y + 1) + c.At(l - 1, 2 * x + 1, 2 * y + 1));
    c.levels.push_back(std::move(v));
  }
  return c;
}

// The true box-filtered value: the texture's average over the pixel's footprint, the rectangle
// (du x dv in uv) centred on (u, v), by dense point sampling of the piecewise-constant level 0.
double BoxAverage(const MipChain& c, double u, double v, double du, double dv) {
  constexpr int N = 256;
  double sum = 0;
  for (int j = 0; j < N; ++j)
    for (int i = 0; i < N; ++i) {
      double su = u + du * ((i + 0.5) / N - 0.5), sv = v + dv * ((j + 0.5) / N - 0.5);
      int x = AddressTexel(TEXTURE_ADDRESS_WRAP, int(std::floor(su * c.width)), int(c.width));
      int y = AddressTexel(TEXTURE_ADDRESS_WRAP, int(std::floor(sv * c.height)), int(c.height));
      sum += c.At(0, uint32_t(x), uint32_t(y));
    }
  return sum / (N * N);
}

}  // namespace

SP_PROBE(kGroup, "MipLODBias shifts the LOD of Sample and SampleLevel", "the sampler's MipLODBias is added to the LOD (integer and fractional, both signs)") {
  std::vector<LodSampler> ls;
  for (float b : {1.0f, 2.5f, -1.0f, 0.375f, -0.75f, 10.0f}) {
    ls.push_back({b, -FLT_MAX, FLT_MAX, true});
    ls.push_back({b + (b == 2.5f ? 0.25f : 0.0f), -FLT_MAX, FLT_MAX, false});
  }
  return Run(device, ls, {0, 1, 2.25}, {0, 1, 2});
}

SP_PROBE(kGroup, "MinLOD/MaxLOD clamp the LOD (integer and fractional)", "the LOD is clamped to [MinLOD, MaxLOD] after the bias, for Sample and SampleLevel") {
  std::vector<LodSampler> ls;
  for (bool lin : {true, false}) {
    ls.push_back({0, 1, FLT_MAX, lin});
    ls.push_back({0, -FLT_MAX, 1, lin});
    ls.push_back({0, 1.25f, 2.75f, lin});
    ls.push_back({0, 2, 2, lin});
    ls.push_back({0, 0.375f, 3.625f, lin});
    ls.push_back({0, 10, FLT_MAX, lin});
    ls.push_back({1.0f, -FLT_MAX, 1.75f, lin});
  }
  return Run(device, ls, {-1, 0, 0.25, 1, 1.75, 2.25, 3, 4, 6}, {-1, 0, 1, 2, 3});
}

SP_PROBE(kGroup, "Anisotropic x16 beats trilinear on a 16:1 footprint",
         "FILTER_ANISOTROPIC, MaxAnisotropy 16: closer to the footprint's box-filtered average than MIN_MAG_MIP_LINEAR") {
  // Criterion (D3D11 defines no anisotropic weights): over all cases the mean error of the
  // anisotropic result against the box-filtered average of the pixel's footprint must be at most
  // half that of trilinear. The stripes, four texels wide, run along the long axis of 16:1 and
  // 8:1 footprints: a filter that honours the footprint's one-texel short axis resolves them,
  // while trilinear reads level 4 or 3 (uniformly 0.5 there).
  SAMPLER_DESC ad;
  ad.Filter = FILTER_ANISOTROPIC;
  ad.MaxAnisotropy = 16;
  ad.AddressU = ad.AddressV = TEXTURE_ADDRESS_WRAP;
  Ref<SamplerState> aniso = MakeSampler(device, ad);
  Ref<SamplerState> tri = MakeSampler(device, FILTER_MIN_MAG_MIP_LINEAR, TEXTURE_ADDRESS_WRAP, TEXTURE_ADDRESS_WRAP);
  const char* body = R"(
Texture2D<float> tex : register(t0);
SamplerState aniso : register(s0);
SamplerState tri : register(s1);
float4 Probe(Case k, float2 sub) {
  float2 uv = k.a.xy + sub * k.a.zw;
  return float4(tex.Sample(aniso, uv), tex.Sample(tri, uv), 0, 0);
}
)";
  double errAniso = 0, errTri = 0;
  size_t n = 0;
  std::string worstCase;
  double worstErr = -1;
  for (bool horizontal : {true, false}) {
    MipChain c = Stripes(horizontal);
    Ref<Texture2D> tex = MakeFloatTexture(device, c.width, c.height, 1, c.levels);
    Ref<ShaderResourceView> srv = device.CreateShaderResourceView(tex.get());
    // Footprints 16 x 1 and 8 x 1 texels along the stripes, centred at several distances from
    // a stripe edge (texel-space positions across: mid-stripe, one texel in, straddling an edge).
    std::vector<Case> cases;
    for (float ratio : {16.0f, 8.0f})
      for (float across : {2.0f, 3.0f, 3.75f, 5.25f, 6.0f, 9.5f})
        for (int p = 0; p < 3; ++p) {
          float along = (7.0f + 19.0f * float(p)) / 64.0f, cross = (across + 16.0f * float(p)) / 64.0f;
          float du = ratio / 64.0f, dv = 1.0f / 64.0f;
          cases.push_back(horizontal ? Case{{along, cross, du, dv}, {}} : Case{{cross, along, dv, du}, {}});
        }
    std::vector<Float4> got = RunPixel(device, body, "sampling-anisotropic", cases, {srv.get()}, {aniso.get(), tri.get()});
    for (size_t i = 0; i < cases.size(); ++i) {
      double truth = BoxAverage(c, cases[i].a[0], cases[i].a[1], cases[i].a[2], cases[i].a[3]);
      double ea = std::abs(got[i][0] - truth), et = std::abs(got[i][1] - truth);
      errAniso += ea;
      errTri += et;
      ++n;
      if (ea > worstErr) {
        worstErr = ea;
        worstCase = std::string(horizontal ? "horizontal" : "vertical") + " stripes, footprint " + Fmt(cases[i].a[2] * 64) + " x " +
                    Fmt(cases[i].a[3] * 64) + " texels at uv (" + Fmt(cases[i].a[0]) + ", " + Fmt(cases[i].a[1]) + "): box " + Fmt(truth) +
                    ", anisotropic " + Fmt(got[i][0]) + ", trilinear " + Fmt(got[i][1]);
      }
    }
  }
  errAniso /= double(n);
  errTri /= double(n);
  std::string detail = "mean |error| anisotropic " + Fmt(errAniso) + ", trilinear " + Fmt(errTri) + "; worst anisotropic case: " + worstCase;
  if (errTri < 0.1) return Fail("trilinear error " + Fmt(errTri) + " is too small for the probe to tell filters apart; " + detail, errAniso, "abs", 0.5 * errTri);
  Result r = Within(errAniso, 0.5 * errTri, "abs", detail);
  if (r.status == Status::Pass) r.detail = detail;
  return r;
}

}  // namespace sp::conformance::sampling
