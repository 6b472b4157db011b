// Moment shadow maps: what is stored per texel for a depth z in [0, 1], and the visibility
// reconstructed from filtered moments for a receiver depth. Used by moments/resolve.hlsl (writing)
// and by the lighting includes of techniques that filter with moments (reading); the C++ side is
// techniques/moments/moment-maps.h, which sets the defines below from its settings.
//
//   MOMENT_KIND          0 vsm   (z, z^2)                          Donnelly & Lauritzen 2006
//                        1 esm   exp(c z)                          Annen et al. 2008
//                        2 evsm2 (w+, w+^2), w+ = exp(c+ z')       Lauritzen (EVSM), z' = 2z - 1
//                        3 evsm4 (w+, w+^2, w-, w-^2), w- = -exp(-c- z')
//                        4 msm   (z, z^2, z^3, z^4)                Peters & Klein 2015, Hamburger 4MSM
//   MOMENT_FP16          1: 16 bits per channel (R16F/RG16F/RGBA16F; MSM: RGBA16_UNORM of the
//                        quantized moments), 0: 32-bit float channels
//   MOMENT_EXP_POS/NEG   c (esm: POS only), c+ and c- (evsm); clamped below to what the format holds
//   MOMENT_BLEED         light-bleeding reduction: visibility v -> linstep(bleed, 1, v)
//   MOMENT_MIN_VARIANCE  vsm/evsm variance floor, in depth units squared (evsm scales it to the warp)
//   MOMENT_MSM_BIAS      MSM moment bias alpha
#ifndef SP_MOMENTS_HLSLI
#define SP_MOMENTS_HLSLI

#define MOMENT_KIND_VSM 0
#define MOMENT_KIND_ESM 1
#define MOMENT_KIND_EVSM2 2
#define MOMENT_KIND_EVSM4 3
#define MOMENT_KIND_MSM 4

// Defaults let the file compile on its own (the every-shader compile test); techniques set all.
#ifndef MOMENT_KIND
#define MOMENT_KIND MOMENT_KIND_EVSM4
#endif
#ifndef MOMENT_FP16
#define MOMENT_FP16 0
#endif
#ifndef MOMENT_EXP_POS
#define MOMENT_EXP_POS 40.0
#endif
#ifndef MOMENT_EXP_NEG
#define MOMENT_EXP_NEG 5.0
#endif
#ifndef MOMENT_BLEED
#define MOMENT_BLEED 0.0
#endif
#ifndef MOMENT_MIN_VARIANCE
#define MOMENT_MIN_VARIANCE 1e-6
#endif
#ifndef MOMENT_MSM_BIAS
#define MOMENT_MSM_BIAS 3e-5
#endif

// --- Exponent clamps (mirrored in techniques/moments/moment-maps.cpp; keep both in step).
// EVSM stores w and w^2 with w = exp(c z'), z' in [-1, 1], so exp(2c) must stay below the
// format's largest finite value:
//   fp16: 2c <= ln(65504) = 11.0898  ->  c <= 5.5449; we use 5.54 (exp(11.08) = 64913).
//   fp32: 2c <= ln(3.4028e38) = 88.7228 -> c <= 44.36; we use 42, because the negative warp's
//         square exp(-2c) must also stay a normal float (GPUs flush denormals to zero, which
//         would zero the variance): exp(-2c) >= 1.1755e-38 needs c <= 43.67.
//   (fp16's exp(-2c) is subnormal above c = 4.86; fp16 subnormals are kept, only less precise.)
// ESM stores exp(c z), z in [0, 1], unsquared: c <= ln(max):
//   fp16: ln(65504) = 11.0898 -> 11.08;  fp32: ln(3.4028e38) = 88.7228 -> 88.72.
// The lower bound 0.1 keeps the warp from degenerating to a constant (zero variance everywhere).
static const float kMomentMinExponent = 0.1;

float2 ClampEvsmExponents(float2 requested, bool fp16) {
  float limit = fp16 ? 5.54 : 42.0;
  return clamp(requested, kMomentMinExponent, limit);
}

float ClampEsmExponent(float requested, bool fp16) {
  float limit = fp16 ? 11.08 : 88.72;
  return clamp(requested, kMomentMinExponent, limit);
}

// Depth outside [0, 1] (geometry behind the near plane without pancaking, a degenerate
// triangle, an uninitialised texel) must not reach the warps: exp of it can overflow, and one
// infinite texel turns every texel the blur touches into inf or NaN. Negative depth becomes the
// near plane, above 1 the far plane; NaN becomes the far plane (no occluder), which is what the
// comparisons below give since every comparison with NaN is false.
float MomentClampDepth(float z) { return z >= 0.0 ? min(z, 1.0) : (z < 0.0 ? 0.0 : 1.0); }

float MomentLinstep(float lo, float hi, float v) { return saturate((v - lo) / (hi - lo)); }

// Light-bleeding reduction (Lauritzen): visibilities below `bleed` become 0 and the rest is
// stretched back to [0, 1]. Chebyshev-type bounds overestimate visibility where occluders at
// several depths overlap, so the lower tail is exactly where the leaks are.
float MomentReduceBleeding(float visibility, float bleed) { return MomentLinstep(bleed, 1.0, visibility); }

// One-tailed Chebyshev (Cantelli) upper bound on P(occluder >= t) from the mean and second
// moment: 1 when t is in front of the mean, else var / (var + (t - mean)^2).
float MomentChebyshev(float2 m, float t, float minVariance) {
  float variance = max(m.y - m.x * m.x, minVariance);
  float d = t - m.x;
  return t <= m.x ? 1.0 : variance / (variance + d * d);
}

// --- VSM
float4 VsmMoments(float z) {
  z = MomentClampDepth(z);
  return float4(z, z * z, 0.0, 0.0);
}

float VsmVisibility(float4 m, float z, float minVariance, float bleed) {
  z = MomentClampDepth(z);
  return MomentReduceBleeding(MomentChebyshev(m.xy, z, minVariance), bleed);
}

// --- ESM
float4 EsmMoments(float z, float c) { return float4(exp(c * MomentClampDepth(z)), 0.0, 0.0, 0.0); }

// exp(c (z_occ - z)) where the filtered map holds E[exp(c z_occ)]. Written as
// exp(log(m) - c z) so neither exp(-c z) (underflows to 0 for large c z) nor the product is
// formed; m >= 1 since stored depths are >= 0, the max() only guards a map that was never written.
float EsmVisibility(float4 m, float z, float c, float bleed) {
  z = MomentClampDepth(z);
  float v = saturate(exp(log(max(m.x, 1e-30)) - c * z));
  return MomentReduceBleeding(v, bleed);
}

// --- EVSM
float2 EvsmWarp(float z, float2 c) {
  float zs = 2.0 * MomentClampDepth(z) - 1.0;
  return float2(exp(c.x * zs), -exp(-c.y * zs));
}

float4 Evsm2Moments(float z, float2 c) {
  float w = EvsmWarp(z, c).x;
  return float4(w, w * w, 0.0, 0.0);
}

float4 Evsm4Moments(float z, float2 c) {
  float2 w = EvsmWarp(z, c);
  return float4(w.x, w.x * w.x, w.y, w.y * w.y);
}

// Chebyshev in each warped space. The variance floor is given in depth units and stands for the
// rounding noise of the stored occluder depths, so it is carried into warped units with the warp's
// slope at the occluders: d(warp)/dz = 2 c |w| (z' = 2z - 1), taken at the filtered mean. (Taking
// it at the receiver, as is common, makes the floor grow like w_receiver^2 and leaves every
// receiver far behind an occluder lit by about minVariance (2c)^2: 0.0064 for c = 40.)
float EvsmVisibility(float4 m, float z, float2 c, float minVariance, float bleed, bool fourComponent) {
  float2 w = EvsmWarp(z, c);
  // As a standard deviation first: slope^2 alone overflows fp32 (2 * 42 * e^42 squared = 2e40).
  float2 floorStd = sqrt(minVariance) * 2.0 * c * abs(m.xz);
  float v = MomentChebyshev(m.xy, w.x, floorStd.x * floorStd.x);
  if (fourComponent) v = min(v, MomentChebyshev(m.zw, w.y, floorStd.y * floorStd.y));
  return MomentReduceBleeding(v, bleed);
}

// --- MSM
// Peters & Klein's optimised quantisation for 16-bit storage: q = b M + (0.035955884801, 0,
// 0, 0) with b = (z, z^2, z^3, z^4) as a row vector. It maps the moment curve of z in [0, 1]
// into [0, 1]^4 (checked: each channel's range over z in [0, 1] is within [0, 1]) and spreads
// it so that 16-bit UNORM rounding hurts the reconstruction least. Affine, so filtering the
// quantised moments equals quantising the filtered ones. The inverse matrix was computed from M
// (Gauss-Jordan in double precision), not taken from elsewhere.
float4 MsmQuantize(float4 b) {
  float4 q = b.x * float4(-2.07224649, 13.7948857237, 0.105877704, 9.7924062118) +
             b.y * float4(32.23703778, -59.4683975703, -1.9077466311, -33.7652110555) +
             b.z * float4(-68.571074599, 82.0359750338, 9.3496555107, 47.9456096605) +
             b.w * float4(39.3703274134, -35.364903257, -6.6543490743, -23.9728048165);
  return q + float4(0.035955884801, 0.0, 0.0, 0.0);
}

float4 MsmDequantize(float4 q) {
  q.x -= 0.035955884801;
  return q.x * float4(0.2227744146, 0.1549679261, 0.1451988946, 0.1631274430) +
         q.y * float4(0.0771972861, 0.1394629427, 0.2120202157, 0.2591432266) +
         q.z * float4(0.7926986637, 0.7963415838, 0.7258694464, 0.6539092497) +
         q.w * float4(0.0319417555, -0.1722823173, -0.2758014811, -0.3376131734);
}

float4 MsmMoments(float z) {
  z = MomentClampDepth(z);
  float z2 = z * z;
  return float4(z, z2, z2 * z, z2 * z2);
}

// The moment bias pulls b towards a point strictly inside the moment space, so the Hankel matrix
// below stays positive definite after rounding. We use the moments of masses 0.315, 0.37, 0.315
// at depths 0, 1/2, 1 (three atoms: an interior point; in [-1, 1] coordinates this is the
// (0, 0.63, 0, 0.63) often quoted for MSM). The also common (0.5, 0.5, 0.5, 0.5) is the two-atom
// distribution {0, 1}, on the boundary: biasing a z = 1 texel (no occluder) towards it leaves the
// matrix singular.
static const float4 kMsmBiasTarget = float4(0.5, 0.4075, 0.36125, 0.338125);

// Hamburger 4MSM (Peters & Klein 2015, algorithm 2) from raw moments b: the sharpest lower bound
// on the fraction of occluders in front of z over all distributions with these moments, turned
// into visibility 1 - bound.
float MsmVisibility(float4 b, float z, float alpha, float bleed) {
  z = MomentClampDepth(z);
  // Written out rather than lerp(): lerp with a constant endpoint rounds differently on the
  // two backends (Vulkan and GL differ by an ulp), which the cancellation below amplifies.
  b = b + alpha * (kMsmBiasTarget - b);
  // H = [1 b1 b2; b1 b2 b3; b2 b3 b4] = L D L^T with unit lower-triangular L.
  float d2 = b.y - b.x * b.x;
  float l32 = (b.z - b.x * b.y) / d2;
  float d3 = b.w - b.y * b.y - l32 * l32 * d2;
  // Solve H c = (1, z, z^2): forward substitution, scale by D, back substitution.
  float y2 = z - b.x;
  float y3 = z * z - b.y - l32 * y2;
  float c3 = y3 / d3;
  float c2 = y2 / d2 - l32 * c3;
  float c1 = 1.0 - b.x * c2 - b.y * c3;
  // c3 = 0 (z exactly on the curve the first two moments predict) sends one root to infinity;
  // a tiny c3 of the same sign gives the limit.
  c3 = abs(c3) < 1e-20 ? (c3 < 0.0 ? -1e-20 : 1e-20) : c3;
  // The roots z2 <= z3 of c3 x^2 + c2 x + c1 are, with z, the support of the distribution that
  // attains the bound.
  float p = c2 / c3, q = c1 / c3;
  float r = sqrt(max(0.25 * p * p - q, 0.0));
  float lo = -0.5 * p - r, hi = -0.5 * p + r;
  float z2 = min(lo, hi), z3 = max(lo, hi);
  float shadow;
  if (z <= z2) {
    shadow = 0.0;
  } else if (z <= z3) {
    shadow = (z * z3 - b.x * (z + z3) + b.y) / ((z3 - z2) * (z - z2));
  } else {
    shadow = 1.0 - (z2 * z3 - b.x * (z2 + z3) + b.y) / ((z - z2) * (z - z3));
  }
  return MomentReduceBleeding(saturate(1.0 - shadow), bleed);
}

// --- The configured kind (defines above)

float2 MomentExponents() {
#if MOMENT_KIND == MOMENT_KIND_ESM
  return float2(ClampEsmExponent(MOMENT_EXP_POS, MOMENT_FP16 != 0), 0.0);
#else
  return ClampEvsmExponents(float2(MOMENT_EXP_POS, MOMENT_EXP_NEG), MOMENT_FP16 != 0);
#endif
}

// What one depth sample contributes to a texel, in the stored form (MSM 16-bit: quantised).
float4 MomentsFromDepth(float z) {
#if MOMENT_KIND == MOMENT_KIND_VSM
  return VsmMoments(z);
#elif MOMENT_KIND == MOMENT_KIND_ESM
  return EsmMoments(z, MomentExponents().x);
#elif MOMENT_KIND == MOMENT_KIND_EVSM2
  return Evsm2Moments(z, MomentExponents());
#elif MOMENT_KIND == MOMENT_KIND_EVSM4
  return Evsm4Moments(z, MomentExponents());
#elif MOMENT_FP16
  return MsmQuantize(MsmMoments(z));
#else
  return MsmMoments(z);
#endif
}

// Visibility of a receiver at depth z (same space as the map) from filtered stored moments.
float MomentVisibility(float4 stored, float z) {
#if MOMENT_KIND == MOMENT_KIND_VSM
  return VsmVisibility(stored, z, MOMENT_MIN_VARIANCE, MOMENT_BLEED);
#elif MOMENT_KIND == MOMENT_KIND_ESM
  return EsmVisibility(stored, z, MomentExponents().x, MOMENT_BLEED);
#elif MOMENT_KIND == MOMENT_KIND_EVSM2
  return EvsmVisibility(stored, z, MomentExponents(), MOMENT_MIN_VARIANCE, MOMENT_BLEED, false);
#elif MOMENT_KIND == MOMENT_KIND_EVSM4
  return EvsmVisibility(stored, z, MomentExponents(), MOMENT_MIN_VARIANCE, MOMENT_BLEED, true);
#elif MOMENT_FP16
  return MsmVisibility(MsmDequantize(stored), z, MOMENT_MSM_BIAS, MOMENT_BLEED);
#else
  return MsmVisibility(stored, z, MOMENT_MSM_BIAS, MOMENT_BLEED);
#endif
}

// Lookups with the map's sampler (trilinear or anisotropic): moments are filtered like colour.
// Sample needs screen-space derivatives (pixel shaders); SampleLevel works in any stage.
float MomentSampleVisibility(Texture2DArray<float4> map, SamplerState smp, float2 uv, float layer, float z) {
  return MomentVisibility(map.Sample(smp, float3(uv, layer)), z);
}

float MomentSampleLevelVisibility(Texture2DArray<float4> map, SamplerState smp, float2 uv, float layer, float lod, float z) {
  return MomentVisibility(map.SampleLevel(smp, float3(uv, layer), lod), z);
}

#endif  // SP_MOMENTS_HLSLI
