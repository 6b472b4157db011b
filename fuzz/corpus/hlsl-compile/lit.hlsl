// ps_5_0
cbuffer Camera : register(b0) { float4x4 viewProj; float bias; float3 lightDir; };
Texture2D<float> shadowMap : register(t0);
SamplerComparisonState shadowSampler : register(s0);
struct VSOut { float4 pos : SV_Position; float3 normal : NORMAL; float2 uv : TEXCOORD0; };
float4 main(VSOut i) : SV_Target {
  float s = 0;
  [unroll] for (int x = -1; x <= 1; ++x) s += shadowMap.SampleCmpLevelZero(shadowSampler, i.uv, bias, int2(x, 0));
  return float4(i.normal * lightDir * s, 1);
}
