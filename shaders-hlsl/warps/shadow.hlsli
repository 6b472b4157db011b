// Lighting side of the perspective-warp techniques psm, lispsm and tsm (techniques/warps). Each
// cascade is a world -> clip matrix with a perspective w (FitWarp's viewProj) into one slice of a
// Texture2DArray; the cascade is chosen by view depth (csm's interval selection). The compared
// depth is the warped z after the divide (depth=warped) or the light-space linear depth row
// (depth=linear, the map holding what warps/depth-linear.hlsl wrote, bias included), both read
// with the comparison filter SHADOW_FILTER / SHADOW_KERNEL select (common/shadow-filter.hlsli;
// hw2x2 by default). Points outside the map, beyond its far plane or behind the warp's eye
// (w <= 0: outside every body FitWarp fits) are lit. With receiver_plane=1 every filter tap
// compares against the receiver's plane, from the screen derivatives of the map coordinates after
// the divide (the warp is not affine, but over a pixel's footprint it nearly is); where
// neighbouring pixels read different cascades the derivatives are wrong for those pixels only.
// The warps keep their rasterizer (or linear) slope bias under the receiver plane, so its
// footprint term can be bounded: 0.002 of the cascade's depth range. Unbounded, it leaked light
// under the capitals of ShadowColumns lit from overhead (gamma 90, 3x3 box: psm 3.86 %
// misclassified, 0.52 % without the receiver plane); bounded, 0.41 % (test:
// ReceiverPlaneBiasDoesNotLeakOnSteepReceivers).
#define RECEIVER_PLANE_MAX_FOOTPRINT 0.002
#include "common/frame.hlsli"
#include "common/shadow-lookup.hlsli"
#include "common/shadow-filter.hlsli"

#define WARP_MAX_CASCADES 4

cbuffer WarpShadow : register(b2) {
  float4x4 warpViewProj[WARP_MAX_CASCADES];  // world -> clip per cascade
  float4 warpLinear[WARP_MAX_CASCADES];      // world -> light-space linear depth per cascade
  float4 warpSplitFar;                       // view depth where each cascade ends
  float4 warpCameraForward;                  // w: cascade count
  float4 warpSettings;                       // x: linear depth (0/1), y: map resolution (texels), z: receiver plane (0/1)
};

Texture2DArray<float> WarpMap : register(t0);
SamplerComparisonState WarpSampler : register(s0);

// The cascade of a point by its view depth, or -1 beyond the last.
int WarpSelect(float3 worldPos) {
  float d = dot(worldPos - cameraPos, warpCameraForward.xyz);
  int count = (int)warpCameraForward.w;
  for (int c = 0; c < count; ++c)
    if (d < warpSplitFar[c]) return c;
  return -1;
}

// Map uv (row 0 at the top) and the depth to compare in cascade c; w in .w (<= 0: not mapped).
float4 WarpCoord(float3 worldPos, int c) {
  float4 p = mul(warpViewProj[c], float4(worldPos, 1.0));
  float w = p.w;
  // Keep the divide finite where w <= 0; such points are reported as unmapped.
  float3 q = p.xyz / (w > 0.0 ? w : 1.0);
  float depth = warpSettings.x > 0.5 ? dot(warpLinear[c], float4(worldPos, 1.0)) : q.z;
  return float4(q.xy * float2(0.5, -0.5) + 0.5, depth, w);
}

bool WarpOutside(float4 m) { return m.w <= 0.0 || any(m.xy < 0.0) || any(m.xy > 1.0) || m.z > 1.0; }

float ShadowVisibility(float3 worldPos, float3 worldNormal, float4 svPosition) {
  int c = WarpSelect(worldPos);
  // Derivatives first, in uniform control flow (lit.hlsl calls this for every pixel).
  float4 m = WarpCoord(worldPos, max(c, 0));
  float3 mDdx = ddx(m.xyz);
  float3 mDdy = ddy(m.xyz);
  if (c < 0 || WarpOutside(m)) return 1.0;
  ShadowFilterInput fi;
  fi.uv = m.xy;
  fi.layer = (float)c;
  fi.depth = m.z;
  fi.texelSize = 1.0 / warpSettings.yy;
  fi.uvClamp = float4(0.0, 0.0, 1.0, 1.0);
  fi.depthGradient = warpSettings.z > 0.5 ? ReceiverPlaneDepthGradient(mDdx, mDdy) : float2(0.0, 0.0);
  fi.pixel = svPosition.xy;
  return ShadowFilter(WarpMap, WarpSampler, fi);
}

// Layer = cascade; texels of its slice (row 0 at the top).
float2 ShadowTexel(float3 worldPos, float layer) { return WarpCoord(worldPos, (int)layer).xy * warpSettings.y; }

ShadowLookup ShadowLocate(float3 worldPos, float3 worldNormal) {
  int c = WarpSelect(worldPos);
  if (c < 0) return MakeShadowLookup(kShadowNoLayer, float2(0.0, 0.0));
  float4 m = WarpCoord(worldPos, c);
  if (WarpOutside(m)) return MakeShadowLookup(kShadowNoLayer, float2(0.0, 0.0));  // as ShadowVisibility: no read
  return MakeShadowLookup((float)c, m.xy * warpSettings.y);
}
