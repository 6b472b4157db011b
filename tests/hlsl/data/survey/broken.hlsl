// Two entry points that use names the file never declares: the survey reports one cause, twice.
#include "common.hlsli"

VSOut BrokenVS(float3 pos : POSITION) {
  VSOut o;
  o.pos = mul(viewProj, float4(pos * undefinedScale, 1.0));
  o.uv = 0;
  return o;
}

float4 BrokenPS(VSOut i) : SV_Target {
  return tint * missingTint;
}
