// SDSM GPU-driven caster culling and drawing. For each partition and each mesh batch (instances
// sharing one index range), the culling pass writes one DrawIndexedInstancedIndirect record whose
// InstanceCount is the number of instances whose light-space box can cast onto the partition's
// receivers, and compacts their indices into a per-(partition, batch) list; the shadow pass then
// draws each record with the vertex shader below, which finds its instance through that list.
// Nothing is read back: the bounds come from the analysis results on the GPU.
//! cs_5_0 CullReset
//! cs_5_0 CullCasters
//! vs_5_0 VSCaster
//! vs_5_0 VSCasterId
//! vs_5_0 VSCasterGpu
#define SDSM_LAYOUT_ONLY
#include "sdsm/analysis.hlsli"

struct CasterInstance {   // C++: CasterCuller::GpuInstance
  float3 worldMin;
  uint batch;
  float3 worldMax;
  uint pad;
};
struct CasterBatch {      // C++: CasterCuller::GpuBatch
  uint indexCount;
  uint firstIndex;
  int baseVertex;
  uint listOffset;        // first slot of the batch's instances in a partition's list
};

cbuffer SdsmCull : register(b0) {
  float4x4 cullLightView;  // world -> light view, the frame the bounds were reduced in
  uint instanceCount;
  uint batchCount;
  uint cullPartitions;
  float dilation;          // world units added around the bounds, as the shadow matrices do
};

ByteAddressBuffer analysis : register(t0);
StructuredBuffer<CasterInstance> instances : register(t1);
StructuredBuffer<CasterBatch> batches : register(t2);
RWByteAddressBuffer drawArgs : register(u0);       // 5 words per (partition, batch) record
RWStructuredBuffer<uint> visibleOut : register(u1);  // per partition, instanceCount slots

[numthreads(64, 1, 1)]
void CullReset(uint r : SV_DispatchThreadID) {
  if (r >= batchCount * cullPartitions) return;
  CasterBatch b = batches[r % batchCount];
  drawArgs.Store4(r * 20, uint4(b.indexCount, 0u, b.firstIndex, asuint(b.baseVertex)));
  drawArgs.Store(r * 20 + 16, 0u);
}

// x: instance, y: partition.
[numthreads(64, 1, 1)]
void CullCasters(uint3 id : SV_DispatchThreadID) {
  uint i = id.x, p = id.y;
  if (i >= instanceCount || p >= cullPartitions) return;
  uint base = (SDSM_W_BOUNDS + p * 8) * 4;
  if (analysis.Load(base + 12) == 0) return;  // no receiver in this partition
  uint3 minKey = analysis.Load3(base), maxKey = analysis.Load3(base + 16);
  float3 lo = float3(SdsmFromOrderedKey(minKey.x), SdsmFromOrderedKey(minKey.y), SdsmFromOrderedKey(minKey.z)) - dilation;
  float3 hi = float3(SdsmFromOrderedKey(maxKey.x), SdsmFromOrderedKey(maxKey.y), SdsmFromOrderedKey(maxKey.z)) + dilation;

  CasterInstance inst = instances[i];
  float3 centre = (inst.worldMin + inst.worldMax) * 0.5, extent = (inst.worldMax - inst.worldMin) * 0.5;
  float3 c = mul(cullLightView, float4(centre, 1.0)).xyz;
  // |R| extent, row by row: glslang turns abs() of a matrix into invalid SPIR-V.
  float3x3 r = (float3x3)cullLightView;
  float3 e = float3(dot(abs(r[0]), extent), dot(abs(r[1]), extent), dot(abs(r[2]), extent));
  // The light looks down -z: a caster shadows receivers that lie further down (smaller z), so
  // only a box entirely below the lowest receiver is culled in z; boxes above the highest one
  // still cast (the shadow pass clamps them onto its near plane).
  bool overlaps = all(c.xy + e.xy >= lo.xy) && all(c.xy - e.xy <= hi.xy) && c.z + e.z >= lo.z;
  if (!overlaps) return;
  uint record = p * batchCount + inst.batch, slot;
  drawArgs.InterlockedAdd(record * 20 + 4, 1u, slot);
  visibleOut[p * instanceCount + batches[inst.batch].listOffset + slot] = i;
}

// --- Drawing the survivors

struct CasterTransform {  // rows of the instance's world matrix (its last row is 0 0 0 1)
  float4 row0;
  float4 row1;
  float4 row2;
};
StructuredBuffer<CasterTransform> transforms : register(t0);
StructuredBuffer<uint> visible : register(t1);

cbuffer SdsmCasterDraw : register(b0) {
  float4x4 casterViewProj;  // world -> the partition's shadow clip space
  uint listBase;            // partition * instanceCount + the batch's listOffset
  uint matrixAddress;       // VSCasterGpu: byte address of the partition's matrix in partitionMatrices
  uint2 casterPad;
};
// VSCasterGpu: world -> clip matrices written by a compute pass (sdsm cull=gpu: FitPartitions in
// sdsm/fit.hlsl), four float4 rows each, so the CPU never learns the partition's projection.
ByteAddressBuffer partitionMatrices : register(t2);

float4 CasterPosition(float3 pos, uint instance) {
  CasterTransform t = transforms[instance];
  float4 p = float4(pos, 1.0);
  float3 world = float3(dot(t.row0, p), dot(t.row1, p), dot(t.row2, p));
  return mul(casterViewProj, float4(world, 1.0));
}

// SV_InstanceID counts from 0 in every draw (the records' StartInstanceLocation is 0).
float4 VSCaster(float3 pos : POSITION, uint inst : SV_InstanceID) : SV_Position {
  return CasterPosition(pos, visible[listBase + inst]);
}

float4 VSCasterGpu(float3 pos : POSITION, uint inst : SV_InstanceID) : SV_Position {
  CasterTransform t = transforms[visible[listBase + inst]];
  float4 p = float4(pos, 1.0);
  float4 world = float4(dot(t.row0, p), dot(t.row1, p), dot(t.row2, p), 1.0);
  float4 r0 = asfloat(partitionMatrices.Load4(matrixAddress));
  float4 r1 = asfloat(partitionMatrices.Load4(matrixAddress + 16));
  float4 r2 = asfloat(partitionMatrices.Load4(matrixAddress + 32));
  float4 r3 = asfloat(partitionMatrices.Load4(matrixAddress + 48));
  return float4(dot(r0, world), dot(r1, world), dot(r2, world), dot(r3, world));
}

// The same, passing the scene instance index on (for tests and debug views).
struct CasterIdOut {
  float4 position : SV_Position;
  nointerpolation uint instance : INSTANCE;
};
CasterIdOut VSCasterId(float3 pos : POSITION, uint inst : SV_InstanceID) {
  CasterIdOut o;
  uint k = visible[listBase + inst];
  o.position = CasterPosition(pos, k);
  o.instance = k;
  return o;
}
