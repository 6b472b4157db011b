// SDSM depth reduction: min and max view depth of the camera's non-sky pixels (depth 1.0 = sky).
// Each group of SDSM_STRIP threads reduces an SDSM_STRIP^2 tile: every thread walks one row of it
// keeping its min/max in registers, then merges them into the group's with groupshared
// InterlockedMin/Max on the float bits (view depths are positive, and the bits of non-negative
// floats order like the floats, so uint atomics do float min/max). Then either a second pass
// reduces the tiles' results (ReduceTiles + ReduceFinal), or each tile merges its result into the
// global one the same way (ReduceAtomic).
// Why rows in registers rather than a groupshared tree per pixel: Mesa's CPU drivers run a group
// on one thread, a few lanes at a time, and every barrier switches through all of the group's
// lanes; a 16x16 tree paid 9 barriers and 256 groupshared stores per 256 pixels (70x the time of
// reading the depth once, eval/experiments/sdsm-analysis-cost.sh).
//! cs_5_0 ReduceTiles
//! cs_5_0 ReduceFinal
//! cs_5_0 ReduceAtomic
#include "sdsm/analysis.hlsli"

Texture2D<float> cameraDepth : register(t0);
RWByteAddressBuffer results : register(u0);
RWStructuredBuffer<uint2> tiles : register(u1);  // per tile: min and max bits (two-pass mode)

groupshared uint gsMin, gsMax;

// The group's tile reduced into gsMin/gsMax (float bits); every thread of the group calls it.
void ReduceTile(uint2 group, uint gi) {
  if (gi == 0) {
    gsMin = asuint(SDSM_INFINITY);
    gsMax = 0;
  }
  float lo = SDSM_INFINITY, hi = 0.0;
  uint2 first = SdsmStripRow(group, gi);
  uint xEnd = SdsmStripRowEnd(group, gi);
  for (uint x = first.x; x < xEnd; ++x) {
    float d = cameraDepth.Load(int3(x, first.y, 0));
    if (d < 1.0) {
      float z = SdsmViewDepth(d);
      lo = min(lo, z);
      hi = max(hi, z);
    }
  }
  GroupMemoryBarrierWithGroupSync();
  if (lo <= hi) {
    InterlockedMin(gsMin, asuint(lo));
    InterlockedMax(gsMax, asuint(hi));
  }
  GroupMemoryBarrierWithGroupSync();
}

[numthreads(SDSM_STRIP, 1, 1)]
void ReduceTiles(uint3 group : SV_GroupID, uint gi : SV_GroupIndex) {
  ReduceTile(group.xy, gi);
  if (gi == 0) tiles[group.y * SdsmStripTiles().x + group.x] = uint2(gsMin, gsMax);
}

[numthreads(SDSM_GROUP_THREADS, 1, 1)]
void ReduceFinal(uint gi : SV_GroupIndex) {
  if (gi == 0) {
    gsMin = asuint(SDSM_INFINITY);
    gsMax = 0;
  }
  uint lo = asuint(SDSM_INFINITY), hi = 0;
  uint2 tileCount = SdsmStripTiles();
  uint n = tileCount.x * tileCount.y;
  for (uint t = gi; t < n; t += SDSM_GROUP_THREADS) {
    uint2 v = tiles[t];
    lo = min(lo, v.x);
    hi = max(hi, v.y);
  }
  GroupMemoryBarrierWithGroupSync();
  InterlockedMin(gsMin, lo);
  InterlockedMax(gsMax, hi);
  GroupMemoryBarrierWithGroupSync();
  if (gi == 0) results.Store2(SDSM_W_MIN * 4, uint2(gsMin, gsMax));
}

[numthreads(SDSM_STRIP, 1, 1)]
void ReduceAtomic(uint3 group : SV_GroupID, uint gi : SV_GroupIndex) {
  ReduceTile(group.xy, gi);
  // An all-sky tile has nothing to merge; skipping it saves two atomics per such tile.
  if (gi == 0 && gsMin <= gsMax) {
    uint ignored;
    results.InterlockedMin(SDSM_W_MIN * 4, gsMin, ignored);
    results.InterlockedMax(SDSM_W_MAX * 4, gsMax, ignored);
  }
}
