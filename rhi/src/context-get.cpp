// D3D11's *Get* calls: the bound state back, as the application set it (null where nothing is
// bound; the core's stand-ins for unbound registers never show here).
#include "context-internal.h"
#include "validate.h"

namespace sp {
using namespace detail;
namespace {

void CheckRange(uint32_t start, uint32_t num, uint32_t limit, const char* call, const char* what) {
  if (uint64_t(start) + num > limit)
    Fail(ErrorId::SLOT_OUT_OF_RANGE, call, what,
         "slots [" + std::to_string(start) + ", " + std::to_string(uint64_t(start) + num) + ") exceed the " + std::to_string(limit) + " available");
}

template <class T, class Slots>
void CopyOut(const Slots& slots, uint32_t start, uint32_t num, const OutPtr<T>& out) {
  for (uint32_t i = 0; i < num; ++i) out.Set(i, slots[start + i]);
}

template <class T>
void GetShaderOf(const PipelineState& s, ShaderStage stage, const OutPtr<T>& out, ClassInstance** instances, uint32_t* numInstances) {
  out.Set(std::static_pointer_cast<T>(s.stage(stage).shader));
  // No class instances are ever bound (class linkage is not supported).
  if (numInstances) {
    if (instances)
      for (uint32_t i = 0; i < *numInstances; ++i) instances[i] = nullptr;
    *numInstances = 0;
  }
}

}  // namespace

void DeviceContext::IAGetInputLayout(OutPtr<InputLayout> layout) const { layout.Set(state_->inputLayout); }

void DeviceContext::IAGetPrimitiveTopology(PRIMITIVE_TOPOLOGY* topology) const {
  if (topology) *topology = state_->topology;
}

void DeviceContext::IAGetVertexBuffers(uint32_t start, uint32_t num, OutPtr<Buffer> buffers, uint32_t* strides, uint32_t* offsets) const {
  CheckRange(start, num, IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT, "IAGetVertexBuffers", "vertex buffer slots");
  CopyOut(state_->vertexBuffers, start, num, buffers);
  for (uint32_t i = 0; i < num; ++i) {
    if (strides) strides[i] = state_->vertexStrides[start + i];
    if (offsets) offsets[i] = state_->vertexOffsets[start + i];
  }
}

void DeviceContext::IAGetIndexBuffer(OutPtr<Buffer> buffer, FORMAT* format, uint32_t* offset) const {
  buffer.Set(state_->indexBuffer);
  if (format) *format = state_->indexFormat;
  if (offset) *offset = state_->indexOffset;
}

void DeviceContext::VSGetShader(OutPtr<VertexShader> s, ClassInstance** ci, uint32_t* n) const { GetShaderOf(*state_, ShaderStage::Vertex, s, ci, n); }
void DeviceContext::PSGetShader(OutPtr<PixelShader> s, ClassInstance** ci, uint32_t* n) const { GetShaderOf(*state_, ShaderStage::Pixel, s, ci, n); }
void DeviceContext::GSGetShader(OutPtr<GeometryShader> s, ClassInstance** ci, uint32_t* n) const { GetShaderOf(*state_, ShaderStage::Geometry, s, ci, n); }
void DeviceContext::CSGetShader(OutPtr<ComputeShader> s, ClassInstance** ci, uint32_t* n) const { GetShaderOf(*state_, ShaderStage::Compute, s, ci, n); }

void DeviceContext::GetConstantBuffers(ShaderStage stage, uint32_t start, uint32_t num, OutPtr<Buffer> out, const char* call) const {
  CheckRange(start, num, COMMONSHADER_CONSTANT_BUFFER_API_SLOT_COUNT, call, "constant buffer slots");
  CopyOut(state_->stage(stage).constantBuffers, start, num, out);
}

void DeviceContext::GetShaderResources(ShaderStage stage, uint32_t start, uint32_t num, OutPtr<ShaderResourceView> out, const char* call) const {
  CheckRange(start, num, COMMONSHADER_INPUT_RESOURCE_SLOT_COUNT, call, "shader resource slots");
  CopyOut(state_->stage(stage).shaderResources, start, num, out);
}

void DeviceContext::GetSamplers(ShaderStage stage, uint32_t start, uint32_t num, OutPtr<SamplerState> out, const char* call) const {
  CheckRange(start, num, COMMONSHADER_SAMPLER_SLOT_COUNT, call, "sampler slots");
  CopyOut(state_->stage(stage).samplers, start, num, out);
}

void DeviceContext::CSGetUnorderedAccessViews(uint32_t start, uint32_t num, OutPtr<UnorderedAccessView> views) const {
  CheckRange(start, num, PS_CS_UAV_REGISTER_COUNT, "CSGetUnorderedAccessViews", "UAV slots");
  CopyOut(state_->computeUavs, start, num, views);
}

void DeviceContext::RSGetState(OutPtr<RasterizerState> state) const { state.Set(state_->rasterizerState); }

void DeviceContext::RSGetViewports(uint32_t* num, VIEWPORT* viewports) const {
  if (!num) Fail(ErrorId::INVALID_ARGUMENT, "RSGetViewports", "viewports", "pNumViewports is null");
  if (!viewports) {
    *num = state_->numViewports;
    return;
  }
  for (uint32_t i = 0; i < *num && i < VIEWPORT_AND_SCISSORRECT_OBJECT_COUNT_PER_PIPELINE; ++i)
    viewports[i] = i < state_->numViewports ? state_->viewports[i] : VIEWPORT{0, 0, 0, 0, 0, 0};
}

void DeviceContext::RSGetScissorRects(uint32_t* num, RECT* rects) const {
  if (!num) Fail(ErrorId::INVALID_ARGUMENT, "RSGetScissorRects", "scissor rects", "pNumRects is null");
  if (!rects) {
    *num = state_->numScissorRects;
    return;
  }
  for (uint32_t i = 0; i < *num && i < VIEWPORT_AND_SCISSORRECT_OBJECT_COUNT_PER_PIPELINE; ++i)
    rects[i] = i < state_->numScissorRects ? state_->scissorRects[i] : RECT{};
}

void DeviceContext::OMGetRenderTargets(uint32_t numViews, OutPtr<RenderTargetView> rtvs, OutPtr<DepthStencilView> dsv) const {
  CheckRange(0, numViews, SIMULTANEOUS_RENDER_TARGET_COUNT, "OMGetRenderTargets", "render targets");
  CopyOut(state_->renderTargets, 0, numViews, rtvs);
  dsv.Set(state_->depthStencil);
}

void DeviceContext::OMGetRenderTargetsAndUnorderedAccessViews(uint32_t numRTVs, OutPtr<RenderTargetView> rtvs, OutPtr<DepthStencilView> dsv,
                                                              uint32_t uavStart, uint32_t numUAVs, OutPtr<UnorderedAccessView> uavs) const {
  const char* call = "OMGetRenderTargetsAndUnorderedAccessViews";
  CheckRange(0, numRTVs, SIMULTANEOUS_RENDER_TARGET_COUNT, call, "render targets");
  CheckRange(uavStart, numUAVs, PS_CS_UAV_REGISTER_COUNT, call, "UAV slots");
  CopyOut(state_->renderTargets, 0, numRTVs, rtvs);
  dsv.Set(state_->depthStencil);
  CopyOut(state_->pixelUavs, uavStart, numUAVs, uavs);
}

void DeviceContext::OMGetDepthStencilState(OutPtr<DepthStencilState> state, uint32_t* stencilRef) const {
  state.Set(state_->depthStencilState);
  if (stencilRef) *stencilRef = state_->stencilRef;
}

void DeviceContext::OMGetBlendState(OutPtr<BlendState> state, float blendFactor[4], uint32_t* sampleMask) const {
  state.Set(state_->blendState);
  if (blendFactor)
    for (int i = 0; i < 4; ++i) blendFactor[i] = state_->blendFactor[i];
  if (sampleMask) *sampleMask = state_->sampleMask;
}

}  // namespace sp
