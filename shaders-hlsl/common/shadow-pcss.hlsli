// Percentage-closer soft shadows (Fernando, "Percentage-closer soft shadows", SIGGRAPH 2005
// sketch), SHADOW_FILTER 5 of common/shadow-filter.hlsli, in three steps:
//   1. blocker search: a pcssSearch x pcssSearch grid of point loads (Load: no second sampler,
//      so the D3D11 bindings stay one map and one comparison sampler) over the square of the map
//      that the light subtends from the receiver, averaging the depths in front of the receiver
//      (linearised: an average of perspective depths is not the depth of an average);
//   2. penumbra width from the average blocker depth and the light's size (ShadowPcssInput);
//   3. a box PCF of that width, any real width (not just odd texel counts), from GatherCmp.
// The box, not rotated Poisson taps: it is deterministic and noise-free, so the penumbra's ramp is
// exactly linear across a straight edge (what the tests measure), and GatherCmp keeps a wide one
// affordable: ceil((w + 2) / 2)^2 gathers for width w texels.
// No blocker in the search region: fully lit, without the PCF.
//
// Light-size semantics (the ray-traced area-light reference uses the same):
//   directional (orthographic map): a disc of angular diameter `angle`; penumbra width in world
//     units w = (dR - dB) * 2 tan(angle / 2), dR and dB the receiver's and blockers' depths along
//     the light direction in world units;
//   spot/point (perspective map): a disc of radius r facing the receiver; by similar triangles
//     w = 2 r (dR - dB) / dB at the receiver, dR and dB view-space depths from the light.
// Either way the width in the receiver's map texels is
//   penumbraScale * (dR - dB)               orthographic, penumbraScale = 2 tan(angle/2) / worldTexel
//   penumbraScale * (dR - dB) / (dB dR)     perspective,  penumbraScale = 2 r * mapSize / (2 tan(fov/2))
// (at depth dR one texel covers dR * 2 tan(fov/2) / mapSize world units), clamped to
// [1, maxKernel]: width 1 is the bilinear 2x2 (a 1-texel box over texel-sized cells).
#ifndef SHADOW_PCSS_HLSLI
#define SHADOW_PCSS_HLSLI

#include "common/shadow-filter.hlsli"

struct ShadowPcssInput {
  float2 depthRange;     // the light view's near and far planes, world units along its axis
  float2 penumbraScale;  // see above, per map axis (an orthographic fit's texels need not be square)
  float perspective;     // 0: orthographic, map depth linear in depthRange; 1: D3D perspective depth
  float searchTaps;      // blocker-search grid taps per axis, >= 2
  float maxKernel;       // widest PCF in texels
  float padPcss;
};

// Depth along the light's axis in world units from the map's [0, 1] depth.
float ShadowPcssLinearDepth(ShadowPcssInput p, float d) {
  float n = p.depthRange.x, f = p.depthRange.y;
  // D3D perspective (zero-to-one): d = f (z - n) / (z (f - n)), so z = n f / (f - d (f - n)).
  return p.perspective != 0.0 ? n * f / (f - d * (f - n)) : n + d * (f - n);
}

// Penumbra width in texels for receiver and blocker depths (world units along the light's axis).
float2 ShadowPcssWidth(ShadowPcssInput p, float dR, float dB) {
  float2 w = p.penumbraScale * (dR - dB);
  return p.perspective != 0.0 ? w / (dB * dR) : w;
}

// Visibility of a box of width w texels centred on f.s, over texel-sized cells (texel t covers
// [t - 0.5, t + 0.5] in texel space), one GatherCmp per 2x2 block of the footprint.
float ShadowPcssBox(Texture2DArray<float> map, SamplerComparisonState cmp, ShadowFilterInput i, ShadowFilterFrame f, float2 w) {
  float2 a = f.s - 0.5 * w, b = f.s + 0.5 * w;
  float2 first = floor(a + 0.5), last = floor(b + 0.5);
  int2 blocks = int2(last - first) / 2 + 1;
  float sum = 0.0;
  [loop] for (int gy = 0; gy < blocks.y; ++gy) {
    [loop] for (int gx = 0; gx < blocks.x; ++gx) {
      float2 t = first + 2.0 * float2(gx, gy);
      // Overlap of each texel's cell with [a, b]; the last block may reach one texel past `last`,
      // whose weight is 0.
      float2 w0 = max(min(t + 0.5, b) - max(t - 0.5, a), 0.0);
      float2 w1 = max(min(t + 1.5, b) - max(t + 0.5, a), 0.0);
      sum += ShadowGatherBlock(map, cmp, i, f, t, w0, w1);
    }
  }
  return saturate(sum / (w.x * w.y));
}

float ShadowFilterPcss(Texture2DArray<float> map, SamplerComparisonState cmp, ShadowFilterInput i, ShadowPcssInput p) {
  ShadowFilterFrame f = ShadowFilterSetup(i);
  float dR = ShadowPcssLinearDepth(p, i.depth);
  // Blockers nearer the light than the near plane are not in the map, so the widest penumbra
  // that can reach the receiver is that of a blocker on the near plane; no wider than the PCF.
  float2 radius = min(0.5 * ShadowPcssWidth(p, dR, p.depthRange.x), 0.5 * p.maxKernel);
  int taps = int(p.searchTaps);
  float2 step = 2.0 * radius / float(taps - 1);
  float blockers = 0.0, depthSum = 0.0;
  [loop] for (int y = 0; y < taps; ++y) {
    [loop] for (int x = 0; x < taps; ++x) {
      float2 t = clamp(floor(f.s - radius + step * float2(x, y) + 0.5), f.lo, f.hi);
      float stored = map.Load(int4(int2(t), int(i.layer), 0));
      if (stored < ShadowFilterReference(i, f, t)) {
        blockers += 1.0;
        depthSum += ShadowPcssLinearDepth(p, stored);
      }
    }
  }
  if (blockers == 0.0) return 1.0;
  float2 w = clamp(ShadowPcssWidth(p, dR, depthSum / blockers), 1.0, p.maxKernel);
  return ShadowPcssBox(map, cmp, i, f, w);
}

#endif  // SHADOW_PCSS_HLSLI
