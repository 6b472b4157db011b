// SDSM: resetting the analysis results, and the histogram of log view depth between the reduced
// min and max (read from the results buffer on the GPU, so no readback sits between the passes).
// Each group counts into a groupshared histogram and adds its non-zero bins to the global one,
// which keeps global atomics to at most one per bin and group.
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

// One SDSM_STRIP^2 tile per group, one row of it per thread. Neighbours along a row mostly share
// a bin (a floor's row is one depth), so a thread counts a run of equal bins in a register and
// adds it to the groupshared bin when the bin changes: a groupshared atomic per run, not per
// pixel. Zeroing and flushing the groupshared bins is paid once per 4096 pixels, not per 256.
[numthreads(SDSM_STRIP, 1, 1)]
void Histogram(uint3 group : SV_GroupID, uint gi : SV_GroupIndex) {
  for (uint b = gi; b < SDSM_BINS; b += SDSM_STRIP) gsHistogram[b] = 0;
  if (gi == 0) gsSamples = 0;
  GroupMemoryBarrierWithGroupSync();
  SdsmBinRange range = SdsmHistogramRange(asfloat(results.Load(SDSM_W_MIN * 4)), asfloat(results.Load(SDSM_W_MAX * 4)));
  uint2 first = SdsmStripRow(group.xy, gi);
  uint xEnd = SdsmStripRowEnd(group.xy, gi);
  uint run = 0, runBin = 0, samples = 0;
  for (uint x = first.x; x < xEnd; ++x) {
    float d = cameraDepth.Load(int3(x, first.y, 0));
    if (d < 1.0) {
      uint bin = SdsmHistogramBin(SdsmViewDepth(d), range);
      if (bin != runBin) {
        if (run != 0) InterlockedAdd(gsHistogram[runBin], run);
        runBin = bin;
        run = 0;
      }
      ++run;
      ++samples;
    }
  }
  if (run != 0) InterlockedAdd(gsHistogram[runBin], run);
  if (samples != 0) InterlockedAdd(gsSamples, samples);
  GroupMemoryBarrierWithGroupSync();
  for (uint c = gi; c < SDSM_BINS; c += SDSM_STRIP) {
    uint n = gsHistogram[c];
    if (n != 0) InterlockedAdd(histogram[c], n);
  }
  if (gi == 0 && gsSamples != 0) {
    uint ignored;
    results.InterlockedAdd(SDSM_W_SAMPLES * 4, gsSamples, ignored);
  }
}
