// The local lights of the lit pass: the scene's point and spot lights (techniques/include/sp/tech/
// technique.h, LocalLight; the renderer fills the cbuffer, techniques/renderer.cpp), shaded with
// glTF's recommended falloff (KHR_lights_punctual):
//   range:  saturate(1 - (d / range)^4) / d^2
//   spot:   t = saturate((dot(axis, light -> point) - cos outer) / max(1e-3, cos inner - cos outer)), t^2
// b6 belongs to the lit pass (b2-b5 are the technique's).
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

#endif
