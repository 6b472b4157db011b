// Shadow pass of the warp techniques with depth=linear (techniques/warps): the rasterizer places
// the triangle with the warped viewProj (Frame.viewProj), the pixel shader writes light-space
// linear depth through SV_Depth. The linear depth is an affine function of the world position, so
// the rasterizer's perspective-correct interpolation gives it exactly at every pixel; writing
// it as clip z (times w) from the vertex shader instead would be interpolated linearly in the
// map, which is not linear depth inside a triangle once the warp has a perspective w.
//! vs_5_0 VSMain
//! ps_5_0 PSMain
#include "common/frame.hlsli"

cbuffer WarpLinearDepth : register(b2) {
  float4 warpLinearRow;  // dot with (world, 1): linear depth, [0, 1] over the cascade's body and casters
  float4 warpLinearBias; // x: constant bias (linear units), y: slope bias (times the depth slope per texel)
};

struct VSOut {
  float4 pos : SV_Position;
  float linearDepth : TEXCOORD0;
};

VSOut VSMain(float3 pos : POSITION) {
  VSOut o;
  float4 w = mul(world, float4(pos, 1.0));
  o.pos = mul(viewProj, w);
  o.linearDepth = dot(warpLinearRow, w);
  return o;
}

float PSMain(VSOut i) : SV_Depth {
  // D3D11's bias formula in linear depth: constant + slope * the largest depth change per texel.
  float slope = max(abs(ddx(i.linearDepth)), abs(ddy(i.linearDepth)));
  // Casters in front of the near plane clamp to 0 (pancaking, as depth clamping does for z).
  return saturate(i.linearDepth + warpLinearBias.x + warpLinearBias.y * slope);
}
