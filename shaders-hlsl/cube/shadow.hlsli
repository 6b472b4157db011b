// Lighting side of the cube technique (techniques/cube/): one point light's shadow in a TextureCube
// of planar window depth. Every face has the same near and far, so the depth a face stored for a
// point is a function of the major axis of its light-relative direction alone:
//   z = a + b / max(|x|, |y|, |z|),   a = far / (far - near),  b = -far near / (far - near)
// (King, "Shadow Mapping Algorithms"), and the lookup is one SampleCmpLevelZero on the TextureCube:
// the hardware picks the face and filters 2x2 across face edges (seamless on D3D11, and on GL and
// Vulkan as the RHI sets them up). Face order and (s, t) axes: techniques/cube/cube-faces.h.
// SP_CUBE_RADIAL=1 (storage=radial): the map holds distances in an R32_FLOAT cube instead, compared
// in the shader.
#include "common/shadow-lookup.hlsli"

#include "cube/constants.hlsli"

#ifndef SP_CUBE_RADIAL
#define SP_CUBE_RADIAL 0
#endif

#if SP_CUBE_RADIAL
TextureCube<float> CubeShadowMap : register(t0);  // R32_FLOAT: distance to the light
SamplerState CubeShadowPointSampler : register(s0);
#else
TextureCube<float> CubeShadowMap : register(t0);  // planar window z
SamplerComparisonState CubeShadowSampler : register(s0);
#endif

float CubeMajorAxis(float3 d) { return max(abs(d.x), max(abs(d.y), abs(d.z))); }

float CubeFace(float3 d);
float2 CubeFaceUv(float3 d, float face);

#define SP_LOCAL_SHADOWS 1
float LocalShadowVisibility(uint light, float3 worldPos, float3 worldNormal) {
  if (light != cubeLightIndex) return 1.0;
  float3 d = worldPos - cubeLightPos;
  float z = cubeDepthA + cubeDepthB / CubeMajorAxis(d);
  // Beyond the range the light contributes nothing; nearer than `near` nothing was drawn.
  if (z > 1.0) return 1.0;
#if SP_CUBE_RADIAL
  // Compare in the shader, 2x2 taps from Gather (seamless across face edges like the filter),
  // weighted bilinearly by the position within the face the direction selects. No rasterizer bias
  // applies to a colour target: a receiver bias of a constant plus the distance change across a
  // texel at the receiver's angle to the light (tan of it, at most 10).
  float dist = length(d);
  float cosTheta = saturate(dot(worldNormal, -d / dist));
  float tanTheta = min(sqrt(max(1.0 - cosTheta * cosTheta, 0.0)) / max(cosTheta, 1e-4), 10.0);
  float texelWorld = 2.0 * CubeMajorAxis(d) / cubeFaceSize;
  float reference = dist - cubeRadialBias - cubeRadialSlope * texelWorld * tanTheta;
  // Gather's order: (i0, j1), (i1, j1), (i1, j0), (i0, j0).
  float4 stored = CubeShadowMap.Gather(CubeShadowPointSampler, d);
  float4 lit = float4(reference <= stored.x, reference <= stored.y, reference <= stored.z, reference <= stored.w);
  float2 f = frac(CubeFaceUv(d, CubeFace(d)) * cubeFaceSize - 0.5);
  return lerp(lerp(lit.w, lit.z, f.x), lerp(lit.x, lit.y, f.x), f.y);
#else
  return CubeShadowMap.SampleCmpLevelZero(CubeShadowSampler, d, z);
#endif
}

// The directional light is not this technique's.
float ShadowVisibility(float3 worldPos, float3 worldNormal, float4 svPosition) { return 1.0; }

// Lab: the layer is the face (0..5 in D3D11 order: +X, -X, +Y, -Y, +Z, -Z), texels within it.
float CubeFace(float3 d) {
  float3 a = abs(d);
  if (a.z >= a.x && a.z >= a.y) return d.z >= 0.0 ? 4.0 : 5.0;
  if (a.y >= a.x) return d.y >= 0.0 ? 2.0 : 3.0;
  return d.x >= 0.0 ? 0.0 : 1.0;
}

float2 CubeFaceUv(float3 d, float face) {
  float2 st;  // (sc, tc) and the major axis of cube-faces.h's table
  float ma;
  if (face == 0.0) { st = float2(-d.z, -d.y); ma = d.x; }
  else if (face == 1.0) { st = float2(d.z, -d.y); ma = -d.x; }
  else if (face == 2.0) { st = float2(d.x, d.z); ma = d.y; }
  else if (face == 3.0) { st = float2(d.x, -d.z); ma = -d.y; }
  else if (face == 4.0) { st = float2(d.x, -d.y); ma = d.z; }
  else { st = float2(-d.x, -d.y); ma = -d.z; }
  return (st / ma + 1.0) * 0.5;
}

float2 ShadowTexel(float3 worldPos, float layer) { return CubeFaceUv(worldPos - cubeLightPos, layer) * cubeFaceSize; }

ShadowLookup ShadowLocate(float3 worldPos, float3 worldNormal) {
  float3 d = worldPos - cubeLightPos;
  float z = cubeDepthA + cubeDepthB / CubeMajorAxis(d);
  if (z > 1.0) return MakeShadowLookup(kShadowNoLayer, float2(0.0, 0.0));
  float face = CubeFace(d);
  return MakeShadowLookup(face, CubeFaceUv(d, face) * cubeFaceSize);
}
