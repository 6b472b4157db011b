// The two passes of the smallest shadow-mapping program, in HLSL as a D3D11 program writes it.
// Compiled unchanged for Vulkan (SPIR-V) and OpenGL (GLSL) by ShadowPort's toolchain.

cbuffer Frame : register(b0) {
  float4x4 g_viewProj;       // camera: world -> clip
  float4x4 g_lightViewProj;  // light: world -> clip of the shadow map
  float3 g_toLight;          // unit vector towards the directional light
  float g_ambient;
};

struct VSIn {
  float3 pos : POSITION;
  float3 normal : NORMAL;
  float3 color : COLOR;
};

// Pass 1: depth only, from the light. No pixel shader is bound.
float4 VSShadow(VSIn v) : SV_Position {
  return mul(g_lightViewProj, float4(v.pos, 1.0));
}

// Pass 2: the scene from the camera, lit where the shadow map says the light reaches.
struct PSIn {
  float4 pos : SV_Position;
  float3 world : WORLDPOS;
  float3 normal : NORMAL;
  float3 color : COLOR;
};

PSIn VSScene(VSIn v) {
  PSIn o;
  o.pos = mul(g_viewProj, float4(v.pos, 1.0));
  o.world = v.pos;
  o.normal = v.normal;
  o.color = v.color;
  return o;
}

Texture2D<float> g_shadowMap : register(t0);
SamplerComparisonState g_shadowSampler : register(s0);

float4 PSScene(PSIn i) : SV_Target {
  float4 light = mul(g_lightViewProj, float4(i.world, 1.0));
  // Clip space to texture space: D3D's y points down in textures.
  float2 uv = light.xy * float2(0.5, -0.5) + 0.5;
  // 2x2 PCF in hardware: 1 where the receiver is at or in front of the stored depth.
  float lit = g_shadowMap.SampleCmpLevelZero(g_shadowSampler, uv, light.z);
  float ndotl = saturate(dot(normalize(i.normal), g_toLight));
  return float4(i.color * (g_ambient + (1.0 - g_ambient) * ndotl * lit), 1.0);
}
