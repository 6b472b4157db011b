// Textures: VkImages for GPU textures (TYPELESS families MUTABLE_FORMAT, depth-stencil textures in
// the family's depth format, cube maps CUBE_COMPATIBLE), and for USAGE_STAGING host memory laid
// out row by row as D3D11 maps it, with separate depth and stencil planes for the packed
// depth-stencil formats (Vulkan copies the two aspects separately).
#include <algorithm>
#include <cstring>

#include "vulkan-internal.h"

namespace sp::vk {
namespace {

VkDeviceSize AlignUp(VkDeviceSize v, VkDeviceSize a) { return (v + a - 1) / a * a; }

const char* CallFor(const TextureShape& s) {
  switch (s.dimension) {
    case RESOURCE_DIMENSION_TEXTURE1D: return "CreateTexture1D";
    case RESOURCE_DIMENSION_TEXTURE3D: return "CreateTexture3D";
    default: return "CreateTexture2D";
  }
}

std::string UsageString(VkImageUsageFlags u) {
  std::string s;
  auto add = [&](VkImageUsageFlags bit, const char* name) {
    if (!(u & bit)) return;
    if (!s.empty()) s += '|';
    s += name;
  };
  add(VK_IMAGE_USAGE_SAMPLED_BIT, "SAMPLED");
  add(VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, "COLOR_ATTACHMENT");
  add(VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, "DEPTH_STENCIL_ATTACHMENT");
  add(VK_IMAGE_USAGE_STORAGE_BIT, "STORAGE");
  return s;
}

void CreateStaging(VulkanDevice* dev, VkTextureObj& t, const SUBRESOURCE_DATA* init, const char* call, const std::string& object) {
  const TextureShape& s = t.shape;
  const FormatInfo& fi = GetFormatInfo(s.format);
  FORMAT family = fi.typelessFamily;
  t.usesPlanes = family == FORMAT_R24G8_TYPELESS || family == FORMAT_R32G8X24_TYPELESS;
  t.subs.resize(s.subresourceCount());
  VkDeviceSize total = 0, depthTotal = 0, stencilTotal = 0;
  for (uint32_t slice = 0; slice < s.arraySize; ++slice) {
    for (uint32_t mip = 0; mip < s.mipLevels; ++mip) {
      VkTextureObj::Sub& sub = t.subs[CalcSubresource(mip, slice, s.mipLevels)];
      uint64_t texels = uint64_t(s.mipWidth(mip)) * s.mipHeight(mip) * s.mipDepth(mip);
      sub.rowPitch = s.mipWidth(mip) * fi.bytesPerElement;
      sub.depthPitch = sub.rowPitch * s.mipHeight(mip);
      sub.offset = total;
      total = AlignUp(total + VkDeviceSize(sub.depthPitch) * s.mipDepth(mip), 16);
      sub.depthOffset = depthTotal;
      depthTotal = AlignUp(depthTotal + texels * 4, 16);
      sub.stencilOffset = stencilTotal;
      stencilTotal = AlignUp(stencilTotal + texels, 16);
    }
  }
  MemoryKind kind = (s.cpuAccessFlags & CPU_ACCESS_READ) ? MemoryKind::Readback : MemoryKind::Upload;
  t.main = dev->alloc.AllocateBuffer(total, kind, call, object);
  std::memset(t.main.mapped, 0, total);
  if (t.usesPlanes) {
    t.depthPlane = dev->alloc.AllocateBuffer(depthTotal, MemoryKind::Readback, call, object);
    t.stencilPlane = dev->alloc.AllocateBuffer(stencilTotal, MemoryKind::Readback, call, object);
    std::memset(t.depthPlane.mapped, 0, depthTotal);
    std::memset(t.stencilPlane.mapped, 0, stencilTotal);
  }
  if (!init) return;
  for (uint32_t i = 0; i < s.subresourceCount(); ++i) {
    const VkTextureObj::Sub& sub = t.subs[i];
    uint32_t mip = detail::SubresourceOf(s, i).mip;
    const SUBRESOURCE_DATA& sd = init[i];
    uint32_t rowPitch = sd.SysMemPitch ? sd.SysMemPitch : sub.rowPitch;
    uint32_t slicePitch = sd.SysMemSlicePitch ? sd.SysMemSlicePitch : rowPitch * s.mipHeight(mip);
    for (uint32_t z = 0; z < s.mipDepth(mip); ++z)
      for (uint32_t y = 0; y < s.mipHeight(mip); ++y)
        std::memcpy(t.main.mapped + sub.offset + VkDeviceSize(z) * sub.depthPitch + VkDeviceSize(y) * sub.rowPitch,
                    static_cast<const uint8_t*>(sd.pSysMem) + size_t(z) * slicePitch + size_t(y) * rowPitch, sub.rowPitch);
  }
}

}  // namespace

std::unique_ptr<VkTextureObj> CreateTextureObj(VulkanDevice* dev, Texture& texture, const SUBRESOURCE_DATA* init) {
  auto t = std::make_unique<VkTextureObj>();
  t->dev = dev;
  t->owner = &texture;
  t->shape = texture.Shape();
  const TextureShape& s = t->shape;
  const char* call = CallFor(s);
  std::string object = DescribeObject(&texture);
  if (s.usage == USAGE_STAGING) {
    t->staging = true;
    CreateStaging(dev, *t, init, call, object);
    if (t->usesPlanes && init) SplitPlanes(*t);
    return t;
  }

  t->format = ImageFormatOf(s);
  if (t->format == VK_FORMAT_UNDEFINED)
    Throw(ErrorId::FORMAT_UNSUPPORTED, call, object, std::string(FormatName(s.format)) + " has no Vulkan equivalent");
  t->aspects = AspectsOf(t->format);
  bool depth = IsDepthStencilFormat(t->format);
  bool typeless = GetFormatInfo(s.format).kind == FormatKind::Typeless && !depth;

  VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ci.imageType = s.dimension == RESOURCE_DIMENSION_TEXTURE1D ? VK_IMAGE_TYPE_1D
                 : s.dimension == RESOURCE_DIMENSION_TEXTURE3D ? VK_IMAGE_TYPE_3D
                                                               : VK_IMAGE_TYPE_2D;
  ci.format = t->format;
  ci.extent = {s.width, s.height, s.dimension == RESOURCE_DIMENSION_TEXTURE3D ? s.depth : 1};
  ci.mipLevels = s.mipLevels;
  t->layers = s.dimension == RESOURCE_DIMENSION_TEXTURE3D ? 1 : s.arraySize;
  ci.arrayLayers = t->layers;
  ci.samples = VkSampleCountFlagBits(s.sampleCount);
  ci.tiling = VK_IMAGE_TILING_OPTIMAL;
  ci.usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  if (s.bindFlags & BIND_SHADER_RESOURCE) ci.usage |= VK_IMAGE_USAGE_SAMPLED_BIT;
  if (s.bindFlags & BIND_UNORDERED_ACCESS) ci.usage |= VK_IMAGE_USAGE_STORAGE_BIT;
  if (depth) {
    ci.usage |= VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
  } else {
    // Every colour image that can be one is an attachment: render-target clears, and resolves
    // into textures created without BIND_RENDER_TARGET, go through dynamic rendering.
    VkFormatProperties fp;
    vkGetPhysicalDeviceFormatProperties(dev->physical, t->format, &fp);
    if ((s.bindFlags & BIND_RENDER_TARGET) || (fp.optimalTilingFeatures & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT))
      ci.usage |= VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
  }
  if (s.isCube()) ci.flags |= VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT;
  if (typeless) ci.flags |= VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT | VK_IMAGE_CREATE_EXTENDED_USAGE_BIT;
  if (s.dimension == RESOURCE_DIMENSION_TEXTURE3D && (s.bindFlags & BIND_RENDER_TARGET)) ci.flags |= VK_IMAGE_CREATE_2D_ARRAY_COMPATIBLE_BIT;
  ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;

  VkImageFormatProperties ip{};
  VkResult r = vkGetPhysicalDeviceImageFormatProperties(dev->physical, ci.format, ci.imageType, ci.tiling, ci.usage, ci.flags, &ip);
  if (r != VK_SUCCESS)
    Throw(ErrorId::FORMAT_UNSUPPORTED, call, object, std::string(FormatName(s.format)) + " cannot be used for this texture on this device (Vulkan usage " +
                                                       UsageString(ci.usage) + ")");
  if (!(ip.sampleCounts & ci.samples))
    Throw(ErrorId::FORMAT_UNSUPPORTED, call, object, std::to_string(s.sampleCount) + "x MSAA is not supported for " + std::string(FormatName(s.format)) +
                                                       " on this device (check CheckMultisampleQualityLevels)");
  if (ci.extent.width > ip.maxExtent.width || ci.extent.height > ip.maxExtent.height || ci.extent.depth > ip.maxExtent.depth ||
      ci.arrayLayers > ip.maxArrayLayers || ci.mipLevels > ip.maxMipLevels)
    Throw(ErrorId::SIZE_OUT_OF_RANGE, call, object, "the size exceeds what the device supports for this format (max " + std::to_string(ip.maxExtent.width) + "x" +
                                                      std::to_string(ip.maxExtent.height) + "x" + std::to_string(ip.maxExtent.depth) + ", " +
                                                      std::to_string(ip.maxArrayLayers) + " layers)");
  if (s.isCube() && s.arraySize > 6 && !dev->feat.cubeArray && (s.bindFlags & BIND_SHADER_RESOURCE))
    dev->Message(MessageSeverity::Warning, std::string(call) + ": the device has no imageCubeArray; cube array views of " + object + " will fail");

  Check(vkCreateImage(dev->device, &ci, nullptr, &t->image), call, object, "vkCreateImage");
  dev->Name(VK_OBJECT_TYPE_IMAGE, uint64_t(t->image), object);
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(dev->device, t->image, &req);
  try {
    t->memory = dev->alloc.AllocateImage(req, call, object);
    Check(vkBindImageMemory(dev->device, t->image, t->memory.memory, t->memory.offset), call, object, "vkBindImageMemory");
  } catch (...) {
    vkDestroyImage(dev->device, t->image, nullptr);
    dev->alloc.Free(t->memory);
    t->image = VK_NULL_HANDLE;
    throw;
  }
  t->states.resize(size_t(s.mipLevels) * t->layers);

  if (init) {
    for (uint32_t i = 0; i < s.subresourceCount(); ++i) {
      const detail::Subresource at = detail::SubresourceOf(s, i);
      const SUBRESOURCE_DATA& sd = init[i];
      uint32_t rowPitch = sd.SysMemPitch ? sd.SysMemPitch : at.width * GetFormatInfo(s.format).bytesPerElement;
      uint32_t slicePitch = sd.SysMemSlicePitch ? sd.SysMemSlicePitch : rowPitch * at.height;
      dev->ctx->UploadToImage(*t, at, at.box(), sd.pSysMem, rowPitch, slicePitch);
    }
  } else {
    dev->ctx->ZeroImage(*t);
  }
  return t;
}

VkTextureObj::~VkTextureObj() {
  VulkanDevice* d = dev;
  VkImage img = image;
  Allocation mem = memory;
  if (img) {
    d->Defer(lastUse, [d, img, mem]() mutable {
      vkDestroyImage(d->device, img, nullptr);
      d->alloc.Free(mem);
    });
  }
  ReleaseBufferRange(dev, main, lastUse);
  ReleaseBufferRange(dev, depthPlane, lastUse);
  ReleaseBufferRange(dev, stencilPlane, lastUse);
}

}  // namespace sp::vk
