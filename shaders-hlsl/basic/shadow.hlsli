// Lighting side of the basic technique: one shadow map fitted to the scene, sampled with the
// hardware's 2x2 comparison filter (SampleCmpLevelZero), or with the PCF library's filter
// (SHADOW_FILTER 1..4 with SHADOW_KERNEL, 5 pcss), and SHADOW_ACCEL's secondary map deciding
// whole footprints before the filter runs (common/hpsm.hlsli). SHAFTS=1 adds sun shafts
// (ShadowInScatter, common/shafts.hlsli).
#include "common/shadow-lookup.hlsli"
#include "common/shadow-pcss.hlsli"
#if defined(SHADOW_ACCEL) && SHADOW_ACCEL != 0
#include "common/hpsm.hlsli"
#endif

cbuffer BasicShadow : register(b2) {
  float4x4 lightViewProj;
  float2 shadowMapSize;  // texels; for the lab's ShadowTexel
  float2 padBasicShadow;
  ShadowPcssInput basicPcss;  // filter=pcss: orthographic, the sun's angular size
  float4 basicShafts;         // shafts: density per world unit, steps
};

Texture2DArray<float> ShadowMap : register(t0);
SamplerComparisonState ShadowSampler : register(s0);
#if (defined(SHADOW_ACCEL) && SHADOW_ACCEL != 0) || (defined(SHAFT_ACCEL) && SHAFT_ACCEL != 0)
Texture2DArray<float4> HpsmMap : register(t1);
#endif
#if (defined(SHADOW_ACCEL) && SHADOW_ACCEL != 0 && HPSM_COUNTERS) || (defined(SHAFT_COUNTERS) && SHAFT_COUNTERS)
// Decisions (kHpsm* words), for HpsmDecisions(); u7 stays clear of the lab's six render targets.
RWByteAddressBuffer HpsmCounters : register(u7);
#endif

// Map coordinates of a world point: uv in [0, 1] (D3D: NDC +y is the top row, so v = 0.5 - 0.5 y)
// and the light-space depth.
float3 BasicShadowCoord(float3 worldPos) {
  float4 p = mul(lightViewProj, float4(worldPos, 1.0));
  p.xyz /= p.w;
  return float3(p.xy * float2(0.5, -0.5) + 0.5, p.z);
}

bool BasicOutsideMap(float3 c) { return any(c.xy < 0.0) || any(c.xy > 1.0) || c.z > 1.0; }

float ShadowVisibility(float3 worldPos, float3 worldNormal, float4 svPosition) {
  float3 c = BasicShadowCoord(worldPos);
  if (BasicOutsideMap(c)) return 1.0;
  // The rasterizer's depth bias is the only bias: no receiver-plane gradient.
  ShadowFilterInput i = {c.xy, 0.0, c.z, 1.0 / shadowMapSize, float4(0, 0, 1, 1), float2(0, 0), svPosition.xy};
#if defined(SHADOW_ACCEL) && SHADOW_ACCEL != 0
  uint how;
#if SHADOW_FILTER == 5
  float v = HpsmShadowFilterPcss(ShadowMap, ShadowSampler, HpsmMap, i, basicPcss, how);
#else
  float v = HpsmShadowFilter(ShadowMap, ShadowSampler, HpsmMap, i, how);
#endif
#if HPSM_COUNTERS
  HpsmCounters.InterlockedAdd(how * 4, 1);
#endif
  return v;
#elif SHADOW_FILTER == 5
  return ShadowFilterPcss(ShadowMap, ShadowSampler, i, basicPcss);
#elif SHADOW_FILTER == 0
  return ShadowMap.SampleCmpLevelZero(ShadowSampler, float3(c.xy, 0), c.z);
#else
  return ShadowFilter(ShadowMap, ShadowSampler, i);
#endif
}

// One layer (0); points outside the map are lit without a lookup.
float2 ShadowTexel(float3 worldPos, float layer) { return BasicShadowCoord(worldPos).xy * shadowMapSize; }

ShadowLookup ShadowLocate(float3 worldPos, float3 worldNormal) {
  float3 c = BasicShadowCoord(worldPos);
  return MakeShadowLookup(BasicOutsideMap(c) ? kShadowNoLayer : 0.0, c.xy * shadowMapSize);
}

#if defined(SHAFTS) && SHAFTS
#include "common/frame.hlsli"
#define SHAFT_MAP ShadowMap
#define SHAFT_HPSM HpsmMap
#include "common/shafts.hlsli"

// In-scattered light along the view ray from the camera to worldPos, in units of lightColor. The
// light's projection is orthographic, so the world steps map to evenly spaced map coordinates.
float ShadowInScatter(float3 worldPos) {
  float3 a = BasicShadowCoord(cameraPos), b = BasicShadowCoord(worldPos);
  ShaftRay r;
  r.steps = uint(basicShafts.y);
  r.c0 = float3(a.xy * shadowMapSize, a.z);
  r.dc = (float3(b.xy * shadowMapSize, b.z) - r.c0) / float(r.steps);
  r.dt = length(worldPos - cameraPos) / float(r.steps);
  r.density = basicShafts.x;
  r.mapSize = int2(shadowMapSize);
  ShaftResult s = ShaftMarch(r);
#if SHAFT_COUNTERS
  HpsmCounters.InterlockedAdd(kShaftLookedUp * 4, s.lookedUp);
  HpsmCounters.InterlockedAdd(kShaftSkipped * 4, s.skipped);
#endif
  return s.inScatter;
}
#endif
