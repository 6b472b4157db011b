// SDSM partition schemes, computed on the GPU from the reduced depth range and the histogram of
// log view depth, into K + 1 split distances in the results buffer (first = min, last = max).
// One group of 256 threads; positions are worked out in bin units u in [0, SDSM_BINS] of the
// log-depth axis (bin b covers [b, b + 1)) and turned into view depth at the end:
//   z(u) = exp(log zMin + (log zMax - log zMin) * (u / SDSM_BINS)).
// The rules (and their CPU twin) are in techniques/sdsm/partitions.h. The arithmetic is chosen to
// be reproducible on the CPU: integer tests for adaptive-log, serial sums in a fixed order for
// k-means; only the final exp/log differ from the CPU's in the last bits.
//! cs_5_0 Partitions
#include "sdsm/analysis.hlsli"

#if (SDSM_BINS % SDSM_GROUP_THREADS) != 0 || SDSM_BINS > 1024
#error SDSM_BINS must be a multiple of 256, at most 1024
#endif
#define SDSM_BINS_PER_THREAD (SDSM_BINS / SDSM_GROUP_THREADS)
#define SDSM_MAX_KMEANS_ITERATIONS 64

RWByteAddressBuffer results : register(u0);
RWStructuredBuffer<uint> histogram : register(u1);

groupshared uint gsCount[SDSM_BINS];
groupshared uint gsAssign[SDSM_BINS];
groupshared uint gsScan[SDSM_GROUP_THREADS];
groupshared float gsCentre[SDSM_MAX_PARTITIONS];
groupshared float gsPosition[SDSM_MAX_PARTITIONS + 1];

// Log splits over the occupied bins only, then snapped onto nearby gaps (rule in
// techniques/sdsm/partitions.h). Every test is on integers: measures are compared multiplied by K.
groupshared uint gsSnap[SDSM_MAX_PARTITIONS];  // per split: (2 |iM - accK|) << 16 | gap end bin

void AdaptiveLog(uint gi, uint K) {
  uint base = gi * SDSM_BINS_PER_THREAD;
  uint local = 0;
  [unroll] for (uint j = 0; j < SDSM_BINS_PER_THREAD; ++j) local += gsCount[base + j] > gapThreshold ? 1u : 0u;
  gsScan[gi] = local;
  if (gi < SDSM_MAX_PARTITIONS) gsSnap[gi] = 0xffffffffu;
  GroupMemoryBarrierWithGroupSync();
  [unroll] for (uint off = 1; off < SDSM_GROUP_THREADS; off <<= 1) {
    uint v = gi >= off ? gsScan[gi - off] : 0u;
    GroupMemoryBarrierWithGroupSync();
    gsScan[gi] += v;
    GroupMemoryBarrierWithGroupSync();
  }
  uint M = gsScan[SDSM_GROUP_THREADS - 1];
  if (M == 0) return;  // nothing occupied: keep the log splits
  uint acc = gsScan[gi] - local;
  [unroll] for (uint k = 0; k < SDSM_BINS_PER_THREAD; ++k) {
    uint b = base + k;
    if (gsCount[b] <= gapThreshold) continue;
    bool gapEnd = b > 0 && acc > 0 && gsCount[b - 1] <= gapThreshold;
    for (uint i = 1; i < K; ++i) {
      uint target = i * M;
      if (acc * K <= target && target < (acc + 1) * K) gsPosition[i] = float(b) + float(target - acc * K) / float(K);
      uint distance2 = 2 * (target > acc * K ? target - acc * K : acc * K - target);
      if (gapEnd && distance2 < M) InterlockedMin(gsSnap[i], (distance2 << 16) | b);
    }
    ++acc;
  }
  GroupMemoryBarrierWithGroupSync();
  if (gi > 0 && gi < K && gsSnap[gi] != 0xffffffffu) gsPosition[gi] = float(gsSnap[gi] & 0xffffu);
}

// Weighted Lloyd iterations in 1D over the bin centres b + 0.5 (weights = counts), K centres
// starting at the middles of the log partitions; a centre that gets no samples stays where it is.
// Splits at the midpoints between neighbouring centres.
void KMeans(uint gi, uint K) {
  if (gi < K) gsCentre[gi] = (float(gi) + 0.5) * float(SDSM_BINS) / float(K);
  GroupMemoryBarrierWithGroupSync();
  uint iterations = min(kmeansIterations, uint(SDSM_MAX_KMEANS_ITERATIONS));
  for (uint it = 0; it < iterations; ++it) {
    [unroll] for (uint j = 0; j < SDSM_BINS_PER_THREAD; ++j) {
      uint b = gi * SDSM_BINS_PER_THREAD + j;
      float x = float(b) + 0.5;
      uint best = 0;
      float bestDistance = abs(x - gsCentre[0]);
      for (uint k = 1; k < K; ++k) {
        float d = abs(x - gsCentre[k]);
        if (d < bestDistance) {
          best = k;
          bestDistance = d;
        }
      }
      gsAssign[b] = best;
    }
    GroupMemoryBarrierWithGroupSync();
    // One thread per cluster sums serially in bin order: the CPU reference sums in that order too.
    if (gi < K) {
      precise float weight = 0.0;
      precise float moment = 0.0;
      for (uint b = 0; b < SDSM_BINS; ++b) {
        if (gsAssign[b] != gi) continue;
        float w = float(gsCount[b]);
        weight += w;
        moment += w * (float(b) + 0.5);
      }
      if (weight > 0.0) gsCentre[gi] = moment / weight;
    }
    GroupMemoryBarrierWithGroupSync();
  }
  if (gi > 0 && gi < K) gsPosition[gi] = (gsCentre[gi - 1] + gsCentre[gi]) * 0.5;
}

[numthreads(SDSM_GROUP_THREADS, 1, 1)]
void Partitions(uint gi : SV_GroupIndex) {
  uint K = clamp(partitionCount, 1u, uint(SDSM_MAX_PARTITIONS));
  float zMin = asfloat(results.Load(SDSM_W_MIN * 4));
  float zMax = asfloat(results.Load(SDSM_W_MAX * 4));
  bool covered = zMin <= zMax;
  uint scheme = covered ? partitionScheme : 0u;
  if (!covered) {
    zMin = fallbackNear;
    zMax = fallbackFar;
  }
  [unroll] for (uint j = 0; j < SDSM_BINS_PER_THREAD; ++j) gsCount[gi * SDSM_BINS_PER_THREAD + j] = histogram[gi * SDSM_BINS_PER_THREAD + j];
  if (gi <= K) gsPosition[gi] = float(gi * SDSM_BINS) / float(K);
  GroupMemoryBarrierWithGroupSync();
  if (scheme == 1) AdaptiveLog(gi, K);
  if (scheme == 2) KMeans(gi, K);
  GroupMemoryBarrierWithGroupSync();
  if (gi <= K) {
    float z = gi == 0 ? zMin : zMax;
    if (gi != 0 && gi != K) {
      float lmin = log(zMin);
      float lmax = log(zMax);
      z = clamp(exp(lmin + (lmax - lmin) * (gsPosition[gi] / float(SDSM_BINS))), zMin, zMax);
    }
    results.Store((SDSM_W_SPLITS + gi) * 4, asuint(z));
  }
  if (gi == 0) results.Store(SDSM_W_PARTITIONS * 4, K);
}
