// What the lit pass of an accelerated comparison filter decided (techniques/hpsm-maps.h,
// shaders-hlsl/common/hpsm.hlsli), for the lab and the tests: public so the bench can record it.
#pragma once
#include <array>
#include <cstdint>

namespace sp::tech {

// Decision counts of the lit pass (common/hpsm.hlsli's kHpsm* order).
struct HpsmCounts {
  std::array<uint64_t, 5> n{};  // lit min/max, shadowed min/max, lit plane, shadowed plane, filtered
  uint64_t total() const { return n[0] + n[1] + n[2] + n[3] + n[4]; }
  double minMaxFraction() const { return total() ? double(n[0] + n[1]) / double(total()) : 0.0; }
  double planeFraction() const { return total() ? double(n[2] + n[3]) / double(total()) : 0.0; }
  double filteredFraction() const { return total() ? double(n[4]) / double(total()) : 0.0; }
};

// Implemented by techniques with an `accel` parameter, beside Technique: the lit passes' decisions
// since the last shadow pass (a readback stall; all zero with accel=none or hpsm_counters=0). Find it with
// dynamic_cast<const HpsmCounterSource*>(&technique).
class HpsmCounterSource {
 public:
  virtual ~HpsmCounterSource() = default;
  virtual HpsmCounts HpsmDecisions() const = 0;
};

}  // namespace sp::tech
