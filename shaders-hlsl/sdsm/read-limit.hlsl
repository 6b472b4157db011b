// The physical limit the SDSM analysis is measured against (techniques/sdsm/analysis-cost.h): a
// pass that reads every texel of the camera depth once and writes one word per group. A texel
// only reaches the output through a test no depth passes (a sum of depths in [0, 1] is never
// negative), so the compiler cannot drop the loads, yet nothing else is stored.
//   ReadTexel: one texel per thread, 16x16 threads per 16x16 tile (the analysis' old layout).
//   ReadStrip: SDSM_STRIP threads per SDSM_STRIP^2 tile, each thread walking one row of it (the
//              layout of the analysis passes).
//   Empty:     no reads: one group of one thread, the cost of a dispatch alone.
//! cs_5_0 ReadTexel
//! cs_5_0 ReadStrip
//! cs_5_0 Empty
#include "sdsm/analysis.hlsli"

Texture2D<float> cameraDepth : register(t0);
RWByteAddressBuffer perGroup : register(u1);

void Keep(float sum, uint gi, uint group) {
  if (gi == 0 || sum < 0.0) perGroup.Store(group * 4, asuint(sum));
}

[numthreads(SDSM_TILE, SDSM_TILE, 1)]
void ReadTexel(uint3 pixel : SV_DispatchThreadID, uint3 group : SV_GroupID, uint gi : SV_GroupIndex) {
  float sum = 0.0;
  if (all(pixel.xy < depthSize)) sum = cameraDepth.Load(int3(pixel.xy, 0));
  Keep(sum, gi, group.y * tileCount.x + group.x);
}

[numthreads(SDSM_STRIP, 1, 1)]
void ReadStrip(uint3 group : SV_GroupID, uint gi : SV_GroupIndex) {
  float sum = 0.0;
  uint2 first = SdsmStripRow(group.xy, gi);
  uint xEnd = SdsmStripRowEnd(group.xy, gi);
  for (uint x = first.x; x < xEnd; ++x) sum += cameraDepth.Load(int3(x, first.y, 0));
  Keep(sum, gi, group.y * SdsmStripTiles().x + group.x);
}

[numthreads(1, 1, 1)]
void Empty(uint3 group : SV_GroupID) {
  if (depthSize.x == 0) perGroup.Store(group.x * 4, 0u);
}
