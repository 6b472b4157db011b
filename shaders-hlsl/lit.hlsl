// The lit pass: Lambert diffuse with the shadow technique's visibility, plus ambient and the
// local lights (common/local-lights.hlsli). Compiled after the technique's include, which defines
//   float ShadowVisibility(float3 worldPos, float3 worldNormal, float4 svPosition)
// returning 1 for lit and 0 for shadowed (filtered techniques return values in between), and,
// for the lab, ShadowLocate and ShadowTexel (common/shadow-lookup.hlsli). A technique that
// defines SHAFTS=1 also defines float ShadowInScatter(float3 worldPos): sun shafts, added.
//
// SP_LAB=1 compiles the lab's variant: the same colour plus what the measurements need, one
// render target each (techniques/renderer.h, LabBuffers). The normal variant is unchanged by it.
#include "common/frame.hlsli"
#include "common/local-lights.hlsli"
#ifndef SP_LAB
#define SP_LAB 0
#endif

struct VSIn {
  float3 pos : POSITION;
  float3 normal : NORMAL;
};

struct VSOut {
  float4 pos : SV_Position;
  float3 worldPos : WORLDPOS;
  float3 normal : NORMAL;
};

VSOut VSMain(VSIn i) {
  VSOut o;
  float4 wp = mul(world, float4(i.pos, 1.0));
  o.worldPos = wp.xyz;
  // Normals of the built-in scenes and glTF meshes use uniform or no scaling.
  o.normal = mul((float3x3)world, i.normal);
  o.pos = mul(viewProj, wp);
  return o;
}

#if !SP_LAB

float4 PSMain(VSOut i) : SV_Target {
  float3 n = normalize(i.normal);
  float ndotl = saturate(dot(n, toLight));
  // Unconditionally, in uniform control flow: lookups may take derivatives (csm's receiver plane).
  // Where ndotl is 0 the visibility does not change the colour.
  float visibility = ShadowVisibility(i.worldPos, n, i.pos);
  float3 color = albedo * (ambient + lightColor * ndotl * visibility + LocalLighting(i.worldPos, n));
#if defined(SHAFTS) && SHAFTS
  color += lightColor * ShadowInScatter(i.worldPos);
#endif
  return float4(color, 1.0);
}

#else

struct LabOut {
  float4 color : SV_Target0;       // as the normal variant
  float4 position : SV_Target1;    // world position; w = 1 (the clear leaves 0 where nothing was drawn)
  float4 normal : SV_Target2;      // unit world normal; w = N.L, saturated, of the judged light
  float visibility : SV_Target3;   // the judged light's visibility for every pixel, facing it or not
  float4 lookup : SV_Target4;      // layer (-1: no map read), texel x, texel y, texels per pixel
  float4 albedo : SV_Target5;      // to shade the reference image the same way on the CPU
};

LabOut PSMain(VSOut i) {
  // Derivatives first, in uniform control flow.
  float3 dpdx = ddx(i.worldPos);
  float3 dpdy = ddy(i.worldPos);
  float3 n = normalize(i.normal);
  float ndotl = saturate(dot(n, toLight));
  float visibility = ShadowVisibility(i.worldPos, n, i.pos);
  ShadowLookup l = ShadowLocate(i.worldPos, n);
  // What the lab judges: the directional light, or the local light SP_LAB_LOCAL_LIGHT of a
  // local-light technique (Technique::LabLocalLight): its N.L, 0 where it lights nothing (beyond
  // its range, outside a spot's outer cone), and its visibility.
#ifdef SP_LAB_LOCAL_LIGHT
  LocalLightData labLight = localLights[SP_LAB_LOCAL_LIGHT];
  float3 toLab = labLight.position - i.worldPos;
  bool labReached = length(toLab) < labLight.range && LocalSpotFactor(labLight, -normalize(toLab)) > 0.0;
  float labNdotl = labReached ? saturate(dot(n, normalize(toLab))) : 0.0;
  float labVisibility = LocalShadowVisibility(SP_LAB_LOCAL_LIGHT, i.worldPos, n);
#else
  float labNdotl = ndotl;
  float labVisibility = visibility;
#endif
  // Texels per pixel: the square root of the map area, in texels, that the pixel's footprint
  // covers: |det J| of the 2x2 Jacobian of texel coordinates over screen x and y, with the layer
  // held at the pixel's own.
  float texelsPerPixel = 0.0;
  if (l.layer >= 0.0) {
    float2 t0 = ShadowTexel(i.worldPos, l.layer);
    float2 jx = ShadowTexel(i.worldPos + dpdx, l.layer) - t0;
    float2 jy = ShadowTexel(i.worldPos + dpdy, l.layer) - t0;
    texelsPerPixel = sqrt(abs(jx.x * jy.y - jx.y * jy.x));
  }
  LabOut o;
  // The same expression as the normal variant, so the colour is the same.
  o.color = float4(albedo * (ambient + lightColor * ndotl * visibility + LocalLighting(i.worldPos, n)), 1.0);
#if defined(SHAFTS) && SHAFTS
  o.color.rgb += lightColor * ShadowInScatter(i.worldPos);
#endif
  o.position = float4(i.worldPos, 1.0);
  o.normal = float4(n, labNdotl);
  o.visibility = labVisibility;
  o.lookup = float4(l.layer, l.texel, texelsPerPixel);
  o.albedo = float4(albedo, 1.0);
  return o;
}

#endif
