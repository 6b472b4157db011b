// SDSM: tight light-space bounds per partition. Every non-sky pixel is put back at its view
// depth along its camera ray, assigned to the partition its view depth falls in (partition p
// covers [split p, split p+1); the last one includes the max), moved to light space and merged
// into that partition's axis-aligned box. The reduction is segmented by partition: each group
// first merges into groupshared boxes with atomics on order-preserving keys of the floats (light
// coordinates can be negative), then adds each non-empty box to the global one with one atomic
// per word.
//! cs_5_0 Bounds
#include "sdsm/analysis.hlsli"

Texture2D<float> cameraDepth : register(t0);
RWByteAddressBuffer results : register(u0);

groupshared uint gsBox[SDSM_MAX_PARTITIONS * 8];  // the results layout of SDSM_W_BOUNDS
groupshared float gsSplit[SDSM_MAX_PARTITIONS + 1];

[numthreads(SDSM_TILE, SDSM_TILE, 1)]
void Bounds(uint3 pixel : SV_DispatchThreadID, uint gi : SV_GroupIndex) {
  uint K = clamp(partitionCount, 1u, uint(SDSM_MAX_PARTITIONS));
  if (gi < SDSM_MAX_PARTITIONS * 8) gsBox[gi] = gi % 8 < 3 ? 0xffffffffu : 0u;
  if (gi <= K) gsSplit[gi] = asfloat(results.Load((SDSM_W_SPLITS + gi) * 4));
  GroupMemoryBarrierWithGroupSync();
  if (all(pixel.xy < depthSize)) {
    float d = cameraDepth.Load(int3(pixel.xy, 0));
    if (d < 1.0) {
      float z = SdsmViewDepth(d);
      uint p = 0;
      for (uint i = 1; i < K; ++i) p = z >= gsSplit[i] ? i : p;
      float3 l = SdsmLightPosition(pixel.xy, z);
      uint base = p * 8;
      InterlockedMin(gsBox[base + 0], SdsmOrderedKey(l.x));
      InterlockedMin(gsBox[base + 1], SdsmOrderedKey(l.y));
      InterlockedMin(gsBox[base + 2], SdsmOrderedKey(l.z));
      InterlockedAdd(gsBox[base + 3], 1u);
      InterlockedMax(gsBox[base + 4], SdsmOrderedKey(l.x));
      InterlockedMax(gsBox[base + 5], SdsmOrderedKey(l.y));
      InterlockedMax(gsBox[base + 6], SdsmOrderedKey(l.z));
    }
  }
  GroupMemoryBarrierWithGroupSync();
  if (gi < K * 8 && gi % 8 != 7 && gsBox[(gi / 8) * 8 + 3] != 0) {
    uint slot = gi % 8, address = (SDSM_W_BOUNDS + gi) * 4, v = gsBox[gi], ignored;
    if (slot < 3) results.InterlockedMin(address, v, ignored);
    else if (slot == 3) results.InterlockedAdd(address, v, ignored);
    else results.InterlockedMax(address, v, ignored);
  }
}
