// Sample Distribution Shadow Maps: GPU-driven shadow-caster culling against the partitions'
// light-space bounds, and the indirect draws that render the survivors, with no CPU readback.
//
// Design: instances are grouped into batches that share one index range (one mesh of the
// scene). For every (partition, batch) the culling pass writes one DrawIndexedInstancedIndirect
// record {IndexCountPerInstance, InstanceCount, StartIndexLocation, BaseVertexLocation, 0}; each
// surviving instance bumps InstanceCount with an atomic on the record and writes its index into
// the (partition, batch) slice of a visible list at the slot the atomic returned. The vertex
// shader reads its instance through that list and a per-instance transform buffer.
//
// Why not the two options of the brief: one record per instance (InstanceCount 0 when culled)
// keeps the CPU issuing one draw per instance per partition, which is the cost GPU culling is
// meant to remove in scenes of many instances of few meshes (the built-in scenes); an append
// buffer with CopyStructureCount compacts, but gives one count per UAV, i.e. one append UAV per
// (partition, batch), and D3D11 has no multi-draw-indirect to spread one count over meshes.
// The atomic on the record is the append buffer's counter placed where the draw reads it (the
// conformance probe "GPU culling: DrawIndexedInstancedIndirect with compute-written args (raw
// view)" checks this pattern on both backends). The CPU issues K x batches draws per frame,
// empty ones included (it does not know which are empty).
//
// Culling test, in light view space (looking down -z): an instance's world box, transformed as a
// box (centre and |R| extent), must overlap the partition box grown by `dilation` in x and y and
// reach at least down to its lowest receiver in z; boxes above the highest receiver still cast
// and are kept (the shadow pass pancakes them).
#pragma once
#include <glm/glm.hpp>
#include <sp/rhi/rhi.h>
#include <vector>

#include <sp/scene/gpu-scene.h>
#include <sp/tech/gpu-timer.h>
#include "sdsm/partitions.h"

namespace sp::tech::sdsm {

class CasterCuller {
 public:
  static constexpr uint32_t kArgsStride = 20;  // bytes per DrawIndexedInstancedIndirect record

  struct Batch {
    uint32_t indexCount = 0, firstIndex = 0;
    int32_t baseVertex = 0;
    uint32_t listOffset = 0;  // first slot of its casters in a partition's visible list
    std::vector<uint32_t> casters;
  };

  // Casters are the scene's draws (scene::GpuScene::draws()), caster i being draws()[i]; builds the
  // instance, batch and transform buffers once. The scene must outlive the culler.
  CasterCuller(Device& device, const scene::GpuScene& scene);

  // Resets the records of `partitionCount` partitions and culls every caster against the bounds in
  // `analysisResults` (a ByteAddressBuffer view of DepthAnalysis::results(), or of any buffer in
  // that layout). lightView: the frame the bounds were reduced in. Unbinds the VS slots t0-t1 the
  // draws use (its outputs are written there) and, at the end, its own compute bindings.
  void Cull(DeviceContext& ctx, ShaderResourceView* analysisResults, const glm::mat4& lightView, uint32_t partitionCount,
            float dilation, GpuTimer* timer = nullptr);

  enum class Shader { DepthOnly, InstanceId };
  // Draws partition p's survivors with one DrawIndexedInstancedIndirect per batch, transformed by
  // viewProj (world -> the partition's clip space). Binds the scene geometry, an input layout, the
  // vertex shader with its constants (b0) and resources (t0, t1). Render targets, viewport,
  // rasterizer and pixel shader are the caller's. InstanceId: the vertex shader also outputs the
  // caster index as `nointerpolation uint INSTANCE` (shaders-hlsl/sdsm/casters.hlsl, VSCasterId).
  // Returns the number of draw calls issued.
  uint32_t DrawPartition(DeviceContext& ctx, uint32_t partition, const glm::mat4& viewProj, Shader shader = Shader::DepthOnly);
  // The same with the world -> clip matrix read on the GPU: four float4 rows at byte
  // `matrixAddress` of `matrices` (a raw view; bound to VS t2, left bound). For partitions whose
  // projection only the GPU knows (the sdsm technique's cull=gpu).
  uint32_t DrawPartition(DeviceContext& ctx, uint32_t partition, ShaderResourceView* matrices, uint32_t matrixAddress);

  uint32_t casterCount() const { return uint32_t(casters_.size()); }
  uint32_t sceneInstance(uint32_t caster) const { return casters_[caster]; }
  const std::vector<Batch>& batches() const { return batches_; }
  // Record of (partition, batch) at byte (partition * batches().size() + batch) * kArgsStride.
  Buffer* args() const { return args_.get(); }
  // Per partition casterCount() slots: the survivors of each batch from listOffset on.
  Buffer* visible() const { return visible_.get(); }

 private:
  const scene::GpuScene& scene_;
  std::vector<uint32_t> casters_;  // caster -> scene instance
  std::vector<Batch> batches_;
  Ref<Buffer> instances_, batchBuffer_, transforms_, visible_, args_, cullConstants_, drawConstants_;
  Ref<ShaderResourceView> instancesSrv_, batchesSrv_, transformsSrv_, visibleSrv_;
  Ref<UnorderedAccessView> visibleUav_, argsUav_;
  Ref<ComputeShader> reset_, cull_;
  uint32_t Draw(DeviceContext& ctx, uint32_t partition, const glm::mat4& viewProj, uint32_t matrixAddress);

  Ref<VertexShader> vs_, vsId_, vsGpu_;
  Ref<InputLayout> layout_, layoutId_, layoutGpu_;
};

}  // namespace sp::tech::sdsm
