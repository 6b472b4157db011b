// The moment functions of shaders-hlsl/moments/moments.hlsli against CPU reference
// implementations written here from the papers (double precision, and for MSM a different solver:
// Gaussian elimination instead of the shader's Cholesky), the exponent clamps on both sides, and
// the parameter parser.
#include <algorithm>
#include <cmath>
#include <limits>

#include "backend-test.h"
#include "moments/moment-maps.h"

namespace sp::test {
namespace {

using tech::MomentKind;
using tech::MomentPrecision;

// --- CPU references

double Linstep(double lo, double hi, double v) { return std::clamp((v - lo) / (hi - lo), 0.0, 1.0); }
double ClampDepth(double z) { return std::isnan(z) ? 1.0 : std::clamp(z, 0.0, 1.0); }

double Chebyshev(double mean, double second, double t, double minVariance) {
  if (t <= mean) return 1.0;
  double var = std::max(second - mean * mean, minVariance);
  return var / (var + (t - mean) * (t - mean));
}

double VsmRef(const double* m, double z, double minVariance, double bleed) {
  return Linstep(bleed, 1, Chebyshev(m[0], m[1], ClampDepth(z), minVariance));
}

double EsmRef(const double* m, double z, double c, double bleed) {
  return Linstep(bleed, 1, std::min(1.0, m[0] * std::exp(-c * ClampDepth(z))));
}

double EvsmRef(const double* m, double z, double cp, double cn, double minVariance, double bleed, bool four) {
  double zs = 2 * ClampDepth(z) - 1;
  double wp = std::exp(cp * zs), wn = -std::exp(-cn * zs);
  // The floor scales with the warp's slope at the filtered mean (the occluders).
  double v = Chebyshev(m[0], m[1], wp, minVariance * (2 * cp * m[0]) * (2 * cp * m[0]));
  if (four) v = std::min(v, Chebyshev(m[2], m[3], wn, minVariance * (2 * cn * m[2]) * (2 * cn * m[2])));
  return Linstep(bleed, 1, v);
}

// The bias target: the moments of masses 0.315, 0.37, 0.315 at depths 0, 1/2, 1.
void MsmBiasTarget(double t[4]) {
  for (int k = 0; k < 4; ++k) t[k] = 0.37 * std::pow(0.5, k + 1) + 0.315;
}

// Hamburger 4MSM (Peters & Klein 2015, algorithm 2) with Gaussian elimination for the 3x3 solve.
double MsmRef(const double* raw, double z, double alpha, double bleed) {
  z = ClampDepth(z);
  double t[4], b[4];
  MsmBiasTarget(t);
  for (int k = 0; k < 4; ++k) b[k] = (1 - alpha) * raw[k] + alpha * t[k];
  double a[3][4] = {{1, b[0], b[1], 1}, {b[0], b[1], b[2], z}, {b[1], b[2], b[3], z * z}};
  for (int col = 0; col < 3; ++col) {
    int piv = col;
    for (int r = col + 1; r < 3; ++r)
      if (std::abs(a[r][col]) > std::abs(a[piv][col])) piv = r;
    std::swap(a[col], a[piv]);
    for (int r = 0; r < 3; ++r) {
      if (r == col) continue;
      double f = a[r][col] / a[col][col];
      for (int k = col; k < 4; ++k) a[r][k] -= f * a[col][k];
    }
  }
  double c1 = a[0][3] / a[0][0], c2 = a[1][3] / a[1][1], c3 = a[2][3] / a[2][2];
  double p = c2 / c3, q = c1 / c3, r = std::sqrt(std::max(0.25 * p * p - q, 0.0));
  double z2 = -0.5 * p - r, z3 = -0.5 * p + r;
  double shadow;
  if (z <= z2)
    shadow = 0;
  else if (z <= z3)
    shadow = (z * z3 - b[0] * (z + z3) + b[1]) / ((z3 - z2) * (z - z2));
  else
    shadow = 1 - (z2 * z3 - b[0] * (z2 + z3) + b[1]) / ((z - z2) * (z - z3));
  return Linstep(bleed, 1, std::clamp(1 - shadow, 0.0, 1.0));
}

// Peters & Klein's quantisation, q = b M + (0.035955884801, 0, 0, 0) (b a row vector).
const double kMsmM[4][4] = {{-2.07224649, 13.7948857237, 0.105877704, 9.7924062118},
                            {32.23703778, -59.4683975703, -1.9077466311, -33.7652110555},
                            {-68.571074599, 82.0359750338, 9.3496555107, 47.9456096605},
                            {39.3703274134, -35.364903257, -6.6543490743, -23.9728048165}};
void MsmQuantizeRef(const double* b, double* q) {
  for (int j = 0; j < 4; ++j) {
    q[j] = j == 0 ? 0.035955884801 : 0.0;
    for (int i = 0; i < 4; ++i) q[j] += b[i] * kMsmM[i][j];
  }
}

// Stored moments of one depth (MSM raw, unquantised).
void MomentsRef(MomentKind k, double z, double cp, double cn, double* m) {
  z = ClampDepth(z);
  double zs = 2 * z - 1, wp = std::exp(cp * zs), wn = -std::exp(-cn * zs);
  switch (k) {
    case MomentKind::Vsm: m[0] = z, m[1] = z * z, m[2] = m[3] = 0; break;
    case MomentKind::Esm: m[0] = std::exp(cp * z), m[1] = m[2] = m[3] = 0; break;
    case MomentKind::Evsm2: m[0] = wp, m[1] = wp * wp, m[2] = m[3] = 0; break;
    case MomentKind::Evsm4: m[0] = wp, m[1] = wp * wp, m[2] = wn, m[3] = wn * wn; break;
    case MomentKind::Msm: m[0] = z, m[1] = z * z, m[2] = z * z * z, m[3] = z * z * z * z; break;
  }
}

// --- The shader under test: one case per thread, every function of moments.hlsli.

const char* kEvalCS = R"(
#include "moments/moments.hlsli"
struct Case {
  float4 moments;
  float4 params;   // receiver depth, bleed, min variance, msm bias
  float4 params2;  // c+ (esm: c), c-
  uint4 kind;      // MomentKind, or 5: MSM through the quantised form; 6: exponent clamps (y = fp16)
};
struct Result { float4 generated; float4 visibility; };
StructuredBuffer<Case> cases : register(t0);
RWStructuredBuffer<Result> results : register(u0);
cbuffer Count : register(b0) { uint caseCount; uint3 padCount; };

[numthreads(64, 1, 1)] void main(uint3 id : SV_DispatchThreadID) {
  if (id.x >= caseCount) return;
  Case c = cases[id.x];
  float z = c.params.x, bleed = c.params.y, minVariance = c.params.z, alpha = c.params.w;
  Result r;
  r.generated = 0.0;
  r.visibility = 0.0;
  uint k = c.kind.x;
  if (k == 0) {
    r.generated = VsmMoments(z);
    r.visibility.x = VsmVisibility(c.moments, z, minVariance, bleed);
  } else if (k == 1) {
    r.generated = EsmMoments(z, c.params2.x);
    r.visibility.x = EsmVisibility(c.moments, z, c.params2.x, bleed);
  } else if (k == 2) {
    r.generated = Evsm2Moments(z, c.params2.xy);
    r.visibility.x = EvsmVisibility(c.moments, z, c.params2.xy, minVariance, bleed, false);
  } else if (k == 3) {
    r.generated = Evsm4Moments(z, c.params2.xy);
    r.visibility.x = EvsmVisibility(c.moments, z, c.params2.xy, minVariance, bleed, true);
  } else if (k == 4) {
    r.generated = MsmMoments(z);
    r.visibility.x = MsmVisibility(c.moments, z, alpha, bleed);
  } else if (k == 5) {
    r.generated = MsmQuantize(MsmMoments(z));
    r.visibility = MsmDequantize(c.moments);
  } else {
    r.generated = float4(ClampEvsmExponents(c.params2.xy, c.kind.y != 0), ClampEsmExponent(c.params2.x, c.kind.y != 0), 0.0);
  }
  results[id.x] = r;
}
)";

struct Case {
  float moments[4];
  float params[4];
  float params2[4];
  uint32_t kind[4];
};
static_assert(sizeof(Case) == 64);
struct Result {
  float generated[4];
  float visibility[4];
};

std::vector<Result> RunCases(Device& dev, const std::vector<Case>& cases) {
  DeviceContext& ctx = *dev.GetImmediateContext();
  Ref<Buffer> in = MakeBuffer(dev, BIND_SHADER_RESOURCE, cases.data(), uint32_t(cases.size() * sizeof(Case)), RESOURCE_MISC_BUFFER_STRUCTURED,
                              sizeof(Case));
  Ref<Buffer> out = MakeBuffer(dev, BIND_UNORDERED_ACCESS, nullptr, uint32_t(cases.size() * sizeof(Result)), RESOURCE_MISC_BUFFER_STRUCTURED,
                               sizeof(Result));
  uint32_t count[4] = {uint32_t(cases.size()), 0, 0, 0};
  Ref<Buffer> cb = MakeBuffer(dev, BIND_CONSTANT_BUFFER, count, 16);
  Ref<ShaderResourceView> srv = dev.CreateShaderResourceView(in.get());
  Ref<UnorderedAccessView> uav = dev.CreateUnorderedAccessView(out.get());
  Ref<ComputeShader> cs = dev.CreateComputeShader(CompileHlsl(kEvalCS, "cs_5_0", "main"));
  ctx.CSSetShader(cs.get());
  ctx.CSSetShaderResources(0, {srv.get()});
  ctx.CSSetUnorderedAccessViews(0, {uav.get()});
  ctx.CSSetConstantBuffers(0, {cb.get()});
  ctx.Dispatch(uint32_t(cases.size() + 63) / 64, 1, 1);
  return ReadAs<Result>(ReadBuffer(dev, ctx, out.get()));
}

class MomentEvalTest : public BackendTest {
 protected:
  std::vector<Result> Run(const std::vector<Case>& cases) { return RunCases(device(), cases); }
};

// Depth distributions a filter footprint can hold (depths, weights): one occluder, two at
// several separations and mixes, three, and the extremes of the range.
struct Mixture {
  std::vector<double> depth, weight;
};
const std::vector<Mixture> kMixtures = {
    {{0.3}, {1}},           {{0.2, 0.6}, {0.5, 0.5}},  {{0.45, 0.55}, {0.7, 0.3}}, {{0.1, 0.5, 0.9}, {0.2, 0.5, 0.3}},
    {{0.05, 0.95}, {0.9, 0.1}}, {{0.7, 0.72}, {0.5, 0.5}}, {{0.0, 1.0}, {0.3, 0.7}},   {{1.0}, {1}},
    {{0.25, 0.4, 0.41, 0.8}, {0.25, 0.25, 0.25, 0.25}},
};
const double kReceivers[] = {0.0, 0.1, 0.2, 0.25, 0.3, 0.35, 0.45, 0.5, 0.56, 0.6, 0.65, 0.71, 0.8, 0.9, 0.97, 1.0};

// The cases: each kind's moments of the mixtures above (averaged in double, then rounded to float as
// a fp32 map stores them) with a range of receivers, and the CPU's visibility and moments.
struct Table {
  std::vector<Case> cases;
  std::vector<double> expected, expectedGen[4];
  std::vector<double> tolerance;
  std::vector<std::string> label;
  std::vector<double> truth;     // fraction of the mixture at or behind the receiver
  std::vector<bool> unreduced;   // bleed 0: the reference must bound the truth from above
};

Table BuildTable() {
  struct Config {
    MomentKind kind;
    double cp, cn, minVariance, bleed, alpha, tolerance;
  };
  const Config configs[] = {
      {MomentKind::Vsm, 0, 0, 1e-6, 0.0, 0, 2e-5},    {MomentKind::Vsm, 0, 0, 1e-4, 0.3, 0, 2e-5},
      {MomentKind::Esm, 80, 0, 0, 0.0, 0, 2e-5},      {MomentKind::Esm, 11.08, 0, 0, 0.1, 0, 2e-5},
      {MomentKind::Evsm2, 40, 5, 1e-6, 0.0, 0, 2e-5}, {MomentKind::Evsm4, 40, 5, 1e-6, 0.0, 0, 2e-5},
      {MomentKind::Evsm4, 42, 42, 1e-6, 0.1, 0, 2e-5}, {MomentKind::Evsm4, 5.54, 5.54, 1e-5, 0.05, 0, 2e-5},
      {MomentKind::Msm, 0, 0, 0, 0.0, 3e-5, 1e-3},    {MomentKind::Msm, 0, 0, 0, 0.03, 6e-5, 1e-3},
  };
  Table t;
  auto& cases = t.cases;
  auto &expected = t.expected, &tolerance = t.tolerance;
  auto& expectedGen = t.expectedGen;
  auto& label = t.label;
  for (const Config& cfg : configs)
    for (size_t mi = 0; mi < kMixtures.size(); ++mi)
      for (double zr : kReceivers) {
        double m[4] = {0, 0, 0, 0};
        for (size_t i = 0; i < kMixtures[mi].depth.size(); ++i) {
          double one[4];
          MomentsRef(cfg.kind, kMixtures[mi].depth[i], cfg.cp, cfg.cn, one);
          for (int k = 0; k < 4; ++k) m[k] += kMixtures[mi].weight[i] * one[k];
        }
        Case c{};
        double stored[4];
        for (int k = 0; k < 4; ++k) stored[k] = c.moments[k] = float(m[k]);
        c.params[0] = float(zr), c.params[1] = float(cfg.bleed), c.params[2] = float(cfg.minVariance), c.params[3] = float(cfg.alpha);
        c.params2[0] = float(cfg.cp), c.params2[1] = float(cfg.cn);
        c.kind[0] = uint32_t(cfg.kind);
        double z = c.params[0], cp = c.params2[0], cn = c.params2[1], mv = c.params[2], bl = c.params[1], al = c.params[3];
        double v = 0;
        switch (cfg.kind) {
          case MomentKind::Vsm: v = VsmRef(stored, z, mv, bl); break;
          case MomentKind::Esm: v = EsmRef(stored, z, cp, bl); break;
          case MomentKind::Evsm2: v = EvsmRef(stored, z, cp, cn, mv, bl, false); break;
          case MomentKind::Evsm4: v = EvsmRef(stored, z, cp, cn, mv, bl, true); break;
          case MomentKind::Msm: v = MsmRef(stored, z, al, bl); break;
        }
        double gen[4];
        MomentsRef(cfg.kind, z, cp, cn, gen);
        cases.push_back(c);
        expected.push_back(v);
        for (int k = 0; k < 4; ++k) expectedGen[k].push_back(gen[k]);
        tolerance.push_back(cfg.tolerance);
        double lit = 0;
        for (size_t i = 0; i < kMixtures[mi].depth.size(); ++i) lit += kMixtures[mi].depth[i] >= z ? kMixtures[mi].weight[i] : 0.0;
        t.truth.push_back(lit);
        t.unreduced.push_back(cfg.bleed == 0);
        label.push_back(tech::MomentKindName(cfg.kind) + " mixture " + std::to_string(mi) + " receiver " + std::to_string(zr) +
                        " bleed " + std::to_string(cfg.bleed));
      }
  return t;
}

// Visibility from every kind's HLSL equals the CPU reference for filtered moments of the
// mixtures above (moments averaged in double, then rounded to float as a fp32 map stores them)
// and a range of receivers; generated moments equal the CPU's for the receiver depth.
// Tolerances (absolute, visibility in [0, 1]): 2e-5 for vsm, esm, evsm (float rounding of the
// inputs, amplified at most ~10x by Chebyshev's division; measured <= 1e-6); 1e-3 for msm: the
// Hankel solve loses up to log10(cond) ~ 4 digits of fp32's 7 where two occluders are close
// (measured worst 2.4e-4 on lavapipe and llvmpipe). Generated moments: see below.
TEST_P(MomentEvalTest, HlslEvaluationMatchesCpuReference) {
  const Table t = BuildTable();
  const auto& cases = t.cases;
  const auto &expected = t.expected, &tolerance = t.tolerance;
  const auto& expectedGen = t.expectedGen;
  const auto& label = t.label;
  std::vector<Result> r = Run(cases);
  ASSERT_EQ(r.size(), cases.size());
  double worst[5] = {0, 0, 0, 0, 0};
  for (size_t i = 0; i < cases.size(); ++i) {
    double err = std::abs(r[i].visibility[0] - expected[i]);
    worst[cases[i].kind[0]] = std::max(worst[cases[i].kind[0]], err);
    EXPECT_LE(err, tolerance[i]) << label[i] << ": HLSL " << r[i].visibility[0] << ", CPU " << expected[i];
    for (int k = 0; k < 4; ++k) {
      // exp(x) in float is off by about |x| ulps (x itself is rounded by half an ulp of |x|):
      // relative tolerance 4 eps (1 + |x|), x the warp's argument (2x for the squares).
      double e = expectedGen[k][i], x = 0;
      MomentKind kind = MomentKind(cases[i].kind[0]);
      if (kind == MomentKind::Esm) x = cases[i].params2[0];
      if (kind == MomentKind::Evsm2 || kind == MomentKind::Evsm4) x = (k < 2 ? cases[i].params2[0] : cases[i].params2[1]) * (k % 2 ? 2 : 1);
      EXPECT_LE(std::abs(r[i].generated[k] - e), 4 * std::numeric_limits<float>::epsilon() * (1 + x) * std::abs(e) + 1e-30)
          << label[i] << " generated moment " << k << ": HLSL " << r[i].generated[k] << ", CPU " << e;
    }
  }
  for (int k = 0; k < 5; ++k) std::printf("  %s: worst |HLSL - CPU| = %.3g\n", tech::MomentKindName(MomentKind(k)).c_str(), worst[k]);
}

// The references themselves: every method bounds the true visibility of the mixture (the
// fraction of occluders at or behind the receiver) from above, since Chebyshev's inequality,
// Markov's (ESM) and the 4MSM lower bound on shadow intensity all do. Biases only loosen the bound
// (MSM within 1e-3, the pull of alpha towards an interior point). Guards against a reference
// and the shader sharing one mistake.
TEST(MomentReferences, BoundTheTrueVisibilityFromAbove) {
  const Table t = BuildTable();
  size_t checked = 0;
  for (size_t i = 0; i < t.cases.size(); ++i) {
    if (!t.unreduced[i]) continue;
    // 1e-6: the moments are rounded to float, and Chebyshev is tight for two-point mixtures.
    double slack = t.cases[i].kind[0] == uint32_t(MomentKind::Msm) ? 1e-3 : 1e-6;
    EXPECT_GE(t.expected[i], t.truth[i] - slack) << t.label[i];
    ++checked;
  }
  EXPECT_GT(checked, size_t(500));
}

// Both backends evaluate the same functions from the same SPIR-V (Vulkan) or the GLSL made from
// it (GL). On Mesa (llvmpipe behind both) the results must be bit-identical, as the toolchain's
// fixed arithmetic promises for the lit pass; elsewhere within the tolerances above. (MSM's bias
// is written as b + alpha (t - b) because lerp() with a constant endpoint broke this: see the
// comment in moments.hlsli.)
TEST(MomentCrossBackend, EvaluationAgreesAcrossBackends) {
  const Table t = BuildTable();
  std::vector<Result> r[2];
  bool mesa = true;
  const Backend backends[2] = {Backend::Vulkan, Backend::OpenGL};
  for (int b = 0; b < 2; ++b) {
    DeviceDesc dd;
    dd.backend = backends[b];
    Ref<Device> dev = CreateDevice(dd);
    mesa &= dev->Info().deviceName.find("llvmpipe") != std::string::npos;
    r[b] = RunCases(*dev, t.cases);
    EXPECT_EQ(dev->ValidationErrorCount(), 0u) << dev->LastValidationError();
  }
  double worst[5] = {0, 0, 0, 0, 0};
  size_t differing[5] = {0, 0, 0, 0, 0};
  for (size_t i = 0; i < t.cases.size(); ++i) {
    uint32_t k = t.cases[i].kind[0];
    double d = std::abs(double(r[0][i].visibility[0]) - r[1][i].visibility[0]);
    worst[k] = std::max(worst[k], d);
    differing[k] += d != 0;
    EXPECT_LE(d, mesa ? 0.0 : t.tolerance[i]) << t.label[i] << ": Vulkan " << r[0][i].visibility[0] << ", OpenGL " << r[1][i].visibility[0];
  }
  for (int k = 0; k < 5; ++k)
    std::printf("  %s: %zu cases differ across backends, by at most %.3g\n", tech::MomentKindName(MomentKind(k)).c_str(), differing[k], worst[k]);
}

// The quantisation is invertible (MsmDequantize(MsmQuantize(b)) = b to float precision), the
// quantised moments of every depth lie in [0, 1] (so RGBA16_UNORM holds them), and the HLSL
// quantisation equals the CPU's.
TEST_P(MomentEvalTest, MsmQuantisationRoundTripsAndFitsUnorm) {
  std::vector<Case> cases;
  std::vector<double> z;
  for (int i = 0; i <= 64; ++i) {
    Case c{};
    double b[4], q[4];
    z.push_back(i / 64.0);
    MomentsRef(MomentKind::Msm, z.back(), 0, 0, b);
    MsmQuantizeRef(b, q);
    for (int k = 0; k < 4; ++k) {
      EXPECT_GE(q[k], 0.0) << "z " << z.back() << " channel " << k;
      EXPECT_LE(q[k], 1.0) << "z " << z.back() << " channel " << k;
      c.moments[k] = float(q[k]);
    }
    c.params[0] = float(z.back());
    c.kind[0] = 5;
    cases.push_back(c);
  }
  std::vector<Result> r = Run(cases);
  for (size_t i = 0; i < cases.size(); ++i) {
    double b[4], q[4];
    MomentsRef(MomentKind::Msm, z[i], 0, 0, b);
    MsmQuantizeRef(b, q);
    for (int k = 0; k < 4; ++k) {
      // Quantised: the sums cancel terms up to ~70, so 70 * 4 ulp absolute.
      EXPECT_NEAR(r[i].generated[k], q[k], 70 * 4 * std::numeric_limits<float>::epsilon()) << "z " << z[i] << " channel " << k;
      EXPECT_NEAR(r[i].visibility[k], b[k], 2e-6) << "round trip, z " << z[i] << " channel " << k;
    }
  }
}

// ClampEvsmExponents / ClampEsmExponent give the same numbers in HLSL and C++, and the limits
// are what the formats hold: exp(2 c) for evsm and exp(c) for esm below the largest finite value.
TEST_P(MomentEvalTest, ExponentClampsAgreeInHlslAndCpp) {
  const float requested[][2] = {{0.0f, 0.0f}, {1.0f, 2.0f}, {5.0f, 5.6f}, {6.0f, 100.0f}, {41.0f, 43.0f}, {80.0f, 1.0f}, {200.0f, 200.0f}};
  std::vector<Case> cases;
  for (uint32_t fp16 = 0; fp16 < 2; ++fp16)
    for (const auto& q : requested) {
      Case c{};
      c.params2[0] = q[0], c.params2[1] = q[1];
      c.kind[0] = 6, c.kind[1] = fp16;
      cases.push_back(c);
    }
  std::vector<Result> r = Run(cases);
  for (size_t i = 0; i < cases.size(); ++i) {
    bool fp16 = cases[i].kind[1] != 0;
    glm::vec2 evsm = tech::ClampEvsmExponents({cases[i].params2[0], cases[i].params2[1]}, fp16);
    float esm = tech::ClampEsmExponent(cases[i].params2[0], fp16);
    EXPECT_EQ(r[i].generated[0], evsm.x) << i;
    EXPECT_EQ(r[i].generated[1], evsm.y) << i;
    EXPECT_EQ(r[i].generated[2], esm) << i;
  }
  const double half = 65504.0, single = std::numeric_limits<float>::max();
  EXPECT_LT(std::exp(2.0 * tech::kEvsmMaxExponentFp16), half);
  EXPECT_GT(std::exp(2.0 * (tech::kEvsmMaxExponentFp16 + 0.01)), half);  // within 0.01 of the limit
  EXPECT_LT(std::exp(2.0 * tech::kEvsmMaxExponentFp32), single);
  EXPECT_GT(std::exp(-2.0 * tech::kEvsmMaxExponentFp32), double(std::numeric_limits<float>::min()));  // negative warp stays normal
  EXPECT_LT(std::exp(double(tech::kEsmMaxExponentFp16)), half);
  EXPECT_LT(std::exp(double(tech::kEsmMaxExponentFp32)), single);
}

SP_INSTANTIATE_BACKEND_TESTS(MomentEvalTest);

// --- The parameter parser (no device)

TEST(MomentParams, DefaultsPerKindAndClampedExponents) {
  tech::MomentOptions o = tech::ParseMomentOptions({{"filter", "evsm4"}});
  EXPECT_EQ(o.kind, MomentKind::Evsm4);
  EXPECT_EQ(o.precision, MomentPrecision::Fp32);
  EXPECT_EQ(o.msaa, 1u);
  EXPECT_EQ(o.exponents, glm::vec2(40.0f, 5.0f));
  o = tech::ParseMomentOptions({{"filter", "evsm4"}, {"precision", "fp16"}, {"exponents", "100,100"}, {"msaa", "4"}, {"blur", "0.5"},
                                {"bleed", "0.25"}, {"resolution", "1024"}});
  EXPECT_EQ(o.exponents, glm::vec2(tech::kEvsmMaxExponentFp16));
  EXPECT_EQ(o.msaa, 4u);
  EXPECT_FLOAT_EQ(o.blur, 0.5f);
  EXPECT_FLOAT_EQ(o.bleed, 0.25f);
  o = tech::ParseMomentOptions({{"filter", "esm"}, {"exponents", "500"}});
  EXPECT_EQ(o.exponents.x, tech::kEsmMaxExponentFp32);
  o = tech::ParseMomentOptions({{"filter", "msm"}, {"precision", "fp16"}});
  EXPECT_EQ(tech::MomentFormat(o.kind, o.precision), FORMAT_R16G16B16A16_UNORM);
  EXPECT_FLOAT_EQ(o.msmBias, 6e-5f);
  EXPECT_FLOAT_EQ(tech::BlurRadiusTexels(0.5f, 100.0f, 2048), 10.24f);
  EXPECT_EQ(tech::BlurRadiusTexels(50.0f, 100.0f, 2048), tech::kMaxBlurRadiusTexels);
  // A technique's declared parameters (ParamValues fills defaults) parse as the moment options.
  std::vector<tech::ParamSpec> specs = tech::MomentParamSpecs();
  specs.push_back({tech::ParamSpec::Choice, "filter", "", "evsm4", 0, 0, tech::MomentFilterNames()});
  tech::ParamValues pv = tech::ParamValues::Parse("test", specs, {{"filter", "vsm"}, {"msaa", "4"}});
  o = tech::ParseMomentOptions(pv.all());
  EXPECT_EQ(o.kind, MomentKind::Vsm);
  EXPECT_EQ(o.msaa, 4u);
  EXPECT_FLOAT_EQ(o.bleed, 0.2f);
  o = tech::ParseMomentOptions({{"filter", "msm"}, {"precision", "fp16"}});
  std::vector<hlsl::Define> d = tech::MomentDefines(o);
  ASSERT_FALSE(d.empty());
  EXPECT_EQ(d[0].name, "MOMENT_KIND");
  EXPECT_EQ(d[0].value, "4");
}

TEST(MomentParams, ErrorsNameTheParameterAndListValidValues) {
  auto message = [](const std::map<std::string, std::string>& p) {
    try {
      tech::ParseMomentOptions(p);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_NE(message({{"filter", "pcf"}}).find("filter=pcf is not valid; filter takes vsm|evsm2|evsm4|esm|msm"), std::string::npos);
  EXPECT_NE(message({{"filter", "vsm"}, {"msaa", "2"}}).find("msaa=2 is not valid; msaa takes 1|4"), std::string::npos);
  EXPECT_NE(message({{"filter", "vsm"}, {"bleed", "1"}}).find("bleed=1 is not valid; bleed takes a number in [0, 1)"), std::string::npos);
  EXPECT_NE(message({{"filter", "vsm"}, {"blur", "-1"}}).find("blur=-1"), std::string::npos);
  EXPECT_NE(message({{"filter", "evsm4"}, {"exponents", "40,x"}}).find("exponents=40,x is not valid"), std::string::npos);
  EXPECT_NE(message({{"filter", "esm"}, {"exponents", "40,5"}}).find("one number for esm"), std::string::npos);
  EXPECT_NE(message({{"filter", "msm"}, {"precision", "fp64"}}).find("precision takes fp16|fp32"), std::string::npos);
}

}  // namespace
}  // namespace sp::test
