// The lit pass: Lambert diffuse with the shadow technique's visibility, plus ambient.
// The renderer compiles it after the technique's lighting include, which defines
//   float ShadowVisibility(float3 worldPos, float3 worldNormal, float4 svPosition)
// returning 1 for lit and 0 for shadowed (filtered techniques return values in between).
#include "common/frame.hlsli"

struct VSIn {
  float3 pos : POSITION;
  float3 normal : NORMAL;
};

struct VSOut {
  float4 pos : SV_Position;
  float3 worldPos : WORLDPOS;
  float3 normal : NORMAL;
};

VSOut VSMain(VSIn i) {
  VSOut o;
  float4 wp = mul(world, float4(i.pos, 1.0));
  o.worldPos = wp.xyz;
  // Normals of the built-in scenes and glTF meshes use uniform or no scaling.
  o.normal = mul((float3x3)world, i.normal);
  o.pos = mul(viewProj, wp);
  return o;
}

float4 PSMain(VSOut i) : SV_Target {
  float3 n = normalize(i.normal);
  float ndotl = saturate(dot(n, toLight));
  float visibility = ndotl > 0.0 ? ShadowVisibility(i.worldPos, n, i.pos) : 0.0;
  float3 color = albedo * (ambient + lightColor * ndotl * visibility);
  return float4(color, 1.0);
}
