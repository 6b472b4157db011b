// Adaptive shadow maps, allocation=gpu: writes one level's change records (key, table value),
// made by asm/gpu-allocation.hlsl's CSScatter, into that level of the page tables (a UAV of one
// mip of the R32_UINT table texture). Dispatched once per refinable level with indirect
// arguments sized by CSAssign.
//! cs_5_0 CSPublish

cbuffer AsmPublish : register(b0) {
  uint publishLevel;
  uint3 pad;
};

ByteAddressBuffer State : register(t0);    // word 3: change records
ByteAddressBuffer Changes : register(t1);
RWTexture2D<uint> TableLevel : register(u0);

[numthreads(64, 1, 1)] void CSPublish(uint i : SV_DispatchThreadID) {
  if (i >= State.Load(3 * 4)) return;
  uint2 c = Changes.Load2(i * 8);
  if ((c.x >> 28) == publishLevel) TableLevel[uint2(c.x & 0x3fffu, (c.x >> 14) & 0x3fffu)] = c.y;
}
