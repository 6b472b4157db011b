// Lighting side of the paraboloid technique (techniques/paraboloid/): one point light's shadow in
// two paraboloid depth maps (a Texture2DArray of 2 slices). The receiver's direction from the
// light picks the hemisphere by the sign of its frame z and the map point (x, y) / (1 + |z|) of the
// unit direction; its depth is the linear distance (L - near) / (range - near), what the shadow
// pass wrote at the vertices; one SampleCmpLevelZero filters 2x2. The pass drew each hemisphere a
// few texels past its rim, so the filter of a receiver next to the seam reads written texels.
// Geometry: techniques/paraboloid/paraboloid-map.h.
#include "common/shadow-lookup.hlsli"

#include "paraboloid/constants.hlsli"

Texture2DArray<float> ParaboloidShadowMap : register(t0);
SamplerComparisonState ParaboloidShadowSampler : register(s0);

float3 ParaboloidFrameDir(float3 worldPos) {
  float4 p = float4(worldPos, 1.0);
  return float3(dot(parabFrame[0], p), dot(parabFrame[1], p), dot(parabFrame[2], p));
}

float ParaboloidHemisphere(float3 d) { return d.z >= 0.0 ? 0.0 : 1.0; }

// uv in the map of `hemisphere` (D3D: NDC +y is row 0).
float2 ParaboloidUv(float3 d, float hemisphere) {
  float3 n = normalize(float3(d.xy, hemisphere == 0.0 ? d.z : -d.z));
  float2 ndc = n.xy / max(1.0 + n.z, 1e-6);
  return ndc * float2(0.5, -0.5) + 0.5;
}

#define SP_LOCAL_SHADOWS 1
float LocalShadowVisibility(uint light, float3 worldPos, float3 worldNormal) {
  if (light != parabLightIndex) return 1.0;
  float3 d = ParaboloidFrameDir(worldPos);
  float z = ParaboloidDepth(length(d));
  // Beyond the range the light contributes nothing; nearer than `near` nothing was drawn.
  if (z > 1.0) return 1.0;
  float h = ParaboloidHemisphere(d);
  return ParaboloidShadowMap.SampleCmpLevelZero(ParaboloidShadowSampler, float3(ParaboloidUv(d, h), h), z);
}

// The directional light is not this technique's.
float ShadowVisibility(float3 worldPos, float3 worldNormal, float4 svPosition) { return 1.0; }

// Lab: the layer is the hemisphere (0 front, 1 back), texels within its map.
float2 ShadowTexel(float3 worldPos, float layer) { return ParaboloidUv(ParaboloidFrameDir(worldPos), layer) * parabMapSize; }

ShadowLookup ShadowLocate(float3 worldPos, float3 worldNormal) {
  float3 d = ParaboloidFrameDir(worldPos);
  if (ParaboloidDepth(length(d)) > 1.0) return MakeShadowLookup(kShadowNoLayer, float2(0.0, 0.0));
  float h = ParaboloidHemisphere(d);
  return MakeShadowLookup(h, ParaboloidUv(d, h) * parabMapSize);
}
