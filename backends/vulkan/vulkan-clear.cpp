// Clears, mip generation, resolves and append-counter commands. Render-target and depth clears
// are dynamic-rendering passes with a CLEAR load op on the view itself (so view formats, layers
// and sRGB conversion behave as in D3D11, and scissor and write masks do not apply). UAV clears
// write the core's packed texels (detail::UavClearValue) by fills, copies or bit-exact clears.
#include <cmath>
#include <cstring>

#include "vulkan-internal.h"

namespace sp::vk {
namespace {

VkClearColorValue ClearColor(FORMAT f, const float rgba[4]) {
  VkClearColorValue v{};
  FormatKind k = GetFormatInfo(f).kind;
  for (int i = 0; i < 4; ++i) {
    float x = std::isnan(rgba[i]) ? 0.0f : rgba[i];
    if (k == FormatKind::UInt) v.uint32[i] = x <= 0 ? 0u : x >= 4294967295.0f ? 0xffffffffu : uint32_t(x);
    else if (k == FormatKind::SInt) v.int32[i] = int32_t(std::fmax(std::fmin(x, 2147483520.0f), -2147483648.0f));
    else v.float32[i] = rgba[i];
  }
  return v;
}

// Whether vkCmdClearColorImage writes the packed words unchanged: 32-bit channels, where integer
// formats take them as they are and float formats need no conversion (NaNs might be canonicalised).
bool ClearColorKeepsBits(FORMAT f, const uint8_t* texel) {
  const FormatInfo& fi = GetFormatInfo(f);
  if (fi.components == 0 || fi.bytesPerElement != 4 * fi.components) return false;
  if (fi.kind == FormatKind::UInt || fi.kind == FormatKind::SInt) return true;
  if (fi.kind != FormatKind::Float) return false;
  for (uint32_t c = 0; c < fi.components; ++c) {
    float x;
    std::memcpy(&x, texel + 4 * c, 4);
    if (std::isnan(x)) return false;
  }
  return true;
}

}  // namespace

void VulkanContext::ClearRenderTargetView(RenderTargetView* rtv, const float rgba[4]) {
  VkViewObj& v = ViewOf(rtv);
  VkCommandBuffer cmd = Cmd();
  UseView(v, access::ColorAttachment());
  FlushBarriers();
  VkRenderingAttachmentInfo a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  a.imageView = v.view;
  a.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  a.clearValue.color = ClearColor(rtv->ViewFormat(), rgba);
  const TextureShape& s = v.texture->shape;
  VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
  ri.renderArea = {{0, 0}, {s.mipWidth(v.firstMip), s.mipHeight(v.firstMip)}};
  ri.layerCount = v.renderLayers;
  ri.colorAttachmentCount = 1;
  ri.pColorAttachments = &a;
  vkCmdBeginRendering(cmd, &ri);
  vkCmdEndRendering(cmd);
  CountWork();
}

void VulkanContext::ClearDepthStencilView(DepthStencilView* dsv, uint32_t flags, float depth, uint8_t stencil) {
  VkViewObj& v = ViewOf(dsv);
  VkCommandBuffer cmd = Cmd();
  UseView(v, access::DepthAttachment(VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL, true));
  FlushBarriers();
  VkRenderingAttachmentInfo d{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  d.imageView = v.view;
  d.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
  d.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  d.clearValue.depthStencil = {depth, stencil};
  VkRenderingAttachmentInfo st = d;
  d.loadOp = (flags & CLEAR_DEPTH) ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
  st.loadOp = (flags & CLEAR_STENCIL) ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
  const TextureShape& s = v.texture->shape;
  VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
  ri.renderArea = {{0, 0}, {s.mipWidth(v.firstMip), s.mipHeight(v.firstMip)}};
  ri.layerCount = v.renderLayers;
  if (v.texture->aspects & VK_IMAGE_ASPECT_DEPTH_BIT) ri.pDepthAttachment = &d;
  if (v.texture->aspects & VK_IMAGE_ASPECT_STENCIL_BIT) ri.pStencilAttachment = &st;
  vkCmdBeginRendering(cmd, &ri);
  vkCmdEndRendering(cmd);
  CountWork();
}

void VulkanContext::ClearImageViaCopy(VkViewObj& v, const uint8_t* texel, uint32_t texelSize) {
  VkTextureObj& t = *v.texture;
  const TextureShape& s = t.shape;
  uint32_t w = s.mipWidth(v.firstMip), h = s.mipHeight(v.firstMip);
  bool is3D = s.dimension == RESOURCE_DIMENSION_TEXTURE3D;
  uint32_t z0 = is3D ? v.owner->Range().firstSlice : 0, dz = is3D ? v.owner->Range().sliceCount : 1;
  VkDeviceSize bytes = VkDeviceSize(w) * h * dz * texelSize;
  VkCommandBuffer cmd = Cmd();
  UploadSpan up = Upload(bytes, 16);
  for (VkDeviceSize i = 0; i < bytes; i += texelSize) std::memcpy(up.ptr + i, texel, texelSize);
  UseView(v, access::TransferWrite());
  FlushBarriers();
  std::vector<VkBufferImageCopy> regions;
  for (uint32_t l = v.firstLayer; l < v.firstLayer + v.layerCount; ++l)
    regions.push_back({up.offset, 0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, v.firstMip, l, 1}, {0, 0, int32_t(z0)}, {w, h, dz}});
  vkCmdCopyBufferToImage(cmd, up.buffer, t.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, uint32_t(regions.size()), regions.data());
  CountWork();
}

namespace {

// A typed buffer view filled with one texel: a fill when the texel is one 32-bit word, else a copy.
void ClearTexelBuffer(VulkanContext& ctx, VkViewObj& v, const uint8_t* texel, uint32_t size) {
  VkCommandBuffer cmd = ctx.Cmd();
  VkBufferObj& b = *v.buffer;
  ctx.UseBuffer(b, access::TransferWrite());
  v.lastUse = b.lastUse;
  if (size == 4) {
    ctx.FlushBarriers();
    uint32_t word;
    std::memcpy(&word, texel, 4);
    vkCmdFillBuffer(cmd, b.range.buffer, b.range.offset + v.byteOffset, v.byteSize, word);
    return;
  }
  UploadSpan up = ctx.Upload(v.byteSize, 16);
  for (VkDeviceSize i = 0; i + size <= v.byteSize; i += size) std::memcpy(up.ptr + i, texel, size);
  ctx.FlushBarriers();
  VkBufferCopy c{up.offset, b.range.offset + v.byteOffset, v.byteSize};
  vkCmdCopyBuffer(cmd, up.buffer, b.range.buffer, 1, &c);
}

}  // namespace

void VulkanContext::ClearUnorderedAccessView(UnorderedAccessView* uav, const detail::UavClearValue& value) {
  VkViewObj& v = ViewOf(uav);
  if (v.buffer) {
    if (value.perWord) {
      VkCommandBuffer cmd = Cmd();
      UseBuffer(*v.buffer, access::TransferWrite());
      v.lastUse = v.buffer->lastUse;
      FlushBarriers();
      uint32_t word;
      std::memcpy(&word, value.texel, 4);
      vkCmdFillBuffer(cmd, v.buffer->range.buffer, v.buffer->range.offset + v.byteOffset, v.byteSize, word);
    } else {
      ClearTexelBuffer(*this, v, value.texel, value.texelBytes);
    }
    CountWork();
    return;
  }
  if (v.format == v.texture->format && ClearColorKeepsBits(uav->ViewFormat(), value.texel)) {
    VkCommandBuffer cmd = Cmd();
    UseView(v, access::TransferWrite());
    FlushBarriers();
    VkClearColorValue c{};
    std::memcpy(c.uint32, value.texel, value.texelBytes);
    VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, v.firstMip, 1, v.firstLayer, v.layerCount};
    vkCmdClearColorImage(cmd, v.texture->image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &c, 1, &range);
    CountWork();
    return;
  }
  ClearImageViaCopy(v, value.texel, value.texelBytes);
}

// ---------------------------------------------------------------------------------------------

void VulkanContext::GenerateMips(ShaderResourceView* srv) {
  VkViewObj& v = ViewOf(srv);
  VkTextureObj& t = *v.texture;
  VkFormatProperties fp;
  vkGetPhysicalDeviceFormatProperties(dev_->physical, t.format, &fp);
  const VkFormatFeatureFlags need = VK_FORMAT_FEATURE_BLIT_SRC_BIT | VK_FORMAT_FEATURE_BLIT_DST_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
  if ((fp.optimalTilingFeatures & need) != need)
    Throw(ErrorId::NOT_SUPPORTED, "GenerateMips", DescribeObject(srv), std::string(FormatName(t.shape.format)) + " cannot be filtered by blits on this device");
  VkCommandBuffer cmd = Cmd();
  const TextureShape& s = t.shape;
  for (uint32_t mip = v.firstMip + 1; mip < v.firstMip + v.mipCount; ++mip) {
    UseImage(t, mip - 1, 1, v.firstLayer, v.layerCount, access::TransferRead());
    UseImage(t, mip, 1, v.firstLayer, v.layerCount, access::TransferWrite());
    FlushBarriers();
    VkImageBlit b{};
    b.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, mip - 1, v.firstLayer, v.layerCount};
    b.srcOffsets[1] = {int32_t(s.mipWidth(mip - 1)), int32_t(s.mipHeight(mip - 1)), int32_t(s.mipDepth(mip - 1))};
    b.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, mip, v.firstLayer, v.layerCount};
    b.dstOffsets[1] = {int32_t(s.mipWidth(mip)), int32_t(s.mipHeight(mip)), int32_t(s.mipDepth(mip))};
    vkCmdBlitImage(cmd, t.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, t.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &b, VK_FILTER_LINEAR);
  }
  v.lastUse = dev_->recordingSerial;
  CountWork();
}

void VulkanContext::ResolveSubresource(Resource* dst, const detail::Subresource& dstSr, Resource* src, const detail::Subresource& srcSr, FORMAT format) {
  const char* call = "ResolveSubresource";
  VkTextureObj &d = TextureOf(dst), &s = TextureOf(src);
  if (IsIntegerFormat(format))
    Throw(ErrorId::FORMAT_UNSUPPORTED, call, DescribeObject(src), std::string(FormatName(format)) + " cannot be resolved (integer formats have no MULTISAMPLE_RESOLVE)");
  const uint32_t sm = srcSr.mip, slayer = srcSr.slice, dm = dstSr.mip, dlayer = dstSr.slice;
  VkFormat vf = VkFormatOf(format);
  VkCommandBuffer cmd = Cmd();
  VkExtent3D extent{d.shape.mipWidth(dm), d.shape.mipHeight(dm), 1};
  if (s.format == vf && d.format == vf) {
    UseImage(s, sm, 1, slayer, 1, access::TransferRead());
    UseImage(d, dm, 1, dlayer, 1, access::TransferWrite());
    FlushBarriers();
    VkImageResolve r{{VK_IMAGE_ASPECT_COLOR_BIT, sm, slayer, 1}, {0, 0, 0}, {VK_IMAGE_ASPECT_COLOR_BIT, dm, dlayer, 1}, {0, 0, 0}, extent};
    vkCmdResolveImage(cmd, s.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, d.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &r);
    CountWork();
    return;
  }
  // The storage formats differ (a TYPELESS resource on one side): resolve in the view format
  // through a rendering pass with a resolve attachment.
  auto makeView = [&](VkTextureObj& t, uint32_t mip, uint32_t layer) {
    VkImageViewUsageCreateInfo uci{VK_STRUCTURE_TYPE_IMAGE_VIEW_USAGE_CREATE_INFO};
    uci.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    VkImageViewCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    ci.pNext = &uci;
    ci.image = t.image;
    ci.viewType = VK_IMAGE_VIEW_TYPE_2D;
    ci.format = vf;
    ci.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, mip, 1, layer, 1};
    VkImageView iv;
    Check(vkCreateImageView(dev_->device, &ci, nullptr, &iv), call, DescribeObject(t.owner), "vkCreateImageView");
    VulkanDevice* dv = dev_;
    dev_->Defer(dev_->recordingSerial, [dv, iv] { vkDestroyImageView(dv->device, iv, nullptr); });
    return iv;
  };
  VkImageView sv = makeView(s, sm, slayer), dv = makeView(d, dm, dlayer);
  UseImage(s, sm, 1, slayer, 1, {VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, false});
  UseImage(d, dm, 1, dlayer, 1, access::ColorAttachment());
  FlushBarriers();
  VkRenderingAttachmentInfo a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  a.imageView = sv;
  a.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  a.resolveMode = VK_RESOLVE_MODE_AVERAGE_BIT;
  a.resolveImageView = dv;
  a.resolveImageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  a.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  a.storeOp = VK_ATTACHMENT_STORE_OP_NONE;
  VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
  ri.renderArea = {{0, 0}, {extent.width, extent.height}};
  ri.layerCount = 1;
  ri.colorAttachmentCount = 1;
  ri.pColorAttachments = &a;
  vkCmdBeginRendering(cmd, &ri);
  vkCmdEndRendering(cmd);
  CountWork();
}

void VulkanContext::CopyStructureCount(Buffer* dst, uint32_t dstOffset, UnorderedAccessView* src) {
  VkViewObj& v = ViewOf(src);
  VkBufferObj& b = BufferOf(dst);
  VkCommandBuffer cmd = Cmd();
  UseRange(v.counterState, access::TransferRead());
  v.lastUse = dev_->recordingSerial;
  UseBuffer(b, access::TransferWrite());
  FlushBarriers();
  VkBufferCopy c{v.counter.offset, b.range.offset + dstOffset, 4};
  vkCmdCopyBuffer(cmd, v.counter.buffer, b.range.buffer, 1, &c);
  CountWork();
}

void VulkanContext::SetUavCounter(UnorderedAccessView* uav, uint32_t value) {
  VkViewObj& v = ViewOf(uav);
  VkCommandBuffer cmd = Cmd();
  UseRange(v.counterState, access::TransferWrite());
  v.lastUse = dev_->recordingSerial;
  FlushBarriers();
  vkCmdFillBuffer(cmd, v.counter.buffer, v.counter.offset, 4, value);
  CountWork();
}

}  // namespace sp::vk
