#include "asm/page-allocator.h"

#include <stdexcept>

namespace sp::tech::asmap {

PageAllocator::PageAllocator(uint32_t capacity) : slots_(capacity) {
  if (capacity == 0) throw std::invalid_argument("PageAllocator: capacity must be at least one page");
  Reset();
}

void PageAllocator::Reset() {
  for (Slot& s : slots_) s = Slot{};
  free_.clear();
  // Free slots are taken from the back: slot 0 first.
  for (uint32_t i = uint32_t(slots_.size()); i-- > 0;) free_.push_back(i);
  index_.clear();
  frame_ = 1;
  tick_ = 0;
  requests_ = created_ = evictions_ = unserved_ = 0;
}

void PageAllocator::BeginFrame() {
  ++frame_;
  requests_ = created_ = evictions_ = unserved_ = 0;
}

PageAllocator::Result PageAllocator::Request(const PageKey& key, bool pinned) {
  ++requests_;
  Result r;
  auto it = index_.find(key.packed());
  if (it != index_.end()) {
    Slot& s = slots_[it->second];
    s.lastFrame = frame_;
    s.lastTick = ++tick_;
    s.pinned |= pinned;
    r.served = true;
    r.slot = it->second;
    return r;
  }
  uint32_t slot;
  if (!free_.empty()) {
    slot = free_.back();
    free_.pop_back();
  } else {
    // Least recently used among the slots not used this frame and not pinned. A linear scan: the
    // pool holds a few thousand pages and misses are few per frame once the view settles.
    int64_t best = -1;
    for (uint32_t i = 0; i < slots_.size(); ++i) {
      const Slot& s = slots_[i];
      if (s.pinned || s.lastFrame == frame_) continue;
      if (best < 0 || s.lastTick < slots_[size_t(best)].lastTick) best = i;
    }
    if (best < 0) {
      ++unserved_;
      return r;
    }
    slot = uint32_t(best);
    r.evicted = slots_[slot].key;
    index_.erase(slots_[slot].key.packed());
    ++evictions_;
  }
  slots_[slot] = Slot{true, pinned, key, frame_, ++tick_};
  index_[key.packed()] = slot;
  ++created_;
  r.served = r.created = true;
  r.slot = slot;
  return r;
}

std::optional<uint32_t> PageAllocator::SlotOf(const PageKey& key) const {
  auto it = index_.find(key.packed());
  if (it == index_.end()) return std::nullopt;
  return it->second;
}

}  // namespace sp::tech::asmap
