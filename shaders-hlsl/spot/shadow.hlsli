// Lighting side of the spot technique (techniques/spot/): one spot light's shadow in one
// perspective depth map, sampled with the 2x2 hardware comparison filter. Other lights: 1.
#include "common/shadow-lookup.hlsli"

cbuffer SpotShadow : register(b2) {
  float4x4 spotViewProj;
  float2 spotMapSize;   // texels; for the lab's ShadowTexel
  uint spotLightIndex;  // the local light this map shadows
  float padSpotShadow;
};

Texture2D<float> SpotShadowMap : register(t0);
SamplerComparisonState SpotShadowSampler : register(s0);

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
  return SpotShadowMap.SampleCmpLevelZero(SpotShadowSampler, c.xy, c.z);
}

// The directional light is not this technique's.
float ShadowVisibility(float3 worldPos, float3 worldNormal, float4 svPosition) { return 1.0; }

float2 ShadowTexel(float3 worldPos, float layer) { return SpotShadowCoord(worldPos).xy * spotMapSize; }

ShadowLookup ShadowLocate(float3 worldPos, float3 worldNormal) {
  float3 c = SpotShadowCoord(worldPos);
  return MakeShadowLookup(SpotOutsideMap(c) ? kShadowNoLayer : 0.0, c.xy * spotMapSize);
}
