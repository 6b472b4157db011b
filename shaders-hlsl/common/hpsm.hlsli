// Accelerated comparison filtering: hybrid min/max plane shadow maps (HPSM; Gruen, "Fast
// Conventional Shadow Filtering", GPU Pro, 2010) and the hierarchical min/max baseline (Dmitriev
// and Uralsky, "Soft shadows in games", 2007). A secondary texture says, per block of shadow-map
// texels, either min and max depth or a plane that fits every depth within a residual; a lookup
// whose whole filter footprint lies on one side of it skips the filter with one (min/max: four)
// loads. Built by common/hpsm-build.hlsl; the C++ side is techniques/hpsm-maps.h.
//
// Defines (the technique's, from HpsmDefines()):
//   SHADOW_ACCEL  1 hpsm, 2 minmax (0 or undefined: this file only declares the build's helpers)
//   HPSM_BLOCK    shadow-map texels per secondary texel and axis (minmax: 2^level)
//   HPSM_REACH    R, the footprint reach the maps were built for (below)
//   HPSM_COUNTERS 1: the technique counts decisions (its own UAV; hpsm-maps.h's BindCounters)
//   HPSM_PCSS_MAX_KERNEL  SHADOW_FILTER 5: pcss_max_kernel M, which bounds PCSS's footprint
//
// Footprint: a lookup centred at s (texel space, ShadowFilterSetup) reads only texels
// [floor(s) - R, floor(s) + R + 1] per axis, clamped into the filter's [lo, hi]: R = 0 for hw2x2,
// N/2 for box, gauss and gathercmp (taps at s + o, |o| <= N/2, each reading floor(p), floor(p)+1),
// N/2 + 1 for poisson (taps within 0.98 N/2 < N/2 + 1/2). A texel outside it can be read only by a
// tap whose coordinate the sampler rounded across a texel centre, with a weight of that rounding's
// size (zero where coordinates are exact, as with power-of-two maps, or snapped to 8 subtexel
// bits, as on D3D11 hardware).
// PCSS (common/shadow-pcss.hlsli): the search's radius r is at most M/2 and its loads read texel
// floor(p + 1/2) for p in [s - r, s + r]; the box of width w <= M (clamped) gives weight only to
// texels whose cell meets (s - w/2, s + w/2). Both are texels t with |t - s| < M/2 + 1/2, i.e.
// [floor(s) - ceil((M-1)/2), floor(s) + ceil((M-1)/2) + 1]; R = floor(M/2) + 1 is one more, for
// the search's last tap s - r + 2r, which float rounding may carry past s + r (one texel in about
// 10^4 at s ~ 2000). Gathers of the box's last 2x2 block may read one texel further with weight 0.
//
// Exactness: with LESS_EQUAL (reference <= depth is lit) every tap is 1 when each reference any
// tap uses is <= every depth it reads, 0 when each is > every depth it reads; the filters' tap
// weights then sum to the result, 1 (box, gauss, poisson exactly; gathercmp to the float rounding
// of its weights, about 1e-7) or 0. Every tap position p (ShadowFilterTap's clamped p, gathercmp's
// g + 1/2) lies in the footprint's rectangle [t0, t1]^2, and its reference is
// reference + (p - s).G (ShadowFilterReference). Decisions:
//   min/max: the references' range over the rectangle (exact without a gradient) against the
//     block's min and max, which are exact;
//   plane: Q(t) = plane(t) - reference(t), affine, at least |G|1 + residual above zero (lit) or
//     below (shadowed) over the whole rectangle; a tap reading t is within one texel of it, so its
//     reference differs from reference(t) by at most |G|1, and depth(t) from plane(t) by the stored
//     residual. kHpsmRounding of the magnitudes involved covers the float evaluation of the plane
//     and the references here and in the build.
// PCSS: lit when every texel of the footprint is >= every reference: no search load finds a
// blocker (stored < reference), and shadow-pcss.hlsli returns exactly 1 without running its box.
// Shadowed when every texel is < every reference: every search load is a blocker, so the average
// blocker depth is only known to lie in the blockers' range, but the box's width is clamped to
// <= M whatever it is, so every texel with a non-zero weight lies in the footprint and compares
// 0: the sum is exactly 0 (weight-zero texels outside add 0 * 0 or 0 * 1).
#ifndef SP_HPSM_HLSLI
#define SP_HPSM_HLSLI

#include "common/shadow-filter.hlsli"

// Decisions, also the counters' word indices.
static const uint kHpsmLitMinMax = 0;
static const uint kHpsmShadowedMinMax = 1;
static const uint kHpsmLitPlane = 2;
static const uint kHpsmShadowedPlane = 3;
static const uint kHpsmFiltered = 4;
static const uint kHpsmDecisions = 5;

// w of a min/max texel (min, max, 0, w); plane texels (a, b, c, residual) have w >= 0.
static const float kHpsmMinMaxTag = -1.0;
// 2^-19: bounds the relative float error of a 3-term plane evaluation done twice (build and
// lookup) plus the subtractions around it (Higham's gamma_n, n <= 12, is below 12 * 2^-24).
static const float kHpsmRounding = 1.9073486e-6;

// The texels secondary texel b covers along one axis: its block [bB, bB + B) widened by `before`
// and `after` texels (the footprint's reach on each side), clamped into the map as the filter
// clamps its taps.
int2 HpsmSupport(int b, int block, int before, int after, int size) {
  return int2(max(0, b * block - before), min(size - 1, b * block + block - 1 + after));
}

// The plane's origin: the middle of the support, so its constant term is the mean depth and the
// slopes multiply small offsets.
float2 HpsmPlaneOrigin(int2 sx, int2 sy) { return float2(sx.x + sx.y, sy.x + sy.y) * 0.5; }

#ifndef HPSM_COUNTERS
#define HPSM_COUNTERS 0
#endif

#if defined(SHADOW_ACCEL) && SHADOW_ACCEL != 0

#if SHADOW_FILTER == 0
#define HPSM_FILTER_REACH 0
#elif SHADOW_FILTER == 1 || SHADOW_FILTER == 2 || SHADOW_FILTER == 3
#define HPSM_FILTER_REACH SHADOW_KERNEL_HALF
#elif SHADOW_FILTER == 4
#define HPSM_FILTER_REACH (SHADOW_KERNEL_HALF + 1)
#elif SHADOW_FILTER == 5
#if !defined(HPSM_PCSS_MAX_KERNEL) || HPSM_PCSS_MAX_KERNEL < 1
#error SHADOW_ACCEL with pcss needs HPSM_PCSS_MAX_KERNEL, the widest box the maps were built for
#endif
#define HPSM_FILTER_REACH (HPSM_PCSS_MAX_KERNEL / 2 + 1)
#include "common/shadow-pcss.hlsli"
#else
#error hpsm.hlsli does not know the footprint of this SHADOW_FILTER
#endif
#if !defined(HPSM_BLOCK) || !defined(HPSM_REACH) || HPSM_BLOCK < 1
#error SHADOW_ACCEL needs HPSM_BLOCK >= 1 and HPSM_REACH
#endif
#if HPSM_REACH < HPSM_FILTER_REACH
#error HPSM_REACH is smaller than the footprint reach of the filter: the maps were built for a narrower kernel
#endif
#if SHADOW_ACCEL == 2 && (HPSM_BLOCK & (HPSM_BLOCK - 1)) != 0
#error the min/max baseline needs HPSM_BLOCK to be a power of two (the level of a mip chain)
#endif
#if SHADOW_ACCEL == 2 && HPSM_BLOCK < 2 * HPSM_REACH + 2
#error the min/max baseline level must be at least as wide as the footprint (2 HPSM_REACH + 2)
#endif

#if SHADOW_ACCEL == 2
// Min and max depth over texels [t0, t1] of a layer from the min/max level, whose texels are at
// least as wide as the footprint (2R + 2 <= HPSM_BLOCK): the footprint spans at most 2 x 2 of them.
float2 HpsmMinMaxOver(Texture2DArray<float4> hpsm, int2 t0, int2 t1, int layer) {
  int2 b0 = t0 / HPSM_BLOCK, b1 = t1 / HPSM_BLOCK;
  float2 m00 = hpsm.Load(int4(b0.x, b0.y, layer, 0)).xy, m10 = hpsm.Load(int4(b1.x, b0.y, layer, 0)).xy;
  float2 m01 = hpsm.Load(int4(b0.x, b1.y, layer, 0)).xy, m11 = hpsm.Load(int4(b1.x, b1.y, layer, 0)).xy;
  return float2(min(min(m00.x, m10.x), min(m01.x, m11.x)), max(max(m00.y, m10.y), max(m01.y, m11.y)));
}
#endif

// Which decision the secondary map makes for lookup i (kHpsm*).
uint HpsmDecide(Texture2DArray<float4> hpsm, ShadowFilterInput i) {
  ShadowFilterFrame f = ShadowFilterSetup(i);
  // Clamping moves the taps of a receiver outside the clamp rectangle off the footprint below.
  if (any(f.s < f.lo - 0.5) || any(f.s > f.hi + 0.5)) return kHpsmFiltered;
  int2 fs = int2(floor(f.s));
  int2 t0 = max(int2(f.lo), fs - HPSM_REACH), t1 = min(int2(f.hi), fs + HPSM_REACH + 1);
  int layer = int(i.layer);
  // References: a tap at p compares reference + (p - s).G, G the receiver's depth step per texel,
  // and p lies in the footprint's rectangle (both texels it reads do), so the references lie within
  // refExtent of their value at the rectangle's middle m. Exact without a gradient.
  float2 G = i.depthGradient * i.texelSize;
  float2 m = float2(t0 + t1) * 0.5, e = float2(t1 - t0) * 0.5;
  float refCentre = f.reference + dot(m - f.s, G);
  float refExtent = dot(abs(G), e);
  bool tilted = any(G != 0.0);
  float refSlack = tilted ? kHpsmRounding * (abs(f.reference) + dot(abs(G), abs(m - f.s) + e)) : 0.0;
  float refLo = refCentre - refExtent - refSlack, refHi = refCentre + refExtent + refSlack;
#if SHADOW_ACCEL == 2
  float2 range = HpsmMinMaxOver(hpsm, t0, t1, layer);
  if (refHi <= range.x) return kHpsmLitMinMax;
  if (refLo > range.y) return kHpsmShadowedMinMax;
  return kHpsmFiltered;
#else
  int2 mapSize = int2(round(1.0 / i.texelSize));
  int2 blocks = (mapSize + HPSM_BLOCK - 1) / HPSM_BLOCK;
  // fs may be -1 (s in the first half texel): its footprint lies in block 0's support.
  int2 b = clamp(fs / HPSM_BLOCK, int2(0, 0), blocks - 1);
  float4 h = hpsm.Load(int4(b, layer, 0));
  if (h.w < 0.0) {
    if (refHi <= h.x) return kHpsmLitMinMax;
    if (refLo > h.y) return kHpsmShadowedMinMax;
    return kHpsmFiltered;
  }
  // A plane follows a tilted receiver: compare depth and reference texel by texel. A tap at p
  // reads texels t within one texel of p per axis, so its reference is within |G|1 of
  // reference(t); every t has P(t) - residual <= depth(t) <= P(t) + residual. Q(t) = P(t) -
  // reference(t) is affine, its extremes over the rectangle at the corners.
  float2 origin = HpsmPlaneOrigin(HpsmSupport(b.x, HPSM_BLOCK, HPSM_REACH, HPSM_REACH + 1, mapSize.x),
                                  HpsmSupport(b.y, HPSM_BLOCK, HPSM_REACH, HPSM_REACH + 1, mapSize.y));
  float2 mo = m - origin;
  float q = h.z + h.x * mo.x + h.y * mo.y - refCentre;
  float qExtent = abs(h.x - G.x) * e.x + abs(h.y - G.y) * e.y;
  float margin = h.w + dot(abs(G), float2(1, 1)) + refSlack +
                 kHpsmRounding * (1.0 + abs(h.z) + abs(f.reference) + abs(h.x) * (abs(mo.x) + e.x) + abs(h.y) * (abs(mo.y) + e.y) + refExtent);
  if (q - qExtent >= margin) return kHpsmLitPlane;
  if (q + qExtent < -margin) return kHpsmShadowedPlane;
  return kHpsmFiltered;
#endif
}

#if SHADOW_FILTER != 5
// ShadowFilter, skipped where the secondary map decides; `how` is the decision.
float HpsmShadowFilter(Texture2DArray<float> map, SamplerComparisonState cmp, Texture2DArray<float4> hpsm, ShadowFilterInput i, out uint how) {
  how = HpsmDecide(hpsm, i);
  if (how == kHpsmFiltered) return ShadowFilter(map, cmp, i);
  return (how == kHpsmLitMinMax || how == kHpsmLitPlane) ? 1.0 : 0.0;
}
#else
// ShadowFilterPcss, skipped where the maps decide; p.maxKernel must be HPSM_PCSS_MAX_KERNEL or less.
float HpsmShadowFilterPcss(Texture2DArray<float> map, SamplerComparisonState cmp, Texture2DArray<float4> hpsm, ShadowFilterInput i, ShadowPcssInput p,
                           out uint how) {
  how = HpsmDecide(hpsm, i);
  if (how == kHpsmFiltered) return ShadowFilterPcss(map, cmp, i, p);
  return (how == kHpsmLitMinMax || how == kHpsmLitPlane) ? 1.0 : 0.0;
}
#endif

#endif
#endif  // SP_HPSM_HLSLI
