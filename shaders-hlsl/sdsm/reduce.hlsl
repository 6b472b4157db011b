// SDSM depth reduction: min and max view depth of the camera's non-sky pixels (depth 1.0 = sky).
// Each 16x16 tile is reduced in groupshared memory as a tree; then either a second pass reduces
// the tiles' results (ReduceTiles + ReduceFinal), or each tile merges its result with
// InterlockedMin/Max on the float bits (ReduceAtomic): view depths are positive, and the bits of
// non-negative floats order like the floats, so uint atomics do float min/max.
//! cs_5_0 ReduceTiles
//! cs_5_0 ReduceFinal
//! cs_5_0 ReduceAtomic
#include "sdsm/analysis.hlsli"

Texture2D<float> cameraDepth : register(t0);
RWByteAddressBuffer results : register(u0);
RWStructuredBuffer<uint2> tiles : register(u1);  // per tile: min and max bits (two-pass mode)

groupshared float gsMin[SDSM_GROUP_THREADS];
groupshared float gsMax[SDSM_GROUP_THREADS];

// Tree reduction of gsMin/gsMax; the result ends in element 0. Every thread of the group calls it.
void ReduceGroupShared(uint gi) {
  GroupMemoryBarrierWithGroupSync();
  [unroll] for (uint s = SDSM_GROUP_THREADS / 2; s > 0; s >>= 1) {
    if (gi < s) {
      gsMin[gi] = min(gsMin[gi], gsMin[gi + s]);
      gsMax[gi] = max(gsMax[gi], gsMax[gi + s]);
    }
    GroupMemoryBarrierWithGroupSync();
  }
}

// Loads one pixel; sky and pixels beyond the edge of the last tiles get the neutral elements.
void LoadTile(uint2 pixel, uint gi) {
  float lo = SDSM_INFINITY, hi = 0.0;
  if (all(pixel < depthSize)) {
    float d = cameraDepth.Load(int3(pixel, 0));
    if (d < 1.0) {
      lo = SdsmViewDepth(d);
      hi = lo;
    }
  }
  gsMin[gi] = lo;
  gsMax[gi] = hi;
  ReduceGroupShared(gi);
}

[numthreads(SDSM_TILE, SDSM_TILE, 1)]
void ReduceTiles(uint3 pixel : SV_DispatchThreadID, uint3 group : SV_GroupID, uint gi : SV_GroupIndex) {
  LoadTile(pixel.xy, gi);
  if (gi == 0) tiles[group.y * tileCount.x + group.x] = uint2(asuint(gsMin[0]), asuint(gsMax[0]));
}

[numthreads(SDSM_GROUP_THREADS, 1, 1)]
void ReduceFinal(uint gi : SV_GroupIndex) {
  float lo = SDSM_INFINITY, hi = 0.0;
  uint n = tileCount.x * tileCount.y;
  for (uint t = gi; t < n; t += SDSM_GROUP_THREADS) {
    uint2 v = tiles[t];
    lo = min(lo, asfloat(v.x));
    hi = max(hi, asfloat(v.y));
  }
  gsMin[gi] = lo;
  gsMax[gi] = hi;
  ReduceGroupShared(gi);
  if (gi == 0) results.Store2(SDSM_W_MIN * 4, uint2(asuint(gsMin[0]), asuint(gsMax[0])));
}

[numthreads(SDSM_TILE, SDSM_TILE, 1)]
void ReduceAtomic(uint3 pixel : SV_DispatchThreadID, uint gi : SV_GroupIndex) {
  LoadTile(pixel.xy, gi);
  // An all-sky tile has nothing to merge; skipping it saves two atomics per such tile.
  if (gi == 0 && gsMin[0] <= gsMax[0]) {
    uint ignored;
    results.InterlockedMin(SDSM_W_MIN * 4, asuint(gsMin[0]), ignored);
    results.InterlockedMax(SDSM_W_MAX * 4, asuint(gsMax[0]), ignored);
  }
}
