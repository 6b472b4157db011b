// Descriptor sets: one per stage, written from the D3D11 slots the stage's shader reads. The
// resolved descriptors are compared with the previous draw's, so a set is only rewritten when
// something it points at changed (a rebind, a dynamic buffer that moved, an image layout).
#include "vulkan-internal.h"

namespace sp::vk {
namespace {

VkPipelineStageFlags2 StageBit(ShaderStage s) {
  switch (s) {
    case ShaderStage::Vertex: return VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT;
    case ShaderStage::Pixel: return VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
    case ShaderStage::Geometry: return VK_PIPELINE_STAGE_2_GEOMETRY_SHADER_BIT;
    default: return VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
  }
}

const UnorderedAccessView* UavAt(const PipelineState& s, ShaderStage stage, uint32_t reg) {
  return stage == ShaderStage::Compute ? s.computeUavs[reg].get() : s.pixelUavs[reg].get();
}

bool Overlaps(uint32_t a0, uint32_t an, uint32_t b0, uint32_t bn) { return a0 < b0 + bn && b0 < a0 + an; }

// The core's dirty bits under which a stage's resolved descriptors may change: its own bindings
// (and shader), the depth target (SrvLayout) and the UAVs it sees.
uint32_t StageInputs(ShaderStage stage) {
  uint32_t bits = DIRTY_BINDINGS_VS << uint32_t(stage);
  if (stage == ShaderStage::Compute) return bits | DIRTY_COMPUTE_UAVS;
  bits |= DIRTY_RENDER_TARGETS;
  return stage == ShaderStage::Pixel ? bits | DIRTY_PIXEL_UAVS : bits;
}

// The key of setCache_, whose hits compare the items in full, so a collision costs a set write,
// never a wrong set. An item holds one kind of handle (buffer range, view and layout, sampler or
// texel view) and zeros elsewhere, so its fields are folded together and mixed once: mixing each
// field was a third of the per-draw cost of a texture change (bench-rhi's texture case).
uint64_t HashItems(VkDescriptorSetLayout layout, const std::vector<DescriptorItem>& items) {
  uint64_t h = uint64_t(layout);
  for (const DescriptorItem& it : items) {
    uint64_t v = (uint64_t(it.binding) << 40) ^ (uint64_t(it.type) << 32) ^ (uint64_t(it.layout) << 48) ^ uint64_t(it.buffer) ^
                 (it.offset * 0x9e3779b97f4a7c15ull) ^ (it.range << 24) ^ uint64_t(it.view) ^ uint64_t(it.sampler) ^ uint64_t(it.texel);
    h = (h ^ v) * 0x100000001b3ull;
  }
  return h ^ (h >> 29);
}

}  // namespace

VkImageLayout DsvLayout(const VkViewObj& v) {
  if (v.depthReadOnly && v.stencilReadOnly) return VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
  if (v.depthReadOnly) return VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_STENCIL_ATTACHMENT_OPTIMAL;
  if (v.stencilReadOnly && (v.texture->aspects & VK_IMAGE_ASPECT_STENCIL_BIT)) return VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_STENCIL_READ_ONLY_OPTIMAL;
  return VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
}

VkImageLayout VulkanContext::SrvLayout(const PipelineState& s, const VkViewObj& v) const {
  if (!(v.aspect & (VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT))) return VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  // Sampling a depth texture that is also the (read-only) depth target: one layout serves both.
  if (s.depthStencil) {
    const VkViewObj& d = ViewOf(s.depthStencil.get());
    if (d.texture == v.texture && Overlaps(d.firstMip, d.mipCount, v.firstMip, v.mipCount) &&
        Overlaps(d.firstLayer, d.layerCount, v.firstLayer, v.layerCount))
      return DsvLayout(d);
  }
  return VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
}

void VulkanContext::CheckSampling(const PipelineState& s, ShaderStage stage, const VkShaderObj& sh, uint32_t dirty, const char* call) {
  if (!(dirty & StageInputs(stage))) return;  // depends on the bindings only: an unchanged stage passed before
  const StageBindings& b = s.stage(stage);
  for (const SampledPair& p : sh.sampledPairs) {
    const ShaderResourceView* srv = b.shaderResources[p.textureReg].get();
    const SamplerState* smp = b.samplers[p.samplerReg].get();
    if (!srv || !smp) continue;
    const VkViewObj& v = ViewOf(srv);
    if (!v.texture) continue;
    VkFormatFeatureFlags2 f = dev_->OptimalFeatures(v.format);
    const SAMPLER_DESC& sd = smp->GetDesc();
    // Built only for an error: per sampled pair and draw it was an allocation on the hot path.
    auto slot = [&] { return std::string(ShaderStagePrefix(stage)) + " slot t" + std::to_string(p.textureReg); };
    if (p.compared && !(f & VK_FORMAT_FEATURE_2_SAMPLED_IMAGE_DEPTH_COMPARISON_BIT))
      Throw(ErrorId::NOT_SUPPORTED, call, DescribeObject(srv),
            "the shader compares (SampleCmp/GatherCmp) the texture at " + slot() + ", but this device compares only depth textures; create it with a depth "
            "family (e.g. R32_TYPELESS with BIND_DEPTH_STENCIL) and read it through its depth view format");
    bool linear = !FilterIsComparison(sd.Filter) && FilterReduction(sd.Filter) == 0 &&
                  (FilterIsAnisotropic(sd.Filter) || FilterMinLinear(sd.Filter) || FilterMagLinear(sd.Filter));
    if (p.filtered && linear && !(f & VK_FORMAT_FEATURE_2_SAMPLED_IMAGE_FILTER_LINEAR_BIT))
      Throw(ErrorId::NOT_SUPPORTED, call, DescribeObject(srv),
            "the shader samples the texture at " + slot() + " with a linear filter (" + DescribeObject(smp) + "), which this device does not support for " +
                std::string(FormatName(srv->ViewFormat())) + " views of this texture; use a point filter, Load or Gather");
  }
}

void VulkanContext::TrackStageResources(const PipelineState& s, ShaderStage stage, const VkShaderObj& sh) {
  const StageBindings& b = s.stage(stage);
  VkPipelineStageFlags2 bit = StageBit(stage);
  uint64_t serial = dev_->recordingSerial;
  for (const ShaderBinding& sb : sh.bindings) {
    switch (sb.cls) {
      case RegisterClass::ConstantBuffer: {
        VkBufferObj& buf = BufferOf(b.constantBuffers[sb.reg].get());
        if (const CBufferRepack* rp = sh.RepackFor(sb.reg)) repacked_[size_t(stage)][sb.reg] = RepackConstants(buf, *rp, sh.uid * 16 + sb.reg, bit);
        else UseBuffer(buf, access::ShaderRead(bit, VK_ACCESS_2_UNIFORM_READ_BIT));
        break;
      }
      case RegisterClass::ShaderResource: {
        VkViewObj& v = ViewOf(b.shaderResources[sb.reg].get());
        if (sb.type == VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE) UseView(v, access::ShaderRead(bit, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, SrvLayout(s, v)));
        else if (sb.type == VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER) UseView(v, access::ShaderRead(bit, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT));
        else UseView(v, access::ShaderRead(bit, VK_ACCESS_2_SHADER_STORAGE_READ_BIT));
        break;
      }
      case RegisterClass::Sampler:
        detail::BackendAs<VkSamplerObj>(b.samplers[sb.reg]).lastUse = serial;
        break;
      case RegisterClass::UnorderedAccess: {
        VkViewObj& v = ViewOf(UavAt(s, stage, sb.reg));
        if (sb.resType == ShaderResourceType::UavCounter) {
          UseRange(v.counterState, access::ShaderWrite(bit));
          v.lastUse = serial;
        } else {
          UseView(v, access::ShaderWrite(bit, VK_IMAGE_LAYOUT_GENERAL));
        }
        break;
      }
    }
  }
}

void VulkanContext::ResolveDescriptors(const PipelineState& s, ShaderStage stage, const VkShaderObj& sh, std::vector<DescriptorItem>& out,
                                       std::vector<uint32_t>& dynamicOffsets, const char* call) {
  const StageBindings& b = s.stage(stage);
  out.clear();
  dynamicOffsets.clear();
  for (const ShaderBinding& sb : sh.bindings) {
    DescriptorItem it;
    it.binding = sb.binding;
    it.type = sb.type;
    switch (sb.cls) {
      case RegisterClass::ConstantBuffer: {
        const VkBufferObj& buf = BufferOf(b.constantBuffers[sb.reg].get());
        if (sh.RepackFor(sb.reg)) {
          const RepackedConstants& rc = repacked_[size_t(stage)][sb.reg];
          it.buffer = rc.buffer;
          it.offset = rc.offset;
          it.range = rc.size;
        } else {
          it.buffer = buf.range.buffer;
          it.offset = buf.range.offset;
          it.range = buf.desc.ByteWidth;
        }
        // The set holds the buffer and size only: a renamed cbuffer keeps its set.
        if (sb.type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC) {
          dynamicOffsets.push_back(uint32_t(it.offset));
          it.offset = 0;
        }
        break;
      }
      case RegisterClass::ShaderResource: {
        VkViewObj& v = ViewOf(b.shaderResources[sb.reg].get());
        if (sb.type == VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE) {
          it.view = v.view;
          it.layout = SrvLayout(s, v);
        } else if (sb.type == VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER) {
          it.texel = v.TexelView(call);
        } else {
          it.buffer = v.buffer->range.buffer;
          it.offset = v.buffer->range.offset + v.byteOffset;
          it.range = v.byteSize;
        }
        break;
      }
      case RegisterClass::Sampler:
        it.sampler = detail::BackendAs<VkSamplerObj>(b.samplers[sb.reg]).sampler;
        break;
      case RegisterClass::UnorderedAccess: {
        const UnorderedAccessView* uav = UavAt(s, stage, sb.reg);
        VkViewObj& v = ViewOf(uav);
        if (sb.resType == ShaderResourceType::UavCounter) {
          if (!v.counter)
            Throw(ErrorId::RESOURCE_TYPE_MISMATCH, call, DescribeObject(uav), "the shader uses the hidden counter of u" + std::to_string(sb.reg) +
                                                                                  " but the view was created without BUFFER_UAV_FLAG_APPEND or _COUNTER");
          it.buffer = v.counter.buffer;
          it.offset = v.counter.offset;
          it.range = 4;
        } else if (sb.type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE) {
          it.view = v.view;
          it.layout = VK_IMAGE_LAYOUT_GENERAL;
        } else if (sb.type == VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER) {
          it.texel = v.TexelView(call);
        } else {
          it.buffer = v.buffer->range.buffer;
          it.offset = v.buffer->range.offset + v.byteOffset;
          it.range = v.byteSize;
        }
        break;
      }
    }
    out.push_back(it);
  }
}

bool VulkanContext::PrepareDescriptors(StageDescriptors& sd, VkDescriptorSetLayout layout, std::vector<DescriptorItem>& items,
                                       std::vector<uint32_t>& dynamicOffsets, VkPipelineLayout pipeLayout) {
  if (items.empty()) return false;
  bool rewrite = !(sd.set && sd.layout == layout && sd.items == items);
  CachedSet* cached = nullptr;
  if (rewrite) {
    if (setCache_.size() > 4096) setCache_.clear();
    cached = &setCache_[HashItems(layout, items)];
  }
  if (rewrite && cached->set && cached->layout == layout && cached->items == items) {
    sd.set = cached->set;
    sd.layout = layout;
    sd.items.swap(items);
  } else if (rewrite) {
    VkDescriptorSet set = AllocateSet(layout);
    // Reused between rewrites: three allocations per set and draw showed in the per-draw cost.
    static thread_local std::vector<VkWriteDescriptorSet> writes;
    static thread_local std::vector<VkDescriptorImageInfo> images;
    static thread_local std::vector<VkDescriptorBufferInfo> buffers;
    writes.resize(items.size());
    images.resize(items.size());
    buffers.resize(items.size());
    for (size_t i = 0; i < items.size(); ++i) {
      const DescriptorItem& it = items[i];
      VkWriteDescriptorSet& w = writes[i];
      w = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
      w.dstSet = set;
      w.dstBinding = it.binding;
      w.descriptorCount = 1;
      w.descriptorType = it.type;
      switch (it.type) {
        case VK_DESCRIPTOR_TYPE_SAMPLER:
          images[i] = {it.sampler, VK_NULL_HANDLE, VK_IMAGE_LAYOUT_UNDEFINED};
          w.pImageInfo = &images[i];
          break;
        case VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE:
        case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE:
          images[i] = {VK_NULL_HANDLE, it.view, it.layout};
          w.pImageInfo = &images[i];
          break;
        case VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER:
        case VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER:
          w.pTexelBufferView = &items[i].texel;
          break;
        default:
          buffers[i] = {it.buffer, it.offset, it.range};
          w.pBufferInfo = &buffers[i];
          break;
      }
    }
    vkUpdateDescriptorSets(dev_->device, uint32_t(writes.size()), writes.data(), 0, nullptr);
    *cached = {layout, items, set};
    sd.set = set;
    sd.layout = layout;
    sd.items.swap(items);
  }
  if (!rewrite && sd.boundWith == pipeLayout && sd.dynamicOffsets == dynamicOffsets) return false;
  sd.boundWith = pipeLayout;
  sd.dynamicOffsets.swap(dynamicOffsets);
  return true;
}

bool VulkanContext::KeepDescriptors(StageDescriptors& sd, const PipelineState& s, ShaderStage stage, const VkShaderObj& sh, uint32_t dirty) {
  if (!sh.setKeptAcrossDraws || !sd.set || sd.shaderUid != sh.uid || sd.layout != sh.setLayout || (dirty & StageInputs(stage))) return false;
  if (sh.rangeInSet && sd.viewRenames != viewRenames_) return false;
  // Same bindings: only the dynamic cbuffers' offsets may have moved, within the same VkBuffer.
  const StageBindings& b = s.stage(stage);
  scratchOffsets_.clear();
  size_t i = 0;
  for (const ShaderBinding& sb : sh.bindings) {
    if (sb.type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC) {
      const BufferRange& r = BufferOf(b.constantBuffers[sb.reg].get()).range;
      if (r.buffer != sd.items[i].buffer) return false;
      scratchOffsets_.push_back(uint32_t(r.offset));
    }
    ++i;
  }
  return true;
}

bool VulkanContext::StageDescriptorsFor(StageDescriptors& sd, const PipelineState& s, ShaderStage stage, const VkShaderObj& sh, uint32_t dirty,
                                        VkPipelineLayout pipeLayout, const char* call) {
  if (KeepDescriptors(sd, s, stage, sh, dirty)) {
    if (sd.boundWith == pipeLayout && sd.dynamicOffsets == scratchOffsets_) return false;
    sd.boundWith = pipeLayout;
    sd.dynamicOffsets.swap(scratchOffsets_);
    return true;
  }
  ResolveDescriptors(s, stage, sh, scratchItems_, scratchOffsets_, call);
  bool bind = PrepareDescriptors(sd, sh.setLayout, scratchItems_, scratchOffsets_, pipeLayout);
  sd.shaderUid = sh.uid;
  sd.viewRenames = viewRenames_;
  return bind;
}

void VulkanContext::BindSets(VkPipelineBindPoint point, VkPipelineLayout pipeLayout, uint32_t firstSet, const StageDescriptors* first,
                             const StageDescriptors* second) {
  if (!second) {
    vkCmdBindDescriptorSets(cur_->cmd, point, pipeLayout, firstSet, 1, &first->set, uint32_t(first->dynamicOffsets.size()),
                            first->dynamicOffsets.data());
    return;
  }
  // One call for neighbouring sets: lavapipe allocates per call (it copies the set and offset
  // arrays into its command stream), the largest per-draw cost left in docs/rhi-cost.md.
  const VkDescriptorSet sets[2] = {first->set, second->set};
  bindOffsets_.assign(first->dynamicOffsets.begin(), first->dynamicOffsets.end());
  bindOffsets_.insert(bindOffsets_.end(), second->dynamicOffsets.begin(), second->dynamicOffsets.end());
  vkCmdBindDescriptorSets(cur_->cmd, point, pipeLayout, firstSet, 2, sets, uint32_t(bindOffsets_.size()), bindOffsets_.data());
}

}  // namespace sp::vk
