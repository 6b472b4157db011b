// Lighting side of the basic technique: one shadow map fitted to the scene, sampled with the
// hardware's 2x2 comparison filter (SampleCmpLevelZero).
#include "common/shadow-lookup.hlsli"

cbuffer BasicShadow : register(b2) {
  float4x4 lightViewProj;
  float2 shadowMapSize;  // texels; for the lab's ShadowTexel
  float2 padBasicShadow;
};

Texture2D<float> ShadowMap : register(t0);
SamplerComparisonState ShadowSampler : register(s0);

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
  return ShadowMap.SampleCmpLevelZero(ShadowSampler, c.xy, c.z);
}

// One layer (0); points outside the map are lit without a lookup.
float2 ShadowTexel(float3 worldPos, float layer) { return BasicShadowCoord(worldPos).xy * shadowMapSize; }

ShadowLookup ShadowLocate(float3 worldPos, float3 worldNormal) {
  float3 c = BasicShadowCoord(worldPos);
  return MakeShadowLookup(BasicOutsideMap(c) ? kShadowNoLayer : 0.0, c.xy * shadowMapSize);
}
