// Depth -> moments, one thread per texel of every layer (dispatch z = layer). With MOMENT_MSAA 4
// the source is a 4x depth array and the texel gets the mean of the four samples' moments: the
// moments are linear in the samples, so this is the filter a 4x box would give, and no
// multisampled moment buffer ever exists (the resolve the SDSM paper describes). Averaging the
// depths first would instead put one fake occluder at the mean depth on every silhouette.
//! cs_5_0 main
#include "moments/moments.hlsli"

#ifndef MOMENT_MSAA
#define MOMENT_MSAA 1
#endif

cbuffer MomentResolve : register(b0) {
  uint2 resolveSize;  // texels of one layer
  uint resolveLayers;
  uint padMomentResolve;
};

#if MOMENT_MSAA > 1
Texture2DMSArray<float> depthSource : register(t0);
#else
Texture2DArray<float> depthSource : register(t0);
#endif
RWTexture2DArray<float4> moments : register(u0);

[numthreads(8, 8, 1)] void main(uint3 id : SV_DispatchThreadID) {
  if (any(id.xy >= resolveSize) || id.z >= resolveLayers) return;
#if MOMENT_MSAA > 1
  float4 sum = 0.0;
  [unroll] for (int s = 0; s < MOMENT_MSAA; ++s) sum += MomentsFromDepth(depthSource.Load(int3(id), s));
  moments[id] = sum * (1.0 / MOMENT_MSAA);
#else
  moments[id] = MomentsFromDepth(depthSource.Load(int4(id, 0)));
#endif
}
