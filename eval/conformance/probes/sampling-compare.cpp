// Comparison sampling (SampleCmp, SampleCmpLevelZero) on a D32_FLOAT depth texture read through
// an R32_FLOAT view. D3D11 (functional spec, 7.18.7 "Comparison Filtering") compares first and
// filters after: each texel of the footprint gives 1 when `reference OP texel` holds, else 0,
// and those results are blended with the ordinary point or bilinear weights. So the expected
// value is the CPU bilinear filter of the 0/1 comparison results.
//
// Tolerance: 1/256 of the difference between the blended comparison results per linearly
// filtered axis (8-bit subtexel precision, see sampling-util.h) plus float rounding; point
// filtering and footprints whose four results agree must be exact.
//
// The depth texture is made both ways a shadow map is: rendered into its DSV (SV_Depth) and
// uploaded through a staging copy; both must give the same results. Reference values include
// every footprint texel's own value, where LESS and LESS_EQUAL differ.
#include "sampling-util.h"

namespace sp::conformance::sampling {
namespace {

constexpr uint32_t W = 8, H = 8;

// Distinct neighbouring depths k/64 (exact in float32), not monotonic in x or y.
std::vector<float> Depths() {
  std::vector<float> d(W * H);
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) d[y * W + x] = float(1 + (x * 37 + y * 11) % 62) / 64.0f;
  return d;
}

// Sample positions in texel space (s = u * W - 0.5): texel centres, points between texels with
// weights on the 1/256 grid and off it, and positions past the edges (CLAMP).
const std::array<double, 2> kPositions[] = {{2.0, 3.0},  {2.25, 3.5},  {4.5, 1.75},   {5.3, 6.7}, {0.6, 2.2},
                                            {3.125, 4.875}, {-0.3, 3.4}, {7.2, 7.4}, {6.75, -0.25}, {1.5, 0.5}};

bool Compare(COMPARISON_FUNC f, double ref, double texel) {
  switch (f) {
    case COMPARISON_LESS: return ref < texel;
    case COMPARISON_LESS_EQUAL: return ref <= texel;
    case COMPARISON_GREATER: return ref > texel;
    default: return false;
  }
}

const char* FuncName(COMPARISON_FUNC f) { return f == COMPARISON_LESS ? "LESS" : f == COMPARISON_LESS_EQUAL ? "LESS_EQUAL" : "GREATER"; }

struct CmpCase {
  float u, v, ref;
};

// Per position: each footprint texel's value exactly, and just below and above it, plus
// references below and above every depth.
std::vector<CmpCase> Cases(const std::vector<float>& depths) {
  std::vector<CmpCase> cases;
  for (auto [sx, sy] : kPositions) {
    float u = float((sx + 0.5) / W), v = float((sy + 0.5) / H);
    std::vector<float> refs = {0.0f, 1.0f};
    int i0 = int(std::floor(sx)), j0 = int(std::floor(sy));
    for (int dj = 0; dj < 2; ++dj)
      for (int di = 0; di < 2; ++di) {
        float d = depths[std::clamp(j0 + dj, 0, int(H) - 1) * W + std::clamp(i0 + di, 0, int(W) - 1)];
        refs.insert(refs.end(), {d, d - 1.0f / 128, d + 1.0f / 128});
      }
    for (float r : refs) cases.push_back({u, v, r});
  }
  return cases;
}

// The three comparison functions at once: s0 LESS, s1 LESS_EQUAL, s2 GREATER -> x, y, z.
const char* kLevelZeroBody = R"(
Texture2D<float> shadow : register(t0);
SamplerComparisonState less : register(s0);
SamplerComparisonState lessEqual : register(s1);
SamplerComparisonState greater : register(s2);
float4 Probe(Case k, uint index) {
  return float4(shadow.SampleCmpLevelZero(less, k.a.xy, k.a.z), shadow.SampleCmpLevelZero(lessEqual, k.a.xy, k.a.z),
                shadow.SampleCmpLevelZero(greater, k.a.xy, k.a.z), 0);
}
)";
// One texel per pixel: the implicit LOD is 0, as for a shadow map drawn at its own resolution.
const char* kImplicitBody = R"(
Texture2D<float> shadow : register(t0);
SamplerComparisonState less : register(s0);
SamplerComparisonState lessEqual : register(s1);
SamplerComparisonState greater : register(s2);
float4 Probe(Case k, float2 sub) {
  float2 uv = k.a.xy + sub * float2(1.0 / 8, 1.0 / 8);
  return float4(shadow.SampleCmp(less, uv, k.a.z), shadow.SampleCmp(lessEqual, uv, k.a.z), shadow.SampleCmp(greater, uv, k.a.z), 0);
}
)";

const COMPARISON_FUNC kFuncs[3] = {COMPARISON_LESS, COMPARISON_LESS_EQUAL, COMPARISON_GREATER};

// Runs every case with both depth textures; checks the functions in `funcs` (indices into kFuncs).
Result Run(Device& device, bool implicitLod, bool linear, std::vector<int> funcs) {
  if (!(device.CheckFormatSupport(FORMAT_R32_FLOAT) & FORMAT_SUPPORT_SHADER_SAMPLE_COMPARISON))
    return Unsupported("R32_FLOAT of a D32_FLOAT texture does not support comparison sampling");
  std::vector<float> depths = Depths();
  std::vector<CmpCase> cc = Cases(depths);
  std::vector<Case> cases;
  for (const CmpCase& c : cc) cases.push_back({{c.u, c.v, c.ref, 0}, {}});
  std::vector<Ref<SamplerState>> keep;
  std::vector<SamplerState*> samplers;
  for (COMPARISON_FUNC f : kFuncs) {
    SAMPLER_DESC d;
    d.Filter = linear ? FILTER_COMPARISON_MIN_MAG_LINEAR_MIP_POINT : FILTER_COMPARISON_MIN_MAG_MIP_POINT;
    d.ComparisonFunc = f;
    keep.push_back(MakeSampler(device, d));
    samplers.push_back(keep.back().get());
  }
  Worst worst;
  for (bool rendered : {false, true}) {
    DepthTexture tex = MakeDepthTexture(device, W, H, depths, rendered);
    std::vector<Float4> got = implicitLod ? RunPixel(device, kImplicitBody, "sampling-samplecmp", cases, {tex.srv.get()}, samplers)
                                          : RunCompute(device, kLevelZeroBody, "sampling-samplecmplevelzero", cases, {tex.srv.get()}, samplers);
    for (int fi : funcs) {
      for (size_t i = 0; i < cc.size(); ++i) {
        MipChain results{W, H, {std::vector<float>(W * H)}};
        for (uint32_t t = 0; t < W * H; ++t) results.levels[0][t] = Compare(kFuncs[fi], cc[i].ref, depths[t]) ? 1.0f : 0.0f;
        SamplerModel model;
        model.linear = linear;
        Expected e = SampleLevelCpu(results, 0, cc[i].u, cc[i].v, model);
        worst.Add(got[i][fi], e,
                  std::string(FuncName(kFuncs[fi])) + (rendered ? " rendered" : " uploaded") + " depth, uv (" + Fmt(cc[i].u) + ", " + Fmt(cc[i].v) +
                      ") ref " + Fmt(cc[i].ref));
      }
    }
  }
  return worst.Finish("abs");
}

}  // namespace

SP_PROBE(kGroup, "SampleCmpLevelZero LESS, bilinear", "ref < texel per texel, then bilinear weights of the 0/1 results (compare, then filter)") {
  return Run(device, false, true, {0});
}
SP_PROBE(kGroup, "SampleCmpLevelZero LESS_EQUAL, bilinear", "ref <= texel per texel, then bilinear weights; differs from LESS where ref equals a texel") {
  return Run(device, false, true, {1});
}
SP_PROBE(kGroup, "SampleCmpLevelZero GREATER, bilinear", "ref > texel per texel, then bilinear weights of the 0/1 results") {
  return Run(device, false, true, {2});
}
SP_PROBE(kGroup, "SampleCmp LESS, bilinear", "SampleCmp (implicit LOD, pixel shader): ref < texel, then bilinear weights") {
  return Run(device, true, true, {0});
}
SP_PROBE(kGroup, "SampleCmp LESS_EQUAL, bilinear", "SampleCmp (implicit LOD, pixel shader): ref <= texel, then bilinear weights") {
  return Run(device, true, true, {1});
}
SP_PROBE(kGroup, "SampleCmp GREATER, bilinear", "SampleCmp (implicit LOD, pixel shader): ref > texel, then bilinear weights") {
  return Run(device, true, true, {2});
}
SP_PROBE(kGroup, "SampleCmpLevelZero point-filtered, LESS/LESS_EQUAL/GREATER", "COMPARISON_MIN_MAG_MIP_POINT returns the 0/1 result of the nearest texel") {
  return Run(device, false, false, {0, 1, 2});
}
SP_PROBE(kGroup, "SampleCmp point-filtered, LESS/LESS_EQUAL/GREATER", "COMPARISON_MIN_MAG_MIP_POINT returns the 0/1 result of the nearest texel") {
  return Run(device, true, false, {0, 1, 2});
}

}  // namespace sp::conformance::sampling
