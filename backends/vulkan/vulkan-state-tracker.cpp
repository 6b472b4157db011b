// D3D11 hides barriers; this is where they come from. Every buffer and every image subresource
// remembers its layout, its last write and the reads since; an access that conflicts with that
// history adds a barrier to the batch recorded before the command. Buffers (sub-allocated from
// shared VkBuffers) use a global memory barrier; image layout transitions use image barriers.
#include <algorithm>

#include "vulkan-internal.h"

namespace sp::vk {

namespace access {
Access TransferRead() {
  return {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, false};
}
Access TransferWrite() {
  return {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, true};
}
Access ShaderRead(VkPipelineStageFlags2 stage, VkAccessFlags2 a, VkImageLayout layout) { return {stage, a, layout, false}; }
Access ShaderWrite(VkPipelineStageFlags2 stage, VkImageLayout layout) {
  return {stage, VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, layout, true};
}
Access ColorAttachment() {
  return {VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
          VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, true};
}
Access DepthAttachment(VkImageLayout layout, bool write) {
  return {VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
          VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | (write ? VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT : 0), layout, write};
}
Access VertexInput() { return {VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT, VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, false}; }
Access IndexInput() { return {VK_PIPELINE_STAGE_2_INDEX_INPUT_BIT, VK_ACCESS_2_INDEX_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, false}; }
Access IndirectArgs() { return {VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, false}; }
}  // namespace access

namespace {

constexpr VkAccessFlags2 kWriteBits = VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |
                                      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_HOST_WRITE_BIT |
                                      VK_ACCESS_2_MEMORY_WRITE_BIT;

bool Covers(const AccessState& s, const Access& a) {
  return (s.visibleStages & a.stages) == a.stages && (s.visibleAccess & a.access) == a.access;
}

}  // namespace

void BarrierBatch::Global(VkPipelineStageFlags2 src, VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dst, VkAccessFlags2 dstAccess) {
  srcStages_ |= src;
  srcAccess_ |= srcAccess;
  dstStages_ |= dst;
  dstAccess_ |= dstAccess;
}

bool BarrierBatch::Buffer(AccessState& s, const Access& a) {
  bool needed = false;
  if (a.write) {
    if (s.writeStages | s.readStages) {
      Global(s.writeStages | s.readStages, s.writeAccess, a.stages, a.access);
      needed = true;
    }
    s.writeStages = a.stages;
    s.writeAccess = a.access & kWriteBits;
    s.readStages = 0;
    s.visibleStages = 0;
    s.visibleAccess = 0;
  } else {
    if (s.writeStages && !Covers(s, a)) {
      Global(s.writeStages, s.writeAccess, a.stages, a.access);
      s.visibleStages |= a.stages;
      s.visibleAccess |= a.access;
      needed = true;
    }
    s.readStages |= a.stages;
  }
  return needed;
}

bool BarrierBatch::Image(AccessState& s, const Access& a, VkImage image, VkImageAspectFlags aspects, uint32_t mip, uint32_t layer) {
  if (s.layout == a.layout) return Buffer(s, a);
  VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  b.srcStageMask = s.writeStages | s.readStages;
  b.srcAccessMask = s.writeAccess;
  b.dstStageMask = a.stages;
  b.dstAccessMask = a.access;
  b.oldLayout = s.layout;
  b.newLayout = a.layout;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {aspects, mip, 1, layer, 1};
  images_.push_back(b);
  s.layout = a.layout;
  if (a.write) {
    s.writeStages = a.stages;
    s.writeAccess = a.access & kWriteBits;
    s.readStages = 0;
    s.visibleStages = 0;
    s.visibleAccess = 0;
  } else {
    // The transition is a write that later accesses chain after; it is visible to this access.
    s.writeStages = a.stages;
    s.writeAccess = 0;
    s.readStages = a.stages;
    s.visibleStages = a.stages;
    s.visibleAccess = a.access;
  }
  return true;
}

void BarrierBatch::Record(VkCommandBuffer cmd) {
  if (Empty()) return;
  // Merge per-subresource barriers: consecutive layers of one mip, then consecutive mips.
  auto same = [](const VkImageMemoryBarrier2& x, const VkImageMemoryBarrier2& y) {
    return x.image == y.image && x.oldLayout == y.oldLayout && x.newLayout == y.newLayout && x.srcStageMask == y.srcStageMask &&
           x.srcAccessMask == y.srcAccessMask && x.dstStageMask == y.dstStageMask && x.dstAccessMask == y.dstAccessMask &&
           x.subresourceRange.aspectMask == y.subresourceRange.aspectMask;
  };
  std::vector<VkImageMemoryBarrier2> merged;
  for (const VkImageMemoryBarrier2& b : images_) {
    if (!merged.empty()) {
      VkImageMemoryBarrier2& m = merged.back();
      const VkImageSubresourceRange &mr = m.subresourceRange, &br = b.subresourceRange;
      if (same(m, b) && mr.baseMipLevel == br.baseMipLevel && mr.levelCount == br.levelCount &&
          mr.baseArrayLayer + mr.layerCount == br.baseArrayLayer) {
        m.subresourceRange.layerCount += br.layerCount;
        continue;
      }
      if (same(m, b) && mr.baseArrayLayer == br.baseArrayLayer && mr.layerCount == br.layerCount &&
          mr.baseMipLevel + mr.levelCount == br.baseMipLevel) {
        m.subresourceRange.levelCount += br.levelCount;
        continue;
      }
    }
    merged.push_back(b);
  }
  VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  mb.srcStageMask = srcStages_;
  mb.srcAccessMask = srcAccess_;
  mb.dstStageMask = dstStages_;
  mb.dstAccessMask = dstAccess_;
  VkDependencyInfo di{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  if (srcStages_ || dstStages_) {
    di.memoryBarrierCount = 1;
    di.pMemoryBarriers = &mb;
  }
  di.imageMemoryBarrierCount = uint32_t(merged.size());
  di.pImageMemoryBarriers = merged.data();
  vkCmdPipelineBarrier2(cmd, &di);
  images_.clear();
  srcStages_ = dstStages_ = 0;
  srcAccess_ = dstAccess_ = 0;
}

}  // namespace sp::vk
