// Adaptive shadow maps, compaction=prefix: the paper's stream compaction of the analysis'
// requests (four slots per pixel, 0xffffffff where none; asm/analysis.hlsl with
// ASM_PREFIX_COMPACTION) into a dense request stream by a prefix sum, instead of the append
// buffer's atomic counter. Order-preserving: the stream lists pixels in order. Three passes:
//  CSCountBlocks   each group of 256 threads counts the requests of its block of 1024 slots;
//  CSScanBlocks    one group: an exclusive prefix sum over the block counts (1024 at a time, with
//                  a carry), and the total (the stream's length);
//  CSScatter       each block again: its requests' ranks within the block (a group prefix sum)
//                  plus the block's offset give their place in the stream.
// The paper's version was O(n log n) in passes over the whole stream (no scatter on its GPUs);
// this one reads the slots twice.
//! cs_5_0 CSCountBlocks
//! cs_5_0 CSScanBlocks
//! cs_5_0 CSScatter

cbuffer AsmCompaction : register(b0) {
  uint slotCount;   // 4 per pixel
  uint blockCount;  // ceil(slotCount / 1024)
  uint2 pad;
};

static const uint kNoRequest = 0xffffffffu;
static const uint kBlock = 1024;

StructuredBuffer<uint> PixelRequests : register(t0);
RWByteAddressBuffer BlockSums : register(u0);         // per block: count, then its offset
RWStructuredBuffer<uint> Requests : register(u1);     // the stream
RWByteAddressBuffer Count : register(u2);             // word 0: the stream's length

groupshared uint gSum[kBlock];

// Exclusive prefix sum of gSum[0..1023] (each thread owns 4 entries), returning the total.
uint ScanShared(uint t) {
  // Up-sweep and down-sweep (Blelloch) over 1024 entries with 256 threads.
  uint offset = 1;
  for (uint d = kBlock >> 1; d > 0; d >>= 1) {
    GroupMemoryBarrierWithGroupSync();
    for (uint k = t; k < d; k += 256) {
      uint a = offset * (2 * k + 1) - 1, b = offset * (2 * k + 2) - 1;
      gSum[b] += gSum[a];
    }
    offset <<= 1;
  }
  GroupMemoryBarrierWithGroupSync();
  uint total = gSum[kBlock - 1];
  GroupMemoryBarrierWithGroupSync();
  if (t == 0) gSum[kBlock - 1] = 0;
  for (uint d2 = 1; d2 < kBlock; d2 <<= 1) {
    offset >>= 1;
    GroupMemoryBarrierWithGroupSync();
    for (uint k = t; k < d2; k += 256) {
      uint a = offset * (2 * k + 1) - 1, b = offset * (2 * k + 2) - 1;
      uint v = gSum[a];
      gSum[a] = gSum[b];
      gSum[b] += v;
    }
  }
  GroupMemoryBarrierWithGroupSync();
  return total;
}

bool Valid(uint i) { return i < slotCount && PixelRequests[i] != kNoRequest; }

[numthreads(256, 1, 1)] void CSCountBlocks(uint t : SV_GroupIndex, uint3 g : SV_GroupID) {
  uint base = g.x * kBlock;
  uint n = 0;
  [unroll] for (uint k = 0; k < 4; ++k) n += Valid(base + t * 4 + k) ? 1 : 0;
  gSum[t] = n;
  GroupMemoryBarrierWithGroupSync();
  for (uint s = 128; s > 0; s >>= 1) {
    if (t < s) gSum[t] += gSum[t + s];
    GroupMemoryBarrierWithGroupSync();
  }
  if (t == 0) BlockSums.Store(g.x * 8, gSum[0]);
}

[numthreads(256, 1, 1)] void CSScanBlocks(uint t : SV_GroupIndex) {
  uint carry = 0;
  for (uint start = 0; start < blockCount; start += kBlock) {
    [unroll] for (uint k = 0; k < 4; ++k) {
      uint b = start + t * 4 + k;
      gSum[t * 4 + k] = b < blockCount ? BlockSums.Load(b * 8) : 0;
    }
    uint total = ScanShared(t);
    [unroll] for (uint k2 = 0; k2 < 4; ++k2) {
      uint b = start + t * 4 + k2;
      if (b < blockCount) BlockSums.Store(b * 8 + 4, carry + gSum[t * 4 + k2]);
    }
    carry += total;
    GroupMemoryBarrierWithGroupSync();
  }
  if (t == 0) Count.Store(0, carry);
}

[numthreads(256, 1, 1)] void CSScatter(uint t : SV_GroupIndex, uint3 g : SV_GroupID) {
  uint base = g.x * kBlock;
  [unroll] for (uint k = 0; k < 4; ++k) gSum[t * 4 + k] = Valid(base + t * 4 + k) ? 1 : 0;
  ScanShared(t);
  uint offset = BlockSums.Load(g.x * 8 + 4);
  [unroll] for (uint k2 = 0; k2 < 4; ++k2) {
    uint i = base + t * 4 + k2;
    if (Valid(i)) Requests[offset + gSum[t * 4 + k2]] = PixelRequests[i];
  }
}
