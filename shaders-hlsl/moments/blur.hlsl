// One direction of the separable moment blur (run twice: blurDirection (1, 0), then (0, 1)).
// The radius is per layer and fractional, in texels: the technique converts one world-space
// radius to each cascade's texels, so every partition blurs the same distance and penumbrae do
// not jump at cascade borders. A fractional radius must change the result continuously, so
// the outermost taps get fractional weights instead of the radius being rounded.
//   MOMENT_BLUR_KERNEL 0 box:      weight(i) = saturate(r + 1 - |i|), sums to 2r + 1
//                      1 gaussian: sigma = r / 2, taps |i| <= ceil(r) (2 sigma), renormalised
// Both stay within r texels (rounded up), so a technique's padding for the blur is simply r.
// Texels beyond the layer's edge repeat the edge texel (clamp-to-edge, as the sampler does).
//! cs_5_0 main
#ifndef MOMENT_BLUR_KERNEL
#define MOMENT_BLUR_KERNEL 1
#endif
// Bounds the loop; the C++ side clamps radii to it (kMaxBlurRadiusTexels).
#define MOMENT_MAX_BLUR_RADIUS 32

cbuffer MomentBlur : register(b0) {
  uint2 blurSize;  // texels of one layer
  uint blurLayers;
  uint padMomentBlur;
  int2 blurDirection;
  int2 padMomentBlur2;
  float4 blurRadius[4];  // texels, layer i in blurRadius[i / 4][i % 4]
};

Texture2DArray<float4> blurInput : register(t0);
RWTexture2DArray<float4> blurOutput : register(u0);

float TapWeight(float r, int i) {
#if MOMENT_BLUR_KERNEL == 0
  return saturate(r + 1.0 - abs(float(i)));
#else
  float sigma = r / 2.0;
  return exp(-float(i * i) / (2.0 * sigma * sigma));
#endif
}

[numthreads(8, 8, 1)] void main(uint3 id : SV_DispatchThreadID) {
  if (any(id.xy >= blurSize) || id.z >= blurLayers) return;
  float r = min(blurRadius[id.z / 4][id.z % 4], float(MOMENT_MAX_BLUR_RADIUS));
  if (r < 1e-3) {
    blurOutput[id] = blurInput.Load(int4(id, 0));
    return;
  }
  int reach = int(ceil(r));
  // Normalised weights: a sum of unnormalised taps of ESM/EVSM moments near the format's
  // largest value (exp(88.72) in fp32) would overflow before the division.
  float total = 0.0;
  for (int j = -reach; j <= reach; ++j) total += TapWeight(r, j);
  int2 last = int2(blurSize) - 1;
  float4 sum = 0.0;
  for (int i = -reach; i <= reach; ++i) {
    int2 p = clamp(int2(id.xy) + blurDirection * i, int2(0, 0), last);
    sum += (TapWeight(r, i) / total) * blurInput.Load(int4(p, id.z, 0));
  }
  blurOutput[id] = sum;
}
