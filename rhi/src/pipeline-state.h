// The complete D3D11 pipeline state as the core tracks it, and the dirty bits it sets between
// draws (private: the core hands it to backends at draw and dispatch; applications read it back
// with DeviceContext's *Get* calls).
#pragma once
#include <array>

#include <sp/rhi/context.h>

namespace sp::detail {

// Everything bound to one shader stage.
struct StageBindings {
  Ref<Shader> shader;
  std::array<Ref<Buffer>, COMMONSHADER_CONSTANT_BUFFER_API_SLOT_COUNT> constantBuffers;
  std::array<Ref<ShaderResourceView>, COMMONSHADER_INPUT_RESOURCE_SLOT_COUNT> shaderResources;
  // One past the highest shader-resource slot ever set since the state was reset: walks over the
  // bound views (binding a UAV unbinds its SRVs, as D3D11 does) stop there instead of at 128.
  // Only grows, so it never hides a bound view.
  uint32_t shaderResourceEnd = 0;
  std::array<Ref<SamplerState>, COMMONSHADER_SAMPLER_SLOT_COUNT> samplers;
};

struct PipelineState {
  std::array<StageBindings, SHADER_STAGE_COUNT> stages;
  // Output-merger UAVs (pixel shader, OMSetRenderTargetsAndUnorderedAccessViews) and compute UAVs.
  std::array<Ref<UnorderedAccessView>, PS_CS_UAV_REGISTER_COUNT> pixelUavs;
  std::array<Ref<UnorderedAccessView>, PS_CS_UAV_REGISTER_COUNT> computeUavs;

  Ref<InputLayout> inputLayout;
  PRIMITIVE_TOPOLOGY topology = PRIMITIVE_TOPOLOGY_UNDEFINED;
  std::array<Ref<Buffer>, IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT> vertexBuffers;
  std::array<uint32_t, IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT> vertexStrides{};
  std::array<uint32_t, IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT> vertexOffsets{};
  Ref<Buffer> indexBuffer;
  FORMAT indexFormat = FORMAT_UNKNOWN;
  uint32_t indexOffset = 0;

  Ref<RasterizerState> rasterizerState;  // null = D3D11 defaults
  std::array<VIEWPORT, VIEWPORT_AND_SCISSORRECT_OBJECT_COUNT_PER_PIPELINE> viewports{};
  uint32_t numViewports = 0;
  std::array<RECT, VIEWPORT_AND_SCISSORRECT_OBJECT_COUNT_PER_PIPELINE> scissorRects{};
  uint32_t numScissorRects = 0;

  Ref<DepthStencilState> depthStencilState;  // null = D3D11 defaults
  uint32_t stencilRef = 0;
  Ref<BlendState> blendState;                // null = D3D11 defaults
  std::array<float, 4> blendFactor{1, 1, 1, 1};
  uint32_t sampleMask = 0xffffffffu;

  std::array<Ref<RenderTargetView>, SIMULTANEOUS_RENDER_TARGET_COUNT> renderTargets;
  uint32_t numRenderTargets = 0;  // as passed to OMSetRenderTargets
  Ref<DepthStencilView> depthStencil;

  const RASTERIZER_DESC& rasterizer() const;
  const DEPTH_STENCIL_DESC& depthStencilDesc() const;
  // D3D11's depth bias for the next draw, resolved for the driver: enabled for triangles only
  // (wireframe too, never lines or points), the constant DepthBias in the driver's units for the
  // bound depth format (DeviceInfo's measured scales), the clamp as given (CreateRasterizerState
  // refuses a non-zero clamp on a device without depth-bias clamping). Backends only translate it.
  struct DepthBias {
    bool enable = false;
    float constant = 0.0f, slope = 0.0f, clamp = 0.0f;
  };
  DepthBias depthBias(const DeviceInfo& info) const;
  // D3D11 cuts strips at the all-ones index (0xffff / 0xffffffff: "generating multiple strips").
  // Lists read it as an ordinary index on both backends: Vulkan restarts lists only with
  // VK_EXT_primitive_topology_list_restart, and llvmpipe scans every index of a draw while
  // GL's restart is on.
  bool cutsAtAllOnesIndex() const { return topology == PRIMITIVE_TOPOLOGY_TRIANGLESTRIP || topology == PRIMITIVE_TOPOLOGY_LINESTRIP; }
  const BLEND_DESC& blend() const;
  StageBindings& stage(ShaderStage s) { return stages[size_t(s)]; }
  const StageBindings& stage(ShaderStage s) const { return stages[size_t(s)]; }
  std::array<Ref<UnorderedAccessView>, PS_CS_UAV_REGISTER_COUNT>& uavs(ShaderStage s) {
    return s == ShaderStage::Compute ? computeUavs : pixelUavs;
  }
};

// Dirty bits the core sets between draws so backends rebuild only what changed.
enum DirtyFlag : uint32_t {
  DIRTY_SHADERS = 1u << 0,
  DIRTY_INPUT_LAYOUT = 1u << 1,  // layout or topology
  DIRTY_VERTEX_BUFFERS = 1u << 2,
  DIRTY_INDEX_BUFFER = 1u << 3,
  DIRTY_RASTERIZER = 1u << 4,
  DIRTY_VIEWPORTS = 1u << 5,  // viewports or scissors
  DIRTY_DEPTH_STENCIL = 1u << 6,
  DIRTY_BLEND = 1u << 7,
  DIRTY_RENDER_TARGETS = 1u << 8,
  DIRTY_BINDINGS_VS = 1u << 9,  // cbuffers, SRVs, samplers of a stage: 1 << (9 + stage)
  DIRTY_BINDINGS_PS = 1u << 10,
  DIRTY_BINDINGS_GS = 1u << 11,
  DIRTY_BINDINGS_CS = 1u << 12,
  DIRTY_PIXEL_UAVS = 1u << 13,
  DIRTY_COMPUTE_UAVS = 1u << 14,
  DIRTY_ALL = 0xffffffffu,
};

}  // namespace sp::detail
