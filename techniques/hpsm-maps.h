// Accelerated comparison filtering for techniques that use common/shadow-filter.hlsli: the
// secondary maps of common/hpsm.hlsli (hybrid min/max plane shadow maps, or the hierarchical
// min/max baseline), their parameters, their build pass and the lit pass's decision counters.
#pragma once
#include <array>
#include <sp/tech/hpsm-counters.h>
#include <sp/tech/technique.h>

namespace sp::tech {

enum class ShadowAccel { None, Hpsm, MinMax };

// Texels a filter (SHADOW_FILTER 0..5, SHADOW_KERNEL; for pcss the kernel is pcss_max_kernel)
// reads beyond floor(s) on each side, R in common/hpsm.hlsli: it reads [floor(s) - R,
// floor(s) + R + 1]. Throws for a filter it does not know.
int FilterReach(int filter, int kernel);

struct HpsmSettings {
  ShadowAccel accel = ShadowAccel::None;
  int reach = 0;     // FilterReach of the technique's filter
  int block = 4;     // texels per secondary texel and axis (minmax: the level's width, 2^k)
  float eps = 0.0f;  // hpsm: the largest plane residual, in depth units
  bool counters = true;  // the lit pass counts its decisions (HpsmCounterSource)
  int pcssMaxKernel = 0;  // filter=pcss: the pcss_max_kernel the reach was derived from (HPSM_PCSS_MAX_KERNEL)
  bool gatherBuild = true;  // hpsm_build: the build fills its tile with GatherRed (false: Load)
};

// The parameters: accel, hpsm_block, hpsm_eps, hpsm_counters, hpsm_build.
std::vector<ParamSpec> HpsmParams();
// For techniques that do not offer acceleration: an `accel` parameter whose only working value is
// none, so that asking for it is refused by RefuseAccel with the technique's reason instead of as
// an unknown parameter.
ParamSpec UnofferedAccelParam(const std::string& why);
void RefuseAccel(const ParamValues& p, const std::string& technique, const std::string& why);
// Reads them for a technique filtering with (filter, kernel; pcss: pcss_max_kernel) a map of `resolution` texels;
// throws std::invalid_argument naming the parameter for values that cannot work.
HpsmSettings ReadHpsmSettings(const ParamValues& p, int filter, int kernel, uint32_t resolution);
// SHADOW_ACCEL, HPSM_BLOCK, HPSM_REACH, HPSM_COUNTERS for the lighting include (none for accel=none).
std::vector<hlsl::Define> HpsmDefines(const HpsmSettings& s);

class HpsmMaps {
 public:
  // Secondary maps for `layers` layers of width x height; s.accel must not be None.
  HpsmMaps(Device& device, const HpsmSettings& s, uint32_t width, uint32_t height, uint32_t layers);
  // Rebuilds every layer from `depth` (an R32_FLOAT Texture2DArray view of the shadow maps) and
  // zeroes the counters, so they count the lit passes that read this build.
  void Build(DeviceContext& ctx, ShaderResourceView* depth);
  ShaderResourceView* srv() const { return srv_.get(); }
  Texture2D* texture() const { return texture_.get(); }
  // Binds the counters as the lit pass's u7 (keeping its render targets).
  void BindCounters(DeviceContext& ctx);
  HpsmCounts ReadCounters(DeviceContext& ctx);
  // Every word of the counters' buffer: the decisions, then the sun shafts' (common/shafts.hlsli).
  static constexpr uint32_t kCounterWords = 8;
  std::array<uint32_t, kCounterWords> ReadCounterWords(DeviceContext& ctx);
  uint64_t memoryBytes() const;
  uint32_t blocksX() const { return blocksX_; }
  uint32_t blocksY() const { return blocksY_; }

 private:
  Device& device_;
  HpsmSettings settings_;
  uint32_t width_, height_, layers_, blocksX_, blocksY_;
  Ref<Texture2D> texture_;
  Ref<ShaderResourceView> srv_;
  Ref<UnorderedAccessView> uav_;
  Ref<ComputeShader> build_;
  Ref<SamplerState> point_;  // hpsm_build=gather
  Ref<Buffer> constants_, counters_, countersStaging_;
  Ref<UnorderedAccessView> countersUav_;
};

}  // namespace sp::tech
