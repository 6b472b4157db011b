// DXGI -> Vulkan formats, the storage format of textures, and CheckFormatSupport answered from
// the driver's format features.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "vulkan-internal.h"

namespace sp::vk {

VkFormat VkFormatOf(FORMAT f) {
  switch (f) {
    case FORMAT_R32G32B32A32_TYPELESS:
    case FORMAT_R32G32B32A32_FLOAT: return VK_FORMAT_R32G32B32A32_SFLOAT;
    case FORMAT_R32G32B32A32_UINT: return VK_FORMAT_R32G32B32A32_UINT;
    case FORMAT_R32G32B32A32_SINT: return VK_FORMAT_R32G32B32A32_SINT;
    case FORMAT_R32G32B32_TYPELESS:
    case FORMAT_R32G32B32_FLOAT: return VK_FORMAT_R32G32B32_SFLOAT;
    case FORMAT_R32G32B32_UINT: return VK_FORMAT_R32G32B32_UINT;
    case FORMAT_R32G32B32_SINT: return VK_FORMAT_R32G32B32_SINT;
    case FORMAT_R16G16B16A16_TYPELESS:
    case FORMAT_R16G16B16A16_FLOAT: return VK_FORMAT_R16G16B16A16_SFLOAT;
    case FORMAT_R16G16B16A16_UNORM: return VK_FORMAT_R16G16B16A16_UNORM;
    case FORMAT_R16G16B16A16_UINT: return VK_FORMAT_R16G16B16A16_UINT;
    case FORMAT_R16G16B16A16_SNORM: return VK_FORMAT_R16G16B16A16_SNORM;
    case FORMAT_R16G16B16A16_SINT: return VK_FORMAT_R16G16B16A16_SINT;
    case FORMAT_R32G32_TYPELESS:
    case FORMAT_R32G32_FLOAT: return VK_FORMAT_R32G32_SFLOAT;
    case FORMAT_R32G32_UINT: return VK_FORMAT_R32G32_UINT;
    case FORMAT_R32G32_SINT: return VK_FORMAT_R32G32_SINT;
    case FORMAT_R32G8X24_TYPELESS:
    case FORMAT_D32_FLOAT_S8X24_UINT:
    case FORMAT_R32_FLOAT_X8X24_TYPELESS:
    case FORMAT_X32_TYPELESS_G8X24_UINT: return VK_FORMAT_D32_SFLOAT_S8_UINT;
    case FORMAT_R10G10B10A2_TYPELESS:
    case FORMAT_R10G10B10A2_UNORM: return VK_FORMAT_A2B10G10R10_UNORM_PACK32;
    case FORMAT_R10G10B10A2_UINT: return VK_FORMAT_A2B10G10R10_UINT_PACK32;
    case FORMAT_R11G11B10_FLOAT: return VK_FORMAT_B10G11R11_UFLOAT_PACK32;
    case FORMAT_R8G8B8A8_TYPELESS:
    case FORMAT_R8G8B8A8_UNORM: return VK_FORMAT_R8G8B8A8_UNORM;
    case FORMAT_R8G8B8A8_UNORM_SRGB: return VK_FORMAT_R8G8B8A8_SRGB;
    case FORMAT_R8G8B8A8_UINT: return VK_FORMAT_R8G8B8A8_UINT;
    case FORMAT_R8G8B8A8_SNORM: return VK_FORMAT_R8G8B8A8_SNORM;
    case FORMAT_R8G8B8A8_SINT: return VK_FORMAT_R8G8B8A8_SINT;
    case FORMAT_R16G16_TYPELESS:
    case FORMAT_R16G16_FLOAT: return VK_FORMAT_R16G16_SFLOAT;
    case FORMAT_R16G16_UNORM: return VK_FORMAT_R16G16_UNORM;
    case FORMAT_R16G16_UINT: return VK_FORMAT_R16G16_UINT;
    case FORMAT_R16G16_SNORM: return VK_FORMAT_R16G16_SNORM;
    case FORMAT_R16G16_SINT: return VK_FORMAT_R16G16_SINT;
    case FORMAT_R32_TYPELESS:
    case FORMAT_R32_FLOAT: return VK_FORMAT_R32_SFLOAT;
    case FORMAT_D32_FLOAT: return VK_FORMAT_D32_SFLOAT;
    case FORMAT_R32_UINT: return VK_FORMAT_R32_UINT;
    case FORMAT_R32_SINT: return VK_FORMAT_R32_SINT;
    case FORMAT_R24G8_TYPELESS:
    case FORMAT_D24_UNORM_S8_UINT:
    case FORMAT_R24_UNORM_X8_TYPELESS:
    case FORMAT_X24_TYPELESS_G8_UINT: return VK_FORMAT_D24_UNORM_S8_UINT;
    case FORMAT_R8G8_TYPELESS:
    case FORMAT_R8G8_UNORM: return VK_FORMAT_R8G8_UNORM;
    case FORMAT_R8G8_UINT: return VK_FORMAT_R8G8_UINT;
    case FORMAT_R8G8_SNORM: return VK_FORMAT_R8G8_SNORM;
    case FORMAT_R8G8_SINT: return VK_FORMAT_R8G8_SINT;
    case FORMAT_R16_TYPELESS:
    case FORMAT_R16_UNORM: return VK_FORMAT_R16_UNORM;
    case FORMAT_R16_FLOAT: return VK_FORMAT_R16_SFLOAT;
    case FORMAT_D16_UNORM: return VK_FORMAT_D16_UNORM;
    case FORMAT_R16_UINT: return VK_FORMAT_R16_UINT;
    case FORMAT_R16_SNORM: return VK_FORMAT_R16_SNORM;
    case FORMAT_R16_SINT: return VK_FORMAT_R16_SINT;
    case FORMAT_R8_TYPELESS:
    case FORMAT_R8_UNORM: return VK_FORMAT_R8_UNORM;
    case FORMAT_R8_UINT: return VK_FORMAT_R8_UINT;
    case FORMAT_R8_SNORM: return VK_FORMAT_R8_SNORM;
    case FORMAT_R8_SINT: return VK_FORMAT_R8_SINT;
    case FORMAT_B8G8R8A8_TYPELESS:
    case FORMAT_B8G8R8A8_UNORM: return VK_FORMAT_B8G8R8A8_UNORM;
    case FORMAT_B8G8R8A8_UNORM_SRGB: return VK_FORMAT_B8G8R8A8_SRGB;
    default: return VK_FORMAT_UNDEFINED;
  }
}

VkFormat ImageFormatOf(const TextureShape& s) {
  if (s.bindFlags & BIND_DEPTH_STENCIL) return VkFormatOf(DepthFormatOfFamily(s.format));
  // R24G8 and R32G8X24 have no colour equivalent: they only exist as depth-stencil images.
  return VkFormatOf(s.format);
}

bool IsDepthStencilFormat(VkFormat f) {
  switch (f) {
    case VK_FORMAT_D16_UNORM:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_D24_UNORM_S8_UINT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT:
    case VK_FORMAT_X8_D24_UNORM_PACK32:
    case VK_FORMAT_S8_UINT: return true;
    default: return false;
  }
}

VkImageAspectFlags AspectsOf(VkFormat f) {
  switch (f) {
    case VK_FORMAT_D16_UNORM:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_X8_D24_UNORM_PACK32: return VK_IMAGE_ASPECT_DEPTH_BIT;
    case VK_FORMAT_D24_UNORM_S8_UINT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT: return VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT;
    case VK_FORMAT_S8_UINT: return VK_IMAGE_ASPECT_STENCIL_BIT;
    default: return VK_IMAGE_ASPECT_COLOR_BIT;
  }
}

bool IsIntegerFormat(FORMAT f) {
  FormatKind k = GetFormatInfo(f).kind;
  return k == FormatKind::UInt || k == FormatKind::SInt;
}

// ---------------------------------------------------------------------------------------------
// CheckFormatSupport

uint32_t VulkanDevice::SampleCountsFor(VkFormat f) const {
  bool depth = IsDepthStencilFormat(f);
  VkImageFormatProperties ip{};
  VkImageUsageFlags usage = depth ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
  if (vkGetPhysicalDeviceImageFormatProperties(physical, f, VK_IMAGE_TYPE_2D, VK_IMAGE_TILING_OPTIMAL, usage, 0, &ip) != VK_SUCCESS) return 1;
  VkSampleCountFlags limit = depth ? props.limits.framebufferDepthSampleCounts : props.limits.framebufferColorSampleCounts;
  return ip.sampleCounts & limit;
}

uint32_t VulkanDevice::MaxSampleCountBackend(FORMAT format) const {
  VkFormat f = VkFormatOf(format);
  if (f == VK_FORMAT_UNDEFINED) return 1;
  uint32_t counts = SampleCountsFor(f);
  uint32_t best = 1;
  for (uint32_t s : {2u, 4u, 8u, 16u, 32u})
    if (counts & s) best = s;
  return best;
}

VkFormatFeatureFlags2 VulkanDevice::OptimalFeatures(VkFormat f) const {
  auto it = formatFeatures_.find(uint32_t(f));
  if (it != formatFeatures_.end()) return it->second;
  VkFormatProperties3 p3{VK_STRUCTURE_TYPE_FORMAT_PROPERTIES_3};
  VkFormatProperties2 p2{VK_STRUCTURE_TYPE_FORMAT_PROPERTIES_2};
  p2.pNext = &p3;
  vkGetPhysicalDeviceFormatProperties2(physical, f, &p2);
  formatFeatures_[uint32_t(f)] = p3.optimalTilingFeatures;
  return p3.optimalTilingFeatures;
}

bool VulkanDevice::SampleCountSupportedBackend(FORMAT format, uint32_t count) const {
  VkFormat f = VkFormatOf(format);
  if (f == VK_FORMAT_UNDEFINED) return count == 1;
  return count == 1 || (SampleCountsFor(f) & count) != 0;
}

uint32_t VulkanDevice::FormatSupportBackend(FORMAT format) const {
  auto cached = formatSupport_.find(format);
  if (cached != formatSupport_.end()) return cached->second;
  const FormatInfo& fi = GetFormatInfo(format);
  VkFormat vf = VkFormatOf(format);
  uint32_t out = 0;
  if (fi.format != FORMAT_UNKNOWN && vf != VK_FORMAT_UNDEFINED) {
    VkFormatProperties3 p3{VK_STRUCTURE_TYPE_FORMAT_PROPERTIES_3};
    VkFormatProperties2 p2{VK_STRUCTURE_TYPE_FORMAT_PROPERTIES_2};
    p2.pNext = &p3;
    vkGetPhysicalDeviceFormatProperties2(physical, vf, &p2);
    VkFormatFeatureFlags2 opt = p3.optimalTilingFeatures, buf = p3.bufferFeatures;
    bool depthFormat = IsDepthStencilFormat(vf);
    bool readsDepthOnly = depthFormat && !fi.isDepthView && fi.kind != FormatKind::Typeless;  // R24_UNORM_X8 etc.
    if (opt & VK_FORMAT_FEATURE_2_SAMPLED_IMAGE_BIT) {
      out |= FORMAT_SUPPORT_TEXTURE2D | FORMAT_SUPPORT_TEXTURECUBE | FORMAT_SUPPORT_SHADER_LOAD | FORMAT_SUPPORT_MIP | FORMAT_SUPPORT_SHADER_GATHER;
      if (!depthFormat) out |= FORMAT_SUPPORT_TEXTURE1D | FORMAT_SUPPORT_TEXTURE3D;
      if ((opt & VK_FORMAT_FEATURE_2_SAMPLED_IMAGE_FILTER_LINEAR_BIT) || depthFormat) out |= FORMAT_SUPPORT_SHADER_SAMPLE;
    }
    if (depthFormat && (opt & VK_FORMAT_FEATURE_2_SAMPLED_IMAGE_DEPTH_COMPARISON_BIT))
      out |= FORMAT_SUPPORT_SHADER_SAMPLE_COMPARISON | FORMAT_SUPPORT_SHADER_GATHER_COMPARISON;
    // Colour formats that are also depth read formats (R32_FLOAT, R16_UNORM) compare through the depth image.
    if (fi.readsDepth && !depthFormat) {
      VkFormatProperties dp;
      vkGetPhysicalDeviceFormatProperties(physical, VkFormatOf(DepthFormatOfFamily(format)), &dp);
      if (dp.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT)
        out |= FORMAT_SUPPORT_SHADER_SAMPLE_COMPARISON | FORMAT_SUPPORT_SHADER_GATHER_COMPARISON;
    }
    if (!readsDepthOnly) {
      if (opt & VK_FORMAT_FEATURE_2_COLOR_ATTACHMENT_BIT) out |= FORMAT_SUPPORT_RENDER_TARGET | FORMAT_SUPPORT_TEXTURE2D;
      if (opt & VK_FORMAT_FEATURE_2_COLOR_ATTACHMENT_BLEND_BIT) out |= FORMAT_SUPPORT_BLENDABLE;
      if ((opt & VK_FORMAT_FEATURE_2_DEPTH_STENCIL_ATTACHMENT_BIT) && fi.isDepthView) out |= FORMAT_SUPPORT_DEPTH_STENCIL | FORMAT_SUPPORT_TEXTURE2D;
      if ((opt & VK_FORMAT_FEATURE_2_STORAGE_IMAGE_BIT) && (opt & VK_FORMAT_FEATURE_2_STORAGE_WRITE_WITHOUT_FORMAT_BIT) &&
          feat.storageWriteWithoutFormat)
        out |= FORMAT_SUPPORT_TYPED_UNORDERED_ACCESS_VIEW;
    }
    if (buf & VK_FORMAT_FEATURE_2_UNIFORM_TEXEL_BUFFER_BIT) out |= FORMAT_SUPPORT_BUFFER;
    if (buf & VK_FORMAT_FEATURE_2_VERTEX_BUFFER_BIT) out |= FORMAT_SUPPORT_IA_VERTEX_BUFFER;
    if (format == FORMAT_R16_UINT || format == FORMAT_R32_UINT) out |= FORMAT_SUPPORT_IA_INDEX_BUFFER;
    if ((out & (FORMAT_SUPPORT_RENDER_TARGET | FORMAT_SUPPORT_DEPTH_STENCIL)) && MaxSampleCountBackend(format) > 1) {
      out |= FORMAT_SUPPORT_MULTISAMPLE_RENDERTARGET | FORMAT_SUPPORT_MULTISAMPLE_LOAD;
      if (!IsIntegerFormat(format) && !depthFormat) out |= FORMAT_SUPPORT_MULTISAMPLE_RESOLVE;
    }
    if (fi.bytesPerElement == 12) out &= ~uint32_t(FORMAT_SUPPORT_TEXTURE1D | FORMAT_SUPPORT_TEXTURE2D | FORMAT_SUPPORT_TEXTURE3D | FORMAT_SUPPORT_TEXTURECUBE |
                                                  FORMAT_SUPPORT_RENDER_TARGET | FORMAT_SUPPORT_TYPED_UNORDERED_ACCESS_VIEW);
  }
  formatSupport_[format] = out;
  return out;
}

}  // namespace sp::vk
