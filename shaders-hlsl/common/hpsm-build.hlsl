// Builds the secondary map of common/hpsm.hlsli from a shadow map, every layer of a
// Texture2DArray: one thread per secondary texel, which reads its whole support.
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
RWTexture2DArray<float4> hpsmOut : register(u0);

[numthreads(8, 8, 1)] void main(uint3 id : SV_DispatchThreadID) {
  uint2 blocks = (mapSize + block - 1) / block;
  if (any(id.xy >= blocks)) return;
  int2 sx = HpsmSupport(int(id.x), int(block), before, after, int(mapSize.x));
  int2 sy = HpsmSupport(int(id.y), int(block), before, after, int(mapSize.y));
  int layer = int(id.z);
  // One pass for min, max and the fit's sums: the support is symmetric about the origin, so
  // sum(x - cx) = 0 and sum(d (x - cx)) needs no mean subtracted first.
  float2 origin = HpsmPlaneOrigin(sx, sy);
  float lo = 3.0e38, hi = -3.0e38, sum = 0.0, sxd = 0.0, syd = 0.0, sxx = 0.0, syy = 0.0;
  for (int y = sy.x; y <= sy.y; ++y) {
    for (int x = sx.x; x <= sx.y; ++x) {
      float d = depthMap.Load(int4(x, y, layer, 0));
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
        residual = max(residual, abs(depthMap.Load(int4(x, y, layer, 0)) - (mean + a * o.x + b * o.y)));
      }
    }
    if (residual <= eps) result = float4(a, b, mean, residual);
  }
  hpsmOut[uint3(id.xy, layer)] = result;
}
