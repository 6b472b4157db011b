// What the sun shafts' march did (shaders-hlsl/common/shafts.hlsli), for the lab and the tests.
#pragma once
#include <cstdint>

namespace sp::tech {

struct ShaftCounts {
  uint64_t lookedUp = 0;  // steps tested against the shadow map
  uint64_t skipped = 0;   // steps inside the map decided by the secondary map without a lookup
  double skippedFraction() const { return lookedUp + skipped ? double(skipped) / double(lookedUp + skipped) : 0.0; }
};

// Implemented by techniques with a `shafts` parameter, beside Technique: the lit passes' steps
// since the last shadow pass (a readback stall; zero unless shaft_accel and hpsm_counters are on).
class ShaftCounterSource {
 public:
  virtual ~ShaftCounterSource() = default;
  virtual ShaftCounts ShaftSteps() const = 0;
};

}  // namespace sp::tech
