// Adaptive shadow maps, allocation=gpu: rendering the pages the GPU allocated, with indirect
// draws (instance i = the i-th new page of this iteration, NewPages[i] = (key, slot)).
//  VSClearSlice  a triangle over slice i at depth 1 (depth test ALWAYS): resets the slice;
//  VSPage  the scene's depth into slice i of a scratch depth array of page-sized slices: the
//          light's projection cropped to the page (as the readback mode's PageViewProj), so the
//          rasterizer's viewport and clipping are the page's own and the depth bias is the same;
//  VSCopy/PSCopy  a quad over the page's slot in the pool copying slice i (SV_Depth, depth test
//          ALWAYS): one pass writes every page of the iteration wherever its slot is, which a
//          viewport or scissor set by the CPU could not.
//! vs_5_0 VSClearSlice
//! vs_5_0 VSPage
//! vs_5_0 VSCopy
//! ps_5_0 PSCopy
#include "common/frame.hlsli"

cbuffer AsmShadow : register(b2) {  // as asm/shadow.hlsli
  float4x4 asmLightViewProj;
  float asmPageSize;
  float asmMaxLevel;
  float asmPoolPages;
  float asmPoolSize;
  float asmFinestPinned;
  float asmClipPages;
  float2 asmCameraUV;
};

ByteAddressBuffer NewPages : register(t2);
Texture2DArray<float> Scratch : register(t3);

struct PageOut {
  float4 pos : SV_Position;
  uint slice : SV_RenderTargetArrayIndex;
};

PageOut VSClearSlice(uint vertex : SV_VertexID, uint instance : SV_InstanceID) {
  float2 t = float2((vertex << 1) & 2, vertex & 2);
  PageOut o;
  o.pos = float4(t * 2.0 - 1.0, 1.0, 1.0);
  o.slice = instance;
  return o;
}

PageOut VSPage(float3 pos : POSITION, uint instance : SV_InstanceID) {
  uint key = NewPages.Load(instance * 8);
  float n = float(1u << (key >> 28));
  float2 page = float2(key & 0x3fffu, (key >> 14) & 0x3fffu);
  float4 c = mul(asmLightViewProj, mul(world, float4(pos, 1.0)));
  // The page spans NDC x in [2 px / n - 1, 2 (px + 1) / n - 1] and y in [1 - 2 (py + 1) / n,
  // 1 - 2 py / n]: scaled by n about its centre it becomes [-1, 1].
  float2 centre = float2((2.0 * page.x + 1.0) / n - 1.0, 1.0 - (2.0 * page.y + 1.0) / n);
  PageOut o;
  o.pos = float4((c.xy - centre * c.w) * n, c.z, c.w);
  o.slice = instance;
  return o;
}

struct CopyOut {
  float4 pos : SV_Position;
  nointerpolation float3 source : SOURCE;  // pool texel of the page's corner, scratch slice
};

CopyOut VSCopy(uint vertex : SV_VertexID, uint instance : SV_InstanceID) {
  uint slot = NewPages.Load(instance * 8 + 4);
  uint pages = uint(asmPoolPages);
  float2 origin = float2(slot % pages, slot / pages) * asmPageSize;
  // Two triangles over the page: corners (0,0) (1,0) (0,1) / (0,1) (1,0) (1,1).
  static const float2 corners[6] = {float2(0, 0), float2(1, 0), float2(0, 1), float2(0, 1), float2(1, 0), float2(1, 1)};
  float2 texel = origin + corners[vertex] * asmPageSize;
  CopyOut o;
  o.pos = float4(texel.x / asmPoolSize * 2.0 - 1.0, 1.0 - texel.y / asmPoolSize * 2.0, 0.0, 1.0);
  o.source = float3(origin, float(instance));
  return o;
}

float PSCopy(CopyOut i) : SV_Depth {
  int2 t = int2(i.pos.xy - i.source.xy);
  return Scratch.Load(int4(t, int(i.source.z), 0));
}
