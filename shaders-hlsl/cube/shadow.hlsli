// Lighting side of the cube technique (techniques/cube/): point lights' shadows in TextureCubes of
// planar window depth, one per shadowed light (slot k reads CubeShadowMap<k> at t<k> and
// cubeSlots[k]). Every face has the same near and far, so the depth a face stored for a point is
// a function of the major axis of its light-relative direction alone:
//   z = a + b / max(|x|, |y|, |z|),   a = far / (far - near),  b = -far near / (far - near)
// (King, "Shadow Mapping Algorithms"), and the lookup is one SampleCmpLevelZero on the TextureCube:
// the hardware picks the face and filters 2x2 across face edges (seamless on D3D11, and on GL and
// Vulkan as the RHI sets them up). Face order and (s, t) axes: techniques/cube/cube-faces.h.
// SP_CUBE_RADIAL=1 (storage=radial): the maps hold distances in R32_FLOAT cubes instead, compared
// in the shader. SP_CUBE_SLOTS: how many lights the technique shadows at most (1..8).
#include "common/shadow-lookup.hlsli"
// The PCF family's kernel choice and weights (SHADOW_FILTER, SHADOW_KERNEL, kShadowBinomial); its
// 2D tap functions are not used here.
#include "common/shadow-filter.hlsli"

#include "cube/constants.hlsli"

#ifndef SP_CUBE_RADIAL
#define SP_CUBE_RADIAL 0
#endif
#ifndef SP_CUBE_SLOTS
#define SP_CUBE_SLOTS 1
#endif
#if SHADOW_FILTER == 3 || SHADOW_FILTER == 4
#error SHADOW_FILTER of the cube technique must be 0 (hw2x2), 1 (box), 2 (gauss) or 5 (pcss)
#endif
#if SHADOW_FILTER == 5 && SP_CUBE_RADIAL
#error filter=pcss of the cube technique needs storage=depth
#endif

// Unused slots' textures are never read and drop out of the compiled shader.
TextureCube<float> CubeShadowMap0 : register(t0);
TextureCube<float> CubeShadowMap1 : register(t1);
TextureCube<float> CubeShadowMap2 : register(t2);
TextureCube<float> CubeShadowMap3 : register(t3);
TextureCube<float> CubeShadowMap4 : register(t4);
TextureCube<float> CubeShadowMap5 : register(t5);
TextureCube<float> CubeShadowMap6 : register(t6);
TextureCube<float> CubeShadowMap7 : register(t7);
#if SP_CUBE_RADIAL
SamplerState CubeShadowPointSampler : register(s0);  // R32_FLOAT: distance to the light
#else
SamplerComparisonState CubeShadowSampler : register(s0);
#endif

float CubeMajorAxis(float3 d) { return max(abs(d.x), max(abs(d.y), abs(d.z))); }

float CubeFace(float3 d);
float2 CubeFaceUv(float3 d, float face);

// Wider kernels than the hardware's 2x2 (SHADOW_FILTER 1 box, 2 gauss) take their taps one
// texel apart in the plane of the face the receiver's direction selects: tap (x, y) looks up
// d + (x S + y T) * 2 ma / faceSize, S and T the face's (s, t) axes (one texel of a face is
// 2 ma / size in that plane). A tap past the face's edge is a direction on the neighbouring face,
// where the seamless lookup reads it: the kernel needs no clamp and no guard band.
// Each tap compares the receiver where the tap's ray from the light meets the receiver's plane
// (the plane through the point with its normal): a receiver-plane bias made exact by the normal
// the lit pass has, where 2D maps estimate the plane from screen derivatives. Without it a tap
// four texels away on a wall the light grazes compares the wall's depth there with the receiver's
// own, and wide kernels darken every such wall (acne). It also keeps face edges seamless: the
// reference is the planar z of the tap's own point in the face that reads it (a point's planar z
// differs between two faces, a + b / ma with each face's major axis).
// Returns the tap's point as a multiple t of the tap direction; t = 1 where the ray runs parallel
// to the plane or meets it behind (grazing receivers), and t stays within [1/2, 2].
float CubeReceiverPlaneT(float3 d, float3 n, float3 tap) {
  float along = dot(n, d), towards = dot(n, tap);
  if (along * towards <= 0.0 || abs(towards) < 1e-6 * length(tap)) return 1.0;
  return clamp(along / towards, 0.5, 2.0);
}

// The receiver plane's planar z along direction q, in the face q selects.
float CubePlaneZ(CubeSlot slot, float3 d, float3 n, float3 q) {
  return slot.depthA + slot.depthB / (CubeReceiverPlaneT(d, n, q) * CubeMajorAxis(q));
}

// The reference a bilinear tap at `tap` compares with its 2x2 texels: the receiver plane's nearest
// planar z over the texel footprint (the four corners one texel away along S and T), since the
// texel centres lie up to a texel from the tap and the plane may be lower there; at a face edge
// some of those texels are the neighbouring face's, whose planar z of the same plane is smaller
// (its major axis is shorter), and the corner on that side is evaluated in that face.
float CubePlaneReference(CubeSlot slot, float3 d, float3 n, float3 tap, float3 S, float3 T) {
  return min(min(CubePlaneZ(slot, d, n, tap + S + T), CubePlaneZ(slot, d, n, tap + S - T)),
             min(CubePlaneZ(slot, d, n, tap - S + T), CubePlaneZ(slot, d, n, tap - S - T)));
}

// One tap at the receiver point t * tap: 1 lit, 0 shadowed, bilinearly filtered over the 2x2
// texels around `tap`. `reference` is its planar z (storage=depth).
float CubeTap(TextureCube<float> map, CubeSlot slot, float3 tap, float t, float radialBias, float reference) {
#if SP_CUBE_RADIAL
  reference = t * length(tap) - radialBias;
  // Gather's order: (i0, j1), (i1, j1), (i1, j0), (i0, j0).
  float4 stored = map.Gather(CubeShadowPointSampler, tap);
  float4 lit = float4(reference <= stored.x, reference <= stored.y, reference <= stored.z, reference <= stored.w);
  float2 f = frac(CubeFaceUv(tap, CubeFace(tap)) * slot.faceSize - 0.5);
  return lerp(lerp(lit.w, lit.z, f.x), lerp(lit.x, lit.y, f.x), f.y);
#else
  return map.SampleCmpLevelZero(CubeShadowSampler, tap, reference);
#endif
}

// The face axes S, T of cube-faces.h's table for the face of d, up to sign (the kernels are
// symmetric).
void CubeFaceAxes(float3 d, out float3 S, out float3 T) {
  float3 a = abs(d);
  if (a.z >= a.x && a.z >= a.y) { S = float3(1, 0, 0); T = float3(0, 1, 0); }
  else if (a.y >= a.x) { S = float3(1, 0, 0); T = float3(0, 0, 1); }
  else { S = float3(0, 0, 1); T = float3(0, 1, 0); }
}

#if SHADOW_FILTER == 5
#include "cube/pcss.hlsli"
#endif

float CubeSlotVisibility(TextureCube<float> map, CubeSlot slot, float3 worldPos, float3 worldNormal) {
  float3 d = worldPos - slot.lightPos;
  float z = slot.depthA + slot.depthB / CubeMajorAxis(d);
  // Beyond the range the light contributes nothing; nearer than `near` nothing was drawn.
  if (z > 1.0) return 1.0;
  float radialBias = 0.0;
#if SP_CUBE_RADIAL
  // Compared in the shader: no rasterizer bias applies to a colour target, so the receiver is
  // biased by a constant plus the distance change across a texel at its angle to the light (tan
  // of it, at most 10).
  float dist = length(d);
  float cosTheta = saturate(dot(worldNormal, -d / dist));
  float tanTheta = min(sqrt(max(1.0 - cosTheta * cosTheta, 0.0)) / max(cosTheta, 1e-4), 10.0);
  float texelWorld = 2.0 * CubeMajorAxis(d) / slot.faceSize;
  radialBias = cubeRadialBias + cubeRadialSlope * texelWorld * tanTheta;
#endif
#if SHADOW_FILTER == 0
  return CubeTap(map, slot, d, 1.0, radialBias, z);
#elif SHADOW_FILTER == 5
  return CubePcssVisibility(map, slot, d, worldNormal);
#else
  float3 S, T;
  CubeFaceAxes(d, S, T);
  float texel = 2.0 * CubeMajorAxis(d) / slot.faceSize;
  S *= texel;
  T *= texel;
  float sum = 0.0;
  float weights = 0.0;
  SHADOW_KERNEL_LOOP for (int y = -SHADOW_KERNEL_HALF; y <= SHADOW_KERNEL_HALF; ++y) {
    SHADOW_KERNEL_LOOP for (int x = -SHADOW_KERNEL_HALF; x <= SHADOW_KERNEL_HALF; ++x) {
#if SHADOW_FILTER == 2
      float w = kShadowBinomial[x + SHADOW_KERNEL_HALF] * kShadowBinomial[y + SHADOW_KERNEL_HALF];
#else
      float w = 1.0;
#endif
      float3 tap = d + float(x) * S + float(y) * T;
#if SP_CUBE_RADIAL
      sum += w * CubeTap(map, slot, tap, CubeReceiverPlaneT(d, worldNormal, tap), radialBias, 0.0);
#else
      sum += w * CubeTap(map, slot, tap, 1.0, 0.0, CubePlaneReference(slot, d, worldNormal, tap, S, T));
#endif
      weights += w;
    }
  }
  return sum / weights;
#endif
}

// Slot k, when it shadows `light`, decides; a light without a slot is unshadowed.
#if defined(SHADOW_ACCEL) && SHADOW_ACCEL != 0
#include "cube/hpsm.hlsli"
#define SP_CUBE_SLOT(k)                                                                   \
  if (k < SP_CUBE_SLOTS && cubeSlots[k].light == light)                                  \
    return CubeSlotVisibilityAccel(CubeShadowMap##k, CubeHpsm##k, cubeSlots[k], worldPos, worldNormal);
#else
#define SP_CUBE_SLOT(k)                                                                   \
  if (k < SP_CUBE_SLOTS && cubeSlots[k].light == light)                                  \
    return CubeSlotVisibility(CubeShadowMap##k, cubeSlots[k], worldPos, worldNormal);
#endif

#define SP_LOCAL_SHADOWS 1
float LocalShadowVisibility(uint light, float3 worldPos, float3 worldNormal) {
  SP_CUBE_SLOT(0)
  SP_CUBE_SLOT(1)
  SP_CUBE_SLOT(2)
  SP_CUBE_SLOT(3)
  SP_CUBE_SLOT(4)
  SP_CUBE_SLOT(5)
  SP_CUBE_SLOT(6)
  SP_CUBE_SLOT(7)
  return 1.0;
}

// The directional light is not this technique's.
float ShadowVisibility(float3 worldPos, float3 worldNormal, float4 svPosition) { return 1.0; }

// Lab: the layer is the face (0..5 in D3D11 order: +X, -X, +Y, -Y, +Z, -Z) of the judged light's
// cube, texels within it.
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

float2 ShadowTexel(float3 worldPos, float layer) {
  CubeSlot slot = cubeSlots[min(cubeLabSlot, SP_CUBE_MAX_SLOTS - 1)];
  return CubeFaceUv(worldPos - slot.lightPos, layer) * slot.faceSize;
}

ShadowLookup ShadowLocate(float3 worldPos, float3 worldNormal) {
  if (cubeLabSlot >= SP_CUBE_MAX_SLOTS) return MakeShadowLookup(kShadowNoLayer, float2(0.0, 0.0));
  CubeSlot slot = cubeSlots[cubeLabSlot];
  float3 d = worldPos - slot.lightPos;
  float z = slot.depthA + slot.depthB / CubeMajorAxis(d);
  if (z > 1.0) return MakeShadowLookup(kShadowNoLayer, float2(0.0, 0.0));
  float face = CubeFace(d);
  return MakeShadowLookup(face, CubeFaceUv(d, face) * slot.faceSize);
}
