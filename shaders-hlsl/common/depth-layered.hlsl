// Depth-only vertex shader for one pass into several layers of a layered depth target: each
// instance of a draw is the mesh in one layer, layerList[SV_InstanceID] says which, and the layer's
// view-projection replaces Frame.viewProj. Needs DeviceInfo::vsRenderTargetArrayIndex.
// Must match SceneDrawer::DrawDepthLayered (techniques/scene-drawer.cpp).
//! vs_5_0 VSMain
#include "frame.hlsli"

#define SP_MAX_DEPTH_LAYERS 8

// b7, b8: above the registers frame.hlsli and the techniques use, so no pass's binding collides.
cbuffer LayerViews : register(b7) {
  float4x4 layerViewProj[SP_MAX_DEPTH_LAYERS];
};

cbuffer LayerList : register(b8) {
  uint4 layerList[SP_MAX_DEPTH_LAYERS / 4];  // instance i draws into layer layerList[i / 4][i % 4]
};

struct VSOut {
  float4 pos : SV_Position;
  uint layer : SV_RenderTargetArrayIndex;
};

VSOut VSMain(float3 pos : POSITION, uint instance : SV_InstanceID) {
  VSOut o;
  o.layer = layerList[instance / 4][instance % 4];
  // The same expression as depth-only.hlsl, so a layer holds the bits a per-layer pass writes.
  o.pos = mul(layerViewProj[o.layer], mul(world, float4(pos, 1.0)));
  return o;
}
