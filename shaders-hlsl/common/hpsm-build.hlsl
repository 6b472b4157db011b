// Builds the secondary map of common/hpsm.hlsli from a shadow map, every layer of a
// Texture2DArray: one thread per secondary texel. Neighbouring texels' supports overlap (by 2R + 1
// texels), so a group of 8 x 8 first loads the union of its supports into groupshared memory,
// each texel once, and its threads read their supports from there; a union wider than
// kHpsmTile (large blocks or kernels) is read from the map directly. HPSM_BUILD_GATHER 1 fills
// the tile with GatherRed, four texels per fetch (issue 15's construction); 0 with one Load per
// texel. Both store the same floats: Gather returns texels unfiltered.
//
// A plane is fitted by least squares over the support (on a regular grid the slopes decouple:
// a = sum(d (x - cx)) / sum((x - cx)^2)), and kept when its largest residual over the
// support, measured with the same float expression the lookup uses, is within eps; otherwise
// (and always in min/max mode) the texel holds the support's min and max. The fit only has to be
// good, not exact: the residual stored with it is what the lookup's bounds rely on.
//! cs_5_0 main
#include "common/hpsm.hlsli"

cbuffer HpsmBuild : register(b0) {
  uint2 mapSize;    // texels of one layer
  uint block;       // HPSM_BLOCK
  uint planes;      // 1: hpsm (planes where they fit); 0: min/max only
  int before;       // support reach below the block (hpsm: R; min/max: 0)
  int after;        // and above it (hpsm: R + 1; min/max: 0)
  float eps;        // the largest residual a plane may have
  float padHpsmBuild;
};

Texture2DArray<float> depthMap : register(t0);
#ifndef HPSM_BUILD_GATHER
#define HPSM_BUILD_GATHER 0
#endif
#if HPSM_BUILD_GATHER
SamplerState depthPoint : register(s0);  // clamp; Gather ignores the filter
#endif
RWTexture2DArray<float4> hpsmOut : register(u0);

#define kHpsmGroup 8
#define kHpsmTile 72  // texels per axis: 8 blocks of 4 and a reach of up to 19, or of 8 and 3
groupshared float tile[kHpsmTile * kHpsmTile];

// The group's union of supports, starting at `origin`; `shared` when it fits the tile.
static int2 tileOrigin;
static bool tileShared;
static int tileLayer;

float Depth(int x, int y) {
  if (tileShared) return tile[(y - tileOrigin.y) * kHpsmTile + (x - tileOrigin.x)];
  return depthMap.Load(int4(x, y, tileLayer, 0));
}

[numthreads(kHpsmGroup, kHpsmGroup, 1)] void main(uint3 id : SV_DispatchThreadID, uint3 group : SV_GroupID, uint3 local : SV_GroupThreadID) {
  int layer = int(id.z);
  tileLayer = layer;
  int first = int(group.x) * kHpsmGroup, firstY = int(group.y) * kHpsmGroup;
  int2 ux = int2(HpsmSupport(first, int(block), before, after, int(mapSize.x)).x, HpsmSupport(first + kHpsmGroup - 1, int(block), before, after, int(mapSize.x)).y);
  int2 uy = int2(HpsmSupport(firstY, int(block), before, after, int(mapSize.y)).x, HpsmSupport(firstY + kHpsmGroup - 1, int(block), before, after, int(mapSize.y)).y);
  tileOrigin = int2(ux.x, uy.x);
  // Uniform across the group (cbuffer and group id only), so the barrier is in uniform flow.
  tileShared = int(block) * kHpsmGroup + before + after <= kHpsmTile;
  if (tileShared) {
    int2 extent = int2(ux.y - ux.x + 1, uy.y - uy.x + 1);
#if HPSM_BUILD_GATHER
    // Quad q covers texels tileOrigin + 2q + {0, 1}^2: Gather at the corner they share returns
    // (i0, j1), (i1, j1), (i1, j0), (i0, j0) with i0 = floor(u W - 1/2) (cross-api-facts.md), so
    // u = (x + 1) / W gives i0 = x exactly. A quad past the map's last row or column reads a
    // clamped texel that lies outside the extent and is not stored.
    int2 quads = (extent + 1) / 2;
    float2 invSize = 1.0 / float2(mapSize);
    for (int t = int(local.y * kHpsmGroup + local.x); t < quads.x * quads.y; t += kHpsmGroup * kHpsmGroup) {
      int2 p = 2 * int2(t % quads.x, t / quads.x);
      float4 g = depthMap.GatherRed(depthPoint, float3(float2(tileOrigin + p + 1) * invSize, float(layer)));
      int i = p.y * kHpsmTile + p.x;
      bool right = p.x + 1 < extent.x, below = p.y + 1 < extent.y;
      tile[i] = g.w;
      if (right) tile[i + 1] = g.z;
      if (below) tile[i + kHpsmTile] = g.x;
      if (right && below) tile[i + kHpsmTile + 1] = g.y;
    }
#else
    for (int t = int(local.y * kHpsmGroup + local.x); t < extent.x * extent.y; t += kHpsmGroup * kHpsmGroup) {
      int2 p = int2(t % extent.x, t / extent.x);
      tile[p.y * kHpsmTile + p.x] = depthMap.Load(int4(tileOrigin + p, layer, 0));
    }
#endif
  }
  GroupMemoryBarrierWithGroupSync();
  uint2 blocks = (mapSize + block - 1) / block;
  if (any(id.xy >= blocks)) return;
  int2 sx = HpsmSupport(int(id.x), int(block), before, after, int(mapSize.x));
  int2 sy = HpsmSupport(int(id.y), int(block), before, after, int(mapSize.y));
  // One pass for min, max and the fit's sums: the support is symmetric about the origin, so
  // sum(x - cx) = 0 and sum(d (x - cx)) needs no mean subtracted first.
  float2 origin = HpsmPlaneOrigin(sx, sy);
  float lo = 3.0e38, hi = -3.0e38, sum = 0.0, sxd = 0.0, syd = 0.0, sxx = 0.0, syy = 0.0;
  for (int y = sy.x; y <= sy.y; ++y) {
    for (int x = sx.x; x <= sx.y; ++x) {
      float d = Depth(x, y);
      float2 o = float2(x, y) - origin;
      lo = min(lo, d);
      hi = max(hi, d);
      sum += d;
      sxd += d * o.x;
      syd += d * o.y;
      sxx += o.x * o.x;
      syy += o.y * o.y;
    }
  }
  float4 result = float4(lo, hi, 0.0, kHpsmMinMaxTag);
  if (planes != 0) {
    float mean = sum / float((sx.y - sx.x + 1) * (sy.y - sy.x + 1));
    float a = sxx > 0.0 ? sxd / sxx : 0.0, b = syy > 0.0 ? syd / syy : 0.0;
    float residual = 0.0;
    for (int y = sy.x; y <= sy.y; ++y) {
      for (int x = sx.x; x <= sx.y; ++x) {
        float2 o = float2(x, y) - origin;
        residual = max(residual, abs(Depth(x, y) - (mean + a * o.x + b * o.y)));
      }
    }
    if (residual <= eps) result = float4(a, b, mean, residual);
  }
  hpsmOut[uint3(id.xy, layer)] = result;
}
