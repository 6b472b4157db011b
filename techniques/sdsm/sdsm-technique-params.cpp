// The sdsm technique's parameters: its own, plus the cascade parameters that still apply, taken
// from csm's specs (same names, ranges and defaults) and translated by csm's SettingsFrom, so the
// filter, bias and moment options are validated and padded exactly as for csm.
#include <stdexcept>

#include "sdsm/sdsm-technique.h"

namespace sp::tech::sdsm {
namespace {

// csm parameters sdsm shares. Not: split, lambda, splits (the analysis places the splits), fit,
// focus, stabilize (the partitions are fitted to the samples; quantize is sdsm's stability
// option), select (interval: the splits are where the samples are), storage (array). accel: the
// secondary maps are built per partition from the slices as csm builds them per cascade. PCSS:
// each partition's texel size and depth range come from its own fitted scale and offset
// (csm/shadow.hlsli), whether the CPU or fit.hlsl wrote them.
const char* const kSharedCsmParams[] = {"cascades",  "resolution", "blend",      "filter",  "kernel",   "bias",       "depth_bias",
                                        "slope_bias", "normal_offset", "msaa",    "blur",    "bleed",    "exponents",  "precision",
                                        "anisotropy", "accel",       "hpsm_block", "hpsm_eps", "hpsm_counters", "hpsm_build", "light_size", "pcss_search",
                                        "pcss_max_kernel"};

}  // namespace

std::vector<ParamSpec> SdsmParams() {
  using P = ParamSpec;
  std::vector<ParamSpec> specs = {
      {P::Choice, "partition", "how the analysed depth range is split: log splits of the tight range, log over the occupied histogram "
                               "bins snapped onto gaps, or k-means of the histogram", "log", 0, 0, {"log", "adaptive-log", "kmeans"}},
      {P::Int, "tight", "1: each partition fitted to the light-space box of its samples; 0: to its frustum slice (PSSM on the tight near/far)",
       "1", 0, 1, {}},
      {P::Choice, "cull",
       "where the partition matrices come from: conservative (CPU frustum slices, no analysis used), readback (this frame's results, "
       "a stall), latent (results `latency` frames old), gpu (matrices and caster culling on the GPU, nothing read back)",
       "gpu", 0, 0, {"conservative", "readback", "latent", "gpu"}},
      {P::Int, "latency", "cull=latent: frames between an analysis and the use of its results", "2", 1, 8, {}},
      {P::Int, "quantize", "1: partition sizes rounded up to powers of two and offsets snapped to their texel grid (temporal stability)",
       "0", 0, 1, {}},
      {P::Float, "dilation", "world units added around every partition's box (and to caster culling)", "0", 0, 1e6, {}},
  };
  const std::vector<ParamSpec> csmSpecs = csm::CsmParams();
  for (const char* name : kSharedCsmParams)
    for (ParamSpec spec : csmSpecs)
      if (spec.name == name) {
        if (spec.name == "cascades") spec.help = "number of partitions (shadow map slices), 1 to 8";
        specs.push_back(spec);
      }
  return specs;
}

SdsmSettings SdsmSettingsFrom(const ParamValues& p) {
  SdsmSettings s;
  std::map<std::string, std::string> shared;
  for (const char* name : kSharedCsmParams)
    if (p.all().count(name)) shared[name] = p.all().at(name);
  s.csm = csm::SettingsFrom(ParamValues::Parse("sdsm", csm::CsmParams(), shared), "sdsm");
  s.partition = ParsePartitionScheme(p.getChoice("partition"));
  s.tight = p.getInt("tight") != 0;
  const std::string& cull = p.getChoice("cull");
  s.cull = cull == "conservative" ? CullMode::Conservative : cull == "readback" ? CullMode::Readback : cull == "latent" ? CullMode::Latent : CullMode::Gpu;
  s.latency = uint32_t(p.getInt("latency"));
  s.quantize = p.getInt("quantize") != 0;
  s.dilation = p.getFloat("dilation");
  return s;
}

}  // namespace sp::tech::sdsm
