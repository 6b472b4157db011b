// Views: a VkImageView per SRV/RTV/DSV/UAV of a texture, VkBufferViews for typed buffer views
// (one per buffer version, since dynamic buffers move), plain ranges for structured and raw
// views, and the hidden counter of append/consume UAVs.
#include <algorithm>

#include "vulkan-internal.h"

namespace sp::vk {
namespace {

const char* CallFor(VkViewObj::Kind k) {
  switch (k) {
    case VkViewObj::SRV: return "CreateShaderResourceView";
    case VkViewObj::RTV: return "CreateRenderTargetView";
    case VkViewObj::DSV: return "CreateDepthStencilView";
    default: return "CreateUnorderedAccessView";
  }
}

struct ImageViewShape {
  VkImageViewType type = VK_IMAGE_VIEW_TYPE_2D;
  uint32_t baseLayer = 0, layers = 1;
};

ImageViewShape ShapeOf(ViewShape shape, const ViewRange& r) {
  switch (shape) {
    case ViewShape::Texture1D: return {VK_IMAGE_VIEW_TYPE_1D, r.firstSlice, 1};
    case ViewShape::Texture1DArray: return {VK_IMAGE_VIEW_TYPE_1D_ARRAY, r.firstSlice, r.sliceCount};
    case ViewShape::Texture2DArray:
    case ViewShape::Texture2DMSArray: return {VK_IMAGE_VIEW_TYPE_2D_ARRAY, r.firstSlice, r.sliceCount};
    case ViewShape::Texture3D: return {VK_IMAGE_VIEW_TYPE_3D, 0, 1};
    case ViewShape::TextureCube: return {VK_IMAGE_VIEW_TYPE_CUBE, r.firstSlice, 6};
    case ViewShape::TextureCubeArray: return {VK_IMAGE_VIEW_TYPE_CUBE_ARRAY, r.firstSlice, r.sliceCount};
    default: return {VK_IMAGE_VIEW_TYPE_2D, r.firstSlice, 1};
  }
}

}  // namespace

std::unique_ptr<VkViewObj> CreateViewObj(VulkanDevice* dev, View& view) {
  auto v = std::make_unique<VkViewObj>();
  v->dev = dev;
  v->owner = &view;
  switch (view.Kind()) {
    case ViewKind::ShaderResource: v->kind = VkViewObj::SRV; break;
    case ViewKind::RenderTarget: v->kind = VkViewObj::RTV; break;
    case ViewKind::DepthStencil: v->kind = VkViewObj::DSV; break;
    case ViewKind::UnorderedAccess: v->kind = VkViewObj::UAV; break;
  }
  const char* call = CallFor(v->kind);
  std::string object = DescribeObject(&view);
  const ViewRange& r = view.Range();
  Resource* res = view.GetResource();
  const VkPhysicalDeviceLimits& lim = dev->props.limits;

  if (view.IsBuffer()) {
    VkBufferObj& b = BufferOf(res);
    v->buffer = &b;
    v->byteOffset = r.firstByte;
    v->byteSize = r.byteCount;
    if (v->kind == VkViewObj::UAV) {
      const auto& d = static_cast<UnorderedAccessView&>(view).GetDesc();
      if (d.Buffer.Flags & (BUFFER_UAV_FLAG_APPEND | BUFFER_UAV_FLAG_COUNTER)) {
        v->counter = dev->alloc.AllocateBuffer(4, MemoryKind::Device, call, object);
        if (v->counter.mapped) {
          *reinterpret_cast<uint32_t*>(v->counter.mapped) = 0;
        } else {
          VkCommandBuffer cmd = dev->ctx->Cmd();
          dev->ctx->UseRange(v->counterState, access::TransferWrite());
          dev->ctx->FlushBarriers();
          vkCmdFillBuffer(cmd, v->counter.buffer, v->counter.offset, 4, 0);
          v->lastUse = dev->recordingSerial;
        }
      }
    }
    v->texel = view.Shape() == ViewShape::TypedBuffer;
    if (v->texel) {
      v->format = VkFormatOf(view.ViewFormat());
      VkFormatProperties fp;
      vkGetPhysicalDeviceFormatProperties(dev->physical, v->format, &fp);
      VkFormatFeatureFlags need = v->kind == VkViewObj::SRV ? VK_FORMAT_FEATURE_UNIFORM_TEXEL_BUFFER_BIT : VK_FORMAT_FEATURE_STORAGE_TEXEL_BUFFER_BIT;
      if (!(fp.bufferFeatures & need))
        Throw(ErrorId::FORMAT_UNSUPPORTED, call, object, std::string(FormatName(view.ViewFormat())) + " cannot be a typed buffer " +
                                                           (v->kind == VkViewObj::SRV ? "SRV" : "UAV") + " on this device");
      uint32_t texelSize = GetFormatInfo(view.ViewFormat()).bytesPerElement;
      if (v->byteSize / texelSize > lim.maxTexelBufferElements)
        Throw(ErrorId::SIZE_OUT_OF_RANGE, call, object, "the device allows at most " + std::to_string(lim.maxTexelBufferElements) + " elements in a typed buffer view");
      if (b.desc.Usage != USAGE_DYNAMIC) v->TexelView(call);
    } else {
      VkDeviceSize align = lim.minStorageBufferOffsetAlignment;
      if (v->byteOffset % align)
        Throw(ErrorId::NOT_SUPPORTED, call, object, "the view starts at byte " + std::to_string(v->byteOffset) + ", but this device's storage-buffer offset alignment is " +
                                                      std::to_string(align) + " bytes (minStorageBufferOffsetAlignment); choose FirstElement accordingly");
      if (v->byteSize > lim.maxStorageBufferRange)
        Throw(ErrorId::SIZE_OUT_OF_RANGE, call, object, "the device binds at most " + std::to_string(lim.maxStorageBufferRange) + " bytes as a storage buffer");
    }
    return v;
  }

  VkTextureObj& t = TextureOf(res);
  v->texture = &t;
  const TextureShape& s = t.shape;
  FORMAT vf = view.ViewFormat();
  const FormatInfo& fi = GetFormatInfo(vf);
  v->format = VkFormatOf(vf);
  if (IsDepthStencilFormat(t.format)) {
    v->format = t.format;  // depth textures are always viewed in their depth format, through an aspect
    if (v->kind == VkViewObj::DSV) v->aspect = t.aspects;
    else v->aspect = fi.readsStencil ? VK_IMAGE_ASPECT_STENCIL_BIT : VK_IMAGE_ASPECT_DEPTH_BIT;
  } else {
    v->aspect = VK_IMAGE_ASPECT_COLOR_BIT;
  }
  v->firstMip = r.firstMip;
  v->mipCount = r.mipCount;
  bool is3D = s.dimension == RESOURCE_DIMENSION_TEXTURE3D;
  v->firstLayer = is3D ? 0 : r.firstSlice;
  v->layerCount = is3D ? 1 : r.sliceCount;
  v->renderLayers = r.sliceCount;

  ImageViewShape shape;
  VkImageUsageFlags usage = 0;
  switch (v->kind) {
    case VkViewObj::SRV: {
      shape = ShapeOf(view.Shape(), r);
      usage = VK_IMAGE_USAGE_SAMPLED_BIT;
      if (shape.type == VK_IMAGE_VIEW_TYPE_CUBE_ARRAY && !dev->feat.cubeArray)
        Throw(ErrorId::NOT_SUPPORTED, call, object, "TextureCubeArray views need imageCubeArray, which this device lacks");
      break;
    }
    case VkViewObj::RTV: {
      usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
      // A 3D mip renders as a 2D array of its W slices.
      shape = is3D ? ImageViewShape{VK_IMAGE_VIEW_TYPE_2D_ARRAY, r.firstSlice, r.sliceCount} : ShapeOf(view.Shape(), r);
      break;
    }
    case VkViewObj::DSV: {
      const auto& d = static_cast<DepthStencilView&>(view).GetDesc();
      usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
      shape = ShapeOf(view.Shape(), r);
      v->depthReadOnly = d.Flags & DSV_READ_ONLY_DEPTH;
      v->stencilReadOnly = (d.Flags & DSV_READ_ONLY_STENCIL) || !(t.aspects & VK_IMAGE_ASPECT_STENCIL_BIT);
      break;
    }
    case VkViewObj::UAV: {
      usage = VK_IMAGE_USAGE_STORAGE_BIT;
      // A Vulkan 3D storage image always covers the whole depth of its mip.
      if (view.Shape() == ViewShape::Texture3D && (r.firstSlice != 0 || r.sliceCount != s.mipDepth(r.firstMip)))
        Throw(ErrorId::NOT_SUPPORTED, call, object, "UAVs of part of a Texture3D's depth (FirstWSlice/WSize) are not supported on Vulkan; view the whole mip");
      shape = ShapeOf(view.Shape(), r);
      break;
    }
  }

  VkImageViewUsageCreateInfo uci{VK_STRUCTURE_TYPE_IMAGE_VIEW_USAGE_CREATE_INFO};
  uci.usage = usage;
  VkImageViewCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  ci.pNext = &uci;
  ci.image = t.image;
  ci.viewType = shape.type;
  ci.format = v->format;
  if (v->kind == VkViewObj::SRV && v->aspect == VK_IMAGE_ASPECT_STENCIL_BIT) {
    // X24_TYPELESS_G8_UINT reads stencil in G; Vulkan returns it in R.
    ci.components = {VK_COMPONENT_SWIZZLE_R, VK_COMPONENT_SWIZZLE_R, VK_COMPONENT_SWIZZLE_ZERO, VK_COMPONENT_SWIZZLE_ONE};
  }
  ci.subresourceRange = {v->aspect, r.firstMip, r.mipCount, shape.baseLayer, shape.layers};
  Check(vkCreateImageView(dev->device, &ci, nullptr, &v->view), call, object, "vkCreateImageView");
  dev->Name(VK_OBJECT_TYPE_IMAGE_VIEW, uint64_t(v->view), object);
  return v;
}

VkBufferView VkViewObj::TexelView(const char* call) {
  const BufferRange& br = buffer->range;
  for (const TexelEntry& tv : texelViews)
    if (tv.buffer == br.buffer && tv.offset == br.offset) return tv.view;
  VkDeviceSize offset = br.offset + byteOffset;
  uint32_t texelSize = GetFormatInfo(owner->ViewFormat()).bytesPerElement;
  bool storage = kind == UAV;
  VkDeviceSize align = storage ? dev->props13.storageTexelBufferOffsetAlignmentBytes : dev->props13.uniformTexelBufferOffsetAlignmentBytes;
  bool single = storage ? dev->props13.storageTexelBufferOffsetSingleTexelAlignment : dev->props13.uniformTexelBufferOffsetSingleTexelAlignment;
  if (align == 0) align = dev->props.limits.minTexelBufferOffsetAlignment;
  if (single) align = std::min<VkDeviceSize>(align, texelSize == 12 ? 4 : texelSize);
  if (offset % align)
    Throw(ErrorId::NOT_SUPPORTED, call, DescribeObject(owner), "the view starts at byte " + std::to_string(byteOffset) + ", but this device's texel-buffer offset alignment is " +
                                                                  std::to_string(align) + " bytes; choose FirstElement accordingly");
  VkBufferViewCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
  ci.buffer = br.buffer;
  ci.format = format;
  ci.offset = offset;
  ci.range = byteSize;
  VkBufferView bv;
  Check(vkCreateBufferView(dev->device, &ci, nullptr, &bv), call, DescribeObject(owner), "vkCreateBufferView");
  texelViews.push_back({br.buffer, br.offset, bv});
  return bv;
}

VkViewObj::~VkViewObj() {
  VulkanDevice* d = dev;
  VkImageView iv = view;
  std::vector<TexelEntry> tvs = std::move(texelViews);
  if (iv || !tvs.empty()) {
    d->Defer(lastUse, [d, iv, tvs] {
      if (iv) vkDestroyImageView(d->device, iv, nullptr);
      for (const TexelEntry& tv : tvs) vkDestroyBufferView(d->device, tv.view, nullptr);
    });
  }
  ReleaseBufferRange(dev, counter, lastUse);
}

}  // namespace sp::vk
