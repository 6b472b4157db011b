// Adaptive shadow maps: what the last frame's refinement did, for tests and the bench (dynamic_cast
// a Technique to AsmCounterSource): public so the bench can record it per frame.
#pragma once
#include <cstdint>
#include <vector>

namespace sp::tech {

struct AsmCounters {
  uint32_t iterations = 0;     // analyses run (each: camera view, Sobel pass, then readback or GPU allocation)
  uint32_t requests = 0;       // pages requested by the analyses (de-duplicated per frame)
  uint32_t pagesRendered = 0;  // pages allocated and rendered (resident levels included)
  uint32_t evicted = 0;        // pages evicted (LRU) to make room
  uint32_t unserved = 0;       // requests refused: every pool page was in use this frame or pinned
  uint32_t resident = 0;       // pages resident after the frame
};

class AsmCounterSource {
 public:
  virtual ~AsmCounterSource() = default;
  virtual AsmCounters AsmFrameCounters() const = 0;
  // Every resident page as (level << 28 | y << 14 | x), ascending, read back from the page tables.
  virtual std::vector<uint32_t> AsmResidentPages() const = 0;
};

}  // namespace sp::tech
