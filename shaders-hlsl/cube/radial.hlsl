// Shadow pass of the cube technique with storage=radial: each face of an R32_FLOAT cube stores the
// distance from the light to the nearest caster (what engines without depth cube maps did); a
// D32 depth buffer per face keeps the nearest. The distance is interpolated from the world
// position, which the rasterizer interpolates perspective-correctly, so it is exact per pixel.
//! vs_5_0 VSMain
//! ps_5_0 PSMain
#include "common/frame.hlsli"
#include "cube/constants.hlsli"

struct VSOut {
  float4 pos : SV_Position;
  float3 worldPos : WORLDPOS;
};

VSOut VSMain(float3 pos : POSITION) {
  VSOut o;
  float4 w = mul(world, float4(pos, 1.0));
  o.pos = mul(viewProj, w);
  o.worldPos = w.xyz;
  return o;
}

float PSMain(VSOut i) : SV_Target { return length(i.worldPos - cubePassLightPos); }
