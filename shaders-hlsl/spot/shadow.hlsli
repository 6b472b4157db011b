// Lighting side of the spot technique (techniques/spot/): one spot light's shadow in one
// perspective depth map, sampled with the 2x2 hardware comparison filter or the PCF library's
// filter (SHADOW_FILTER 1..3 with SHADOW_KERNEL, 5 pcss), SHADOW_ACCEL's secondary map deciding
// whole footprints first (common/hpsm.hlsli). Other lights: 1.
#include "common/shadow-lookup.hlsli"
#include "common/shadow-pcss.hlsli"
#if defined(SHADOW_ACCEL) && SHADOW_ACCEL != 0
#include "common/hpsm.hlsli"
#endif

cbuffer SpotShadow : register(b2) {
  float4x4 spotViewProj;
  float2 spotMapSize;   // texels; for the lab's ShadowTexel
  uint spotLightIndex;  // the local light this map shadows
  float padSpotShadow;
  ShadowPcssInput spotPcss;  // filter=pcss: perspective, the light's disc radius
};

Texture2DArray<float> SpotShadowMap : register(t0);
SamplerComparisonState SpotShadowSampler : register(s0);
#if defined(SHADOW_ACCEL) && SHADOW_ACCEL != 0
Texture2DArray<float4> SpotHpsm : register(t1);
#if HPSM_COUNTERS
RWByteAddressBuffer SpotHpsmCounters : register(u7);  // as basic's: clear of the lab's render targets
#endif
#endif

// uv in [0, 1] (D3D: NDC +y is the top row) and depth; w <= 0 (behind the light) gives z > 1.
float3 SpotShadowCoord(float3 worldPos) {
  float4 p = mul(spotViewProj, float4(worldPos, 1.0));
  if (p.w <= 0.0) return float3(0.5, 0.5, 2.0);
  p.xyz /= p.w;
  return float3(p.xy * float2(0.5, -0.5) + 0.5, p.z);
}

// Outside the frustum the spot light contributes nothing (its cone lies inside): lit, no lookup.
bool SpotOutsideMap(float3 c) { return any(c.xy < 0.0) || any(c.xy > 1.0) || c.z > 1.0; }

#define SP_LOCAL_SHADOWS 1
float LocalShadowVisibility(uint light, float3 worldPos, float3 worldNormal) {
  if (light != spotLightIndex) return 1.0;
  float3 c = SpotShadowCoord(worldPos);
  if (SpotOutsideMap(c)) return 1.0;
  // No pixel position reaches LocalShadowVisibility, hence no poisson (its rotation needs one).
  ShadowFilterInput i = {c.xy, 0.0, c.z, 1.0 / spotMapSize, float4(0, 0, 1, 1), float2(0, 0), float2(0, 0)};
#if defined(SHADOW_ACCEL) && SHADOW_ACCEL != 0
  uint how;
#if SHADOW_FILTER == 5
  float v = HpsmShadowFilterPcss(SpotShadowMap, SpotShadowSampler, SpotHpsm, i, spotPcss, how);
#else
  float v = HpsmShadowFilter(SpotShadowMap, SpotShadowSampler, SpotHpsm, i, how);
#endif
#if HPSM_COUNTERS
  SpotHpsmCounters.InterlockedAdd(how * 4, 1);
#endif
  return v;
#elif SHADOW_FILTER == 0
  return SpotShadowMap.SampleCmpLevelZero(SpotShadowSampler, float3(c.xy, 0), c.z);
#elif SHADOW_FILTER == 5
  return ShadowFilterPcss(SpotShadowMap, SpotShadowSampler, i, spotPcss);
#else
  return ShadowFilter(SpotShadowMap, SpotShadowSampler, i);
#endif
}

// The directional light is not this technique's.
float ShadowVisibility(float3 worldPos, float3 worldNormal, float4 svPosition) { return 1.0; }

float2 ShadowTexel(float3 worldPos, float layer) { return SpotShadowCoord(worldPos).xy * spotMapSize; }

ShadowLookup ShadowLocate(float3 worldPos, float3 worldNormal) {
  float3 c = SpotShadowCoord(worldPos);
  return MakeShadowLookup(SpotOutsideMap(c) ? kShadowNoLayer : 0.0, c.xy * spotMapSize);
}
