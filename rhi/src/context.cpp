// The immediate context's D3D11 front end: argument checks, state tracking, then one call into
// the backend. Hazard rules are in context-hazards.cpp, draw-time checks in context-validate.cpp.
#include <sp/rhi/context.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "context-internal.h"
#include "validate.h"

namespace sp {

static const RASTERIZER_DESC kDefaultRasterizer{};
static const DEPTH_STENCIL_DESC kDefaultDepthStencil{};
static const BLEND_DESC kDefaultBlend{};

namespace detail {
const RASTERIZER_DESC& PipelineState::rasterizer() const { return rasterizerState ? rasterizerState->GetDesc() : kDefaultRasterizer; }
const DEPTH_STENCIL_DESC& PipelineState::depthStencilDesc() const {
  return depthStencilState ? depthStencilState->GetDesc() : kDefaultDepthStencil;
}
const BLEND_DESC& PipelineState::blend() const { return blendState ? blendState->GetDesc() : kDefaultBlend; }

PipelineState::DepthBias PipelineState::depthBias(const DeviceInfo& info) const {
  const RASTERIZER_DESC& r = rasterizer();
  DepthBias b;
  const bool triangles = topology == PRIMITIVE_TOPOLOGY_TRIANGLELIST || topology == PRIMITIVE_TOPOLOGY_TRIANGLESTRIP;
  b.enable = triangles && (r.DepthBias != 0 || r.SlopeScaledDepthBias != 0.0f);
  if (!b.enable) return b;
  float scale = info.depthBiasScaleD32;
  if (depthStencil) {
    FORMAT f = depthStencil->ViewFormat();
    if (f == FORMAT_D16_UNORM) scale = info.depthBiasScaleD16;
    else if (f == FORMAT_D24_UNORM_S8_UINT) scale = info.depthBiasScaleD24;
  }
  b.constant = float(r.DepthBias) * scale;
  b.slope = r.SlopeScaledDepthBias;
  b.clamp = r.DepthBiasClamp;
  return b;
}
}  // namespace detail

using namespace detail;

std::string SlotName(ShaderStage stage, char cls, uint32_t slot) {
  return std::string(ShaderStagePrefix(stage)) + " slot " + cls + std::to_string(slot);
}

DeviceContext::DeviceContext(Device* device, std::unique_ptr<detail::ContextBackend> backend)
    : device_(device), backend_(std::move(backend)), state_(std::make_unique<PipelineState>()), dirty_(DIRTY_ALL) {}

DeviceContext::~DeviceContext() = default;

uint32_t DeviceContext::Release() {
  if (comRefs_ == 0)
    throw Error(ErrorId::INVALID_ARGUMENT, "Release", "DeviceContext",
                "the immediate context holds no COM reference (Release without GetImmediateContext(&ctx), or once too often)");
  return --comRefs_;
}

static void CheckOwner(Device* device, const Object* o, const char* call) {
  if (o && o->GetDevice() != device) Fail(ErrorId::INVALID_ARGUMENT, call, Describe(o), "the object belongs to another device (or outlived its device)");
}

static void CheckSlots(uint32_t start, uint32_t num, uint32_t limit, const char* call, const char* what) {
  if (uint64_t(start) + num > limit)
    Fail(ErrorId::SLOT_OUT_OF_RANGE, call, what,
         "slots [" + std::to_string(start) + ", " + std::to_string(uint64_t(start) + num) + ") exceed the " + std::to_string(limit) + " available");
}

// ---------------------------------------------------------------------------------------------
// Input assembler

void DeviceContext::IASetInputLayout(InputLayout* layout) {
  CheckOwner(device_, layout, "IASetInputLayout");
  state_->inputLayout = RefOf(layout);
  dirty_ |= DIRTY_INPUT_LAYOUT;
}

void DeviceContext::IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY t) {
  if (t > PRIMITIVE_TOPOLOGY_TRIANGLESTRIP)
    Fail(ErrorId::NOT_SUPPORTED, "IASetPrimitiveTopology", "topology " + std::to_string(uint32_t(t)),
         "supported topologies: POINTLIST, LINELIST, LINESTRIP, TRIANGLELIST, TRIANGLESTRIP");
  state_->topology = t;
  dirty_ |= DIRTY_INPUT_LAYOUT;
}

void DeviceContext::IASetVertexBuffers(uint32_t start, uint32_t num, Buffer* const* buffers, const uint32_t* strides, const uint32_t* offsets) {
  const char* call = "IASetVertexBuffers";
  CheckSlots(start, num, IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT, call, "vertex buffer slots");
  if (num && (!buffers || !strides || !offsets)) Fail(ErrorId::INVALID_ARGUMENT, call, "vertex buffers", "ppVertexBuffers, pStrides and pOffsets must not be null");
  for (uint32_t i = 0; i < num; ++i) {
    Buffer* b = buffers[i];
    CheckOwner(device_, b, call);
    if (b && !(b->GetDesc().BindFlags & BIND_VERTEX_BUFFER))
      Fail(ErrorId::BIND_FLAGS_INVALID, call, Describe(b), "the buffer was not created with BIND_VERTEX_BUFFER");
    b = detail::ContextHazards::FilterInputBuffer(*this, b, call, "vertex buffer slot", start + i);
    state_->vertexBuffers[start + i] = RefOf(b);
    state_->vertexStrides[start + i] = strides[i];
    state_->vertexOffsets[start + i] = offsets[i];
  }
  dirty_ |= DIRTY_VERTEX_BUFFERS;
}

void DeviceContext::IASetIndexBuffer(Buffer* b, FORMAT format, uint32_t offset) {
  const char* call = "IASetIndexBuffer";
  CheckOwner(device_, b, call);
  if (b && !(b->GetDesc().BindFlags & BIND_INDEX_BUFFER))
    Fail(ErrorId::BIND_FLAGS_INVALID, call, Describe(b), "the buffer was not created with BIND_INDEX_BUFFER");
  if (b && format != FORMAT_R16_UINT && format != FORMAT_R32_UINT)
    Fail(ErrorId::FORMAT_UNSUPPORTED, call, Describe(b), "index format must be R16_UINT or R32_UINT (got " + std::string(FormatName(format)) + ")");
  if (b && offset % (format == FORMAT_R16_UINT ? 2 : 4))
    Fail(ErrorId::INVALID_ARGUMENT, call, Describe(b), "offset must be a multiple of the index size");
  b = detail::ContextHazards::FilterInputBuffer(*this, b, call, "index buffer", 0);
  state_->indexBuffer = RefOf(b);
  state_->indexFormat = format;
  state_->indexOffset = offset;
  dirty_ |= DIRTY_INDEX_BUFFER;
}

// ---------------------------------------------------------------------------------------------
// Shader stages

void DeviceContext::SetShader(ShaderStage stage, Shader* shader, ClassInstance* const* instances, uint32_t numInstances, const char* call) {
  CheckOwner(device_, shader, call);
  if (instances || numInstances)
    Fail(ErrorId::NOT_SUPPORTED, call, Describe(shader),
         "D3D11 class linkage (dynamic shader linkage) is not supported: pass ppClassInstances = NULL and NumClassInstances = 0");
  if (shader && shader->Stage() != stage) Fail(ErrorId::SHADER_STAGE_MISMATCH, call, Describe(shader), "wrong stage");
  state_->stage(stage).shader = RefOf(shader);
  dirty_ |= DIRTY_SHADERS | (DIRTY_BINDINGS_VS << uint32_t(stage));
}

void DeviceContext::VSSetShader(VertexShader* s, ClassInstance* const* ci, uint32_t n) { SetShader(ShaderStage::Vertex, s, ci, n, "VSSetShader"); }
void DeviceContext::PSSetShader(PixelShader* s, ClassInstance* const* ci, uint32_t n) { SetShader(ShaderStage::Pixel, s, ci, n, "PSSetShader"); }
void DeviceContext::GSSetShader(GeometryShader* s, ClassInstance* const* ci, uint32_t n) { SetShader(ShaderStage::Geometry, s, ci, n, "GSSetShader"); }
void DeviceContext::CSSetShader(ComputeShader* s, ClassInstance* const* ci, uint32_t n) { SetShader(ShaderStage::Compute, s, ci, n, "CSSetShader"); }

void DeviceContext::SetConstantBuffers(ShaderStage stage, uint32_t start, uint32_t num, Buffer* const* buffers, const char* call) {
  CheckSlots(start, num, COMMONSHADER_CONSTANT_BUFFER_API_SLOT_COUNT, call, "constant buffer slots");
  if (num && !buffers) Fail(ErrorId::INVALID_ARGUMENT, call, "constant buffers", "ppConstantBuffers is null");
  for (uint32_t i = 0; i < num; ++i) {
    Buffer* b = buffers[i];
    CheckOwner(device_, b, call);
    if (b && !(b->GetDesc().BindFlags & BIND_CONSTANT_BUFFER))
      Fail(ErrorId::BIND_FLAGS_INVALID, call, Describe(b), "the buffer was not created with BIND_CONSTANT_BUFFER");
    state_->stage(stage).constantBuffers[start + i] = RefOf(b);
  }
  dirty_ |= DIRTY_BINDINGS_VS << uint32_t(stage);
}

void DeviceContext::SetShaderResources(ShaderStage stage, uint32_t start, uint32_t num, ShaderResourceView* const* views, const char* call) {
  CheckSlots(start, num, COMMONSHADER_INPUT_RESOURCE_SLOT_COUNT, call, "shader resource slots");
  if (num && !views) Fail(ErrorId::INVALID_ARGUMENT, call, "shader resources", "ppShaderResourceViews is null");
  for (uint32_t i = 0; i < num; ++i) {
    CheckOwner(device_, views[i], call);
    ShaderResourceView* v = detail::ContextHazards::FilterInput(*this, views[i], call, stage, start + i);
    state_->stage(stage).shaderResources[start + i] = RefOf(v);
  }
  uint32_t& end = state_->stage(stage).shaderResourceEnd;
  end = std::max(end, start + num);
  dirty_ |= DIRTY_BINDINGS_VS << uint32_t(stage);
}

void DeviceContext::SetSamplers(ShaderStage stage, uint32_t start, uint32_t num, SamplerState* const* samplers, const char* call) {
  CheckSlots(start, num, COMMONSHADER_SAMPLER_SLOT_COUNT, call, "sampler slots");
  if (num && !samplers) Fail(ErrorId::INVALID_ARGUMENT, call, "samplers", "ppSamplers is null");
  for (uint32_t i = 0; i < num; ++i) {
    CheckOwner(device_, samplers[i], call);
    state_->stage(stage).samplers[start + i] = RefOf(samplers[i]);
  }
  dirty_ |= DIRTY_BINDINGS_VS << uint32_t(stage);
}

void DeviceContext::CSSetUnorderedAccessViews(uint32_t start, uint32_t num, UnorderedAccessView* const* views, const uint32_t* initialCounts) {
  const char* call = "CSSetUnorderedAccessViews";
  CheckSlots(start, num, PS_CS_UAV_REGISTER_COUNT, call, "UAV slots");
  if (num && !views) Fail(ErrorId::INVALID_ARGUMENT, call, "UAVs", "ppUnorderedAccessViews is null");
  for (uint32_t i = 0; i < num; ++i) {
    UnorderedAccessView* v = views[i];
    CheckOwner(device_, v, call);
    state_->computeUavs[start + i].reset();
    if (v) detail::ContextHazards::UnbindForOutput(*this, v, true, call);
    state_->computeUavs[start + i] = RefOf(v);
    if (v && initialCounts && initialCounts[i] != 0xffffffffu) {
      if (v->GetDesc().ViewDimension == UAV_DIMENSION_BUFFER &&
          (v->GetDesc().Buffer.Flags & (BUFFER_UAV_FLAG_APPEND | BUFFER_UAV_FLAG_COUNTER)))
        backend_->SetUavCounter(v, initialCounts[i]);
    }
  }
  dirty_ |= DIRTY_COMPUTE_UAVS;
}

// ---------------------------------------------------------------------------------------------
// Rasterizer and output merger

void DeviceContext::RSSetState(RasterizerState* s) {
  CheckOwner(device_, s, "RSSetState");
  state_->rasterizerState = RefOf(s);
  dirty_ |= DIRTY_RASTERIZER;
}

void DeviceContext::RSSetViewports(uint32_t num, const VIEWPORT* vps) {
  const char* call = "RSSetViewports";
  CheckSlots(0, num, VIEWPORT_AND_SCISSORRECT_OBJECT_COUNT_PER_PIPELINE, call, "viewports");
  if (num && !vps) Fail(ErrorId::INVALID_ARGUMENT, call, "viewports", "pViewports is null");
  for (uint32_t i = 0; i < num; ++i) {
    const VIEWPORT& v = vps[i];
    std::string obj = "viewport " + std::to_string(i);
    if (!(v.Width >= 0 && v.Height >= 0) || v.Width > 32768 || v.Height > 32768)
      Fail(ErrorId::INVALID_ARGUMENT, call, obj, "Width and Height must be in [0, 32768]");
    if (!(v.MinDepth >= 0 && v.MinDepth <= 1 && v.MaxDepth >= 0 && v.MaxDepth <= 1))
      Fail(ErrorId::INVALID_ARGUMENT, call, obj, "MinDepth and MaxDepth must be in [0, 1]");
    if (!std::isfinite(v.TopLeftX) || !std::isfinite(v.TopLeftY)) Fail(ErrorId::INVALID_ARGUMENT, call, obj, "TopLeftX/Y must be finite");
    state_->viewports[i] = v;
  }
  state_->numViewports = num;
  dirty_ |= DIRTY_VIEWPORTS;
}

void DeviceContext::RSSetScissorRects(uint32_t num, const RECT* rects) {
  const char* call = "RSSetScissorRects";
  CheckSlots(0, num, VIEWPORT_AND_SCISSORRECT_OBJECT_COUNT_PER_PIPELINE, call, "scissor rects");
  if (num && !rects) Fail(ErrorId::INVALID_ARGUMENT, call, "scissor rects", "pRects is null");
  for (uint32_t i = 0; i < num; ++i) state_->scissorRects[i] = rects[i];
  state_->numScissorRects = num;
  dirty_ |= DIRTY_VIEWPORTS;
}

void DeviceContext::OMSetRenderTargets(uint32_t num, RenderTargetView* const* rtvs, DepthStencilView* dsv) {
  OMSetRenderTargetsAndUnorderedAccessViews(num, rtvs, dsv, 0, KEEP_UNORDERED_ACCESS_VIEWS, nullptr, nullptr);
}

void DeviceContext::OMSetRenderTargetsAndUnorderedAccessViews(uint32_t numRTVs, RenderTargetView* const* rtvs, DepthStencilView* dsv,
                                                              uint32_t uavStart, uint32_t numUAVs, UnorderedAccessView* const* uavs,
                                                              const uint32_t* initialCounts) {
  const char* call = numUAVs == KEEP_UNORDERED_ACCESS_VIEWS ? "OMSetRenderTargets" : "OMSetRenderTargetsAndUnorderedAccessViews";
  if (numRTVs != KEEP_RENDER_TARGETS_AND_DEPTH_STENCIL) {
    CheckSlots(0, numRTVs, SIMULTANEOUS_RENDER_TARGET_COUNT, call, "render targets");
    if (numRTVs && !rtvs) Fail(ErrorId::INVALID_ARGUMENT, call, "render targets", "ppRenderTargetViews is null");
    // D3D11: every bound target must have the same size, array size and sample count.
    const View* first = nullptr;
    uint32_t w = 0, h = 0, samples = 0, slices = 0;
    auto checkSize = [&](const View* v) {
      CheckOwner(device_, v, call);
      const Texture* t = AsTexture(v->GetResource());
      uint32_t vw = t->Shape().mipWidth(v->Range().firstMip), vh = t->Shape().mipHeight(v->Range().firstMip);
      if (!first) {
        first = v, w = vw, h = vh, samples = t->Shape().sampleCount, slices = v->Range().sliceCount;
        return;
      }
      if (t->Shape().sampleCount != samples)
        Fail(ErrorId::SAMPLE_COUNT_MISMATCH, call, Describe(v),
             std::to_string(t->Shape().sampleCount) + "x MSAA does not match " + Describe(first) + " (" + std::to_string(samples) + "x)");
      if (vw != w || vh != h || v->Range().sliceCount != slices)
        Fail(ErrorId::OUTPUT_MISMATCH, call, Describe(v), "size " + std::to_string(vw) + "x" + std::to_string(vh) + " does not match " +
                                                            Describe(first) + " (" + std::to_string(w) + "x" + std::to_string(h) + ")");
    };
    for (uint32_t i = 0; i < numRTVs; ++i)
      if (rtvs[i]) checkSize(rtvs[i]);
    if (dsv) checkSize(dsv);
    for (uint32_t i = 0; i < numRTVs; ++i)
      for (uint32_t j = 0; j < i; ++j)
        if (rtvs[i] && rtvs[j] && detail::ContextHazards::ViewWritesOverlap(rtvs[i], rtvs[j]))
          Fail(ErrorId::OUTPUT_MISMATCH, call, Describe(rtvs[i]), "the same subresource is bound to render targets " + std::to_string(j) + " and " + std::to_string(i));

    for (auto& r : state_->renderTargets) r.reset();
    state_->depthStencil.reset();
    for (uint32_t i = 0; i < numRTVs; ++i)
      if (rtvs[i]) detail::ContextHazards::UnbindForOutput(*this, rtvs[i], false, call);
    if (dsv) detail::ContextHazards::UnbindForOutput(*this, dsv, false, call);
    for (uint32_t i = 0; i < numRTVs; ++i) state_->renderTargets[i] = RefOf(rtvs[i]);
    state_->numRenderTargets = numRTVs;
    state_->depthStencil = RefOf(dsv);
    dirty_ |= DIRTY_RENDER_TARGETS;
  }
  if (numUAVs != KEEP_UNORDERED_ACCESS_VIEWS) {
    uint32_t rtCount = numRTVs == KEEP_RENDER_TARGETS_AND_DEPTH_STENCIL ? state_->numRenderTargets : numRTVs;
    if (numUAVs && uavStart < rtCount)
      Fail(ErrorId::OUTPUT_MISMATCH, call, "UAVs", "UAVStartSlot (" + std::to_string(uavStart) + ") must not be below the number of render targets (" + std::to_string(rtCount) + ")");
    CheckSlots(uavStart, numUAVs, PS_CS_UAV_REGISTER_COUNT, call, "UAV slots");
    if (numUAVs && !uavs) Fail(ErrorId::INVALID_ARGUMENT, call, "UAVs", "ppUnorderedAccessViews is null");
    for (auto& u : state_->pixelUavs) u.reset();
    for (uint32_t i = 0; i < numUAVs; ++i) {
      UnorderedAccessView* v = uavs[i];
      CheckOwner(device_, v, call);
      if (v) detail::ContextHazards::UnbindForOutput(*this, v, false, call);
      state_->pixelUavs[uavStart + i] = RefOf(v);
      if (v && initialCounts && initialCounts[i] != 0xffffffffu && v->GetDesc().ViewDimension == UAV_DIMENSION_BUFFER &&
          (v->GetDesc().Buffer.Flags & (BUFFER_UAV_FLAG_APPEND | BUFFER_UAV_FLAG_COUNTER)))
        backend_->SetUavCounter(v, initialCounts[i]);
    }
    dirty_ |= DIRTY_PIXEL_UAVS;
  }
}

void DeviceContext::OMSetDepthStencilState(DepthStencilState* s, uint32_t stencilRef) {
  CheckOwner(device_, s, "OMSetDepthStencilState");
  state_->depthStencilState = RefOf(s);
  state_->stencilRef = stencilRef;
  dirty_ |= DIRTY_DEPTH_STENCIL;
}

void DeviceContext::OMSetBlendState(BlendState* s, const float blendFactor[4], uint32_t sampleMask) {
  CheckOwner(device_, s, "OMSetBlendState");
  state_->blendState = RefOf(s);
  state_->blendFactor = blendFactor ? std::array<float, 4>{blendFactor[0], blendFactor[1], blendFactor[2], blendFactor[3]}
                                   : std::array<float, 4>{1, 1, 1, 1};
  state_->sampleMask = sampleMask;
  dirty_ |= DIRTY_BLEND;
}

// ---------------------------------------------------------------------------------------------
// Draw and dispatch

namespace {
constexpr uint32_t kComputeInputs = DIRTY_BINDINGS_CS | DIRTY_COMPUTE_UAVS;
constexpr uint32_t kDrawInputs = DIRTY_ALL & ~kComputeInputs;
}  // namespace

// A draw's validation depends only on the bound state and on whether it is indexed, so after a
// draw that passed with nothing unbound and no warning, only the rules reading state that changed
// since (its dirty bits) run again, and none when nothing changed: per-draw constant updates
// (Map, UpdateSubresource) change contents, never bindings. This keeps the per-draw cost near a
// raw API's.
void DeviceContext::DoDraw(const detail::DrawArgs& args, const char* call) {
  const bool indexed = args.kind == detail::DrawArgs::DrawIndexed || args.kind == detail::DrawArgs::DrawIndexedInstancedIndirect;
  const uint8_t kind = indexed ? 2 : 1;
  std::vector<UnboundRead> unbound;
  bool repeatable = true;
  const uint32_t recheck = validDraw_ == kind ? dirty_ & kDrawInputs : uint32_t(DIRTY_ALL);
  if (recheck) repeatable = DrawValidator::CheckDraw(*this, args, call, unbound, recheck);
  // D3D11 rasterizes nothing into a viewport of zero width or height (Vulkan forbids one; none set
  // at all is refused by the validator above). The state stays dirty for the next draw.
  const VIEWPORT& vp = state_->viewports[0];
  if (!(vp.Width > 0 && vp.Height > 0)) return;
  // Built only when a register is unbound: constructing and destroying it was about 100
  // instructions of every draw (docs/rhi-cost.md).
  std::optional<NullBindings> nulls;
  if (!unbound.empty()) nulls.emplace(*this, unbound);
  validDraw_ = 0;
  backend_->Draw(*state_, dirty_ | (nulls ? nulls->Dirty() : 0u), args);
  // The compute bits stay for the next dispatch, whose backend has not seen them.
  dirty_ &= kComputeInputs;
  validDraw_ = repeatable && unbound.empty() ? kind : 0;
}

void DeviceContext::DoDispatch(uint32_t x, uint32_t y, uint32_t z, Buffer* argsBuffer, uint32_t argsOffset, const char* call) {
  std::vector<UnboundRead> unbound;
  bool repeatable = true;
  if ((dirty_ & kComputeInputs) || !validDispatch_) repeatable = DrawValidator::CheckDispatch(*this, call, unbound);
  std::optional<NullBindings> nulls;
  if (!unbound.empty()) nulls.emplace(*this, unbound);
  // An empty dispatch records nothing: the backend has not seen the state, which stays dirty.
  if (!argsBuffer && !(x && y && z)) return;
  validDispatch_ = false;
  backend_->Dispatch(*state_, dirty_ | (nulls ? nulls->Dirty() : 0u), x, y, z, argsBuffer, argsOffset);
  dirty_ &= ~kComputeInputs;
  validDispatch_ = repeatable && unbound.empty();
}

void DeviceContext::Draw(uint32_t vertexCount, uint32_t startVertex) {
  detail::DrawArgs a;
  a.kind = detail::DrawArgs::Draw;
  a.count = vertexCount;
  a.start = startVertex;
  DoDraw(a, "Draw");
}

void DeviceContext::DrawIndexed(uint32_t indexCount, uint32_t startIndex, int32_t baseVertex) {
  detail::DrawArgs a;
  a.kind = detail::DrawArgs::DrawIndexed;
  a.count = indexCount;
  a.start = startIndex;
  a.baseVertex = baseVertex;
  DoDraw(a, "DrawIndexed");
}

void DeviceContext::DrawInstanced(uint32_t vertexCount, uint32_t instanceCount, uint32_t startVertex, uint32_t startInstance) {
  detail::DrawArgs a;
  a.kind = detail::DrawArgs::Draw;
  a.count = vertexCount;
  a.instanceCount = instanceCount;
  a.start = startVertex;
  a.startInstance = startInstance;
  DoDraw(a, "DrawInstanced");
}

void DeviceContext::DrawIndexedInstanced(uint32_t indexCount, uint32_t instanceCount, uint32_t startIndex, int32_t baseVertex,
                                         uint32_t startInstance) {
  detail::DrawArgs a;
  a.kind = detail::DrawArgs::DrawIndexed;
  a.count = indexCount;
  a.instanceCount = instanceCount;
  a.start = startIndex;
  a.baseVertex = baseVertex;
  a.startInstance = startInstance;
  DoDraw(a, "DrawIndexedInstanced");
}

static void CheckArgsBuffer(Device* device, Buffer* b, uint32_t offset, uint32_t size, const char* call) {
  if (!b) Fail(ErrorId::INVALID_ARGUMENT, call, "null", "pBufferForArgs is null");
  CheckOwner(device, b, call);
  if (!(b->GetDesc().MiscFlags & RESOURCE_MISC_DRAWINDIRECT_ARGS))
    Fail(ErrorId::BIND_FLAGS_INVALID, call, Describe(b), "the buffer was not created with RESOURCE_MISC_DRAWINDIRECT_ARGS");
  if (offset % 4) Fail(ErrorId::INVALID_ARGUMENT, call, Describe(b), "AlignedByteOffsetForArgs must be a multiple of 4");
  if (uint64_t(offset) + size > b->GetDesc().ByteWidth)
    Fail(ErrorId::SUBRESOURCE_OUT_OF_RANGE, call, Describe(b), std::to_string(size) + " bytes of arguments at offset " + std::to_string(offset) + " exceed the buffer");
}

void DeviceContext::DrawInstancedIndirect(Buffer* args, uint32_t offset) {
  CheckArgsBuffer(device_, args, offset, 16, "DrawInstancedIndirect");
  detail::DrawArgs a;
  a.kind = detail::DrawArgs::DrawInstancedIndirect;
  a.argsBuffer = args;
  a.argsOffset = offset;
  DoDraw(a, "DrawInstancedIndirect");
}

void DeviceContext::DrawIndexedInstancedIndirect(Buffer* args, uint32_t offset) {
  CheckArgsBuffer(device_, args, offset, 20, "DrawIndexedInstancedIndirect");
  detail::DrawArgs a;
  a.kind = detail::DrawArgs::DrawIndexedInstancedIndirect;
  a.argsBuffer = args;
  a.argsOffset = offset;
  DoDraw(a, "DrawIndexedInstancedIndirect");
}

void DeviceContext::Dispatch(uint32_t x, uint32_t y, uint32_t z) {
  if (x > 65535 || y > 65535 || z > 65535)
    Fail(ErrorId::INVALID_ARGUMENT, "Dispatch", "thread groups", "each dimension must be at most 65535 (D3D11_CS_DISPATCH_MAX_THREAD_GROUPS_PER_DIMENSION)");
  DoDispatch(x, y, z, nullptr, 0, "Dispatch");
}

void DeviceContext::DispatchIndirect(Buffer* args, uint32_t offset) {
  CheckArgsBuffer(device_, args, offset, 12, "DispatchIndirect");
  DoDispatch(0, 0, 0, args, offset, "DispatchIndirect");
}

// ---------------------------------------------------------------------------------------------
// Clears

void DeviceContext::ClearRenderTargetView(RenderTargetView* rtv, const float rgba[4]) {
  if (!rtv) Fail(ErrorId::INVALID_ARGUMENT, "ClearRenderTargetView", "null", "pRenderTargetView is null");
  CheckOwner(device_, rtv, "ClearRenderTargetView");
  if (!rgba) Fail(ErrorId::INVALID_ARGUMENT, "ClearRenderTargetView", Describe(rtv), "ColorRGBA is null");
  backend_->ClearRenderTargetView(rtv, rgba);
}

void DeviceContext::ClearDepthStencilView(DepthStencilView* dsv, uint32_t flags, float depth, uint8_t stencil) {
  const char* call = "ClearDepthStencilView";
  if (!dsv) Fail(ErrorId::INVALID_ARGUMENT, call, "null", "pDepthStencilView is null");
  CheckOwner(device_, dsv, call);
  if (flags & ~uint32_t(CLEAR_DEPTH | CLEAR_STENCIL)) Fail(ErrorId::INVALID_ARGUMENT, call, Describe(dsv), "ClearFlags has unknown bits");
  if (!(depth >= 0.0f && depth <= 1.0f)) Fail(ErrorId::INVALID_ARGUMENT, call, Describe(dsv), "Depth must be in [0, 1]");
  if ((flags & CLEAR_STENCIL) && !GetFormatInfo(dsv->ViewFormat()).stencilBits) flags &= ~uint32_t(CLEAR_STENCIL);
  if (flags) backend_->ClearDepthStencilView(dsv, flags, depth, stencil);
}

void DeviceContext::ClearUnorderedAccessViewUint(UnorderedAccessView* uav, const uint32_t values[4]) {
  if (!uav || !values) Fail(ErrorId::INVALID_ARGUMENT, "ClearUnorderedAccessViewUint", Describe(uav), "null argument");
  CheckOwner(device_, uav, "ClearUnorderedAccessViewUint");
  backend_->ClearUnorderedAccessView(uav, ResolveUavClearUint(*uav, values));
}

void DeviceContext::ClearUnorderedAccessViewFloat(UnorderedAccessView* uav, const float values[4]) {
  const char* call = "ClearUnorderedAccessViewFloat";
  if (!uav || !values) Fail(ErrorId::INVALID_ARGUMENT, call, Describe(uav), "null argument");
  CheckOwner(device_, uav, call);
  FormatKind k = GetFormatInfo(uav->ViewFormat()).kind;
  if (k != FormatKind::Float && k != FormatKind::UNorm && k != FormatKind::SNorm && k != FormatKind::UNormSRGB)
    Fail(ErrorId::INVALID_ARGUMENT, call, Describe(uav), "ClearUnorderedAccessViewFloat needs a float/unorm/snorm typed view; use ClearUnorderedAccessViewUint");
  backend_->ClearUnorderedAccessView(uav, ResolveUavClearFloat(*uav, values));
}

// ---------------------------------------------------------------------------------------------
// Copies and updates

static uint32_t SubresourceCount(const Resource* r) {
  const Texture* t = AsTexture(r);
  return t ? t->Shape().subresourceCount() : 1;
}

static void CheckSubresource(const Resource* r, uint32_t sub, const char* call) {
  if (sub >= SubresourceCount(r))
    Fail(ErrorId::SUBRESOURCE_OUT_OF_RANGE, call, Describe(r),
         "subresource " + std::to_string(sub) + " does not exist (the resource has " + std::to_string(SubresourceCount(r)) + ")");
}

// One (validated) subresource, decomposed: what the backends get.
static Subresource Decompose(const Resource* r, uint32_t sub) {
  if (const Buffer* buf = AsBuffer(r)) return BufferSubresource(buf->GetDesc().ByteWidth);
  return SubresourceOf(AsTexture(r)->Shape(), sub);
}

static BOX SubresourceBox(const Resource* r, uint32_t sub) { return Decompose(r, sub).box(); }

static bool SameCopyFamily(FORMAT a, FORMAT b) {
  return a == b || (GetFormatInfo(a).typelessFamily != FORMAT_UNKNOWN && GetFormatInfo(a).typelessFamily == GetFormatInfo(b).typelessFamily);
}

static void CheckCopyDestination(const Resource* dst, const char* call) {
  if (const Buffer* b = AsBuffer(dst)) {
    if (b->GetDesc().Usage == USAGE_IMMUTABLE) Fail(ErrorId::COPY_INVALID, call, Describe(dst), "the destination is USAGE_IMMUTABLE");
  } else if (AsTexture(dst)->Shape().usage == USAGE_IMMUTABLE) {
    Fail(ErrorId::COPY_INVALID, call, Describe(dst), "the destination is USAGE_IMMUTABLE");
  }
}

void DeviceContext::CopyResource(Resource* dst, Resource* src) {
  const char* call = "CopyResource";
  if (!dst || !src) Fail(ErrorId::INVALID_ARGUMENT, call, Describe(dst ? dst : src), "pDstResource and pSrcResource must not be null");
  CheckOwner(device_, dst, call);
  CheckOwner(device_, src, call);
  if (dst == src) Fail(ErrorId::COPY_INVALID, call, Describe(dst), "source and destination are the same resource");
  if (dst->GetType() != src->GetType())
    Fail(ErrorId::COPY_INVALID, call, Describe(dst), "source " + Describe(src) + " is a different kind of resource");
  CheckCopyDestination(dst, call);
  if (const Buffer* d = AsBuffer(dst)) {
    if (d->GetDesc().ByteWidth != AsBuffer(src)->GetDesc().ByteWidth)
      Fail(ErrorId::COPY_INVALID, call, Describe(dst), "buffers differ in size from source " + Describe(src));
  } else {
    const TextureShape &a = AsTexture(dst)->Shape(), &b = AsTexture(src)->Shape();
    if (a.width != b.width || a.height != b.height || a.depth != b.depth || a.mipLevels != b.mipLevels || a.arraySize != b.arraySize)
      Fail(ErrorId::COPY_INVALID, call, Describe(dst), "dimensions differ from source " + Describe(src));
    if (a.sampleCount != b.sampleCount)
      Fail(ErrorId::SAMPLE_COUNT_MISMATCH, call, Describe(dst), "sample count differs from source " + Describe(src));
    if (!SameCopyFamily(a.format, b.format))
      Fail(ErrorId::COPY_INVALID, call, Describe(dst), "format family differs from source " + Describe(src));
  }
  backend_->CopyResource(dst, src);
}

void DeviceContext::CopySubresourceRegion(Resource* dst, uint32_t dstSub, uint32_t x, uint32_t y, uint32_t z, Resource* src,
                                          uint32_t srcSub, const BOX* pBox) {
  const char* call = "CopySubresourceRegion";
  if (!dst || !src) Fail(ErrorId::INVALID_ARGUMENT, call, Describe(dst ? dst : src), "pDstResource and pSrcResource must not be null");
  CheckOwner(device_, dst, call);
  CheckOwner(device_, src, call);
  if (dst->GetType() != src->GetType()) Fail(ErrorId::COPY_INVALID, call, Describe(dst), "source " + Describe(src) + " is a different kind of resource");
  CheckCopyDestination(dst, call);
  CheckSubresource(dst, dstSub, call);
  CheckSubresource(src, srcSub, call);
  BOX srcExtent = SubresourceBox(src, srcSub), dstExtent = SubresourceBox(dst, dstSub);
  BOX box = pBox ? *pBox : srcExtent;
  if (box.left >= box.right || box.top >= box.bottom || box.front >= box.back) return;  // empty: D3D11 does nothing
  if (box.right > srcExtent.right || box.bottom > srcExtent.bottom || box.back > srcExtent.back)
    Fail(ErrorId::SUBRESOURCE_OUT_OF_RANGE, call, Describe(src), "pSrcBox reaches outside the source subresource");
  if (uint64_t(x) + (box.right - box.left) > dstExtent.right || uint64_t(y) + (box.bottom - box.top) > dstExtent.bottom ||
      uint64_t(z) + (box.back - box.front) > dstExtent.back)
    Fail(ErrorId::SUBRESOURCE_OUT_OF_RANGE, call, Describe(dst), "the copied region reaches outside the destination subresource");
  if (dst == src && dstSub == srcSub) {
    bool disjoint = x >= box.right || x + (box.right - box.left) <= box.left || y >= box.bottom || y + (box.bottom - box.top) <= box.top ||
                    z >= box.back || z + (box.back - box.front) <= box.front;
    if (!disjoint) Fail(ErrorId::COPY_INVALID, call, Describe(dst), "source and destination regions overlap");
  }
  if (const Texture* dt = AsTexture(dst)) {
    const TextureShape &a = dt->Shape(), &b = AsTexture(src)->Shape();
    if (!SameCopyFamily(a.format, b.format)) Fail(ErrorId::COPY_INVALID, call, Describe(dst), "format family differs from source " + Describe(src));
    if (a.sampleCount != b.sampleCount) Fail(ErrorId::SAMPLE_COUNT_MISMATCH, call, Describe(dst), "sample count differs from source " + Describe(src));
    bool whole = box.left == 0 && box.top == 0 && box.front == 0 && box.right == srcExtent.right && box.bottom == srcExtent.bottom &&
                 box.back == srcExtent.back && x == 0 && y == 0 && z == 0 && srcExtent.right == dstExtent.right &&
                 srcExtent.bottom == dstExtent.bottom;
    if ((a.sampleCount > 1 || (a.bindFlags & BIND_DEPTH_STENCIL) || (b.bindFlags & BIND_DEPTH_STENCIL)) && !whole)
      Fail(ErrorId::COPY_INVALID, call, Describe(dst), "depth-stencil and multisampled resources can only be copied whole");
  }
  backend_->CopySubresourceRegion(dst, Decompose(dst, dstSub), x, y, z, src, Decompose(src, srcSub), box);
}

void DeviceContext::UpdateSubresource(Resource* dst, uint32_t sub, const BOX* pBox, const void* data, uint32_t rowPitch, uint32_t depthPitch) {
  const char* call = "UpdateSubresource";
  if (!dst) Fail(ErrorId::INVALID_ARGUMENT, call, "null", "pDstResource is null");
  CheckOwner(device_, dst, call);
  if (!data) Fail(ErrorId::INVALID_ARGUMENT, call, Describe(dst), "pSrcData is null");
  CheckSubresource(dst, sub, call);
  if (const Buffer* b = AsBuffer(dst)) {
    if (b->GetDesc().Usage != USAGE_DEFAULT)
      Fail(ErrorId::USAGE_INVALID, call, Describe(dst), "UpdateSubresource needs a USAGE_DEFAULT resource (use Map for " + UsageName(b->GetDesc().Usage) + ")");
  } else {
    const TextureShape& s = AsTexture(dst)->Shape();
    if (s.usage != USAGE_DEFAULT)
      Fail(ErrorId::USAGE_INVALID, call, Describe(dst), "UpdateSubresource needs a USAGE_DEFAULT resource (use Map for " + UsageName(s.usage) + ")");
    if (s.sampleCount > 1) Fail(ErrorId::COPY_INVALID, call, Describe(dst), "multisampled resources cannot be updated");
    if (s.bindFlags & BIND_DEPTH_STENCIL) Fail(ErrorId::COPY_INVALID, call, Describe(dst), "depth-stencil resources cannot be updated");
    uint32_t w = pBox ? pBox->right - pBox->left : SubresourceOf(s, sub).width;
    if (s.dimension != RESOURCE_DIMENSION_TEXTURE1D && rowPitch < w * GetFormatInfo(s.format).bytesPerElement)
      Fail(ErrorId::INVALID_ARGUMENT, call, Describe(dst), "SrcRowPitch " + std::to_string(rowPitch) + " is less than a row of the box");
  }
  BOX extent = SubresourceBox(dst, sub);
  BOX box = pBox ? *pBox : extent;
  if (box.left >= box.right || box.top >= box.bottom || box.front >= box.back) return;
  if (box.right > extent.right || box.bottom > extent.bottom || box.back > extent.back)
    Fail(ErrorId::SUBRESOURCE_OUT_OF_RANGE, call, Describe(dst), "pDstBox reaches outside the subresource");
  backend_->UpdateSubresource(dst, Decompose(dst, sub), box, data, rowPitch, depthPitch);
}

void DeviceContext::CopyStructureCount(Buffer* dst, uint32_t offset, UnorderedAccessView* src) {
  const char* call = "CopyStructureCount";
  if (!dst || !src) Fail(ErrorId::INVALID_ARGUMENT, call, Describe(dst ? static_cast<Object*>(dst) : src), "null argument");
  CheckOwner(device_, dst, call);
  CheckOwner(device_, src, call);
  if (offset % 4 || uint64_t(offset) + 4 > dst->GetDesc().ByteWidth)
    Fail(ErrorId::SUBRESOURCE_OUT_OF_RANGE, call, Describe(dst), "DstAlignedByteOffset must be 4-aligned and inside the buffer");
  if (src->GetDesc().ViewDimension != UAV_DIMENSION_BUFFER || !(src->GetDesc().Buffer.Flags & (BUFFER_UAV_FLAG_APPEND | BUFFER_UAV_FLAG_COUNTER)))
    Fail(ErrorId::INVALID_ARGUMENT, call, Describe(src), "the view has no hidden counter (needs BUFFER_UAV_FLAG_APPEND or _COUNTER)");
  backend_->CopyStructureCount(dst, offset, src);
}

CallStatus DeviceContext::Map(Resource* r, uint32_t sub, MAP type, uint32_t flags, MAPPED_SUBRESOURCE* out) {
  const char* call = "Map";
  if (!r) Fail(ErrorId::INVALID_ARGUMENT, call, "null", "pResource is null");
  CheckOwner(device_, r, call);
  if (!out) Fail(ErrorId::INVALID_ARGUMENT, call, Describe(r), "pMappedResource is null");
  CheckSubresource(r, sub, call);
  if (flags & ~uint32_t(MAP_FLAG_DO_NOT_WAIT)) Fail(ErrorId::INVALID_ARGUMENT, call, Describe(r), "unknown MapFlags");
  USAGE usage;
  uint32_t cpu;
  bool isBuffer = AsBuffer(r) != nullptr;
  if (isBuffer) {
    usage = AsBuffer(r)->GetDesc().Usage;
    cpu = AsBuffer(r)->GetDesc().CPUAccessFlags;
  } else {
    usage = AsTexture(r)->Shape().usage;
    cpu = AsTexture(r)->Shape().cpuAccessFlags;
  }
  switch (type) {
    case MAP_WRITE_DISCARD:
      if (usage != USAGE_DYNAMIC) Fail(ErrorId::MAP_INVALID, call, Describe(r), "MAP_WRITE_DISCARD needs USAGE_DYNAMIC (resource is " + UsageName(usage) + ")");
      break;
    case MAP_WRITE_NO_OVERWRITE:
      if (usage != USAGE_DYNAMIC || !isBuffer) Fail(ErrorId::MAP_INVALID, call, Describe(r), "MAP_WRITE_NO_OVERWRITE needs a USAGE_DYNAMIC buffer");
      break;
    case MAP_READ:
    case MAP_WRITE:
    case MAP_READ_WRITE:
      if (usage != USAGE_STAGING) Fail(ErrorId::MAP_INVALID, call, Describe(r), "MAP_READ/WRITE/READ_WRITE need USAGE_STAGING (resource is " + UsageName(usage) + ")");
      if ((type & MAP_READ) && !(cpu & CPU_ACCESS_READ)) Fail(ErrorId::MAP_INVALID, call, Describe(r), "reading needs CPU_ACCESS_READ");
      if ((type & MAP_WRITE) && !(cpu & CPU_ACCESS_WRITE)) Fail(ErrorId::MAP_INVALID, call, Describe(r), "writing needs CPU_ACCESS_WRITE");
      break;
    default:
      Fail(ErrorId::INVALID_ARGUMENT, call, Describe(r), "unknown MapType");
  }
  for (auto& m : mapped_)
    if (m.first == r && m.second == sub) Fail(ErrorId::MAP_INVALID, call, Describe(r), "subresource " + std::to_string(sub) + " is already mapped");
  if (!backend_->Map(r, Decompose(r, sub), type, flags, out)) return CallStatus(DXGI_ERROR_WAS_STILL_DRAWING);
  mapped_.push_back({r, sub});
  return CallStatus(S_OK);
}

void DeviceContext::Unmap(Resource* r, uint32_t sub) {
  auto it = std::find(mapped_.begin(), mapped_.end(), std::pair<Resource*, uint32_t>(r, sub));
  if (it == mapped_.end()) Fail(ErrorId::MAP_INVALID, "Unmap", Describe(r), "subresource " + std::to_string(sub) + " is not mapped");
  mapped_.erase(it);
  backend_->Unmap(r, Decompose(r, sub));
}

void DeviceContext::GenerateMips(ShaderResourceView* srv) {
  const char* call = "GenerateMips";
  if (!srv) Fail(ErrorId::INVALID_ARGUMENT, call, "null", "pShaderResourceView is null");
  CheckOwner(device_, srv, call);
  const Texture* t = AsTexture(srv->GetResource());
  if (!t || !(t->Shape().miscFlags & RESOURCE_MISC_GENERATE_MIPS))
    Fail(ErrorId::BIND_FLAGS_INVALID, call, Describe(srv), "the resource was not created with RESOURCE_MISC_GENERATE_MIPS");
  if (srv->Range().mipCount > 1) backend_->GenerateMips(srv);
}

void DeviceContext::ResolveSubresource(Resource* dst, uint32_t dstSub, Resource* src, uint32_t srcSub, FORMAT format) {
  const char* call = "ResolveSubresource";
  const Texture *d = AsTexture(dst), *s = AsTexture(src);
  if (!d || !s) Fail(ErrorId::INVALID_ARGUMENT, call, Describe(dst ? dst : src), "source and destination must be textures");
  CheckOwner(device_, dst, call);
  CheckOwner(device_, src, call);
  CheckSubresource(dst, dstSub, call);
  CheckSubresource(src, srcSub, call);
  if (s->Shape().sampleCount < 2) Fail(ErrorId::SAMPLE_COUNT_MISMATCH, call, Describe(src), "the source must be multisampled");
  if (d->Shape().sampleCount != 1) Fail(ErrorId::SAMPLE_COUNT_MISMATCH, call, Describe(dst), "the destination must be single-sampled");
  if (IsDepthFormat(format) || (s->Shape().bindFlags & BIND_DEPTH_STENCIL))
    Fail(ErrorId::NOT_SUPPORTED, call, Describe(src), "D3D11 cannot resolve depth; resolve it in a shader (Texture2DMS.Load)");
  if (!FormatsCompatibleForView(s->Shape().format, format) || !FormatsCompatibleForView(d->Shape().format, format))
    Fail(ErrorId::VIEW_FORMAT_INCOMPATIBLE, call, Describe(dst), std::string(FormatName(format)) + " is not compatible with both resources");
  BOX a = SubresourceBox(dst, dstSub), b = SubresourceBox(src, srcSub);
  if (a.right != b.right || a.bottom != b.bottom) Fail(ErrorId::COPY_INVALID, call, Describe(dst), "sizes differ from " + Describe(src));
  backend_->ResolveSubresource(dst, Decompose(dst, dstSub), src, Decompose(src, srcSub), format);
}

// ---------------------------------------------------------------------------------------------
// Queries

void DeviceContext::Begin(Query* q) {
  const char* call = "Begin";
  if (!q) Fail(ErrorId::INVALID_ARGUMENT, call, "null", "pAsync is null");
  CheckOwner(device_, q, call);
  if (q->GetDesc().Query == QUERY_TIMESTAMP || q->GetDesc().Query == QUERY_EVENT)
    Fail(ErrorId::QUERY_INVALID, call, Describe(q), "TIMESTAMP and EVENT queries only use End");
  if (std::find(activeQueries_.begin(), activeQueries_.end(), q) != activeQueries_.end())
    Fail(ErrorId::QUERY_INVALID, call, Describe(q), "Begin was called twice without End");
  activeQueries_.push_back(q);
  backend_->Begin(q);
}

void DeviceContext::End(Query* q) {
  const char* call = "End";
  if (!q) Fail(ErrorId::INVALID_ARGUMENT, call, "null", "pAsync is null");
  CheckOwner(device_, q, call);
  auto it = std::find(activeQueries_.begin(), activeQueries_.end(), q);
  if (q->GetDesc().Query != QUERY_TIMESTAMP && q->GetDesc().Query != QUERY_EVENT) {
    if (it == activeQueries_.end()) Fail(ErrorId::QUERY_INVALID, call, Describe(q), "End without Begin");
    activeQueries_.erase(it);
  }
  backend_->End(q);
}

CallStatus DeviceContext::GetData(Query* q, void* data, uint32_t size, uint32_t flags) {
  const char* call = "GetData";
  if (!q) Fail(ErrorId::INVALID_ARGUMENT, call, "null", "pAsync is null");
  CheckOwner(device_, q, call);
  if (data && size != q->GetDataSize())
    Fail(ErrorId::QUERY_INVALID, call, Describe(q), "DataSize " + std::to_string(size) + " must be " + std::to_string(q->GetDataSize()));
  if (std::find(activeQueries_.begin(), activeQueries_.end(), q) != activeQueries_.end())
    Fail(ErrorId::QUERY_INVALID, call, Describe(q), "GetData between Begin and End");
  return CallStatus(backend_->GetData(q, data, size, flags) ? S_OK : S_FALSE);
}

// ---------------------------------------------------------------------------------------------

void DeviceContext::ClearState() {
  *state_ = PipelineState{};
  dirty_ = DIRTY_ALL;
}

void DeviceContext::Flush() { backend_->Flush(); }
void DeviceContext::WaitIdle() { backend_->WaitIdle(); }

}  // namespace sp
