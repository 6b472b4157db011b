// Adaptive shadow maps: the CPU side of the physical page pool. Virtual pages (level, x, y) of
// the page-table hierarchy are mapped to slots of the pool; a page not mapped is "not resident".
// The allocator serves the refinement requests of a frame: a resident page is marked used; a
// missing one takes a free slot, or the least recently used slot whose page was not used this
// frame (evicting that page); when every slot holds a page of this frame or a pinned page (the
// always-resident coarse levels), the request is counted as unserved and nothing changes.
#pragma once
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

namespace sp::tech::asmap {

struct PageKey {
  uint32_t level = 0, x = 0, y = 0;
  bool operator==(const PageKey& o) const { return level == o.level && x == o.x && y == o.y; }
  uint64_t packed() const { return (uint64_t(level) << 48) | (uint64_t(y) << 24) | x; }
};

class PageAllocator {
 public:
  // capacity: slots in the pool (> 0).
  explicit PageAllocator(uint32_t capacity);

  // Forgets every page (all slots free) and the counters.
  void Reset();
  // Starts a frame: pages used from now on are this frame's and cannot be evicted until the next.
  void BeginFrame();

  struct Result {
    bool served = false;                 // false: no slot could be given (counted in unserved())
    bool created = false;                // a slot was given now: the page must be rendered
    uint32_t slot = 0;                   // where the page lives (served only)
    std::optional<PageKey> evicted;      // the page that lost the slot (its table entry must go)
  };
  // A page the frame needs. pinned: never evicted (until Reset).
  Result Request(const PageKey& key, bool pinned = false);

  std::optional<uint32_t> SlotOf(const PageKey& key) const;
  uint32_t capacity() const { return uint32_t(slots_.size()); }
  uint32_t resident() const { return uint32_t(index_.size()); }
  // Since BeginFrame: requests, pages created, pages evicted, requests unserved.
  uint32_t requests() const { return requests_; }
  uint32_t created() const { return created_; }
  uint32_t evictions() const { return evictions_; }
  uint32_t unserved() const { return unserved_; }

 private:
  struct Slot {
    bool used = false, pinned = false;
    PageKey key;
    uint64_t lastFrame = 0;  // frame number of the last request
    uint64_t lastTick = 0;   // request order, to break ties within a frame
  };
  std::vector<Slot> slots_;
  std::vector<uint32_t> free_;
  std::unordered_map<uint64_t, uint32_t> index_;  // packed key -> slot
  uint64_t frame_ = 1, tick_ = 0;
  uint32_t requests_ = 0, created_ = 0, evictions_ = 0, unserved_ = 0;
};

}  // namespace sp::tech::asmap
