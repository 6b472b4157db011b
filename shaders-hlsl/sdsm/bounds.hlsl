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

// A thread's box (keys) and sample count of partition p, merged into the group's.
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

// Thread gi's row of tile `group`: one box per partition grown in registers, merged into the
// groupshared boxes after the row, so no atomic sits inside the pixel loop. The per-partition
// selects are unrolled over a compile-time count (the boxes stay in registers, not in a
// dynamically indexed array); `split` holds +inf past K, which no view depth reaches.
// Per pixel this pass is arithmetic-bound on Mesa's CPU drivers (the light-space transform and
// the selects; eval/experiments/sdsm-analysis-cost.sh): BoundsRow4 serves K <= 4, the default,
// at half the selects of BoundsRow8.
#define SDSM_BOUNDS_ROW(NAME, P)                                                                  \
  void NAME(uint2 group, uint gi, float split[SDSM_MAX_PARTITIONS]) {                              \
    uint3 lo[P], hi[P];                                                                             \
    uint n[P];                                                                                      \
    [unroll] for (uint j = 0; j < P; ++j) {                                                         \
      lo[j] = 0xffffffffu;                                                                          \
      hi[j] = 0u;                                                                                   \
      n[j] = 0;                                                                                     \
    }                                                                                               \
    uint2 first = SdsmStripRow(group, gi);                                                          \
    uint xEnd = SdsmStripRowEnd(group, gi);                                                         \
    for (uint x = first.x; x < xEnd; ++x) {                                                         \
      float d = cameraDepth.Load(int3(x, first.y, 0));                                              \
      if (d < 1.0) {                                                                                \
        float z = SdsmViewDepth(d);                                                                 \
        uint p = 0;                                                                                 \
        [unroll] for (uint i = 1; i < P; ++i) p = z >= split[i] ? i : p;                            \
        float3 l = SdsmLightPosition(uint2(x, first.y), z);                                         \
        uint3 key = uint3(SdsmOrderedKey(l.x), SdsmOrderedKey(l.y), SdsmOrderedKey(l.z));           \
        [unroll] for (uint q = 0; q < P; ++q) {                                                     \
          bool mine = p == q;                                                                       \
          lo[q] = mine ? min(lo[q], key) : lo[q];                                                   \
          hi[q] = mine ? max(hi[q], key) : hi[q];                                                   \
          n[q] += mine ? 1u : 0u;                                                                   \
        }                                                                                           \
      }                                                                                             \
    }                                                                                               \
    [unroll] for (uint b = 0; b < P; ++b)                                                           \
      if (n[b] != 0) MergeBox(b, lo[b], hi[b], n[b]);                                               \
  }
SDSM_BOUNDS_ROW(BoundsRow4, 4)
SDSM_BOUNDS_ROW(BoundsRow8, SDSM_MAX_PARTITIONS)

[numthreads(SDSM_STRIP, 1, 1)]
void Bounds(uint3 group : SV_GroupID, uint gi : SV_GroupIndex) {
  uint K = clamp(partitionCount, 1u, uint(SDSM_MAX_PARTITIONS));
  for (uint w = gi; w < SDSM_MAX_PARTITIONS * 8; w += SDSM_STRIP) gsBox[w] = w % 8 < 3 ? 0xffffffffu : 0u;
  if (gi <= K) gsSplit[gi] = asfloat(results.Load((SDSM_W_SPLITS + gi) * 4));
  GroupMemoryBarrierWithGroupSync();
  float split[SDSM_MAX_PARTITIONS];
  [unroll] for (uint j = 0; j < SDSM_MAX_PARTITIONS; ++j) split[j] = j < K ? gsSplit[j] : SDSM_INFINITY;
  if (K <= 4) BoundsRow4(group.xy, gi, split);
  else BoundsRow8(group.xy, gi, split);
  GroupMemoryBarrierWithGroupSync();
  if (gi < K * 8 && gi % 8 != 7 && gsBox[(gi / 8) * 8 + 3] != 0) {
    uint slot = gi % 8, address = (SDSM_W_BOUNDS + gi) * 4, v = gsBox[gi], ignored;
    if (slot < 3) results.InterlockedMin(address, v, ignored);
    else if (slot == 3) results.InterlockedAdd(address, v, ignored);
    else results.InterlockedMax(address, v, ignored);
  }
}
