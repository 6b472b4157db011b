// Lighting side of adaptive shadow maps (techniques/asm): a light-space coordinate is looked up
// by walking the mip hierarchy of page tables (AsmPageTable, mip m = level maxLevel - m, one
// texel per virtual page: the physical page index in the pool, or kAsmNotResident) from the
// finest level down to the first resident page; the shadow term is a 2x2 bilinear comparison
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
  float2 inPage;   // texel position inside the page, [0, pageSize]
};

// The finest resident page covering uv. Level 0 is always resident, so the walk ends there.
AsmPage AsmFindPage(float2 uv) {
  AsmPage r;
  r.level = 0;
  r.physical = 0;
  r.inPage = float2(0, 0);
  uint maxLevel = uint(asmMaxLevel);
  [loop] for (int l = int(maxLevel); l >= 0; --l) {
    uint n = 1u << uint(l);
    float2 v = saturate(uv) * float(n);
    uint2 p = min(uint2(v), uint2(n - 1, n - 1));
    uint e = AsmPageTable.Load(int3(p, int(maxLevel) - l));
    if (e != kAsmNotResident) {
      r.level = uint(l);
      r.physical = e;
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
// whose centre is uv (LESS_EQUAL, as MakeShadowComparisonSampler).
float AsmTexelLit(float2 uv, float z) {
  if (any(uv < 0.0) || any(uv > 1.0)) return 1.0;  // outside the map: lit, as the BORDER sampler
  return z <= AsmPool.Load(int3(AsmPoolTexel(AsmFindPage(uv)), 0)) ? 1.0 : 0.0;
}

// The 2x2 bilinear comparison filter at the resolution of the finest resident page at c.xy.
float AsmVisibility(float3 c) {
  AsmPage pg = AsmFindPage(c.xy);
  float res = asmPageSize * float(1u << pg.level);  // texels per side at that level
  float2 t = c.xy * res - 0.5;
  float2 f = frac(t);
  float2 t0 = (floor(t) + 0.5) / res;
  float d = 1.0 / res;
  float a = lerp(AsmTexelLit(t0, c.z), AsmTexelLit(t0 + float2(d, 0), c.z), f.x);
  float b = lerp(AsmTexelLit(t0 + float2(0, d), c.z), AsmTexelLit(t0 + float2(d, d), c.z), f.x);
  return lerp(a, b, f.y);
}

float ShadowVisibility(float3 worldPos, float3 worldNormal, float4 svPosition) {
  float3 c = AsmShadowCoord(worldPos);
  if (AsmOutsideMap(c)) return 1.0;
  return AsmVisibility(c);
}

// The lab's view: one layer, the pool. ShadowTexel gives the texel at the resolution of the
// level the walk finds (what a pool page holds), so texels per pixel are the pool's.
float2 ShadowTexel(float3 worldPos, float layer) {
  float2 uv = AsmShadowCoord(worldPos).xy;
  AsmPage pg = AsmFindPage(uv);
  return uv * asmPageSize * float(1u << pg.level);
}

ShadowLookup ShadowLocate(float3 worldPos, float3 worldNormal) {
  float3 c = AsmShadowCoord(worldPos);
  if (AsmOutsideMap(c)) return MakeShadowLookup(kShadowNoLayer, float2(0, 0));
  return MakeShadowLookup(0.0, float2(AsmPoolTexel(AsmFindPage(c.xy))) + 0.5);
}
