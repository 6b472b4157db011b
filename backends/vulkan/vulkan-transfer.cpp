// Copies and updates: buffer copies, image <-> image, image <-> staging (staging textures are host
// buffers in D3D11's layout; packed depth-stencil goes through per-aspect planes), uploads
// through the ring for initial data and UpdateSubresource.
#include <cstring>

#include "vulkan-internal.h"

namespace sp::vk {
namespace {


bool HasStencil(const VkTextureObj& t) { return (t.aspects & VK_IMAGE_ASPECT_STENCIL_BIT) != 0; }

// Texel size of the staging planes' depth aspect and of the D3D layout.
uint32_t D3DTexelSize(const VkTextureObj& t) { return GetFormatInfo(t.shape.format).bytesPerElement; }

}  // namespace

// ---------------------------------------------------------------------------------------------
// Uploads

void VulkanContext::UploadToBuffer(VkBufferObj& b, VkDeviceSize offset, const void* data, VkDeviceSize size) {
  if (size == 0) return;
  VkCommandBuffer cmd = Cmd();
  UploadSpan up = Upload(size, 16);
  std::memcpy(up.ptr, data, size);
  UseBuffer(b, access::TransferWrite());
  FlushBarriers();
  VkBufferCopy c{up.offset, b.range.offset + offset, size};
  vkCmdCopyBuffer(cmd, up.buffer, b.range.buffer, 1, &c);
  CountWork();
}

void VulkanContext::ZeroBuffer(VkBufferObj& b) {
  VkCommandBuffer cmd = Cmd();
  UseBuffer(b, access::TransferWrite());
  FlushBarriers();
  vkCmdFillBuffer(cmd, b.range.buffer, b.range.offset, b.range.size, 0);
}

void VulkanContext::UploadToImage(VkTextureObj& t, const detail::Subresource& loc, const BOX& box, const void* data, uint32_t rowPitch, uint32_t depthPitch) {
  uint32_t w = box.right - box.left, h = box.bottom - box.top, d = box.back - box.front;
  uint32_t texel = D3DTexelSize(t);
  uint64_t texels = uint64_t(w) * h * d;
  const uint8_t* src = static_cast<const uint8_t*>(data);
  if (t.shape.dimension == RESOURCE_DIMENSION_TEXTURE1D) rowPitch = w * texel;
  if (d == 1 && depthPitch == 0) depthPitch = rowPitch * h;
  VkCommandBuffer cmd = Cmd();
  VkBufferImageCopy regions[2]{};
  VkImageSubresourceLayers layers{t.aspects, loc.mip, loc.slice, 1};
  VkOffset3D offset{int32_t(box.left), int32_t(box.top), int32_t(box.front)};
  VkExtent3D extent{w, h, d};
  if (HasStencil(t)) {
    // D3D11 packs depth and stencil in one texel; Vulkan copies each aspect on its own.
    UploadSpan dp = Upload(texels * 4, 16), sp = Upload(texels, 16);
    uint64_t i = 0;
    for (uint32_t z = 0; z < d; ++z)
      for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x, ++i) {
          const uint8_t* p = src + size_t(z) * depthPitch + size_t(y) * rowPitch + size_t(x) * texel;
          uint32_t v;
          std::memcpy(&v, p, 4);
          if (texel == 4) {
            uint32_t dv = v & 0xffffff;
            std::memcpy(dp.ptr + i * 4, &dv, 4);
            sp.ptr[i] = uint8_t(v >> 24);
          } else {
            std::memcpy(dp.ptr + i * 4, &v, 4);
            sp.ptr[i] = p[4];
          }
        }
    regions[0] = {dp.offset, 0, 0, {VK_IMAGE_ASPECT_DEPTH_BIT, loc.mip, loc.slice, 1}, offset, extent};
    regions[1] = {sp.offset, 0, 0, {VK_IMAGE_ASPECT_STENCIL_BIT, loc.mip, loc.slice, 1}, offset, extent};
    UseImage(t, loc.mip, 1, loc.slice, 1, access::TransferWrite());
    FlushBarriers();
    // The two spans may lie in different ring chunks (different VkBuffers).
    vkCmdCopyBufferToImage(cmd, dp.buffer, t.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &regions[0]);
    vkCmdCopyBufferToImage(cmd, sp.buffer, t.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &regions[1]);
    CountWork();
    return;
  }
  uint32_t row = w * texel;
  UploadSpan up = Upload(VkDeviceSize(row) * h * d, 16);
  for (uint32_t z = 0; z < d; ++z)
    for (uint32_t y = 0; y < h; ++y)
      std::memcpy(up.ptr + (size_t(z) * h + y) * row, src + size_t(z) * depthPitch + size_t(y) * rowPitch, row);
  regions[0] = {up.offset, 0, 0, layers, offset, extent};
  UseImage(t, loc.mip, 1, loc.slice, 1, access::TransferWrite());
  FlushBarriers();
  vkCmdCopyBufferToImage(cmd, up.buffer, t.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, regions);
  CountWork();
}

void VulkanContext::ZeroImage(VkTextureObj& t) {
  VkCommandBuffer cmd = Cmd();
  UseImage(t, 0, t.shape.mipLevels, 0, t.layers, access::TransferWrite());
  FlushBarriers();
  VkImageSubresourceRange range{t.aspects, 0, t.shape.mipLevels, 0, t.layers};
  if (IsDepthStencilFormat(t.format)) {
    VkClearDepthStencilValue v{0.0f, 0};
    vkCmdClearDepthStencilImage(cmd, t.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &v, 1, &range);
  } else {
    VkClearColorValue v{};
    vkCmdClearColorImage(cmd, t.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &v, 1, &range);
  }
}

void VulkanContext::UpdateSubresource(Resource* dst, const detail::Subresource& sub, const BOX& box, const void* data, uint32_t rowPitch, uint32_t depthPitch) {
  if (dst->GetType() == RESOURCE_DIMENSION_BUFFER) {
    VkBufferObj& b = BufferOf(dst);
    // Host-visible memory is written in place when the GPU is done with it; a whole-buffer update
    // of a busy buffer gets fresh memory (as WRITE_DISCARD), so per-draw constant updates need
    // no copy and do not interrupt the render pass.
    bool whole = box.left == 0 && box.right == b.desc.ByteWidth;
    if (b.range.mapped && whole) Rename(b);
    if (b.range.mapped && b.lastUse < dev_->recordingSerial && !IsBusy(b.lastUse)) {
      std::memcpy(b.range.mapped + box.left, data, box.right - box.left);
      b.contentVersion++;
      return;
    }
    UploadToBuffer(b, box.left, data, box.right - box.left);
    return;
  }
  UploadToImage(TextureOf(dst), sub, box, data, rowPitch, depthPitch);
}

// ---------------------------------------------------------------------------------------------
// Copies

void VulkanContext::CopyResource(Resource* dst, Resource* src) {
  if (dst->GetType() == RESOURCE_DIMENSION_BUFFER) {
    BOX box{0, 0, 0, BufferOf(src).desc.ByteWidth, 1, 1};
    const detail::Subresource whole = detail::BufferSubresource(box.right);
    CopySubresourceRegion(dst, whole, 0, 0, 0, src, whole, box);
    return;
  }
  const TextureShape& s = TextureOf(src).shape;
  for (uint32_t i = 0; i < s.subresourceCount(); ++i) {
    const detail::Subresource at = detail::SubresourceOf(s, i);
    CopySubresourceRegion(dst, at, 0, 0, 0, src, at, at.box());
  }
}

void VulkanContext::CopySubresourceRegion(Resource* dst, const detail::Subresource& dstSub, uint32_t x, uint32_t y, uint32_t z, Resource* src, const detail::Subresource& srcSub,
                                          const BOX& box) {
  if (dst->GetType() == RESOURCE_DIMENSION_BUFFER) {
    VkBufferObj &d = BufferOf(dst), &s = BufferOf(src);
    VkCommandBuffer cmd = Cmd();
    UseBuffer(s, access::TransferRead());
    UseBuffer(d, access::TransferWrite());
    FlushBarriers();
    VkBufferCopy c{s.range.offset + box.left, d.range.offset + x, box.right - box.left};
    vkCmdCopyBuffer(cmd, s.range.buffer, d.range.buffer, 1, &c);
    CountWork();
    return;
  }
  VkTextureObj &d = TextureOf(dst), &s = TextureOf(src);
  if (!s.staging && !d.staging) CopyImageToImage(s, srcSub, d, dstSub, box, x, y, z);
  else if (!s.staging) CopyImageToStaging(s, srcSub, d, dstSub, box, x, y, z);
  else if (!d.staging) CopyStagingToImage(s, srcSub, d, dstSub, box, x, y, z);
  else CopyStagingToStaging(s, srcSub, d, dstSub, box, x, y, z);
  CountWork();
}

void VulkanContext::CopyImageToImage(VkTextureObj& s, const detail::Subresource& srcSub, VkTextureObj& d, const detail::Subresource& dstSub, const BOX& box, uint32_t x, uint32_t y,
                                     uint32_t z) {
  const detail::Subresource &sl = srcSub, &dl = dstSub;
  VkExtent3D extent{box.right - box.left, box.bottom - box.top, box.back - box.front};
  VkOffset3D srcOff{int32_t(box.left), int32_t(box.top), int32_t(box.front)}, dstOff{int32_t(x), int32_t(y), int32_t(z)};
  VkCommandBuffer cmd = Cmd();
  bool depthS = IsDepthStencilFormat(s.format), depthD = IsDepthStencilFormat(d.format);
  if (depthS == depthD) {
    bool self = &s == &d && srcSub.index == dstSub.index;
    VkImageLayout srcLayout = self ? VK_IMAGE_LAYOUT_GENERAL : VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    VkImageLayout dstLayout = self ? VK_IMAGE_LAYOUT_GENERAL : VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    Access r = access::TransferRead(), w = access::TransferWrite();
    r.layout = srcLayout;
    w.layout = dstLayout;
    UseImage(s, sl.mip, 1, sl.slice, 1, r);
    UseImage(d, dl.mip, 1, dl.slice, 1, w);
    FlushBarriers();
    VkImageCopy c{{s.aspects, sl.mip, sl.slice, 1}, srcOff, {d.aspects, dl.mip, dl.slice, 1}, dstOff, extent};
    vkCmdCopyImage(cmd, s.image, srcLayout, d.image, dstLayout, 1, &c);
    return;
  }
  // Depth <-> colour of one family (R32_TYPELESS as D32_FLOAT and as R32_FLOAT): Vulkan copies
  // between them only through a buffer.
  if (s.shape.sampleCount > 1)
    Throw(ErrorId::NOT_SUPPORTED, "CopySubresourceRegion", DescribeObject(d.owner),
          "multisampled copies between depth and colour textures are not supported on Vulkan");
  uint32_t texel = D3DTexelSize(s);
  UploadSpan tmp = Upload(VkDeviceSize(texel) * extent.width * extent.height * extent.depth, 16);
  VkImageAspectFlags sa = depthS ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
  VkImageAspectFlags da = depthD ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
  UseImage(s, sl.mip, 1, sl.slice, 1, access::TransferRead());
  FlushBarriers();
  VkBufferImageCopy r1{tmp.offset, 0, 0, {sa, sl.mip, sl.slice, 1}, srcOff, extent};
  vkCmdCopyImageToBuffer(cmd, s.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, tmp.buffer, 1, &r1);
  AccessState scratch;
  UseRange(scratch, access::TransferWrite());
  UseRange(scratch, access::TransferRead());
  UseImage(d, dl.mip, 1, dl.slice, 1, access::TransferWrite());
  FlushBarriers();
  VkBufferImageCopy r2{tmp.offset, 0, 0, {da, dl.mip, dl.slice, 1}, dstOff, extent};
  vkCmdCopyBufferToImage(cmd, tmp.buffer, d.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &r2);
}

void VulkanContext::CopyImageToStaging(VkTextureObj& s, const detail::Subresource& srcSub, VkTextureObj& d, const detail::Subresource& dstSub, const BOX& box, uint32_t x, uint32_t y,
                                       uint32_t z) {
  const detail::Subresource &sl = srcSub, &dl = dstSub;
  const VkTextureObj::Sub& ds = d.subs[dstSub.index];
  VkExtent3D extent{box.right - box.left, box.bottom - box.top, box.back - box.front};
  VkOffset3D srcOff{int32_t(box.left), int32_t(box.top), int32_t(box.front)};
  uint32_t w = d.shape.mipWidth(dl.mip), h = d.shape.mipHeight(dl.mip);
  VkCommandBuffer cmd = Cmd();
  UseImage(s, sl.mip, 1, sl.slice, 1, access::TransferRead());
  uint64_t serial = dev_->recordingSerial;
  d.lastUse = d.lastWrite = serial;
  if (d.usesPlanes) {
    UseRange(d.depthPlaneState, access::TransferWrite());
    UseRange(d.stencilPlaneState, access::TransferWrite());
    FlushBarriers();
    VkDeviceSize first = (VkDeviceSize(z) * h + y) * w + x;
    VkBufferImageCopy r[2] = {{d.depthPlane.offset + ds.depthOffset + first * 4, w, h, {VK_IMAGE_ASPECT_DEPTH_BIT, sl.mip, sl.slice, 1}, srcOff, extent},
                              {d.stencilPlane.offset + ds.stencilOffset + first, w, h, {VK_IMAGE_ASPECT_STENCIL_BIT, sl.mip, sl.slice, 1}, srcOff, extent}};
    vkCmdCopyImageToBuffer(cmd, s.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, d.depthPlane.buffer, 1, &r[0]);
    vkCmdCopyImageToBuffer(cmd, s.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, d.stencilPlane.buffer, 1, &r[1]);
    d.planesNewer = true;
    return;
  }
  UseRange(d.mainState, access::TransferWrite());
  FlushBarriers();
  uint32_t texel = D3DTexelSize(d);
  VkBufferImageCopy r{d.main.offset + ds.offset + VkDeviceSize(z) * ds.depthPitch + VkDeviceSize(y) * ds.rowPitch + VkDeviceSize(x) * texel,
                      ds.rowPitch / texel, h, {s.aspects, sl.mip, sl.slice, 1}, srcOff, extent};
  vkCmdCopyImageToBuffer(cmd, s.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, d.main.buffer, 1, &r);
}

void VulkanContext::CopyStagingToImage(VkTextureObj& s, const detail::Subresource& srcSub, VkTextureObj& d, const detail::Subresource& dstSub, const BOX& box, uint32_t x, uint32_t y,
                                       uint32_t z) {
  const detail::Subresource &sl = srcSub, &dl = dstSub;
  const VkTextureObj::Sub& ss = s.subs[srcSub.index];
  VkExtent3D extent{box.right - box.left, box.bottom - box.top, box.back - box.front};
  VkOffset3D dstOff{int32_t(x), int32_t(y), int32_t(z)};
  uint32_t w = s.shape.mipWidth(sl.mip), h = s.shape.mipHeight(sl.mip);
  VkCommandBuffer cmd = Cmd();
  UseImage(d, dl.mip, 1, dl.slice, 1, access::TransferWrite());
  s.lastUse = dev_->recordingSerial;
  if (s.usesPlanes) {
    UseRange(s.depthPlaneState, access::TransferRead());
    UseRange(s.stencilPlaneState, access::TransferRead());
    FlushBarriers();
    VkDeviceSize first = (VkDeviceSize(box.front) * h + box.top) * w + box.left;
    VkBufferImageCopy r[2] = {{s.depthPlane.offset + ss.depthOffset + first * 4, w, h, {VK_IMAGE_ASPECT_DEPTH_BIT, dl.mip, dl.slice, 1}, dstOff, extent},
                              {s.stencilPlane.offset + ss.stencilOffset + first, w, h, {VK_IMAGE_ASPECT_STENCIL_BIT, dl.mip, dl.slice, 1}, dstOff, extent}};
    vkCmdCopyBufferToImage(cmd, s.depthPlane.buffer, d.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &r[0]);
    vkCmdCopyBufferToImage(cmd, s.stencilPlane.buffer, d.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &r[1]);
    return;
  }
  UseRange(s.mainState, access::TransferRead());
  FlushBarriers();
  uint32_t texel = D3DTexelSize(s);
  VkBufferImageCopy r{s.main.offset + ss.offset + VkDeviceSize(box.front) * ss.depthPitch + VkDeviceSize(box.top) * ss.rowPitch + VkDeviceSize(box.left) * texel,
                      ss.rowPitch / texel, h, {d.aspects, dl.mip, dl.slice, 1}, dstOff, extent};
  vkCmdCopyBufferToImage(cmd, s.main.buffer, d.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &r);
}

void VulkanContext::CopyStagingToStaging(VkTextureObj& s, const detail::Subresource& srcSub, VkTextureObj& d, const detail::Subresource& dstSub, const BOX& box, uint32_t x, uint32_t y,
                                         uint32_t z) {
  const VkTextureObj::Sub &ss = s.subs[srcSub.index], &ds = d.subs[dstSub.index];
  uint32_t texel = D3DTexelSize(s);
  VkCommandBuffer cmd = Cmd();
  UseRange(s.mainState, access::TransferRead());
  UseRange(d.mainState, access::TransferWrite());
  uint64_t serial = dev_->recordingSerial;
  s.lastUse = serial;
  d.lastUse = d.lastWrite = serial;
  std::vector<VkBufferCopy> rows;
  uint32_t rowBytes = (box.right - box.left) * texel;
  for (uint32_t zz = 0; zz < box.back - box.front; ++zz)
    for (uint32_t yy = 0; yy < box.bottom - box.top; ++yy)
      rows.push_back({s.main.offset + ss.offset + VkDeviceSize(box.front + zz) * ss.depthPitch + VkDeviceSize(box.top + yy) * ss.rowPitch + VkDeviceSize(box.left) * texel,
                      d.main.offset + ds.offset + VkDeviceSize(z + zz) * ds.depthPitch + VkDeviceSize(y + yy) * ds.rowPitch + VkDeviceSize(x) * texel, rowBytes});
  if (s.usesPlanes && d.usesPlanes) {
    // Depth-stencil copies are whole subresources; the planes are what the GPU keeps current.
    UseRange(s.depthPlaneState, access::TransferRead());
    UseRange(s.stencilPlaneState, access::TransferRead());
    UseRange(d.depthPlaneState, access::TransferWrite());
    UseRange(d.stencilPlaneState, access::TransferWrite());
    FlushBarriers();
    VkDeviceSize texels = VkDeviceSize(srcSub.width) * srcSub.height * srcSub.depth;
    VkBufferCopy dc{s.depthPlane.offset + ss.depthOffset, d.depthPlane.offset + ds.depthOffset, texels * 4};
    VkBufferCopy sc{s.stencilPlane.offset + ss.stencilOffset, d.stencilPlane.offset + ds.stencilOffset, texels};
    vkCmdCopyBuffer(cmd, s.depthPlane.buffer, d.depthPlane.buffer, 1, &dc);
    vkCmdCopyBuffer(cmd, s.stencilPlane.buffer, d.stencilPlane.buffer, 1, &sc);
    d.planesNewer = true;
  } else {
    FlushBarriers();
  }
  vkCmdCopyBuffer(cmd, s.main.buffer, d.main.buffer, uint32_t(rows.size()), rows.data());
}

}  // namespace sp::vk
