// The lab's side of the technique lighting contract. Besides
//   float ShadowVisibility(float3 worldPos, float3 worldNormal, float4 svPosition)
// every technique's lighting include defines
//   ShadowLookup ShadowLocate(float3 worldPos, float3 worldNormal)
//     which map layer (cascade, array slice, atlas region: an id as a float) the pixel's lookup
//     reads, and the texel coordinates within that layer the lookup is centred on;
//   float2 ShadowTexel(float3 worldPos, float layer)
//     the texel coordinates of any world point in a given layer (the same mapping ShadowLocate
//     uses, without the layer choice).
// The lab's lit pass (lit.hlsl with SP_LAB=1) measures texels per pixel by differencing
// ShadowTexel over the pixel's world-space derivatives with the layer held fixed, so a cascade
// change between neighbouring pixels does not show up as a huge derivative; the bench counts the
// (layer, floor(texel)) pairs hit for shadow-map utilization.
//
// Texel coordinates: texel (i, j) of a W x H layer covers [i, i+1) x [j, j+1), row 0 at the top
// (D3D's convention), so coordinates run from 0 to W and 0 to H across the layer.
#ifndef SP_SHADOW_LOOKUP_HLSLI
#define SP_SHADOW_LOOKUP_HLSLI

// Layer id of a lookup that reads no map (outside every layer; the technique returns a default).
static const float kShadowNoLayer = -1.0;

struct ShadowLookup {
  float layer;
  float2 texel;
};

ShadowLookup MakeShadowLookup(float layer, float2 texel) {
  ShadowLookup l;
  l.layer = layer;
  l.texel = texel;
  return l;
}

#endif
