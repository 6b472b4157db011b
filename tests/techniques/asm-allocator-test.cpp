// Adaptive shadow maps: the CPU page allocator (techniques/asm/page-allocator.h). Expected
// behaviour from its contract: free slots first, then the least recently used page not used
// this frame and not pinned; otherwise the request is unserved and nothing changes.
#include <gtest/gtest.h>

#include "asm/page-allocator.h"

namespace sp::test {
namespace {

using tech::asmap::PageAllocator;
using tech::asmap::PageKey;

TEST(AsmPageAllocator, FillsFreeSlotsThenEvictsTheLeastRecentlyUsed) {
  PageAllocator a(3);
  a.BeginFrame();
  PageKey p{2, 0, 0}, q{2, 1, 0}, r{2, 2, 0}, s{2, 3, 0};
  EXPECT_TRUE(a.Request(p).created);
  EXPECT_TRUE(a.Request(q).created);
  EXPECT_TRUE(a.Request(r).created);
  EXPECT_EQ(a.resident(), 3u);
  // Next frame: use r, then q; p is the least recently used.
  a.BeginFrame();
  PageAllocator::Result again = a.Request(r);
  EXPECT_TRUE(again.served);
  EXPECT_FALSE(again.created) << "a resident page is not created again";
  a.Request(q);
  a.BeginFrame();
  PageAllocator::Result got = a.Request(s);
  ASSERT_TRUE(got.served);
  EXPECT_TRUE(got.created);
  ASSERT_TRUE(got.evicted.has_value());
  EXPECT_EQ(*got.evicted, p);
  EXPECT_EQ(got.slot, *a.SlotOf(s));
  EXPECT_FALSE(a.SlotOf(p).has_value());
  EXPECT_EQ(a.evictions(), 1u);
  EXPECT_EQ(a.unserved(), 0u);
  // Then r (used one frame earlier than q) goes before q.
  PageAllocator::Result next = a.Request(PageKey{3, 0, 0});
  ASSERT_TRUE(next.evicted.has_value());
  EXPECT_EQ(*next.evicted, r);
}

TEST(AsmPageAllocator, NeverEvictsAPageUsedThisFrameOrPinned) {
  PageAllocator a(3);
  a.BeginFrame();
  a.Request({0, 0, 0}, true);  // pinned
  a.Request({1, 0, 0});
  a.Request({1, 1, 0});
  // Same frame: both unpinned pages are this frame's; the pinned one never goes.
  PageAllocator::Result r = a.Request({1, 0, 1});
  EXPECT_FALSE(r.served);
  EXPECT_FALSE(r.evicted.has_value());
  EXPECT_EQ(a.unserved(), 1u);
  EXPECT_EQ(a.resident(), 3u);
  EXPECT_TRUE(a.SlotOf({1, 0, 0}).has_value());
  EXPECT_TRUE(a.SlotOf({1, 1, 0}).has_value());
  // Next frame, with one of them used again: the other is evicted, never the pinned page.
  a.BeginFrame();
  EXPECT_EQ(a.unserved(), 0u) << "counters are per frame";
  a.Request({1, 1, 0});
  PageAllocator::Result s = a.Request({1, 0, 1});
  ASSERT_TRUE(s.served);
  ASSERT_TRUE(s.evicted.has_value());
  EXPECT_EQ(*s.evicted, (PageKey{1, 0, 0}));
  PageAllocator::Result t = a.Request({1, 1, 1});
  EXPECT_FALSE(t.served) << "only the pinned page and pages of this frame are left";
  EXPECT_TRUE(a.SlotOf({0, 0, 0}).has_value());
  EXPECT_EQ(a.capacity(), 3u);
}

TEST(AsmPageAllocator, ResetFreesEverySlotAndRefusesZeroCapacity) {
  PageAllocator a(2);
  a.BeginFrame();
  a.Request({0, 0, 0}, true);
  a.Request({1, 0, 0});
  a.Reset();
  EXPECT_EQ(a.resident(), 0u);
  a.BeginFrame();
  EXPECT_EQ(a.Request({1, 1, 1}).slot, 0u);
  EXPECT_THROW(PageAllocator(0), std::invalid_argument);
}

}  // namespace
}  // namespace sp::test
