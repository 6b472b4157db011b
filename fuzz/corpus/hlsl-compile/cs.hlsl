// cs_5_0
RWStructuredBuffer<uint> counts : register(u0);
Texture2D<float> depth : register(t0);
groupshared uint bins[64];
[numthreads(8, 8, 1)] void main(uint3 id : SV_DispatchThreadID, uint gi : SV_GroupIndex) {
  bins[gi] = 0;
  GroupMemoryBarrierWithGroupSync();
  InterlockedAdd(bins[uint(depth[id.xy] * 63)], 1);
  GroupMemoryBarrierWithGroupSync();
  InterlockedAdd(counts[gi], bins[gi]);
}
