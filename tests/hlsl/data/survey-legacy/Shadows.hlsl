// Constructs from D3D11-era shadow samples, each of which glslang alone rejects.
#include "shared\FullscreenQuad.hlsli"

cbuffer PerFrame : register(b0) {
  row_major float4x4 g_mLightViewProj;
  float4 g_fCascadeSplitsPacked[2];
  static float g_fCascadeSplits[8] = (float[8])g_fCascadeSplitsPacked;
  int g_iCascadeCount;
};

Texture2DArray g_txShadow : register(t1);
SamplerState g_samLinear : register(s0);
SamplerComparisonState g_samShadow : register(s1);

struct VSOut { float4 pos : SV_Position; float2 uv : TEXCOORD0; };

VSOut QuadVS(uint id : SV_VertexID) {
  VSOut o;
  o.pos = kQuad[id].pos;
  o.uv = kQuad[id].uv;
  return o;
}

float4 ShadowPS(VSOut i) : SV_Target {
  float3 lightDir = g_mLightViewProj._13_23_33;
  for (int cascade = 0; cascade < g_iCascadeCount - 1; ++cascade)
    if (i.pos.z < g_fCascadeSplits[cascade]) break;
  float3 uvw = float3(i.uv, cascade);
#ifdef MOMENTS
  float2 moments = g_txShadow.Sample(g_samLinear, uvw).rg;
  float lit = moments.x;
#else
  float lit = g_txShadow.SampleCmpLevelZero(g_samShadow, uvw, 0.5);
#endif
  float4x4 m = g_mLightViewProj;
  m._41_42_43 = 0;
  return float4(lit * saturate(lightDir), 1) + m[3];
}
