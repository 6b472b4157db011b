// Sample Distribution Shadow Maps: the partition schemes, as the CPU reference of
// shaders-hlsl/sdsm/partitions.hlsl (same rules, same arithmetic where it matters) and for
// CPU-side use.
//
// Input: the tight view-depth range [zMin, zMax] of the visible samples and a histogram of N bins
// over [log zMin, log zMax] (bin b covers u in [b, b + 1) with u = N (log z - log zMin) /
// (log zMax - log zMin)). Output: K + 1 split distances, the first zMin and the last zMax;
// partition p takes view depths in [split p, split p+1) (the last one includes zMax). Interior
// splits are computed as positions u in bin units and turned into depth by
//   z(u) = exp(log zMin + (log zMax - log zMin) * (u / N)).
//
// The schemes:
//   log           u_i = i N / K: logarithmic splits between the tight near and far.
//   adaptive-log  log splits over the occupied part of the axis, then snapped onto gaps. A bin is
//                 empty when it holds at most `gapThreshold` samples; M = occupied bins (M = 0:
//                 log). (1) Cut the empty bins out of the axis and split the remaining measure
//                 M into K equal shares: split i sits at occupied measure t_i = i M / K, i.e. in
//                 the first occupied bin b with acc_b K <= i M < (acc_b + 1) K (acc_b = occupied
//                 bins before b), at u_i = b + (i M - acc_b K) / K. (2) A gap is a run of empty
//                 bins with occupied bins on both sides; it sits at occupied measure acc_g and
//                 ends at bin g (its first occupied bin after). Split i moves to u_i = g, the far
//                 end of the gap nearest to it in occupied measure, when that one is less than
//                 half a share away: 2 |i M - acc_g K| < M (equal distances: the lower gap).
//                 So no split lies inside a gap, every partition keeps some occupied measure
//                 (two snapped splits have at least one occupied bin between them), and no
//                 partition reaches across a gap that a split came within half a share of: no
//                 partition spends its share of the log range on depths where nothing is
//                 visible, as log splits inside gaps do. Without gaps it is log.
//   kmeans        weighted Lloyd iterations in 1D over the bin centres x_b = b + 0.5 with the
//                 counts as weights: K centres start at the middles of the log partitions,
//                 c_k = (k + 0.5) N / K; each iteration assigns every bin to its nearest centre
//                 (ties to the lower index), then moves each centre to the weighted mean of its
//                 bins, summed in bin order (a centre with no samples stays). After `iterations`
//                 rounds, u_i = (c_{i-1} + c_i) / 2.
// With no visible sample (zMin > zMax) every scheme gives log splits of the fallback range.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace sp::tech::sdsm {

constexpr uint32_t kMaxPartitions = 8;
constexpr uint32_t kDefaultHistogramBins = 1024;

enum class PartitionScheme : uint32_t { Log = 0, AdaptiveLog = 1, KMeans = 2 };  // = partitionScheme in HLSL

// "log", "adaptive-log", "kmeans"; throws std::invalid_argument listing them otherwise.
PartitionScheme ParsePartitionScheme(const std::string& name);
std::string PartitionSchemeName(PartitionScheme scheme);

struct PartitionSettings {
  PartitionScheme scheme = PartitionScheme::AdaptiveLog;
  uint32_t count = 4;              // K, 1..kMaxPartitions
  uint32_t gapThreshold = 0;       // adaptive-log: bins with at most this many samples are empty
  uint32_t kmeansIterations = 10;  // at most 64 (the shader's bound)
};

struct PartitionResult {
  std::vector<float> splits;     // K + 1 view depths
  std::vector<float> positions;  // K + 1 positions in bin units (0 and N at the ends)
  std::vector<float> centres;    // kmeans: the K final centres in bin units; else empty
};

// The CPU reference of the GPU pass. `histogram` has N bins (any N > 0; the GPU takes multiples
// of 256 up to 1024). zMin > zMax means no sample: the fallback range and log splits are used.
PartitionResult ComputePartitions(const PartitionSettings& settings, float zMin, float zMax,
                                  const std::vector<uint32_t>& histogram, float fallbackNear, float fallbackFar);

// Bin of view depth z, as the histogram pass computes it (natural logs; the GPU's log differs in
// the last bits, so samples within ~1e-6 of a bin edge may land in the neighbouring bin).
uint32_t HistogramBin(float z, float zMin, float zMax, uint32_t bins);
// View depth at position u (bin units) of the log axis over [zMin, zMax] with `bins` bins.
float DepthAtBinPosition(float u, float zMin, float zMax, uint32_t bins);
// The partition view depth z falls in (splits as returned above).
uint32_t PartitionOf(float z, const std::vector<float>& splits);

// The histogram with its splits as an RGBA8 image (the paper's Figure 2): x is log view depth
// from zMin to zMax, bar heights are sqrt(count) scaled to the tallest column, partitions are
// tinted alternately and each interior split is a red vertical line. `splits` are view depths.
std::vector<uint8_t> RenderHistogramImage(const std::vector<uint32_t>& histogram, float zMin, float zMax,
                                          const std::vector<float>& splits, uint32_t width, uint32_t height);
// The image column an interior split at view depth z is drawn in.
uint32_t HistogramImageColumn(float z, float zMin, float zMax, uint32_t width);

}  // namespace sp::tech::sdsm
