// Adaptive shadow maps, allocation=gpu (techniques/asm/gpu-allocation.cpp): the refinement's
// allocation done on the GPU, with no CPU readback. After the analysis (asm/analysis.hlsl) has
// appended this iteration's requests (pages not requested before in this frame):
//  CSPrepare       resets the iteration's counts and the age histogram, sizes CSTouch's dispatch;
//  CSTouch         a request whose page is resident marks its slot used this frame; the others
//                  are appended to the missing list;
//  CSAgeHistogram  slots that may take a new page (free, or neither pinned nor used this frame)
//                  counted per age bin: bin 0 free, then oldest first (LRU at frame granularity);
//  CSAssign        one group: a prefix sum over the bins gives each bin's first rank; the first
//                  `served` missing pages (at most batchPages, at most the slots available) get a
//                  slot; writes the indirect arguments of the later passes and the draws, and
//                  whether the next iteration runs at all: only if this one placed a page (new
//                  pages can reveal finer edges) or deferred some; otherwise the next
//                  iteration's view is drawn with no instances and its analysis with no groups,
//                  the GPU's own early exit (the readback mode's CPU stops the loop instead);
//  CSOrder         one group: puts the missing list in key order (coarse levels first) and, for
//                  pools of at most 2048 slots, the available slots in a total order (bin, the
//                  page they hold, slot index), so that which pages are served and which are
//                  evicted does not depend on the order of the atomics, which differs between
//                  drivers (measured: lavapipe and llvmpipe evicted different pages under a full
//                  pool before this pass); longer lists keep the atomics' order for what lies
//                  beyond 2048;
//  CSScatter       each available slot takes its rank's missing page (ranks from CSOrder, or
//                  from the bins' cursors for larger pools): the page it held loses its table
//                  entry, the new page gains one (both as change records), and the page is
//                  listed for rendering;
//  CSDefer         missing pages left over because of batchPages (not for want of slots) lose
//                  their request bit, so the next iteration's analysis asks for them again;
//  then asm/gpu-publish.hlsl writes the change records into the page tables, level by level.
// Counts and counters live in State (word offsets below); the CPU reads them only when the lab
// asks (AsmFrameCounters), never on the frame's path.
//! cs_5_0 CSPrepare
//! cs_5_0 CSTouch
//! cs_5_0 CSAgeHistogram
//! cs_5_0 CSAssign
//! cs_5_0 CSOrder
//! cs_5_0 CSScatter
//! cs_5_0 CSDefer

cbuffer AsmGpu : register(b0) {
  uint frameNumber;   // this frame's number, >= 1; kPinned never occurs
  uint slotCount;     // pool slots
  uint batchPages;    // pages rendered per iteration at most (the scratch array's slices)
  uint drawCount;     // scene draw items (per-draw indirect arguments)
  uint orderedSlots;  // 1: slotCount <= kOrderMax, CSOrder ranks the slots
  uint gpuMaxLevel;
  uint requestCapacity;
  uint pad0;
  uint2 analyzeGroups;  // CSAnalyze's dispatch (8x8 threads per group over the view)
  uint viewArgs;        // word offset of the view pass's draw arguments in Args
  uint pad2;
};

// State words.
static const uint kRequestCount = 0;  // written by CopyStructureCount
static const uint kMissing = 1;
static const uint kServed = 2;
static const uint kChanges = 3;
static const uint kAvailable = 4;
static const uint kCountRequests = 5;  // frame counters: requests, pages rendered, evicted,
static const uint kCountRendered = 6;  // unserved (cleared by the CPU each frame) ...
static const uint kCountEvicted = 7;
static const uint kCountUnserved = 8;
static const uint kCountIterations = 9;  // iterations that ran (iteration 0 always does)
static const uint kContinue = 10;        // 1: the current iteration runs (set by the previous)
static const uint kResident = 11;        // pages resident (kept across frames)

// Args words (dispatch and draw arguments).
static const uint kTouchArgs = 0;
static const uint kDeferArgs = 3;
static const uint kPublishArgs = 6;
static const uint kCopyArgs = 9;     // DrawInstanced: 6 vertices, one instance per new page
static const uint kAnalyzeArgs = 13; // the next iteration's CSAnalyze dispatch
static const uint kClearArgs = 16;   // DrawInstanced: 3 vertices, one instance per new page
static const uint kDrawArgs = 20;    // DrawIndexedInstanced per scene draw item, 5 words each,
                                     // then (at viewArgs) the same for the next view pass

static const uint kEmpty = 0xffffffffu;      // a slot's key: no page
static const uint kPinned = 0xffffffffu;     // a slot's last use: pinned, never evicted
static const uint kNotResident = 0xffffffffu;

RWByteAddressBuffer State : register(u0);
RWByteAddressBuffer Args : register(u1);
RWByteAddressBuffer Slots : register(u2);    // per slot: key, last frame used
RWByteAddressBuffer Bins : register(u3);     // 256 counts (cursors after CSAssign), 256 first ranks,
                                             // then kOrderMax slots in rank order (CSOrder)
RWByteAddressBuffer Missing : register(u4);  // request keys of pages not resident
RWByteAddressBuffer Changes : register(u5);  // (key, table value) records
RWByteAddressBuffer NewPages : register(u6); // (key, slot) per page to render
RWByteAddressBuffer Requested : register(u7);// the analysis' per-frame request bitmap

StructuredBuffer<uint> Requests : register(t0);
Texture2D<uint> Table : register(t1);
ByteAddressBuffer DrawTemplate : register(t2);  // per draw item: the 5 argument words

uint KeyLevel(uint k) { return k >> 28; }
uint2 KeyPage(uint k) { return uint2(k & 0x3fffu, (k >> 14) & 0x3fffu); }

[numthreads(256, 1, 1)] void CSPrepare(uint t : SV_GroupIndex) {
  Bins.Store(t * 4, 0);
  if (t != 0) return;
  uint count = min(State.Load(kRequestCount * 4), requestCapacity);
  State.Store(kMissing * 4, 0);
  State.Store(kChanges * 4, 0);
  State.Store(kServed * 4, 0);
  uint old;
  State.InterlockedAdd(kCountRequests * 4, count, old);
  State.InterlockedAdd(kCountIterations * 4, State.Load(kContinue * 4), old);
  Args.Store3(kTouchArgs * 4, uint3((count + 63) / 64, 1, 1));
}

[numthreads(64, 1, 1)] void CSTouch(uint i : SV_DispatchThreadID) {
  if (i >= min(State.Load(kRequestCount * 4), requestCapacity)) return;
  uint key = Requests[i];
  uint2 p = KeyPage(key);
  uint slot = Table.Load(int3(p, int(gpuMaxLevel - KeyLevel(key))));
  if (slot != kNotResident) {
    if (Slots.Load(slot * 8 + 4) != kPinned) Slots.Store(slot * 8 + 4, frameNumber);
    return;
  }
  uint at;
  State.InterlockedAdd(kMissing * 4, 1, at);
  Missing.Store(at * 4, key);
}

// The bin of a slot that may take a page, or -1. Must be the same in both passes.
int SlotBin(uint slot) {
  uint2 s = Slots.Load2(slot * 8);
  if (s.y == kPinned || s.y == frameNumber) return -1;
  if (s.x == kEmpty) return 0;
  return int(255u - min(frameNumber - s.y, 254u));
}

[numthreads(64, 1, 1)] void CSAgeHistogram(uint s : SV_DispatchThreadID) {
  if (s >= slotCount) return;
  int bin = SlotBin(s);
  if (bin < 0) return;
  uint old;
  Bins.InterlockedAdd(uint(bin) * 4, 1, old);
}

groupshared uint gScan[256];

[numthreads(256, 1, 1)] void CSAssign(uint t : SV_GroupIndex) {
  uint own = Bins.Load(t * 4);
  gScan[t] = own;
  GroupMemoryBarrierWithGroupSync();
  [unroll] for (uint d = 1; d < 256; d <<= 1) {
    uint add = t >= d ? gScan[t - d] : 0;
    GroupMemoryBarrierWithGroupSync();
    gScan[t] += add;
    GroupMemoryBarrierWithGroupSync();
  }
  Bins.Store((256 + t) * 4, gScan[t] - own);  // first rank of the bin
  Bins.Store(t * 4, 0);                       // CSScatter's cursor
  uint available = gScan[255];
  uint missing = State.Load(kMissing * 4);
  uint take = min(missing, available);
  uint served = min(take, batchPages);
  uint next = take > 0 ? 1 : 0;
  for (uint d = t; d < drawCount; d += 256) {
    uint4 a = DrawTemplate.Load4(d * 20);
    Args.Store4((kDrawArgs + d * 5) * 4, uint4(a.x, served, a.z, a.w));
    Args.Store((kDrawArgs + d * 5 + 4) * 4, 0);
    Args.Store4((viewArgs + d * 5) * 4, uint4(a.x, next, a.z, a.w));
    Args.Store((viewArgs + d * 5 + 4) * 4, 0);
  }
  if (t != 0) return;
  State.Store(kServed * 4, served);
  State.Store(kAvailable * 4, available);
  State.Store(kContinue * 4, next);
  Args.Store3(kAnalyzeArgs * 4, next ? uint3(analyzeGroups, 1) : uint3(0, 1, 1));
  uint old;
  State.InterlockedAdd(kCountRendered * 4, served, old);
  State.InterlockedAdd(kCountUnserved * 4, missing - take, old);
  Args.Store3(kDeferArgs * 4, uint3((missing + 63) / 64, 1, 1));
  Args.Store3(kPublishArgs * 4, uint3((2 * served + 63) / 64, 1, 1));
  Args.Store4(kCopyArgs * 4, uint4(6, served, 0, 0));
  Args.Store4(kClearArgs * 4, uint4(3, served, 0, 0));
}

static const uint kOrderMax = 2048;
groupshared uint2 gKey[kOrderMax];
groupshared uint gItem[kOrderMax];

bool Before(uint a, uint b) {
  return gKey[a].x != gKey[b].x ? gKey[a].x < gKey[b].x : gKey[a].y != gKey[b].y ? gKey[a].y < gKey[b].y : gItem[a] < gItem[b];
}

// Bitonic sort of the first n entries of gKey/gItem (n a power of two <= kOrderMax, the same in
// every thread: the barriers stay in uniform control flow), ascending.
void SortShared(uint t, uint n) {
  for (uint k = 2; k <= n; k <<= 1)
    for (uint j = k >> 1; j > 0; j >>= 1) {
      [unroll] for (uint h = 0; h < 2; ++h) {
        uint i = t + h * (kOrderMax / 2), l = i ^ j;
        if (i < n && l > i && (((i & k) == 0) == Before(l, i))) {
          uint2 kk = gKey[i];
          gKey[i] = gKey[l];
          gKey[l] = kk;
          uint it = gItem[i];
          gItem[i] = gItem[l];
          gItem[l] = it;
        }
      }
      GroupMemoryBarrierWithGroupSync();
    }
}

uint PowerOfTwoAtLeast(uint v) { return v <= 1 ? 1 : 1u << (firstbithigh(v - 1) + 1); }

// Order matters only under pressure: the missing list when not all of it is served now, the
// slots when a page is evicted (free slots are alike: which one a page gets changes only where
// it lives, and evictions are ranked by the page a slot holds, not by the slot). Otherwise this
// pass sorts nothing (sorting every iteration cost 20 ms per iteration on lavapipe).

[numthreads(1024, 1, 1)] void CSOrder(uint t : SV_GroupIndex) {
  uint missing = min(State.Load(kMissing * 4), kOrderMax);
  uint served = State.Load(kServed * 4);
  if (missing > served) {
    uint n = PowerOfTwoAtLeast(missing);
    [unroll] for (uint h = 0; h < 2; ++h) {
      uint i = t + h * (kOrderMax / 2);
      gKey[i] = i < missing ? uint2(Missing.Load(i * 4), 0) : uint2(kEmpty, kEmpty);
      gItem[i] = i;
    }
    GroupMemoryBarrierWithGroupSync();
    SortShared(t, n);
    [unroll] for (uint h2 = 0; h2 < 2; ++h2) {
      uint i = t + h2 * (kOrderMax / 2);
      if (i < missing) Missing.Store(i * 4, gKey[i].x);
    }
    GroupMemoryBarrierWithGroupSync();
  }
  if (orderedSlots == 0) return;
  // Bin 0 holds the free slots: bin 1's first rank is their count.
  bool evicts = served > Bins.Load((256 + 1) * 4);
  [unroll] for (uint h3 = 0; h3 < 2; ++h3) {
    uint i = t + h3 * (kOrderMax / 2);
    int bin = i < slotCount ? SlotBin(i) : -1;
    gKey[i] = bin >= 0 ? uint2(uint(bin), evicts ? Slots.Load(i * 8) : 0) : uint2(kEmpty, kEmpty);
    gItem[i] = i;
  }
  GroupMemoryBarrierWithGroupSync();
  if (evicts) SortShared(t, PowerOfTwoAtLeast(slotCount));
  else if (t == 0) {
    // No eviction: the free slots in index order, found by one thread (at most kOrderMax).
    uint r = 0;
    for (uint i = 0; i < slotCount && r < served; ++i)
      if (gKey[i].x == 0) gItem[r++] = i;
  }
  GroupMemoryBarrierWithGroupSync();
  [unroll] for (uint h4 = 0; h4 < 2; ++h4) {
    uint i = t + h4 * (kOrderMax / 2);
    if (i < served) Bins.Store((512 + i) * 4, gItem[i]);
  }
}

// orderedSlots: thread r takes the slot CSOrder ranked r; otherwise thread s is slot s and takes
// the next rank of its bin.
[numthreads(64, 1, 1)] void CSScatter(uint id : SV_DispatchThreadID) {
  uint s, rank;
  if (orderedSlots != 0) {
    rank = id;
    if (rank >= State.Load(kServed * 4)) return;
    s = Bins.Load((512 + rank) * 4);
  } else {
    s = id;
    if (s >= slotCount) return;
    int bin = SlotBin(s);
    if (bin < 0) return;
    Bins.InterlockedAdd(uint(bin) * 4, 1, rank);
    rank += Bins.Load((256 + uint(bin)) * 4);
    if (rank >= State.Load(kServed * 4)) return;
  }
  uint key = Missing.Load(rank * 4);
  uint old = Slots.Load(s * 8), at, unused;
  if (old != kEmpty) {
    State.InterlockedAdd(kChanges * 4, 1, at);
    Changes.Store2(at * 8, uint2(old, kNotResident));
    State.InterlockedAdd(kCountEvicted * 4, 1, unused);
  } else {
    State.InterlockedAdd(kResident * 4, 1, unused);
  }
  Slots.Store2(s * 8, uint2(key, frameNumber));
  State.InterlockedAdd(kChanges * 4, 1, at);
  Changes.Store2(at * 8, uint2(key, s));
  NewPages.Store2(rank * 8, uint2(key, s));
}

[numthreads(64, 1, 1)] void CSDefer(uint i : SV_DispatchThreadID) {
  uint missing = State.Load(kMissing * 4);
  if (i >= missing || i < State.Load(kServed * 4) || i >= State.Load(kAvailable * 4)) return;
  uint key = Missing.Load(i * 4);
  uint level = KeyLevel(key), n = 1u << level;
  uint2 p = KeyPage(key);
  uint bit = ((1u << (2u * level)) - 1u) / 3u + p.y * n + p.x, old;
  Requested.InterlockedAnd((bit >> 5) * 4, ~(1u << (bit & 31u)), old);
}
