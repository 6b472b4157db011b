// Draws and dispatches: hazard tracking, dynamic rendering (started lazily, restarted when targets
// change or a barrier is due), pipelines, dynamic state, vertex/index buffers and descriptors.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "vulkan-internal.h"

namespace sp::vk {
namespace {

const char* DrawCallName(detail::DrawArgs::Kind k, const detail::DrawArgs& a) {
  switch (k) {
    case detail::DrawArgs::Draw: return a.instanceCount != 1 || a.startInstance ? "DrawInstanced" : "Draw";
    case detail::DrawArgs::DrawIndexed: return a.instanceCount != 1 || a.startInstance ? "DrawIndexedInstanced" : "DrawIndexed";
    case detail::DrawArgs::DrawInstancedIndirect: return "DrawInstancedIndirect";
    default: return "DrawIndexedInstancedIndirect";
  }
}

uint32_t ColorCount(const PipelineState& s) {
  uint32_t n = 0;
  for (uint32_t i = 0; i < s.numRenderTargets && i < SIMULTANEOUS_RENDER_TARGET_COUNT; ++i)
    if (s.renderTargets[i]) n = i + 1;
  return n;
}

bool UsesVertexInputs(const PipelineState& s) {
  for (const SignatureElement& in : s.stage(ShaderStage::Vertex).shader->Reflection().inputs)
    if (!in.systemValue) return true;
  return false;
}

}  // namespace

void VulkanContext::TrackAttachments(const PipelineState& s) {
  for (uint32_t i = 0; i < ColorCount(s); ++i)
    if (s.renderTargets[i]) UseView(ViewOf(s.renderTargets[i].get()), access::ColorAttachment());
  if (s.depthStencil) {
    VkViewObj& d = ViewOf(s.depthStencil.get());
    UseView(d, access::DepthAttachment(DsvLayout(d), !(d.depthReadOnly && d.stencilReadOnly)));
  }
}

void VulkanContext::BeginRendering(const PipelineState& s) {
  uint32_t colorCount = ColorCount(s);
  std::array<VkRenderingAttachmentInfo, SIMULTANEOUS_RENDER_TARGET_COUNT> colors{};
  VkExtent2D extent{0, 0};
  uint32_t layers = 1;
  RenderPassKey key;
  auto extentOf = [](const VkViewObj& v) {
    const TextureShape& sh = v.texture->shape;
    return VkExtent2D{sh.mipWidth(v.firstMip), sh.mipHeight(v.firstMip)};
  };
  for (uint32_t i = 0; i < colorCount; ++i) {
    colors[i] = {VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    if (!s.renderTargets[i]) continue;
    const VkViewObj& v = ViewOf(s.renderTargets[i].get());
    colors[i].imageView = v.view;
    colors[i].imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    colors[i].loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    colors[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    extent = extentOf(v);
    layers = v.renderLayers;
    key.views[i] = s.renderTargets[i]->UniqueId();
  }
  VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  VkRenderingAttachmentInfo stencil{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
  if (s.depthStencil) {
    const VkViewObj& d = ViewOf(s.depthStencil.get());
    VkImageLayout layout = DsvLayout(d);
    depth.imageView = d.view;
    depth.imageLayout = layout;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    depth.storeOp = d.depthReadOnly ? VK_ATTACHMENT_STORE_OP_NONE : VK_ATTACHMENT_STORE_OP_STORE;
    stencil = depth;
    stencil.storeOp = d.stencilReadOnly ? VK_ATTACHMENT_STORE_OP_NONE : VK_ATTACHMENT_STORE_OP_STORE;
    if (d.texture->aspects & VK_IMAGE_ASPECT_DEPTH_BIT) ri.pDepthAttachment = &depth;
    if (d.texture->aspects & VK_IMAGE_ASPECT_STENCIL_BIT) ri.pStencilAttachment = &stencil;
    extent = extentOf(d);
    layers = d.renderLayers;
    key.views[SIMULTANEOUS_RENDER_TARGET_COUNT] = s.depthStencil->UniqueId();
    key.dsvFlags = s.depthStencil->GetDesc().Flags;
  }
  if (extent.width == 0) {
    // No attachments (UAV-only rendering): the viewport decides the area, as in D3D11.
    const VIEWPORT& vp = s.viewports[0];
    const VkPhysicalDeviceLimits& lim = dev_->props.limits;
    extent.width = uint32_t(std::clamp(std::ceil(double(vp.TopLeftX) + vp.Width), 1.0, double(lim.maxFramebufferWidth)));
    extent.height = uint32_t(std::clamp(std::ceil(double(vp.TopLeftY) + vp.Height), 1.0, double(lim.maxFramebufferHeight)));
    key.views.fill(0);
    key.dsvFlags = extent.width | uint64_t(extent.height) << 16;
  }
  ri.renderArea = {{0, 0}, extent};
  ri.layerCount = layers;
  ri.colorAttachmentCount = colorCount;
  ri.pColorAttachments = colors.data();
  vkCmdBeginRendering(cur_->cmd, &ri);
  rendering_ = true;
  pass_ = key;
  passExtent_ = extent;
}

void VulkanContext::SetDynamicState(const PipelineState& s) {
  VkCommandBuffer cmd = cur_->cmd;
  DynamicValues d;
  const VIEWPORT& v = s.viewports[0];
  d.viewport = {v.TopLeftX, v.TopLeftY, v.Width, v.Height, v.MinDepth, v.MaxDepth};
  const RASTERIZER_DESC& rd = s.rasterizer();
  d.scissor = {{0, 0}, passExtent_};
  if (rd.ScissorEnable) {
    const RECT& r = s.scissorRects[0];
    int32_t l = std::max(r.left, 0), t = std::max(r.top, 0);
    int32_t ri = std::max(r.right, l), b = std::max(r.bottom, t);
    d.scissor = {{l, t}, {uint32_t(ri - l), uint32_t(b - t)}};
  }
  const PipelineState::DepthBias bias = s.depthBias(dev_->Info());
  d.biasEnable = bias.enable;
  d.bias = {bias.constant, bias.clamp, bias.slope};
  std::copy(s.blendFactor.begin(), s.blendFactor.end(), d.blendFactor.begin());
  d.stencilRef = s.stencilRef & 0xff;
  d.strip = s.cutsAtAllOnesIndex();
  // Only the values that changed are recorded: any state-object change brings us here, and every
  // vkCmdSet* is an allocation in the driver's command stream (bench-rhi's state case).
  const DynamicValues& o = lastDynamic_;
  auto changed = [&](const auto& a, const auto& b) { return !dynamicStateValid_ || std::memcmp(&a, &b, sizeof(a)) != 0; };
  if (changed(d.viewport, o.viewport)) vkCmdSetViewportWithCount(cmd, 1, &d.viewport);
  if (changed(d.scissor, o.scissor)) vkCmdSetScissorWithCount(cmd, 1, &d.scissor);
  if (changed(d.biasEnable, o.biasEnable)) vkCmdSetDepthBiasEnable(cmd, d.biasEnable);
  // A bias recorded while disabled was not recorded at all: re-record it when enabling.
  if (d.biasEnable && (changed(d.bias, o.bias) || !o.biasEnable)) vkCmdSetDepthBias(cmd, d.bias[0], d.bias[1], d.bias[2]);
  if (changed(d.blendFactor, o.blendFactor)) vkCmdSetBlendConstants(cmd, d.blendFactor.data());
  if (changed(d.stencilRef, o.stencilRef)) vkCmdSetStencilReference(cmd, VK_STENCIL_FACE_FRONT_AND_BACK, d.stencilRef);
  if (changed(d.strip, o.strip)) vkCmdSetPrimitiveRestartEnable(cmd, d.strip);
  lastDynamic_ = d;
  dynamicStateValid_ = true;
}

void VulkanContext::BindVertexBuffers(const PipelineState& s, uint32_t dirty) {
  // Nothing to compare when neither the bindings nor a vertex buffer's memory moved since the last draw.
  if (vertexEpoch_ == vertexRenames_ && !(dirty & (DIRTY_VERTEX_BUFFERS | DIRTY_INPUT_LAYOUT | DIRTY_SHADERS))) return;
  vertexEpoch_ = vertexRenames_;
  // Built in a reused member: this runs for every draw, and a fresh vector was an allocation each.
  decltype(boundVertex_)& want = wantVertex_;
  want.clear();
  if (s.inputLayout && UsesVertexInputs(s)) {
    uint32_t slots = 0;
    for (const VertexAttribute& a : s.inputLayout->Attributes()) slots |= 1u << a.slot;
    for (uint32_t slot = 0; slot < IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT; ++slot) {
      if (!(slots & (1u << slot))) continue;
      const VkBufferObj& b = BufferOf(s.vertexBuffers[slot].get());
      VkDeviceSize off = std::min<VkDeviceSize>(s.vertexOffsets[slot], b.desc.ByteWidth);
      VkDeviceSize size = std::max<VkDeviceSize>(b.desc.ByteWidth - off, 1);
      want.emplace_back(slot, b.range.buffer, b.range.offset + off, size, s.vertexStrides[slot]);
    }
  }
  if (want == boundVertex_) return;
  for (size_t i = 0; i < want.size();) {
    size_t j = i;
    VkBuffer bufs[IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT];
    VkDeviceSize offs[IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT], sizes[IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT], strides[IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT];
    uint32_t n = 0;
    while (j < want.size() && std::get<0>(want[j]) == std::get<0>(want[i]) + (j - i)) {
      bufs[n] = std::get<1>(want[j]);
      offs[n] = std::get<2>(want[j]);
      sizes[n] = std::get<3>(want[j]);
      strides[n] = std::get<4>(want[j]);
      ++n;
      ++j;
    }
    vkCmdBindVertexBuffers2(cur_->cmd, std::get<0>(want[i]), n, bufs, offs, sizes, strides);
    i = j;
  }
  std::swap(boundVertex_, want);
}

VkPipeline VulkanContext::CachedGraphicsPipeline(const PipelineState& s, uint32_t dirty, uint64_t vsUid, uint64_t psUid, VkPipelineLayout layout,
                                                 const char* call) {
  auto uid = [](const auto& ref) { return ref ? ref->UniqueId() : uint64_t(0); };
  constexpr uint64_t kMix = 0x9e3779b97f4a7c15ull;
  // The core starts a context with every dirty bit set, so the first draw fills these.
  if (dirty & DIRTY_RENDER_TARGETS) {
    for (size_t i = 0; i < SIMULTANEOUS_RENDER_TARGET_COUNT; ++i) pipelineTargets_[i] = uid(s.renderTargets[i]);
    pipelineTargets_[SIMULTANEOUS_RENDER_TARGET_COUNT] = uid(s.depthStencil);
    pipelineTargetsHash_ = 0;
    for (uint64_t v : pipelineTargets_) pipelineTargetsHash_ = (pipelineTargetsHash_ ^ v) * kMix;
  }
  PipelineIdentity id;
  id.objects = {vsUid, psUid, uid(s.inputLayout), uid(s.rasterizerState), uid(s.depthStencilState), uid(s.blendState)};
  id.targets = pipelineTargets_;
  id.layout = layout;
  id.topology = uint32_t(s.topology);
  id.sampleMask = s.sampleMask;
  id.numRenderTargets = s.numRenderTargets;
  uint64_t h = uint64_t(id.topology) * 31 + id.sampleMask + uint64_t(id.layout) + pipelineTargetsHash_;
  for (uint64_t v : id.objects) h = (h ^ v) * kMix;
  auto& slot = recentPipelines_[(h >> 32) % recentPipelines_.size()];
  if (slot.second && slot.first == id) return slot.second;
  slot = {id, GraphicsPipeline(s, layout, call)};
  return slot.second;
}

void VulkanContext::Draw(const PipelineState& s, uint32_t dirty, const detail::DrawArgs& args) {
  const char* call = DrawCallName(args.kind, args);
  if (!cur_) BeginBatch();
  VkShaderObj& vs = detail::BackendAs<VkShaderObj>(s.stage(ShaderStage::Vertex).shader);
  VkShaderObj* ps = s.stage(ShaderStage::Pixel).shader ? &detail::BackendAs<VkShaderObj>(s.stage(ShaderStage::Pixel).shader) : nullptr;
  std::pair<uint64_t, uint64_t> shaders{vs.uid, ps ? ps->uid : 0};
  VkPipelineLayout layout = currentLayout_;
  if (!layout || shaders != layoutShaders_) {
    layout = ps ? dev_->PipelineLayout({vs.setLayout, ps->setLayout}) : dev_->PipelineLayout({vs.setLayout});
    layoutShaders_ = shaders;
  }
  const uint32_t pipelineBits = DIRTY_SHADERS | DIRTY_INPUT_LAYOUT | DIRTY_RASTERIZER | DIRTY_DEPTH_STENCIL | DIRTY_BLEND | DIRTY_RENDER_TARGETS;
  if ((dirty & pipelineBits) || !currentPipeline_ || currentLayout_ != layout) {
    currentPipeline_ = CachedGraphicsPipeline(s, dirty, vs.uid, shaders.second, layout, call);
    currentLayout_ = layout;
  }

  CheckSampling(s, ShaderStage::Vertex, vs, dirty, call);
  if (ps) CheckSampling(s, ShaderStage::Pixel, *ps, dirty, call);
  // Everything the draw reads or writes, so the barriers it needs are known before recording.
  TrackStageResources(s, ShaderStage::Vertex, vs);
  if (ps) TrackStageResources(s, ShaderStage::Pixel, *ps);
  if (s.inputLayout && UsesVertexInputs(s)) {
    for (const VertexAttribute& a : s.inputLayout->Attributes()) UseBuffer(BufferOf(s.vertexBuffers[a.slot].get()), access::VertexInput());
  }
  bool indexed = args.kind == detail::DrawArgs::DrawIndexed || args.kind == detail::DrawArgs::DrawIndexedInstancedIndirect;
  VkBuffer indexBuffer = VK_NULL_HANDLE;
  VkDeviceSize indexOffset = 0;
  if (indexed) {
    VkBufferObj& ib = BufferOf(s.indexBuffer.get());
    indexBuffer = ib.range.buffer;
    indexOffset = ib.range.offset + s.indexOffset;
    if (args.kind == detail::DrawArgs::DrawIndexedInstancedIndirect && indexOffset && dev_->feat.indirectIgnoresIndexOffset) {
      // Give the driver indices that start at offset 0 of a buffer of their own.
      VkDeviceSize size = std::max<VkDeviceSize>(ib.desc.ByteWidth - std::min(s.indexOffset, ib.desc.ByteWidth), 4);
      BufferRange copy = dev_->alloc.AllocateBuffer(size, MemoryKind::Device, call, "index buffer copy", true);
      VkCommandBuffer c = Cmd();
      UseBuffer(ib, access::TransferRead());
      FlushBarriers();
      VkBufferCopy region{indexOffset, 0, std::min<VkDeviceSize>(size, ib.desc.ByteWidth - s.indexOffset)};
      if (region.size) vkCmdCopyBuffer(c, ib.range.buffer, copy.buffer, 1, &region);
      AccessState state;
      UseRange(state, access::TransferWrite());
      UseRange(state, access::IndexInput());
      indexBuffer = copy.buffer;
      indexOffset = 0;
      ReleaseBufferRange(dev_, copy, dev_->recordingSerial);
    } else {
      UseBuffer(ib, access::IndexInput());
    }
  }
  if (args.argsBuffer) UseBuffer(BufferOf(args.argsBuffer), access::IndirectArgs());

  // Our pass is open only if this method opened it (Cmd() closes it for any other command), and
  // it matched the state of the draw that opened or last checked it; so only a change of targets
  // or viewports since then can make it the wrong pass.
  bool restart = !rendering_ || !barriers_.Empty();
  if (!restart && (dirty & (DIRTY_RENDER_TARGETS | DIRTY_VIEWPORTS))) {
    RenderPassKey key;
    for (uint32_t i = 0; i < ColorCount(s); ++i)
      if (s.renderTargets[i]) key.views[i] = s.renderTargets[i]->UniqueId();
    if (s.depthStencil) {
      key.views[SIMULTANEOUS_RENDER_TARGET_COUNT] = s.depthStencil->UniqueId();
      key.dsvFlags = s.depthStencil->GetDesc().Flags;
    }
    bool attachmentless = key.views == RenderPassKey{}.views;
    const VIEWPORT& vp = s.viewports[0];
    bool sameArea = !attachmentless || (passExtent_.width >= uint32_t(std::ceil(double(vp.TopLeftX) + vp.Width)) &&
                                        passExtent_.height >= uint32_t(std::ceil(double(vp.TopLeftY) + vp.Height)));
    restart = !(attachmentless ? pass_.views == key.views && sameArea : pass_ == key);
  }
  if (restart) {
    TrackAttachments(s);
    EndRendering();
    barriers_.Record(cur_->cmd);
    BeginRendering(s);
    dirty |= DIRTY_VIEWPORTS;  // the scissor follows the render area
  }

  VkCommandBuffer cmd = cur_->cmd;
  if (boundPipeline_ != currentPipeline_) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, currentPipeline_);
    boundPipeline_ = currentPipeline_;
  }
  const uint32_t dynamicBits = DIRTY_VIEWPORTS | DIRTY_RASTERIZER | DIRTY_RENDER_TARGETS | DIRTY_BLEND | DIRTY_DEPTH_STENCIL | DIRTY_INPUT_LAYOUT;
  if (!dynamicStateValid_ || (dirty & dynamicBits)) SetDynamicState(s);
  BindVertexBuffers(s, dirty);
  if (indexed) {
    std::tuple<VkBuffer, VkDeviceSize, VkIndexType> want{indexBuffer, indexOffset, s.indexFormat == FORMAT_R16_UINT ? VK_INDEX_TYPE_UINT16 : VK_INDEX_TYPE_UINT32};
    if (want != boundIndex_) {
      vkCmdBindIndexBuffer(cmd, std::get<0>(want), std::get<1>(want), std::get<2>(want));
      boundIndex_ = want;
    }
  }
  const bool bindVs = StageDescriptorsFor(gfxSets_[0], s, ShaderStage::Vertex, vs, dirty, layout, call);
  const bool bindPs = ps && StageDescriptorsFor(gfxSets_[1], s, ShaderStage::Pixel, *ps, dirty, layout, call);
  if (bindVs && bindPs) BindSets(VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, &gfxSets_[0], &gfxSets_[1]);
  else if (bindVs) BindSets(VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, &gfxSets_[0]);
  else if (bindPs) BindSets(VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 1, &gfxSets_[1]);

  switch (args.kind) {
    case detail::DrawArgs::Draw: vkCmdDraw(cmd, args.count, args.instanceCount, args.start, args.startInstance); break;
    case detail::DrawArgs::DrawIndexed:
      vkCmdDrawIndexed(cmd, args.count, args.instanceCount, args.start, args.baseVertex, args.startInstance);
      break;
    case detail::DrawArgs::DrawInstancedIndirect: {
      const VkBufferObj& ab = BufferOf(args.argsBuffer);
      vkCmdDrawIndirect(cmd, ab.range.buffer, ab.range.offset + args.argsOffset, 1, 0);
      break;
    }
    case detail::DrawArgs::DrawIndexedInstancedIndirect: {
      const VkBufferObj& ab = BufferOf(args.argsBuffer);
      vkCmdDrawIndexedIndirect(cmd, ab.range.buffer, ab.range.offset + args.argsOffset, 1, 0);
      break;
    }
  }
  CountWork();
  SubmitIfBusy();
}

void VulkanContext::Dispatch(const PipelineState& s, uint32_t dirty, uint32_t x, uint32_t y, uint32_t z, Buffer* argsBuffer, uint32_t argsOffset) {
  const char* call = argsBuffer ? "DispatchIndirect" : "Dispatch";
  VkShaderObj& cs = detail::BackendAs<VkShaderObj>(s.stage(ShaderStage::Compute).shader);
  const VkPhysicalDeviceLimits& lim = dev_->props.limits;
  if (x > lim.maxComputeWorkGroupCount[0] || y > lim.maxComputeWorkGroupCount[1] || z > lim.maxComputeWorkGroupCount[2])
    Throw(ErrorId::NOT_SUPPORTED, call, DescribeObject(cs.owner), "the thread-group count exceeds this device's maxComputeWorkGroupCount");
  CheckSampling(s, ShaderStage::Compute, cs, dirty, call);
  VkCommandBuffer cmd = Cmd();
  TrackStageResources(s, ShaderStage::Compute, cs);
  if (argsBuffer) UseBuffer(BufferOf(argsBuffer), access::IndirectArgs());
  barriers_.Record(cmd);
  VkPipeline p = ComputePipeline(cs, call);
  if (boundCompute_ != p) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p);
    boundCompute_ = p;
  }
  if (StageDescriptorsFor(computeSet_, s, ShaderStage::Compute, cs, dirty, cs.computeLayout, call))
    BindSets(VK_PIPELINE_BIND_POINT_COMPUTE, cs.computeLayout, 0, &computeSet_);
  if (argsBuffer) {
    const VkBufferObj& ab = BufferOf(argsBuffer);
    vkCmdDispatchIndirect(cmd, ab.range.buffer, ab.range.offset + argsOffset);
  } else {
    vkCmdDispatch(cmd, x, y, z);
  }
  CountWork();
  SubmitIfBusy();
}

}  // namespace sp::vk
