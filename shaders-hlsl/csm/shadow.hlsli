// Lighting side of cascaded shadow maps (techniques/csm). Every cascade is an orthographic
// projection of one shared light view, so a point's light-view position is computed once and each
// cascade maps it to its region with a scale and an offset. The cascades live in a
// Texture2DArray: one slice each (storage=array) or regions of slice 0 (storage=atlas); csmRegion
// says where, so both storages take the same path.
//
// Defines: SHADOW_FILTER and SHADOW_KERNEL, for common/shadow-filter.hlsli. Selection, blending
// and the bias mode are uniform branches on constants.
#include "common/frame.hlsli"
#include "common/shadow-lookup.hlsli"
#include "common/shadow-filter.hlsli"

#define CSM_MAX_CASCADES 8

cbuffer CsmShadow : register(b2) {
  float4x4 csmLightView;                      // world -> the light view all cascades share
  float4 csmToMapScale[CSM_MAX_CASCADES];     // light view -> (slice u, slice v, depth), per cascade
  float4 csmToMapOffset[CSM_MAX_CASCADES];
  float4 csmRegion[CSM_MAX_CASCADES];         // the cascade's region in slice uv: min.xy, size.zw
  float4 csmCascade[CSM_MAX_CASCADES];        // split near, split far (view depth), world texel size, array slice
  float4 csmCameraForward;                    // w: cascade count
  float4 csmSettings;                         // select (0 interval, 1 map), blend, bias (0 const, 1 slope, 2 normal, 3 receiver plane), normal offset (texels)
  float4 csmMapInfo;                          // 1 / texture size (xy), map-select margin in region uv, region size in texels
};

Texture2DArray<float> CsmMap : register(t0);
SamplerComparisonState CsmSampler : register(s0);

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
    if (CsmInsideMap(lv, m, csmMapInfo.z)) return m;
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
    float margin = csmMapInfo.z;
    float2 l = CsmLocalUv(CsmMapCoord(lv, c).xy, c);
    float2 edge = min(l - margin, 1.0 - margin - l);
    toEnd = min(edge.x, edge.y) / (0.5 - margin);
  }
  if (toEnd >= blend || !CsmInsideMap(lv, c + 1, csmMapInfo.z)) return 1.0;
  return saturate(toEnd / blend);
}

// The lookup's light-view position: with bias=normal, moved along the normal by the cascade's
// texel size so the offset is constant in texels whatever the cascade.
float3 CsmLookupPosition(int c, float3 lv, float3 worldNormal) {
  if (CsmBias() != kCsmBiasNormal) return lv;
  float3 offset = NormalOffset(worldNormal, toLight, csmCascade[c].z, csmSettings.w);
  return lv + mul((float3x3)csmLightView, offset);
}

float CsmFiltered(int c, float3 lv, float3 lvDdx, float3 lvDdy, float3 worldNormal, float2 pixel) {
  float3 m = CsmMapCoord(CsmLookupPosition(c, lv, worldNormal), c);
  if (m.z > 1.0) return 1.0;  // beyond the cascade's far plane: nothing there casts
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
  return ShadowFilter(CsmMap, CsmSampler, fi);
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
