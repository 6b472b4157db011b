// Lighting side of the basic technique: one shadow map fitted to the scene, sampled with the
// hardware's 2x2 comparison filter (SampleCmpLevelZero).
cbuffer BasicShadow : register(b2) {
  float4x4 lightViewProj;
};

Texture2D<float> ShadowMap : register(t0);
SamplerComparisonState ShadowSampler : register(s0);

float ShadowVisibility(float3 worldPos, float3 worldNormal, float4 svPosition) {
  float4 p = mul(lightViewProj, float4(worldPos, 1.0));
  p.xyz /= p.w;
  // D3D: NDC +y is the top row of the map, so v = 0.5 - 0.5 y.
  float2 uv = p.xy * float2(0.5, -0.5) + 0.5;
  if (any(uv < 0.0) || any(uv > 1.0) || p.z > 1.0) return 1.0;
  return ShadowMap.SampleCmpLevelZero(ShadowSampler, uv, p.z);
}
