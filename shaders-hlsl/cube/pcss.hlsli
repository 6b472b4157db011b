// PCSS for the cube technique (filter=pcss, storage=depth): the steps of common/shadow-pcss.hlsli,
// in direction space on the face of the receiver's direction d instead of texel space on a 2D map.
// The light is a sphere of radius r = cubePcss.x around the light's position.
//
// Depths: every face is a 90-degree perspective map with the same near and far, so the planar
// depth along the face's axis (the major axis ma) is linear: ma = depthB / (z - depthA). Similar
// triangles with those linear depths, the light as a disc of radius r facing the face's axis (as
// the spot map's disc faces its axis), give the penumbra at the receiver's planar depth dR behind
// blockers at dB, in face texels (one texel at depth dR is 2 dR / faceSize wide):
//   w = r * faceSize * (dR - dB) / (dB dR)
// which is ShadowPcssWidth with penumbraScale = r * faceSize (2 tan(45 deg) = 2).
//
// Face edges: nothing is clamped to the receiver's face. Every tap is a direction
// d + (x S + y T) * texel (S, T the face's unit axes, one texel apart at the receiver's depth); a
// tap past the edge selects the neighbouring face, where the hardware reads it (seamless cube
// sampling, as the box/gauss kernels rely on). A blocker found there stores its planar depth along
// that face's axis; it is brought onto the receiver's axis along the tap's ray (the ray's
// component on the receiver's axis is ma(d), since S and T are perpendicular to it):
//   dB = maB * ma(d) / ma(tap)
// so the average mixes depths on one axis. The PCF box keeps its direction-space spacing across the
// edge: on the neighbouring face the taps are unevenly spaced in that face's texels (at 45 degrees
// by up to a factor 2), which a footprint straddling the edge blurs less evenly there but not
// discontinuously (PcssTest.CubePenumbraAcrossAFaceEdge measures the width at one).
#ifndef SP_CUBE_PCSS_HLSLI
#define SP_CUBE_PCSS_HLSLI

#include "common/shadow-pcss.hlsli"

// The stored depths for the blocker search: point samples, the comparison sampler gives none.
SamplerState CubeShadowDepthSampler : register(s1);

float CubePcssPlanarDepth(CubeSlot slot, float z) { return slot.depthB / (z - slot.depthA); }

float CubePcssVisibility(TextureCube<float> map, CubeSlot slot, float3 d, float3 n) {
  float ma = CubeMajorAxis(d);
  float3 S, T;
  CubeFaceAxes(d, S, T);
  float texel = 2.0 * ma / slot.faceSize;
  S *= texel;
  T *= texel;
  ShadowPcssInput p;
  p.depthRange = float2(-slot.depthB / slot.depthA, slot.range);  // near = -b / a
  p.penumbraScale = cubePcss.xx * slot.faceSize;
  p.perspective = 1.0;
  p.searchTaps = cubePcss.y;
  p.maxKernel = cubePcss.z;
  p.padPcss = 0.0;
  // Blockers nearer than the near plane are not in the map: the widest penumbra is that of one on it.
  float radius = min(0.5 * ShadowPcssWidth(p, ma, p.depthRange.x).x, 0.5 * p.maxKernel);
  int taps = int(p.searchTaps);
  float step = 2.0 * radius / float(taps - 1);
  float blockers = 0.0, depthSum = 0.0;
  [loop] for (int y = 0; y < taps; ++y) {
    [loop] for (int x = 0; x < taps; ++x) {
      float2 o = -radius + step * float2(x, y);
      float3 q = d + o.x * S + o.y * T;
      float stored = map.SampleLevel(CubeShadowDepthSampler, q, 0.0);
      if (stored < CubePlaneReference(slot, d, n, q, S, T)) {
        blockers += 1.0;
        depthSum += CubePcssPlanarDepth(slot, stored) * ma / CubeMajorAxis(q);
      }
    }
  }
  if (blockers == 0.0) return 1.0;
  float w = clamp(ShadowPcssWidth(p, ma, depthSum / blockers).x, 1.0, p.maxKernel);
  // The box: k = ceil(w) bilinear comparison taps per axis, w / k texels apart. Across a straight
  // edge their sum ramps with slope exactly 1 / w (the 2D maps' GatherCmp box gives the same slope),
  // reaching 1 - w / k < 1 texel further at each end where fewer taps overlap.
  int k = int(ceil(w - 1e-3));
  float spacing = w / float(k);
  float sum = 0.0;
  [loop] for (int by = 0; by < k; ++by) {
    [loop] for (int bx = 0; bx < k; ++bx) {
      float2 o = (float2(bx, by) - 0.5 * float(k - 1)) * spacing;
      float3 q = d + o.x * S + o.y * T;
      sum += CubeTap(map, slot, q, 1.0, 0.0, CubePlaneReference(slot, d, n, q, S, T));
    }
  }
  return sum / float(k * k);
}

#endif  // SP_CUBE_PCSS_HLSLI
