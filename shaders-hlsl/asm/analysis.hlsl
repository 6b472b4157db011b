// Adaptive shadow maps: the refinement's analysis (techniques/asm/asm-technique.cpp).
//  VSView/PSView   the camera's view of the scene, writing per pixel the light-space uv, the
//                  shadow term of the current pages (asm/shadow.hlsli) and the page-table level
//                  the pixel needs (one map texel per pixel at most);
//  CSAnalyze       a Sobel edge detector on that shadow term: each boundary pixel requests the
//                  page (level, x, y) it needs (mark=visible: every pixel requests its pages);
//                  a per-frame bitmap (InterlockedOr) lets each page be appended once to the
//                  request stream (AppendStructuredBuffer);
//  VSClearPage     a triangle covering the viewport at depth 1, drawn with depth test ALWAYS to
//                  reset one page of the pool before its depth is rendered (the viewport and
//                  scissor are the page's rectangle; D3D11 clears only whole views).
//! vs_5_0 VSView
//! ps_5_0 PSView
//! cs_5_0 CSAnalyze
//! vs_5_0 VSClearPage
#include "common/frame.hlsli"
#include "asm/shadow.hlsli"

struct ViewOut {
  float4 pos : SV_Position;
  float3 worldPos : WORLDPOS;
};

ViewOut VSView(float3 pos : POSITION) {
  ViewOut o;
  float4 wp = mul(world, float4(pos, 1.0));
  o.worldPos = wp.xyz;
  o.pos = mul(viewProj, wp);
  return o;
}

float4 PSView(ViewOut i) : SV_Target {
  float3 c = AsmShadowCoord(i.worldPos);
  uint level = AsmClipLevel(c.xy, AsmNeededLevel(c.xy));
  if (AsmOutsideMap(c)) return float4(-1, -1, 1, -1);
  // The shadow term as the lit pass computes it (ShadowVisibility's start level).
  return float4(c.xy, AsmVisibility(c, max(level, uint(asmFinestPinned))), float(level));
}

cbuffer AsmAnalysis : register(b0) {
  uint2 analysisSize;
  uint analysisMaxLevel;
  float edgeThreshold;
  uint markVisible;        // 1: every visible pixel requests (mark=visible), 0: Sobel boundaries
  float analysisPageSize;
  uint2 analysisPad;
};

Texture2D<float4> View : register(t0);
RWByteAddressBuffer Requested : register(u0);
#if ASM_PREFIX_COMPACTION
// compaction=prefix: four request slots per pixel (kNoRequest where none), packed into the request
// stream afterwards by asm/compaction.hlsl's prefix sum, the paper's stream compaction.
RWStructuredBuffer<uint> PixelRequests : register(u1);
static const uint kNoRequest = 0xffffffffu;
static uint gSlot = 0;
#else
AppendStructuredBuffer<uint> Requests : register(u1);
#endif

// Requests the page of `level` holding uv unless this frame asked for it already (the per-frame
// bitmap: levels 0..level-1 hold (4^level - 1) / 3 pages before it).
void RequestPage(uint pixel, float2 uv, uint level) {
  uint n = 1u << level;
  uint2 p = min(uint2(saturate(uv) * float(n)), uint2(n - 1, n - 1));
  uint bit = ((1u << (2u * level)) - 1u) / 3u + p.y * n + p.x;
  uint mask = 1u << (bit & 31u), before;
  Requested.InterlockedOr((bit >> 5) * 4, mask, before);
  if ((before & mask) != 0) return;
#if ASM_PREFIX_COMPACTION
  PixelRequests[pixel * 4 + gSlot++] = (level << 28) | (p.y << 14) | p.x;
#else
  Requests.Append((level << 28) | (p.y << 14) | p.x);
#endif
}

[numthreads(8, 8, 1)] void CSAnalyze(uint3 id : SV_DispatchThreadID) {
  if (any(id.xy >= analysisSize)) return;
  uint pixel = id.y * analysisSize.x + id.x;
#if ASM_PREFIX_COMPACTION
  [unroll] for (uint k0 = 0; k0 < 4; ++k0) PixelRequests[pixel * 4 + k0] = kNoRequest;
#endif
  float4 c = View.Load(int3(id.xy, 0));
  if (c.w < 0.0) return;
  if (markVisible != 0) {
    // Every visible sample requests the page its lookup reads at the level it needs, and the
    // pages of the other texels of its 2x2 filter footprint (the margin), which lie across a page
    // edge for pixels near one.
    uint level = min(uint(c.w), analysisMaxLevel);
    float res = analysisPageSize * float(1u << level);
    float2 t0 = (floor(c.xy * res - 0.5) + 0.5) / res;
    [unroll] for (int k = 0; k < 4; ++k) {
      float2 t = t0 + float2(k & 1, k >> 1) / res;
      if (all(t >= 0.0) && all(t <= 1.0)) RequestPage(pixel, t, level);
    }
    return;
  }
  // Sobel on the shadow term; pixels without geometry count as this pixel's value.
  float s[3][3];
  [unroll] for (int y = 0; y < 3; ++y)
    [unroll] for (int x = 0; x < 3; ++x) {
      int2 q = clamp(int2(id.xy) + int2(x - 1, y - 1), int2(0, 0), int2(analysisSize) - 1);
      float4 n = View.Load(int3(q, 0));
      s[y][x] = n.w < 0.0 ? c.z : n.z;
    }
  float gx = (s[0][2] + 2.0 * s[1][2] + s[2][2]) - (s[0][0] + 2.0 * s[1][0] + s[2][0]);
  float gy = (s[2][0] + 2.0 * s[2][1] + s[2][2]) - (s[0][0] + 2.0 * s[0][1] + s[0][2]);
  if (sqrt(gx * gx + gy * gy) < edgeThreshold) return;
  RequestPage(pixel, c.xy, min(uint(c.w), analysisMaxLevel));
}

float4 VSClearPage(uint id : SV_VertexID) : SV_Position {
  float2 t = float2((id << 1) & 2, id & 2);
  return float4(t * 2.0 - 1.0, 1.0, 1.0);
}
