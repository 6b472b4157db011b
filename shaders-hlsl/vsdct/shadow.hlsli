// Lighting side of the vsdct technique (techniques/vsdct/vsdct-technique.cpp, which explains the
// scheme): one point light's cube faces as tiles of a 2D depth atlas. Per lookup: one point
// sample of the indirection cube (the hardware picks the face; the texel holds the face's tile
// position and number), the face coordinates from the direction with that face's axes, then the
// 2D comparison filter of common/shadow-filter.hlsli (SHADOW_FILTER, SHADOW_KERNEL) in the tile.
#include "common/shadow-filter.hlsli"
#include "common/shadow-lookup.hlsli"

cbuffer VsdctShadow : register(b2) {
  float3 vsdctLightPos;
  float vsdctDepthA;        // window z = vsdctDepthA + vsdctDepthB / major axis of the tile's face
  float vsdctDepthB;
  float vsdctFaceSize;      // R: texels of a face's side, guard band not included
  uint vsdctLightIndex;     // the local light this atlas shadows
  float vsdctGuard;         // texels of guard band around each face; 0: taps clamped into the face
  float2 vsdctAtlasSize;    // texels
  uint vsdctReceiverPlane;  // 1: receiver-plane depth bias in the filter (VsdctReceiverPlane)
  float padVsdctShadow;
  float4 vsdctFaceS[6];     // xyz: the face's s, t and major axes (techniques/cube/cube-faces.h)
  float4 vsdctFaceT[6];
  float4 vsdctFaceMajor[6];
};

Texture2DArray<float> VsdctAtlas : register(t0);     // one slice, D32 read as R32_FLOAT
TextureCube<float4> VsdctIndirection : register(t1);  // per face: tile origin (texels), face, 0
SamplerComparisonState VsdctCmpSampler : register(s0);
SamplerState VsdctPointSampler : register(s1);

// A direction's lookup in face `face`: face uv in [0, 1] (D3D: v = 0 on the face's first row) and
// the planar window z that face's tile stores for it. Dividing by this face's major axis (not the
// largest component) keeps uv and z those of the tile read even where the hardware's choice at a
// tie differs from ours.
struct VsdctFaceCoord {
  float2 uv;
  float z;
};

VsdctFaceCoord VsdctInFace(float3 d, uint face) {
  float ma = dot(vsdctFaceMajor[face].xyz, d);
  VsdctFaceCoord c;
  c.uv = (float2(dot(vsdctFaceS[face].xyz, d), dot(vsdctFaceT[face].xyz, d)) / ma + 1.0) * 0.5;
  c.z = vsdctDepthA + vsdctDepthB / ma;
  return c;
}

// The receiver plane's depth slope in atlas uv, exact and without derivatives: along the face's
// direction M + X S + Y T (X, Y its NDC) the plane through the receiver (normal n, at d from the
// light) is met at ma = dot(n, d) / dot(n, M + X S + Y T), so the stored z = a + b / ma is affine in
// (X, Y): dz/dX = b dot(n, S) / dot(n, d). X = 2 u - 1 and u = (atlas u * W - origin) / R. Screen
// derivatives would do the same where neighbouring pixels read one tile, and jump at face edges.
// Without it an N-wide kernel compares the receiver's centre depth with texels N/2 away on a
// tilted receiver: acne the rasterizer's slope bias (about one texel of slope) does not cover.
float2 VsdctReceiverPlane(float3 d, float3 n, uint face) {
  float nd = dot(n, d);
  // Edge-on or facing away from the light: N.L is 0, nothing to bias; keep the slope finite.
  if (!(abs(nd) > 1e-4 * length(d))) return float2(0.0, 0.0);
  return 2.0 * vsdctDepthB / nd * float2(dot(n, vsdctFaceS[face].xyz), dot(n, vsdctFaceT[face].xyz)) * vsdctAtlasSize / vsdctFaceSize;
}

#define SP_LOCAL_SHADOWS 1
float LocalShadowVisibility(uint light, float3 worldPos, float3 worldNormal) {
  if (light != vsdctLightIndex) return 1.0;
  float3 d = worldPos - vsdctLightPos;
  float4 tile = VsdctIndirection.SampleLevel(VsdctPointSampler, d, 0.0);
  VsdctFaceCoord c = VsdctInFace(d, uint(tile.z));
  // Beyond the range the light contributes nothing; nearer than `near` nothing was drawn.
  if (c.z > 1.0) return 1.0;
  float2 texel = tile.xy + c.uv * vsdctFaceSize;
  ShadowFilterInput i;
  i.texelSize = 1.0 / vsdctAtlasSize;
  i.uv = texel * i.texelSize;
  i.layer = 0.0;
  i.depth = c.z;  // the rasterizer's depth bias is in the map
  // With a guard band, taps may read all of it; without, they stay on the face's own texels.
  float margin = vsdctGuard;
  i.uvClamp = float4(tile.xy - margin, tile.xy + vsdctFaceSize + margin) * i.texelSize.xyxy;
  i.depthGradient = vsdctReceiverPlane ? VsdctReceiverPlane(d, worldNormal, uint(tile.z)) : float2(0.0, 0.0);
  // No screen position reaches a local light's lookup: the Poisson rotation is seeded by the
  // receiver's position in the atlas, an eighth of a texel apart (noise at the same scale).
  i.pixel = floor(texel * 8.0);
  return ShadowFilter(VsdctAtlas, VsdctCmpSampler, i);
}

// The directional light is not this technique's.
float ShadowVisibility(float3 worldPos, float3 worldNormal, float4 svPosition) { return 1.0; }

// Lab: the layer is the face (0..5 in D3D11 order: +X, -X, +Y, -Y, +Z, -Z), texels within its
// R x R, as the cube technique reports them.
float2 ShadowTexel(float3 worldPos, float layer) { return VsdctInFace(worldPos - vsdctLightPos, uint(layer)).uv * vsdctFaceSize; }

ShadowLookup ShadowLocate(float3 worldPos, float3 worldNormal) {
  float3 d = worldPos - vsdctLightPos;
  float face = VsdctIndirection.SampleLevel(VsdctPointSampler, d, 0.0).z;
  VsdctFaceCoord c = VsdctInFace(d, uint(face));
  if (c.z > 1.0) return MakeShadowLookup(kShadowNoLayer, float2(0.0, 0.0));
  return MakeShadowLookup(face, c.uv * vsdctFaceSize);
}
