// The local lights of the lit pass: the scene's point and spot lights (techniques/include/sp/tech/
// technique.h, LocalLight; the renderer fills the cbuffer, techniques/renderer.cpp), shaded with
// glTF's recommended falloff (KHR_lights_punctual):
//   range:  saturate(1 - (d / range)^4) / d^2
//   spot:   t = saturate((dot(axis, light -> point) - cos outer) / max(1e-3, cos inner - cos outer)), t^2
// b6 belongs to the lit pass (b2-b5 are the technique's). Included by lit.hlsl only, after the
// technique's include.
#ifndef SP_LOCAL_LIGHTS_HLSLI
#define SP_LOCAL_LIGHTS_HLSLI

#define SP_MAX_LOCAL_LIGHTS 32  // kMaxLocalLights in technique.h
#define SP_LOCAL_POINT 0.0
#define SP_LOCAL_SPOT 1.0

struct LocalLightData {
  float3 position;
  float range;
  float3 color;       // linear intensity before attenuation
  float type;         // SP_LOCAL_POINT or SP_LOCAL_SPOT
  float3 direction;   // spot: unit axis, the way the light travels
  float cosInner;
  float cosOuter;
  float3 padLocalLight;
};

cbuffer LocalLights : register(b6) {
  uint localLightCount;
  uint3 padLocalLights;
  LocalLightData localLights[SP_MAX_LOCAL_LIGHTS];
};

float LocalRangeAttenuation(float d, float range) {
  float r = d / range;
  float r2 = r * r;
  return saturate(1.0 - r2 * r2) / max(d * d, 1e-8);
}

// `fromLight`: unit vector from the light to the shaded point.
float LocalSpotFactor(LocalLightData l, float3 fromLight) {
  if (l.type != SP_LOCAL_SPOT) return 1.0;
  float t = saturate((dot(l.direction, fromLight) - l.cosOuter) / max(1e-3, l.cosInner - l.cosOuter));
  return t * t;
}

// Local-light techniques define SP_LOCAL_SHADOWS and LocalShadowVisibility in their include,
// which the renderer compiles before lit.hlsl (1 = lit, 0 = shadowed, for local light `light`);
// without one, local lights are unshadowed.
#ifndef SP_LOCAL_SHADOWS
float LocalShadowVisibility(uint light, float3 worldPos, float3 worldNormal) { return 1.0; }
#endif

// The sum of every local light's contribution at a point (before albedo).
float3 LocalLighting(float3 worldPos, float3 n) {
  float3 sum = float3(0.0, 0.0, 0.0);
  for (uint i = 0; i < localLightCount; ++i) {
    LocalLightData l = localLights[i];
    float3 v = l.position - worldPos;
    float d = length(v);
    float3 toLightL = v / max(d, 1e-6);
    float ndotl = saturate(dot(n, toLightL));
    float a = LocalRangeAttenuation(d, l.range) * LocalSpotFactor(l, -toLightL);
    float visibility = LocalShadowVisibility(i, worldPos, n);
    sum += l.color * (ndotl * a * visibility);
  }
  return sum;
}

#endif
