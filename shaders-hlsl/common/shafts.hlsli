// Sun shafts: single scattering of the directional light in a homogeneous medium, ray-marched
// through the shadow map from the camera to the shaded surface, optionally walking the ray per
// secondary-map texel (common/hpsm.hlsli's maps) so that whole runs of steps are decided without
// a lookup (the "other use" of min/max maps in Gruen's HPSM chapter; S.T.A.L.K.E.R.: Clear Sky).
//
//   L = lightColor * sigma * dt * sum_k V(x_k) exp(-sigma t_k),  t_k = (k + 1/2) dt,  dt = d / N
//
// sigma the scattering (= extinction) coefficient per world unit, no phase function (isotropic,
// its 1/4pi folded into sigma), d the camera-to-surface distance, N the steps, V the plain shadow
// test of x_k (one Load, lit when its depth <= the stored one; lit outside the map, as the
// technique's own lookup). The surface's radiance is not attenuated: shafts only add.
//
// The includer defines SHAFT_MAP, its shadow map (a Texture2DArray<float>, layer 0), and with
// SHAFT_ACCEL SHAFT_HPSM, the secondary map: names, not parameters, as glslang emits invalid
// SPIR-V for a texture passed beside this file's structs.
// Defines: SHAFT_ACCEL 0 none, 1 hpsm, 2 minmax; SHAFT_BLOCK, SHAFT_REACH the maps' block and
// reach (HpsmSettings); SHAFT_COUNTERS 1: count lookups (kShaftLookedUp) and steps decided
// without one (kShaftSkipped) in the hpsm counters' buffer.
//
// Exactness of the rejection: a step's map coordinates are computed by one expression,
// c0 + (k + 1/2) dc, in both walks; float rounding is monotone, so each coordinate is monotone in
// k and the steps whose texel lies in one block are contiguous, and the run's depth range is that
// of its two end steps. Every step of a decided run is lit (or shadowed) in the plain march too,
// and the weights are added in the same order, so the sum is the same to the bit.
#ifndef SP_SHAFTS_HLSLI
#define SP_SHAFTS_HLSLI

#include "common/hpsm.hlsli"

#ifndef SHAFT_ACCEL
#define SHAFT_ACCEL 0
#endif
#ifndef SHAFT_COUNTERS
#define SHAFT_COUNTERS 0
#endif
#if SHAFT_ACCEL != 0 && (!defined(SHAFT_BLOCK) || !defined(SHAFT_REACH) || !defined(SHAFT_HPSM))
#error SHAFT_ACCEL needs SHAFT_BLOCK, SHAFT_REACH and SHAFT_HPSM
#endif

// Word indices in the hpsm counters' buffer, after its kHpsmDecisions words.
static const uint kShaftLookedUp = 5;
static const uint kShaftSkipped = 6;

// A view ray in the map's space: texel coordinates (xy) and depth (z) of the march's start, the
// step between samples, and the world length of a step.
struct ShaftRay {
  float3 c0;
  float3 dc;
  uint steps;
  float dt;
  float density;
  int2 mapSize;
};

struct ShaftResult {
  float inScatter;  // sigma dt sum: multiply by the light's colour
  uint lookedUp, skipped;
};

// precise: the run's ends and its steps must round alike, whichever walk computes them.
float3 ShaftPoint(ShaftRay r, uint k) {
  precise float3 c = r.c0 + (float(k) + 0.5) * r.dc;
  return c;
}
float ShaftWeight(ShaftRay r, uint k) { return exp(-r.density * r.dt * (float(k) + 0.5)); }
bool ShaftOutside(ShaftRay r, float3 c) { return any(c.xy < 0.0) || any(c.xy >= float2(r.mapSize)) || c.z > 1.0; }

// One step of the plain march: the weight where x_k is lit (outside the map without a lookup),
// and 1 where it looked up.
float2 ShaftStep(ShaftRay r, uint k) {
  float3 c = ShaftPoint(r, k);
  if (ShaftOutside(r, c)) return float2(ShaftWeight(r, k), 0.0);
  return float2(c.z <= SHAFT_MAP.Load(int4(int2(floor(c.xy)), 0, 0)) ? ShaftWeight(r, k) : 0.0, 1.0);
}

#if SHAFT_ACCEL != 0
int2 ShaftBlock(float3 c) { return int2(floor(c.xy)) / SHAFT_BLOCK; }

// The last step whose texel is still in block b, from step k (in b): the analytic exit, then
// moved back onto b with the steps' own expression (monotone, so the steps between are in b too).
uint ShaftRunEnd(ShaftRay r, uint k, int2 b) {
  float exitK = float(r.steps);
  for (int a = 0; a < 2; ++a) {
    if (r.dc[a] == 0.0) continue;
    float edge = float(r.dc[a] > 0.0 ? (b[a] + 1) * SHAFT_BLOCK : b[a] * SHAFT_BLOCK);
    exitK = min(exitK, (edge - r.c0[a]) / r.dc[a] - 0.5);
  }
  uint end = uint(clamp(floor(exitK) + 1.0, float(k), float(r.steps - 1)));
  // int division truncates: texel -1 would land in block 0, hence the outside test.
  [loop] while (end > k && (ShaftOutside(r, ShaftPoint(r, end)) || any(ShaftBlock(ShaftPoint(r, end)) != b))) --end;
  [loop] while (end + 1 < r.steps && !ShaftOutside(r, ShaftPoint(r, end + 1)) && all(ShaftBlock(ShaftPoint(r, end + 1)) == b)) ++end;
  return end;
}

// 1: every step of the run [k, end] is lit, -1: every one is shadowed, 0: undecided.
int ShaftDecide(ShaftRay r, int2 b, uint k, uint end) {
  float3 ca = ShaftPoint(r, k), cb = ShaftPoint(r, end);
  // A step beyond the map's far plane is lit whatever the map says: only decide runs before it.
  if (max(ca.z, cb.z) > 1.0) return 0;
  float4 h = SHAFT_HPSM.Load(int4(b, 0, 0));
  if (SHAFT_ACCEL == 2 || h.w < 0.0) {
    if (max(ca.z, cb.z) <= h.x) return 1;
    if (min(ca.z, cb.z) > h.y) return -1;
    return 0;
  }
  // Plane texel: depth(t) is within residual of P(t) for every texel t of the block's support, and
  // a step at c reads t = floor(c.xy), within a texel of c per axis, so depth(t) is within
  // residual + |a| + |b| of P(c.xy). P(c.xy) - c.z is affine along the run: its ends bound it, up
  // to the rounding of c (kHpsmRounding of the magnitudes, as in hpsm.hlsli).
  float2 origin = HpsmPlaneOrigin(HpsmSupport(b.x, SHAFT_BLOCK, SHAFT_REACH, SHAFT_REACH + 1, r.mapSize.x),
                                  HpsmSupport(b.y, SHAFT_BLOCK, SHAFT_REACH, SHAFT_REACH + 1, r.mapSize.y));
  float2 oa = ca.xy - origin, ob = cb.xy - origin;
  float qa = h.z + h.x * oa.x + h.y * oa.y - ca.z;
  float qb = h.z + h.x * ob.x + h.y * ob.y - cb.z;
  float2 reachAbs = max(abs(oa), abs(ob)) + 1.0;
  float margin = h.w + abs(h.x) + abs(h.y) +
                 kHpsmRounding * (1.0 + abs(h.z) + abs(h.x) * reachAbs.x + abs(h.y) * reachAbs.y + max(abs(ca.z), abs(cb.z)) +
                                  (abs(h.x) + abs(h.y)) * float(max(r.mapSize.x, r.mapSize.y)));
  if (min(qa, qb) >= margin) return 1;
  if (max(qa, qb) < -margin) return -1;
  return 0;
}
#endif

ShaftResult ShaftMarch(ShaftRay r) {
  float sum = 0.0;
  uint lookedUp = 0, skipped = 0;
#if SHAFT_ACCEL == 0
  [loop] for (uint k = 0; k < r.steps; ++k) {
    float2 w = ShaftStep(r, k);
    sum += w.x;
    lookedUp += uint(w.y);
  }
#else
  uint k = 0;
  [loop] while (k < r.steps) {
    float3 c = ShaftPoint(r, k);
    if (ShaftOutside(r, c)) {
      sum += ShaftWeight(r, k);
      ++k;
      continue;
    }
    int2 b = ShaftBlock(c);
    uint end = ShaftRunEnd(r, k, b);
    int d = ShaftDecide(r, b, k, end);
    if (d == 0) {
      [loop] for (uint j = k; j <= end; ++j) {
        float2 w = ShaftStep(r, j);
        sum += w.x;
        lookedUp += uint(w.y);
      }
    } else {
      if (d > 0) [loop] for (uint j = k; j <= end; ++j) sum += ShaftWeight(r, j);
      skipped += end - k + 1;
    }
    k = end + 1;
  }
#endif
  ShaftResult o;
  o.inScatter = r.density * r.dt * sum;
  o.lookedUp = lookedUp;
  o.skipped = skipped;
  return o;
}

#endif  // SP_SHAFTS_HLSLI
