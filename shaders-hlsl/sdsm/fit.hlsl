// SDSM with cull=gpu: the partitions' shadow projections made on the GPU from the analysis
// results, so no frame waits for a readback. One thread per partition writes, into one raw buffer:
//   bytes    0..383   the fitted boxes in the results layout (SDSM_W_BOUNDS), for CasterCuller
//   bytes  384..1023  cbuffer CsmShadow of csm/shadow.hlsli, byte for byte, csmPcss included
//                     (the shader declares it for filter=pcss only); the technique copies this
//                     range into the lit pass's constant buffer (CopySubresourceRegion)
//   bytes 1024..1535  per partition the world -> clip matrix as four rows (VSCasterGpu)
//   bytes 1536..1599  the moment blur's radius per layer in texels (16 floats, as cbuffer
//                     MomentBlur's blurRadius of moments/blur.hlsl holds them; copied there)
// The arithmetic is FitPartition's (techniques/sdsm/sdsm-technique-fit.cpp) operation for
// operation; `precise` keeps the compiler from fusing it into multiply-adds the CPU does not do.
//! cs_5_0 FitPartitions
#define SDSM_LAYOUT_ONLY
#include "sdsm/analysis.hlsli"

#define SDSM_FIT_CONSTANTS 384
#define SDSM_FIT_MATRICES 1024
#define SDSM_FIT_BLUR 1536
#define SDSM_FIT_BLUR_LAYERS 16  // kMaxMomentLayers

cbuffer SdsmFit : register(b0) {
  float4 fitLightView[4];   // world -> light view as glm stores it (columns), copied verbatim
  float4 fitCornerRay[4];   // xyz: light-view offset per unit view depth of the frustum's corners
  float4 fitCameraOrigin;   // xyz: the camera in light view; w: the camera's far plane
  float4 fitGridOrigin;     // xyz: the world origin in light view; w: quantize (0 or 1)
  float4 fitCameraForward;  // xyz: camera forward; w: partition count K
  float4 fitSettings;       // csmSettings: select, blend, bias mode, normal offset
  float4 fitParams;         // resolution, padding texels, dilation, tight (0 or 1)
  float4 fitBlur;           // moment blur radius (world); its padding limit, the blur's radius limit (texels); 0
  float4 fitPcss;           // xyz: csmPcss (one row for every partition: each derives its own scale); w: FitParams::casterTop
};

ByteAddressBuffer analysis : register(t0);
RWByteAddressBuffer fitOut : register(u0);

// The smallest power of two >= x (x > 0, normal), on the float's bits: exact, as on the CPU.
float2 CeilPow2(float2 x) { return asfloat((asuint(x) + 0x007fffffu) & 0xff800000u); }

void StoreRow(uint address, float4 v) { fitOut.Store4(address, asuint(v)); }

// CsmShadow member addresses (D3D packing: one float4 register each, arrays of 8).
#define CSM_LIGHT_VIEW (SDSM_FIT_CONSTANTS + 0)
#define CSM_SCALE(c) (SDSM_FIT_CONSTANTS + 64 + (c) * 16)
#define CSM_OFFSET(c) (SDSM_FIT_CONSTANTS + 192 + (c) * 16)
#define CSM_REGION(c) (SDSM_FIT_CONSTANTS + 320 + (c) * 16)
#define CSM_CASCADE(c) (SDSM_FIT_CONSTANTS + 448 + (c) * 16)
#define CSM_FORWARD (SDSM_FIT_CONSTANTS + 576)
#define CSM_SETTINGS (SDSM_FIT_CONSTANTS + 592)
#define CSM_MAP_INFO (SDSM_FIT_CONSTANTS + 608)
#define CSM_PCSS (SDSM_FIT_CONSTANTS + 624)

void WriteEmpty(uint p) {
  uint b = (SDSM_W_BOUNDS + p * 8) * 4;
  fitOut.Store4(b, uint4(0xffffffffu, 0xffffffffu, 0xffffffffu, 0u));
  fitOut.Store4(b + 16, uint4(0u, 0u, 0u, 0u));
  // Nothing inside: selection's inside test fails and a lookup lands beyond the far plane (lit).
  StoreRow(CSM_SCALE(p), float4(0.0, 0.0, 0.0, 0.0));
  StoreRow(CSM_OFFSET(p), float4(-1.0, -1.0, 2.0, 0.0));
  StoreRow(CSM_REGION(p), float4(0.0, 0.0, 1.0, 1.0));
  for (uint r = 0; r < 4; ++r) StoreRow(SDSM_FIT_MATRICES + p * 64 + r * 16, float4(0.0, 0.0, 0.0, 0.0));
  fitOut.Store(SDSM_FIT_BLUR + p * 4, asuint(0.0));
}

[numthreads(SDSM_MAX_PARTITIONS, 1, 1)]
void FitPartitions(uint p : SV_GroupThreadID) {
  uint K = (uint)fitCameraForward.w;
  float N = fitParams.x;
  if (p == 0) {
    for (uint w = 0; w < SDSM_W_BOUNDS; ++w) fitOut.Store(w * 4, 0u);
    for (uint c = 0; c < 4; ++c) StoreRow(CSM_LIGHT_VIEW + c * 16, fitLightView[c]);
    StoreRow(CSM_FORWARD, fitCameraForward);
    StoreRow(CSM_SETTINGS, fitSettings);
    StoreRow(CSM_MAP_INFO, float4(1.0 / N, 1.0 / N, 0.0, N));
    StoreRow(CSM_PCSS, float4(fitPcss.xyz, 0.0));
    for (uint l = SDSM_MAX_PARTITIONS; l < SDSM_FIT_BLUR_LAYERS; ++l) fitOut.Store(SDSM_FIT_BLUR + l * 4, asuint(0.0));
  }
  if (p >= K) {
    WriteEmpty(p);
    StoreRow(CSM_CASCADE(p), float4(0.0, 0.0, 0.0, 0.0));
    return;
  }
  float splitNear = asfloat(analysis.Load((SDSM_W_SPLITS + p) * 4));
  float splitFar = asfloat(analysis.Load((SDSM_W_SPLITS + p + 1) * 4));
  uint src = (SDSM_W_BOUNDS + p * 8) * 4;
  uint samples = analysis.Load(src + 12);
  // The interval selection reads: the last partition takes everything behind it (the lit pass's
  // view depth of the farthest sample may exceed the analysed maximum in the last bits).
  float selectFar = p + 1 == K ? max(splitFar, fitCameraOrigin.w) : splitFar;
  StoreRow(CSM_CASCADE(p), float4(splitNear, selectFar, 0.0, float(p)));
  // No receiver: no pixel reads the partition (tight=0 too: its slice holds no sample).
  if (samples == 0) {
    WriteEmpty(p);
    return;
  }

  precise float3 lo, hi;
  if (fitParams.w > 0.5) {
    uint3 minKey = analysis.Load3(src), maxKey = analysis.Load3(src + 16);
    lo = float3(SdsmFromOrderedKey(minKey.x), SdsmFromOrderedKey(minKey.y), SdsmFromOrderedKey(minKey.z));
    hi = float3(SdsmFromOrderedKey(maxKey.x), SdsmFromOrderedKey(maxKey.y), SdsmFromOrderedKey(maxKey.z));
  } else {
    // tight=0: the box of the view frustum between the partition's splits.
    lo = float3(1e30, 1e30, 1e30);
    hi = -lo;
    for (uint i = 0; i < 8; ++i) {
      precise float3 q = fitCameraOrigin.xyz + fitCornerRay[i & 3].xyz * (i < 4 ? splitNear : splitFar);
      lo = min(lo, q);
      hi = max(hi, q);
    }
  }

  // FitPartition, step by step.
  float dilation = fitParams.z;
  lo = lo - dilation;
  hi = hi + dilation;
  precise float2 size = max(hi.xy - lo.xy, float2(1e-3, 1e-3));
  precise float2 centre = (lo.xy + hi.xy) * 0.5;
  float pad = fitParams.y;
  if (fitBlur.x > 0.0) pad += min(ceil(fitBlur.x * N / max(size.x, size.y)), fitBlur.y);
  size = size * (N / (N - 2.0 * pad));
  if (fitGridOrigin.w > 0.5) {
    size = CeilPow2(size * (N / (N - 1.0)));
    precise float2 t = size / N;
    centre = fitGridOrigin.xy + floor((centre - fitGridOrigin.xy) / t + 0.5) * t;
  }
  lo.xy = centre - size * 0.5;
  hi.xy = centre + size * 0.5;
  precise float texel = max(size.x, size.y) / N;
  precise float zPad = pad * texel + 1e-4 * (abs(lo.z) + abs(hi.z)) + 1e-4;
  lo.z = lo.z - zPad;
  hi.z = hi.z + zPad;
  hi.z = max(hi.z, fitPcss.w);

  precise float3 extent = hi - lo;
  precise float3 scale = float3(1.0 / extent.x, -1.0 / extent.y, -1.0 / extent.z);
  precise float3 offset = float3(-lo.x * scale.x, hi.y / extent.y, hi.z / extent.z);

  uint b = (SDSM_W_BOUNDS + p * 8) * 4;
  fitOut.Store4(b, uint4(SdsmOrderedKey(lo.x), SdsmOrderedKey(lo.y), SdsmOrderedKey(lo.z), samples));
  fitOut.Store4(b + 16, uint4(SdsmOrderedKey(hi.x), SdsmOrderedKey(hi.y), SdsmOrderedKey(hi.z), 0u));
  StoreRow(CSM_SCALE(p), float4(scale, pad / N));
  StoreRow(CSM_OFFSET(p), float4(offset, 0.0));
  StoreRow(CSM_REGION(p), float4(0.0, 0.0, 1.0, 1.0));
  StoreRow(CSM_CASCADE(p), float4(splitNear, selectFar, texel, float(p)));

  // The world blur radius in this map's texels, as the CPU path's BlurRadiusTexels of the fitted
  // size (same operations), capped by the blur padding reserved above so the kernel never
  // reaches past the map: every partition blurs the same world distance.
  float radius = 0.0;
  if (fitBlur.x > 0.0) {
    precise float layerWidth = texel * N;
    precise float r = fitBlur.x * N / layerWidth;
    radius = min(min(r, fitBlur.z), pad - fitParams.y);
  }
  fitOut.Store(SDSM_FIT_BLUR + p * 4, asuint(radius));

  // Light view -> clip: x = 2u - 1, y = 1 - 2v, z = depth.
  float4 rowX = float4(fitLightView[0].x, fitLightView[1].x, fitLightView[2].x, fitLightView[3].x);
  float4 rowY = float4(fitLightView[0].y, fitLightView[1].y, fitLightView[2].y, fitLightView[3].y);
  float4 rowZ = float4(fitLightView[0].z, fitLightView[1].z, fitLightView[2].z, fitLightView[3].z);
  uint m = SDSM_FIT_MATRICES + p * 64;
  precise float4 clipX = rowX * (2.0 * scale.x) + float4(0.0, 0.0, 0.0, 2.0 * offset.x - 1.0);
  precise float4 clipY = rowY * (-2.0 * scale.y) + float4(0.0, 0.0, 0.0, 1.0 - 2.0 * offset.y);
  precise float4 clipZ = rowZ * scale.z + float4(0.0, 0.0, 0.0, offset.z);
  StoreRow(m, clipX);
  StoreRow(m + 16, clipY);
  StoreRow(m + 32, clipZ);
  StoreRow(m + 48, float4(0.0, 0.0, 0.0, 1.0));
}
