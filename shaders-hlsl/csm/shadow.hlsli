// Lighting side of cascaded shadow maps (techniques/csm). Every cascade is an orthographic
// projection of one shared light view, so a point's light-view position is computed once and each
// cascade maps it to its region with a scale and an offset. The cascades live in a
// Texture2DArray: one slice each (storage=array) or regions of slice 0 (storage=atlas); csmRegion
// says where, so both storages take the same path.
//
// Defines: CSM_MOMENTS 1 selects moment filtering (techniques/moments; the MOMENT_* defines of
// moments/moments.hlsli come with it), else SHADOW_FILTER and SHADOW_KERNEL select the comparison
// filter of common/shadow-filter.hlsli (5: pcss, common/shadow-pcss.hlsli), and SHADOW_ACCEL its
// acceleration (common/hpsm.hlsli). Selection, blending and the bias mode are uniform branches on
// constants.
#include "common/frame.hlsli"
#include "common/shadow-lookup.hlsli"
// Also for the moment filters: NormalOffset.
#include "common/shadow-filter.hlsli"
#include "common/shadow-pcss.hlsli"

#ifndef CSM_MOMENTS
#define CSM_MOMENTS 0
#endif
#if CSM_MOMENTS
#include "moments/moments.hlsli"
#endif

#define CSM_MAX_CASCADES 8

cbuffer CsmShadow : register(b2) {
  float4x4 csmLightView;                      // world -> the light view all cascades share
  float4 csmToMapScale[CSM_MAX_CASCADES];     // xyz: light view -> (slice u, slice v, depth), per cascade; w: map-select margin in region uv
  float4 csmToMapOffset[CSM_MAX_CASCADES];
  float4 csmRegion[CSM_MAX_CASCADES];         // the cascade's region in slice uv: min.xy, size.zw
  float4 csmCascade[CSM_MAX_CASCADES];        // split near, split far (view depth), world texel size, array slice
  float4 csmCameraForward;                    // w: cascade count
  float4 csmSettings;                         // select (0 interval, 1 map), blend, bias (0 const, 1 slope, 2 normal, 3 receiver plane), normal offset (texels)
  float4 csmMapInfo;                          // 1 / texture size (xy), unused, region size in texels
#if SHADOW_FILTER == 5 && !CSM_MOMENTS
  // Declared for pcss only; csm and sdsm (whose fit.hlsl writes this cbuffer on the GPU) always
  // provide it. One row for all cascades: each derives its texel size and depth range below.
  float4 csmPcss;                             // 2 tan(light angle / 2), search taps, max kernel, unused
#endif
};

#if CSM_MOMENTS
// The moments of every cascade, mipmapped, with the map's trilinear/anisotropic sampler.
Texture2DArray<float4> CsmMoments : register(t0);
SamplerState CsmMomentSampler : register(s0);
#else
Texture2DArray<float> CsmMap : register(t0);
SamplerComparisonState CsmSampler : register(s0);
#if defined(SHADOW_ACCEL) && SHADOW_ACCEL != 0
#include "common/hpsm.hlsli"
// The secondary map of every slice (common/hpsm.hlsli); decisions counted for the lab at u7.
Texture2DArray<float4> CsmHpsm : register(t1);
#if HPSM_COUNTERS
RWByteAddressBuffer CsmHpsmCounters : register(u7);
#endif
#endif
#endif

static const int kCsmBiasNormal = 2;
static const int kCsmBiasReceiverPlane = 3;

int CsmCount() { return (int)csmCameraForward.w; }
bool CsmMapSelect() { return csmSettings.x > 0.5; }
int CsmBias() { return (int)(csmSettings.z + 0.5); }

float3 CsmLightView(float3 worldPos) { return mul(csmLightView, float4(worldPos, 1.0)).xyz; }

// Slice uv and depth of a light-view position in cascade c.
float3 CsmMapCoord(float3 lv, int c) { return lv * csmToMapScale[c].xyz + csmToMapOffset[c].xyz; }

// Position within the cascade's own region, [0, 1] across it.
float2 CsmLocalUv(float2 sliceUv, int c) { return (sliceUv - csmRegion[c].xy) / csmRegion[c].zw; }

// Map selection's margin for cascade c (region uv): its padding, which holds the filter's reach
// and, with moments, the blur's, a different number of texels per cascade.
float CsmMargin(int c) { return csmToMapScale[c].w; }

// Inside cascade c's map, `margin` (region uv) away from its border so the whole filter kernel
// reads this cascade, and within its depth range.
bool CsmInsideMap(float3 lv, int c, float margin) {
  float3 m = CsmMapCoord(lv, c);
  float2 l = CsmLocalUv(m.xy, c);
  return all(l >= margin) && all(l <= 1.0 - margin) && m.z >= 0.0 && m.z <= 1.0;
}

float CsmViewDepth(float3 worldPos) { return dot(worldPos - cameraPos, csmCameraForward.xyz); }

// The cascade a point reads, or -1 where none covers it (lit).
int CsmSelect(float3 worldPos, float3 lv) {
  int count = CsmCount();
  if (!CsmMapSelect()) {
    float d = CsmViewDepth(worldPos);
    for (int c = 0; c < count; ++c)
      if (d < csmCascade[c].y) return c;
    return -1;
  }
  for (int m = 0; m < count; ++m)
    if (CsmInsideMap(lv, m, CsmMargin(m))) return m;
  return -1;
}

// Weight of cascade c against c + 1: 1 outside the blend band, falling to 0 at c's end (interval
// selection: its far split; map selection: its usable border). 1 where c + 1 does not cover the
// point either.
float CsmBlendWeight(int c, float3 worldPos, float3 lv) {
  float blend = csmSettings.y;
  if (blend <= 0.0 || c + 1 >= CsmCount()) return 1.0;
  float toEnd;
  if (!CsmMapSelect()) {
    float4 k = csmCascade[c];
    toEnd = (k.y - CsmViewDepth(worldPos)) / (k.y - k.x);
  } else {
    float margin = CsmMargin(c);
    float2 l = CsmLocalUv(CsmMapCoord(lv, c).xy, c);
    float2 edge = min(l - margin, 1.0 - margin - l);
    toEnd = min(edge.x, edge.y) / (0.5 - margin);
  }
  if (toEnd >= blend || !CsmInsideMap(lv, c + 1, CsmMargin(c + 1))) return 1.0;
  return saturate(toEnd / blend);
}

// The lookup's light-view position: with bias=normal, moved along the normal by the cascade's
// texel size so the offset is constant in texels whatever the cascade.
float3 CsmLookupPosition(int c, float3 lv, float3 worldNormal) {
  if (CsmBias() != kCsmBiasNormal) return lv;
  float3 offset = NormalOffset(worldNormal, toLight, csmCascade[c].z, csmSettings.w);
  return lv + mul((float3x3)csmLightView, offset);
}

#if CSM_MOMENTS
// Moments are filtered like colour: one SampleGrad, trilinear or anisotropic. The gradients are
// the shared light-view derivatives scaled into this cascade, not the lookup's own: those jump
// where neighbouring pixels read different cascades (or blend two), and would pick the coarsest
// mip along every cascade border.
float CsmMomentVisibility(int c, float3 m, float3 lvDdx, float3 lvDdy) {
  float2 s = csmToMapScale[c].xy;
  // Onto the region's outermost texel centres, so a bilinear tap never reads a neighbouring
  // region. (Moment filters are limited to storage=array, where the region is the slice and the
  // clamp sampler does the same; lower mips would mix atlas regions anyway.)
  float2 halfTexel = 0.5 * csmMapInfo.xy;
  float2 lo = csmRegion[c].xy, hi = csmRegion[c].xy + csmRegion[c].zw;
  float2 uv = clamp(m.xy, lo + halfTexel, hi - halfTexel);
  float2 gx = lvDdx.xy * s, gy = lvDdy.xy * s;
  // Keep the footprint inside the region: trilinear filtering at a footprint of f texels reads up
  // to 2f texels from the centre (the coarser mip's bilinear pair). The padding holds the blur but
  // not a footprint of many texels, and past the region's edge the clamp repeats edge texels
  // whose depth does not continue the receiver's slope: the mean moves off the receiver and it
  // shadows itself. A smaller footprint there costs some aliasing at the region's rim only.
  float2 texels = 1.0 / csmMapInfo.xy;
  float2 room2 = min(uv - lo, hi - uv) * texels;
  float room = max(min(room2.x, room2.y), 0.5);
  float footprint = sqrt(max(dot(gx * texels, gx * texels), dot(gy * texels, gy * texels)));
  float shrink = min(1.0, room / max(2.0 * footprint, 1e-6));
  float4 moments = CsmMoments.SampleGrad(CsmMomentSampler, float3(uv, csmCascade[c].w), gx * shrink, gy * shrink);
  return MomentVisibility(moments, m.z);
}
#endif

float CsmFiltered(int c, float3 lv, float3 lvDdx, float3 lvDdy, float3 worldNormal, float2 pixel) {
  float3 m = CsmMapCoord(CsmLookupPosition(c, lv, worldNormal), c);
  if (m.z > 1.0) return 1.0;  // beyond the cascade's far plane: nothing there casts
#if CSM_MOMENTS
  return CsmMomentVisibility(c, m, lvDdx, lvDdy);
#else
  ShadowFilterInput fi;
  fi.uv = m.xy;
  fi.layer = csmCascade[c].w;
  fi.depth = m.z;
  fi.texelSize = csmMapInfo.xy;
  // The region's edges (texel boundaries); selection keeps the kernel inside, this keeps any
  // stray tap from reading a neighbouring atlas region.
  fi.uvClamp = float4(csmRegion[c].xy, csmRegion[c].xy + csmRegion[c].zw);
  fi.depthGradient = float2(0.0, 0.0);
  if (CsmBias() == kCsmBiasReceiverPlane) {
    // The shared light-view derivatives, scaled into this cascade: a cascade change between
    // neighbouring pixels does not corrupt them.
    float3 s = csmToMapScale[c].xyz;
    fi.depthGradient = ReceiverPlaneDepthGradient(lvDdx * s, lvDdy * s);
  }
  fi.pixel = pixel;
#if SHADOW_FILTER == 5
  // Each cascade is its own orthographic map: its depth range from the depth mapping
  // (d = z * scale + offset, z the distance along the light), its own world texel size per axis
  // from the same mapping (uv per world unit times the texture's texels per uv): sdsm's tight
  // partitions and csm's stabilize=0 fits have oblong texels, which csmCascade's larger side
  // would make a narrower penumbra along the shorter one.
  ShadowPcssInput pi;
  float depthScale = csmToMapScale[c].z, depthOffset = csmToMapOffset[c].z;
  pi.depthRange = float2(depthOffset, depthOffset - 1.0) / depthScale;
  pi.penumbraScale = csmPcss.x * abs(csmToMapScale[c].xy) / csmMapInfo.xy;
  pi.perspective = 0.0;
  pi.searchTaps = csmPcss.y;
  pi.maxKernel = csmPcss.z;
  pi.padPcss = 0.0;
#endif
#if defined(SHADOW_ACCEL) && SHADOW_ACCEL != 0
  uint how;
#if SHADOW_FILTER == 5
  float v = HpsmShadowFilterPcss(CsmMap, CsmSampler, CsmHpsm, fi, pi, how);
#else
  float v = HpsmShadowFilter(CsmMap, CsmSampler, CsmHpsm, fi, how);
#endif
#if HPSM_COUNTERS
  CsmHpsmCounters.InterlockedAdd(how * 4, 1);
#endif
  return v;
#elif SHADOW_FILTER == 5
  return ShadowFilterPcss(CsmMap, CsmSampler, fi, pi);
#else
  return ShadowFilter(CsmMap, CsmSampler, fi);
#endif
#endif
}

float ShadowVisibility(float3 worldPos, float3 worldNormal, float4 svPosition) {
  float3 lv = CsmLightView(worldPos);
  // Derivatives first, in uniform control flow (lit.hlsl calls this for every pixel).
  float3 lvDdx = ddx(lv);
  float3 lvDdy = ddy(lv);
  int c = CsmSelect(worldPos, lv);
  if (c < 0) return 1.0;
  float v = CsmFiltered(c, lv, lvDdx, lvDdy, worldNormal, svPosition.xy);
  float w = CsmBlendWeight(c, worldPos, lv);
  if (w < 1.0) v = lerp(CsmFiltered(c + 1, lv, lvDdx, lvDdy, worldNormal, svPosition.xy), v, w);
  return v;
}

// Layer = cascade; texels of its region (row 0 at the top).
float2 ShadowTexel(float3 worldPos, float layer) {
  int c = (int)layer;
  return CsmLocalUv(CsmMapCoord(CsmLightView(worldPos), c).xy, c) * csmMapInfo.w;
}

ShadowLookup ShadowLocate(float3 worldPos, float3 worldNormal) {
  float3 lv = CsmLightView(worldPos);
  int c = CsmSelect(worldPos, lv);
  if (c < 0) return MakeShadowLookup(kShadowNoLayer, float2(0.0, 0.0));
  float3 m = CsmMapCoord(CsmLookupPosition(c, lv, worldNormal), c);
  if (m.z > 1.0) return MakeShadowLookup(kShadowNoLayer, float2(0.0, 0.0));  // as ShadowVisibility: no read
  return MakeShadowLookup((float)c, CsmLocalUv(m.xy, c) * csmMapInfo.w);
}
