// The cube technique's accelerated lookup (accel=hpsm|minmax): each face of a slot's cube is a
// layer of CubeHpsm<k> (built from a 2D-array view of the cube, common/hpsm-build.hlsl), and a
// lookup whose footprint lies inside one face is decided there as common/hpsm.hlsli decides the
// 2D filters. Included by cube/shadow.hlsli after its kernel functions.
//
// The footprint: the kernel's taps lie one texel apart in the face's texel space (a tap
// d + x S + y T moves the face coordinate by x texels), so with s = uv N - 1/2 the taps' bilinear
// texels are [floor(s) - R, floor(s) + R + 1] per axis, as for the 2D kernels. Where that
// rectangle, widened by the one texel CubePlaneReference evaluates around each tap, leaves the
// face, a tap or corner belongs to another face: filtered.
//
// The references: each face is a 90-degree perspective view sharing near and far, so the receiver
// plane's planar z along the ray through face texel position t is affine in t:
//   zr(t) = z + (t - s).G,  G = depthB (2 / N) (n.e) / (n.d)  per axis,
// e the world axis along which that face coordinate grows (CubeFaceUv), z the receiver's own
// reference. The kernel's tap at p compares min over its corners p +- 1 of zr (CubePlaneZ with
// CubeReceiverPlaneT unclamped), which is <= zr(t) and >= zr(t) - 2 |G|1 for both texels t it reads
// on each axis; so every tap is lit when zr <= depth at every texel of the rectangle, and shadowed
// when zr - 2 |G|1 > depth there. That holds only where CubeReceiverPlaneT does not clamp, i.e.
// (n.q) / (n.d) stays in [1/2, 2] over the widened rectangle (affine: checked at its corners);
// elsewhere filtered. hw2x2 compares the constant z (G = 0, no corners).
#ifndef SP_CUBE_HPSM_HLSLI
#define SP_CUBE_HPSM_HLSLI

#include "common/hpsm.hlsli"

Texture2DArray<float4> CubeHpsm0 : register(t8);
Texture2DArray<float4> CubeHpsm1 : register(t9);
Texture2DArray<float4> CubeHpsm2 : register(t10);
Texture2DArray<float4> CubeHpsm3 : register(t11);
Texture2DArray<float4> CubeHpsm4 : register(t12);
Texture2DArray<float4> CubeHpsm5 : register(t13);
Texture2DArray<float4> CubeHpsm6 : register(t14);
Texture2DArray<float4> CubeHpsm7 : register(t15);
#if HPSM_COUNTERS
RWByteAddressBuffer CubeHpsmCounters : register(u7);  // as basic's: clear of the lab's render targets
#endif

// World axes along which face coordinates u and v grow (CubeFaceUv's (sc, tc) / ma).
void CubeFaceTexelAxes(float face, out float3 eu, out float3 ev) {
  ev = float3(0, -1, 0);
  if (face == 0.0) eu = float3(0, 0, -1);
  else if (face == 1.0) eu = float3(0, 0, 1);
  else if (face == 2.0) { eu = float3(1, 0, 0); ev = float3(0, 0, 1); }
  else if (face == 3.0) { eu = float3(1, 0, 0); ev = float3(0, 0, -1); }
  else if (face == 4.0) eu = float3(1, 0, 0);
  else eu = float3(-1, 0, 0);
}

// kHpsm* for a receiver at d from the light with normal n; its reference is z.
uint CubeHpsmDecide(Texture2DArray<float4> hpsm, CubeSlot slot, float3 d, float3 n, float z) {
  int size = int(slot.faceSize);
  float face = CubeFace(d);
  float2 s = CubeFaceUv(d, face) * slot.faceSize - 0.5;
  int2 fs = int2(floor(s));
  int2 t0 = fs - HPSM_REACH, t1 = fs + HPSM_REACH + 1;
  if (any(t0 < 1) || any(t1 > size - 2)) return kHpsmFiltered;
  float ma = CubeMajorAxis(d);
  float2 G = float2(0.0, 0.0);
  float shadowMargin = 0.0;
  // Float error of the references the kernel computes: its ratio n.q / n.d loses relative
  // precision as n.d shrinks against |n| |d| (grazing receivers), and b / (t ma) carries it.
  float slack = kHpsmRounding * (1.0 + abs(slot.depthA) + abs(z));
#if SHADOW_FILTER != 0
  float along = dot(n, d), len = length(d);
  if (abs(along) < 1e-3 * len) return kHpsmFiltered;
  float3 eu, ev;
  CubeFaceTexelAxes(face, eu, ev);
  float2 perTexel = float2(dot(n, eu), dot(n, ev)) * (2.0 / slot.faceSize) / along;  // d(ratio)/dt over ma
  // ratio(t) = 1 + ma (t - s).perTexel: in [1/2, 2] over the widened rectangle [t0 - 1, t1 + 1].
  float2 lo = float2(t0 - 1) - s, hi = float2(t1 + 1) - s;
  float rMin = 1.0 + ma * (min(lo.x * perTexel.x, hi.x * perTexel.x) + min(lo.y * perTexel.y, hi.y * perTexel.y));
  float rMax = 1.0 + ma * (max(lo.x * perTexel.x, hi.x * perTexel.x) + max(lo.y * perTexel.y, hi.y * perTexel.y));
  if (rMin < 0.501 || rMax > 1.999) return kHpsmFiltered;
  G = slot.depthB * perTexel;
  shadowMargin = 2.0 * (abs(G.x) + abs(G.y));
  // About 4 + 10 |d| / |n.d| ulps of b / (t ma) <= 2 |b| / ma; kHpsmRounding is 32 ulps.
  slack += kHpsmRounding * (2.0 * abs(slot.depthB) / ma) * (1.0 + len / abs(along));
#endif
  int layer = int(face);
  float2 m = float2(t0 + t1) * 0.5, e = float2(t1 - t0) * 0.5;
  float refCentre = z + dot(m - s, G), refExtent = dot(abs(G), e);
  slack += kHpsmRounding * (abs(refCentre) + refExtent);
#if SHADOW_ACCEL == 2
  float2 range = HpsmMinMaxOver(hpsm, t0, t1, layer);
  if (refCentre + refExtent + slack <= range.x) return kHpsmLitMinMax;
  if (refCentre - refExtent - shadowMargin - slack > range.y) return kHpsmShadowedMinMax;
  return kHpsmFiltered;
#else
  int2 b = fs / HPSM_BLOCK;
  float4 h = hpsm.Load(int4(b, layer, 0));
  if (h.w < 0.0) {
    if (refCentre + refExtent + slack <= h.x) return kHpsmLitMinMax;
    if (refCentre - refExtent - shadowMargin - slack > h.y) return kHpsmShadowedMinMax;
    return kHpsmFiltered;
  }
  // Q(t) = plane(t) - zr(t), affine: its extremes over the rectangle at the corners.
  float2 origin = HpsmPlaneOrigin(HpsmSupport(b.x, HPSM_BLOCK, HPSM_REACH, HPSM_REACH + 1, size),
                                  HpsmSupport(b.y, HPSM_BLOCK, HPSM_REACH, HPSM_REACH + 1, size));
  float2 mo = m - origin;
  float q = h.z + h.x * mo.x + h.y * mo.y - refCentre;
  float qExtent = abs(h.x - G.x) * e.x + abs(h.y - G.y) * e.y;
  float margin = h.w + slack + kHpsmRounding * (abs(h.z) + abs(h.x) * (abs(mo.x) + e.x) + abs(h.y) * (abs(mo.y) + e.y));
  if (q - qExtent >= margin) return kHpsmLitPlane;
  if (q + qExtent < -margin - shadowMargin) return kHpsmShadowedPlane;
  return kHpsmFiltered;
#endif
}

// CubeSlotVisibility, skipped where the slot's secondary map decides.
float CubeSlotVisibilityAccel(TextureCube<float> map, Texture2DArray<float4> hpsm, CubeSlot slot, float3 worldPos, float3 worldNormal) {
  float3 d = worldPos - slot.lightPos;
  float z = slot.depthA + slot.depthB / CubeMajorAxis(d);
  if (z > 1.0) return 1.0;
  uint how = CubeHpsmDecide(hpsm, slot, d, worldNormal, z);
#if HPSM_COUNTERS
  CubeHpsmCounters.InterlockedAdd(how * 4, 1);
#endif
  if (how == kHpsmFiltered) return CubeSlotVisibility(map, slot, worldPos, worldNormal);
  return (how == kHpsmLitMinMax || how == kHpsmLitPlane) ? 1.0 : 0.0;
}

#endif
