// SDSM: resetting the analysis results, and the histogram of log view depth between the reduced
// min and max (read from the results buffer on the GPU, so no readback sits between the passes).
// Each 16x16 group counts into a groupshared histogram and adds its non-zero bins to the global
// one, which keeps global atomics to at most one per bin and group.
//! cs_5_0 ResetResults
//! cs_5_0 Histogram
#include "sdsm/analysis.hlsli"

Texture2D<float> cameraDepth : register(t0);
RWByteAddressBuffer results : register(u0);
RWStructuredBuffer<uint> histogram : register(u1);

// One thread per word of the results and per bin: dispatch ceil(max(SDSM_BINS, 96) / 256) groups.
[numthreads(SDSM_GROUP_THREADS, 1, 1)]
void ResetResults(uint i : SV_DispatchThreadID) {
  if (i < SDSM_BINS) histogram[i] = 0;
  if (i >= SDSM_RESULT_WORDS) return;
  uint v = 0;
  if (i == SDSM_W_MIN) v = asuint(SDSM_INFINITY);
  if (i == SDSM_W_PARTITIONS) v = partitionCount;
  // Bounds: min keys start at the largest key, max keys at the smallest, so any sample wins.
  if (i >= SDSM_W_BOUNDS && i < SDSM_W_BOUNDS + 8 * SDSM_MAX_PARTITIONS && (i - SDSM_W_BOUNDS) % 8 < 3) v = 0xffffffffu;
  results.Store(i * 4, v);
}

groupshared uint gsHistogram[SDSM_BINS];
groupshared uint gsSamples;

[numthreads(SDSM_TILE, SDSM_TILE, 1)]
void Histogram(uint3 pixel : SV_DispatchThreadID, uint gi : SV_GroupIndex) {
  for (uint b = gi; b < SDSM_BINS; b += SDSM_GROUP_THREADS) gsHistogram[b] = 0;
  if (gi == 0) gsSamples = 0;
  GroupMemoryBarrierWithGroupSync();
  float zMin = asfloat(results.Load(SDSM_W_MIN * 4));
  float zMax = asfloat(results.Load(SDSM_W_MAX * 4));
  if (all(pixel.xy < depthSize)) {
    float d = cameraDepth.Load(int3(pixel.xy, 0));
    if (d < 1.0) {
      InterlockedAdd(gsHistogram[SdsmHistogramBin(SdsmViewDepth(d), zMin, zMax)], 1u);
      InterlockedAdd(gsSamples, 1u);
    }
  }
  GroupMemoryBarrierWithGroupSync();
  for (uint c = gi; c < SDSM_BINS; c += SDSM_GROUP_THREADS) {
    uint n = gsHistogram[c];
    if (n != 0) InterlockedAdd(histogram[c], n);
  }
  if (gi == 0 && gsSamples != 0) {
    uint ignored;
    results.InterlockedAdd(SDSM_W_SAMPLES * 4, gsSamples, ignored);
  }
}
