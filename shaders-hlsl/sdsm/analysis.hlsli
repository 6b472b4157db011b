// Sample Distribution Shadow Maps (Lauritzen, Salvi, Lefohn 2011): what the analysis passes share.
// The C++ mirror of every constant and layout here is techniques/sdsm/analysis-frame.h and
// depth-analysis.h; the CPU reference in techniques/sdsm/ repeats the per-pixel arithmetic with
// the same float operations in the same order, which is why the critical expressions are
// `precise` (no contraction into fused multiply-adds, which the CPU does not do either).
#ifndef SP_SDSM_ANALYSIS_HLSLI
#define SP_SDSM_ANALYSIS_HLSLI

#ifndef SDSM_BINS
#define SDSM_BINS 1024
#endif
#define SDSM_MAX_PARTITIONS 8
#define SDSM_TILE 16
#define SDSM_GROUP_THREADS (SDSM_TILE * SDSM_TILE)
// Passes that walk the depth buffer in strips: a group of SDSM_STRIP threads covers an
// SDSM_STRIP x SDSM_STRIP tile, one row per thread (C++: kStripTile).
#define SDSM_STRIP 64

// The results buffer (RWByteAddressBuffer, 32-bit words).
#define SDSM_W_MIN 0          // min view depth of non-sky pixels (float bits; +inf when none)
#define SDSM_W_MAX 1          // max view depth (float bits; 0 when none)
#define SDSM_W_SAMPLES 2      // non-sky pixels counted by the histogram pass
#define SDSM_W_PARTITIONS 3   // partition count K of the last partition pass
#define SDSM_W_SPLITS 4       // K + 1 split distances (floats), first = min, last = max
#define SDSM_W_BOUNDS 20      // per partition 8 words: ordered keys of light-space min xyz,
                              // sample count, ordered keys of max xyz, 0
#define SDSM_RESULT_WORDS 96

#define SDSM_INFINITY asfloat(0x7f800000u)

// SDSM_LAYOUT_ONLY: just the constants above and the key mapping (for shaders with their own b0).
#ifndef SDSM_LAYOUT_ONLY
// Per-frame constants of every analysis pass (C++: AnalysisConstants).
cbuffer SdsmAnalysis : register(b0) {
  uint2 depthSize;         // camera depth buffer, pixels
  uint2 tileCount;         // ceil(depthSize / SDSM_TILE)
  float depthA;            // view depth = depthA / (depthB - d), from the camera projection
  float depthB;
  float fallbackNear;      // the camera's near/far: the range when no pixel is covered
  float fallbackFar;
  float2 ndcScale;         // ndc = (pixel + 0.5) * ndcScale + ndcOffset
  float2 ndcOffset;
  float2 rayScale;         // view-space ray per unit view depth: (ndc * rayScale + rayOffset, -1)
  float2 rayOffset;
  float3 lightRayX;        // light-view images of the camera's view axes x, y and -z,
  uint partitionCount;
  float3 lightRayY;
  uint partitionScheme;    // 0 log, 1 adaptive-log, 2 k-means
  float3 lightRayZ;
  uint gapThreshold;       // adaptive-log: bins with at most this many samples count as empty
  float3 lightOrigin;      // and of the camera position
  uint kmeansIterations;
};

// Strip tiles: how many cover the depth buffer, and the pixels of thread gi's row of tile `group`
// (x from SdsmStripRow(...).x to SdsmStripRowEnd(...), exclusive; an empty range below the
// buffer's last row).
uint2 SdsmStripTiles() { return (depthSize + SDSM_STRIP - 1) / SDSM_STRIP; }
uint2 SdsmStripRow(uint2 group, uint gi) { return group * SDSM_STRIP + uint2(0, gi); }
uint SdsmStripRowEnd(uint2 group, uint gi) {
  return group.y * SDSM_STRIP + gi < depthSize.y ? min(group.x * SDSM_STRIP + SDSM_STRIP, depthSize.x) : 0;
}

float SdsmViewDepth(float d) {
  precise float z = depthA / (depthB - d);
  return z;
}

// Light-view position of the pixel's sample at view depth z: the camera ray through the pixel
// centre, scaled by z, in light space. Only multiplies and adds, so the CPU reproduces it exactly.
float3 SdsmLightPosition(uint2 pixel, float z) {
  precise float2 ndc = (float2(pixel) + 0.5) * ndcScale + ndcOffset;
  precise float2 ray = ndc * rayScale + rayOffset;
  precise float3 l = lightRayX * ray.x + lightRayY * ray.y + lightRayZ;
  precise float3 p = lightOrigin + l * z;
  return p;
}

// Histogram bin of view depth z over [log zMin, log zMax] (clamped to the end bins), in two steps
// so a pass computes the range's part once rather than per pixel.
struct SdsmBinRange {
  float lmin, scale;
};
SdsmBinRange SdsmHistogramRange(float zMin, float zMax) {
  SdsmBinRange r;
  r.lmin = log(zMin);
  float range = log(zMax) - r.lmin;
  r.scale = range > 0 ? float(SDSM_BINS) / range : 0.0;
  return r;
}
uint SdsmHistogramBin(float z, SdsmBinRange r) {
  float t = (log(z) - r.lmin) * r.scale;
  return min(uint(max(t, 0.0)), uint(SDSM_BINS - 1));
}
#endif  // SDSM_LAYOUT_ONLY

// A float's bits mapped to a uint whose unsigned order is the float order, negatives included
// (so InterlockedMin/Max on the key is a float min/max).
// (Negative: all bits flipped; otherwise the sign bit set. As one xor with the sign smeared by
// an arithmetic shift: the bounds pass does this three times per pixel.)
uint SdsmOrderedKey(float f) {
  uint u = asuint(f);
  return u ^ (uint(asint(u) >> 31) | 0x80000000u);
}
float SdsmFromOrderedKey(uint k) {
  return asfloat((k & 0x80000000u) != 0 ? (k & 0x7fffffffu) : ~k);
}

#endif
