// Lighting side of adaptive shadow maps (techniques/asm): a light-space coordinate is looked up
// by walking the mip hierarchy of page tables (AsmPageTable, mip m = level maxLevel - m, one
// texel per virtual page: the physical page index in the pool, or kAsmNotResident) from the
// level the pixel's footprint needs (the level the analysis requests for it, from the screen
// derivatives of the map coordinates) down to the first resident page. Starting at the finest
// level instead cost up to maxLevel + 1 dependent loads per texel wherever the view needs a
// coarse level: the lit pass at 131072 effective texels cost 3-4x basic's. The shadow term is a 2x2 bilinear comparison
// filter (the hardware filter's weights, LESS_EQUAL) at that page's resolution, done by hand:
// each of the four texels is looked up through the page tables itself, so a footprint that
// crosses a page edge reads the neighbouring virtual page (wherever the pool holds it, at its
// own finest resident level) instead of an unrelated pool neighbour. Pages need no border.
// Clamping the hardware filter's footprint into the page was the first version: it turned every
// shadow edge lying on a page border into a hard step (found by asm-technique-test's edge test,
// whose edge lies on a page border of every level from 3 on).
#include "common/shadow-lookup.hlsli"

cbuffer AsmShadow : register(b2) {
  float4x4 asmLightViewProj;  // the light's view of the scene bounds: level 0's page
  float asmPageSize;          // texels per page side
  float asmMaxLevel;          // finest level (2^maxLevel pages per side)
  float asmPoolPages;         // pages per pool side
  float asmPoolSize;          // texels per pool side
  float asmFinestPinned;      // resident_levels - 1: always resident, so a walk never starts coarser
  float asmClipPages;         // clipmap: pages per side of each level's window around the camera (0: off)
  float2 asmCameraUV;         // the camera's position in map coordinates (the windows' centre)
};

Texture2D<float> AsmPool : register(t0);
Texture2D<uint> AsmPageTable : register(t1);

static const uint kAsmNotResident = 0xffffffffu;

// Map coordinates: uv in [0, 1] over level 0 (v = 0 the top row, as D3D) and light depth.
float3 AsmShadowCoord(float3 worldPos) {
  float4 p = mul(asmLightViewProj, float4(worldPos, 1.0));
  p.xyz /= p.w;
  return float3(p.xy * float2(0.5, -0.5) + 0.5, p.z);
}

bool AsmOutsideMap(float3 c) { return any(c.xy < 0.0) || any(c.xy > 1.0) || c.z > 1.0; }

struct AsmPage {
  uint level;
  uint physical;   // pool page index
  uint2 page;      // virtual page at that level
  float2 inPage;   // texel position inside the page, [0, pageSize]
};

// The level a pixel needs: one map texel per pixel at most along its footprint's longer axis
// (level L has 2^L times level 0's texels). The analysis requests pages at this level. Must be
// called in uniform control flow (derivatives).
uint AsmNeededLevel(float2 uv) {
  float2 dx = ddx(uv), dy = ddy(uv);
  float footprint = max(length(dx), length(dy)) * asmPageSize;  // level-0 texels per pixel
  float need = footprint > 0.0 ? ceil(log2(1.0 / footprint)) : asmMaxLevel;
  return uint(clamp(need, 0.0, asmMaxLevel));
}

// clipmap=W: the finest level at or below `level` whose window (the W x W pages around the
// camera's page at that level) holds uv. Level L's window spans W / 2^L of the map, so each level
// is refined only near the camera, as the levels of a clipmap; coarser levels cover the rest.
uint AsmClipLevel(float2 uv, uint level) {
  if (asmClipPages <= 0.0) return level;
  [loop] while (level > 0) {
    float n = float(1u << level);
    float2 d = floor(saturate(uv) * n) - floor(saturate(asmCameraUV) * n);
    if (all(d >= -0.5 * asmClipPages) && all(d < 0.5 * asmClipPages)) break;
    --level;
  }
  return level;
}

// The finest resident page covering uv at level `start` or coarser. Level 0 is always resident,
// so the walk ends there.
AsmPage AsmFindPage(float2 uv, uint start) {
  AsmPage r;
  r.level = 0;
  r.physical = 0;
  r.page = uint2(0, 0);
  r.inPage = float2(0, 0);
  uint maxLevel = uint(asmMaxLevel);
  [loop] for (int l = int(min(start, maxLevel)); l >= 0; --l) {
    uint n = 1u << uint(l);
    float2 v = saturate(uv) * float(n);
    uint2 p = min(uint2(v), uint2(n - 1, n - 1));
    uint e = AsmPageTable.Load(int3(p, int(maxLevel) - l));
    if (e != kAsmNotResident) {
      r.level = uint(l);
      r.physical = e;
      r.page = p;
      r.inPage = (v - float2(p)) * asmPageSize;
      break;
    }
  }
  return r;
}

// The pool texel holding a page position.
int2 AsmPoolTexel(AsmPage pg) {
  uint pages = uint(asmPoolPages);
  float2 origin = float2(pg.physical % pages, pg.physical / pages) * asmPageSize;
  return int2(origin + min(floor(pg.inPage), asmPageSize - 1.0));
}

// 1 where the receiver depth z is at or in front of the depth stored for the virtual texel
// whose centre is uv (LESS_EQUAL, as MakeShadowComparisonSampler). `home` is the page found for
// the pixel: a texel inside it needs no walk when no finer page can exist (home is at `start`).
float AsmTexelLit(float2 uv, float z, AsmPage home, uint start) {
  if (any(uv < 0.0) || any(uv > 1.0)) return 1.0;  // outside the map: lit, as the BORDER sampler
  AsmPage pg = home;
  float2 v = uv * float(1u << home.level);
  if (home.level == start && all(uint2(v) == home.page))
    pg.inPage = (v - float2(home.page)) * asmPageSize;
  else
    pg = AsmFindPage(uv, start);
  return z <= AsmPool.Load(int3(AsmPoolTexel(pg), 0)) ? 1.0 : 0.0;
}

// The 2x2 bilinear comparison filter at the resolution of the finest resident page at c.xy from
// level `start` down.
float AsmVisibility(float3 c, uint start) {
  AsmPage pg = AsmFindPage(c.xy, start);
  float res = asmPageSize * float(1u << pg.level);  // texels per side at that level
  float2 t = c.xy * res - 0.5;
  float2 f = frac(t);
  float2 t0 = (floor(t) + 0.5) / res;
  float d = 1.0 / res;
  float a = lerp(AsmTexelLit(t0, c.z, pg, start), AsmTexelLit(t0 + float2(d, 0), c.z, pg, start), f.x);
  float b = lerp(AsmTexelLit(t0 + float2(0, d), c.z, pg, start), AsmTexelLit(t0 + float2(d, d), c.z, pg, start), f.x);
  return lerp(a, b, f.y);
}

// Where the pixel's walk starts: its needed level, or the finest pinned level where that is finer
// (it is always resident: a coarser start would only lose resolution). Kept for the lab's
// ShadowTexel and ShadowLocate, which the lit pass calls after ShadowVisibility, some in
// non-uniform control flow (no derivatives there).
static uint gAsmStartLevel = 0;

float ShadowVisibility(float3 worldPos, float3 worldNormal, float4 svPosition) {
  float3 c = AsmShadowCoord(worldPos);
  gAsmStartLevel = max(AsmClipLevel(c.xy, AsmNeededLevel(c.xy)), uint(asmFinestPinned));
  if (AsmOutsideMap(c)) return 1.0;
  return AsmVisibility(c, gAsmStartLevel);
}

// The lab's view: one layer, the pool. ShadowTexel gives the texel at the resolution of the
// level the walk finds (what a pool page holds), so texels per pixel are the pool's.
float2 ShadowTexel(float3 worldPos, float layer) {
  float2 uv = AsmShadowCoord(worldPos).xy;
  AsmPage pg = AsmFindPage(uv, gAsmStartLevel);
  return uv * asmPageSize * float(1u << pg.level);
}

ShadowLookup ShadowLocate(float3 worldPos, float3 worldNormal) {
  float3 c = AsmShadowCoord(worldPos);
  if (AsmOutsideMap(c)) return MakeShadowLookup(kShadowNoLayer, float2(0, 0));
  return MakeShadowLookup(0.0, float2(AsmPoolTexel(AsmFindPage(c.xy, gAsmStartLevel))) + 0.5);
}
