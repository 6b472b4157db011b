// Lighting side of the basic technique: one shadow map fitted to the scene, sampled with the
// hardware's 2x2 comparison filter (SampleCmpLevelZero), or, when the technique defines
// SHADOW_FILTER (a filter other than hw2x2, or an accelerated one), with common/shadow-filter.hlsli
// and SHADOW_ACCEL's secondary map (common/hpsm.hlsli).
#include "common/shadow-lookup.hlsli"
#ifdef SHADOW_FILTER
#include "common/hpsm.hlsli"
#endif

cbuffer BasicShadow : register(b2) {
  float4x4 lightViewProj;
  float2 shadowMapSize;  // texels; for the lab's ShadowTexel
  float2 padBasicShadow;
};

Texture2D<float> ShadowMap : register(t0);
SamplerComparisonState ShadowSampler : register(s0);
#ifdef SHADOW_FILTER
Texture2DArray<float> ShadowMapArray : register(t1);  // the same map, as ShadowFilter reads it
#if defined(SHADOW_ACCEL) && SHADOW_ACCEL != 0
Texture2DArray<float4> HpsmMap : register(t2);
#if HPSM_COUNTERS
// Decisions (kHpsm* words), for HpsmDecisions(); u7 stays clear of the lab's six render targets.
RWByteAddressBuffer HpsmCounters : register(u7);
#endif
#endif
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
#ifdef SHADOW_FILTER
  ShadowFilterInput fi;
  fi.uv = c.xy;
  fi.layer = 0.0;
  fi.depth = c.z;
  fi.texelSize = 1.0 / shadowMapSize;
  fi.uvClamp = float4(0, 0, 1, 1);
  fi.depthGradient = float2(0, 0);  // basic's bias is the rasterizer's
  fi.pixel = svPosition.xy;
#if defined(SHADOW_ACCEL) && SHADOW_ACCEL != 0
  uint how;
  float v = HpsmShadowFilter(ShadowMapArray, ShadowSampler, HpsmMap, fi, how);
#if HPSM_COUNTERS
  HpsmCounters.InterlockedAdd(how * 4, 1);
#endif
  return v;
#else
  return ShadowFilter(ShadowMapArray, ShadowSampler, fi);
#endif
#else
  return ShadowMap.SampleCmpLevelZero(ShadowSampler, c.xy, c.z);
#endif
}

// One layer (0); points outside the map are lit without a lookup.
float2 ShadowTexel(float3 worldPos, float layer) { return BasicShadowCoord(worldPos).xy * shadowMapSize; }

ShadowLookup ShadowLocate(float3 worldPos, float3 worldNormal) {
  float3 c = BasicShadowCoord(worldPos);
  return MakeShadowLookup(BasicOutsideMap(c) ? kShadowNoLayer : 0.0, c.xy * shadowMapSize);
}
