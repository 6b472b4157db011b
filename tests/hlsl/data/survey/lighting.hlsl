// A vertex shader returning a struct with SV_Position (declared in the include), and a pixel
// shader calling a helper that carries a semantic of its own but is no entry point.
#include "common.hlsli"

VSOut VSMain(float3 pos : POSITION, float2 uv : TEXCOORD0) {
  VSOut o;
  o.pos = mul(viewProj, float4(pos, 1.0));
  o.uv = uv;
  return o;
}

float4 Shade(VSOut i) : SV_Target {
  return tint * float4(i.uv, 0.0, 1.0);
}

float4 PSMain(VSOut i) : SV_Target0 {
  return Shade(i);
}
