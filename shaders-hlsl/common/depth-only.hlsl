// Depth-only vertex shader for shadow passes: the light's view-projection is in Frame.viewProj.
//! vs_5_0 VSMain
#include "frame.hlsli"

float4 VSMain(float3 pos : POSITION) : SV_Position {
  return mul(viewProj, mul(world, float4(pos, 1.0)));
}
