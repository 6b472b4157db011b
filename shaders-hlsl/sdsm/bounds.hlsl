// SDSM: tight light-space bounds per partition. Every non-sky pixel is put back at its view
// depth along its camera ray, assigned to the partition its view depth falls in (partition p
// covers [split p, split p+1); the last one includes the max), moved to light space and merged
// into that partition's axis-aligned box. The reduction is segmented by partition: each group
// first merges into groupshared boxes with atomics on order-preserving keys of the floats (light
// coordinates can be negative), then adds each non-empty box to the global one with one atomic
// per word. The keys order like the floats, so min/max over keys in registers is exact.
//! cs_5_0 Bounds
#include "sdsm/analysis.hlsli"

Texture2D<float> cameraDepth : register(t0);
RWByteAddressBuffer results : register(u0);

groupshared uint gsBox[SDSM_MAX_PARTITIONS * 8];  // the results layout of SDSM_W_BOUNDS
groupshared float gsSplit[SDSM_MAX_PARTITIONS + 1];

// Thread gi's running box (keys) and sample count of partition p, merged into the group's.
void MergeBox(uint p, uint3 lo, uint3 hi, uint n) {
  uint base = p * 8;
  InterlockedMin(gsBox[base + 0], lo.x);
  InterlockedMin(gsBox[base + 1], lo.y);
  InterlockedMin(gsBox[base + 2], lo.z);
  InterlockedAdd(gsBox[base + 3], n);
  InterlockedMax(gsBox[base + 4], hi.x);
  InterlockedMax(gsBox[base + 5], hi.y);
  InterlockedMax(gsBox[base + 6], hi.z);
}

// One SDSM_STRIP^2 tile per group, one row of it per thread. A row stays in one partition for long
// runs, so each thread grows a box in registers and merges it into the groupshared one only when
// its partition changes: seven groupshared atomics per run instead of per pixel.
[numthreads(SDSM_STRIP, 1, 1)]
void Bounds(uint3 group : SV_GroupID, uint gi : SV_GroupIndex) {
  uint K = clamp(partitionCount, 1u, uint(SDSM_MAX_PARTITIONS));
  for (uint w = gi; w < SDSM_MAX_PARTITIONS * 8; w += SDSM_STRIP) gsBox[w] = w % 8 < 3 ? 0xffffffffu : 0u;
  if (gi <= K) gsSplit[gi] = asfloat(results.Load((SDSM_W_SPLITS + gi) * 4));
  GroupMemoryBarrierWithGroupSync();
  uint2 first = SdsmStripRow(group.xy, gi);
  uint xEnd = SdsmStripRowEnd(group.xy, gi);
  uint runP = 0, n = 0;
  uint3 lo = 0xffffffffu, hi = 0u;
  for (uint x = first.x; x < xEnd; ++x) {
    float d = cameraDepth.Load(int3(x, first.y, 0));
    if (d < 1.0) {
      float z = SdsmViewDepth(d);
      uint p = 0;
      for (uint i = 1; i < K; ++i) p = z >= gsSplit[i] ? i : p;
      if (p != runP) {
        if (n != 0) MergeBox(runP, lo, hi, n);
        runP = p;
        n = 0;
        lo = 0xffffffffu;
        hi = 0u;
      }
      float3 l = SdsmLightPosition(uint2(x, first.y), z);
      uint3 key = uint3(SdsmOrderedKey(l.x), SdsmOrderedKey(l.y), SdsmOrderedKey(l.z));
      lo = min(lo, key);
      hi = max(hi, key);
      ++n;
    }
  }
  if (n != 0) MergeBox(runP, lo, hi, n);
  GroupMemoryBarrierWithGroupSync();
  if (gi < K * 8 && gi % 8 != 7 && gsBox[(gi / 8) * 8 + 3] != 0) {
    uint slot = gi % 8, address = (SDSM_W_BOUNDS + gi) * 4, v = gsBox[gi], ignored;
    if (slot < 3) results.InterlockedMin(address, v, ignored);
    else if (slot == 3) results.InterlockedAdd(address, v, ignored);
    else results.InterlockedMax(address, v, ignored);
  }
}
