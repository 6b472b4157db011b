// D3D11 sampler states as VkSamplers: every FILTER (comparison and min/max reduction included),
// every address mode (MIRROR_ONCE = mirror-clamp-to-edge), border colours (custom when none of
// Vulkan's three predefined ones matches), LOD bias and clamps.
#include <algorithm>
#include <cfloat>

#include "vulkan-internal.h"

namespace sp::vk {
namespace {

VkSamplerAddressMode AddressMode(TEXTURE_ADDRESS_MODE m) {
  switch (m) {
    case TEXTURE_ADDRESS_WRAP: return VK_SAMPLER_ADDRESS_MODE_REPEAT;
    case TEXTURE_ADDRESS_MIRROR: return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
    case TEXTURE_ADDRESS_BORDER: return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
    case TEXTURE_ADDRESS_MIRROR_ONCE: return VK_SAMPLER_ADDRESS_MODE_MIRROR_CLAMP_TO_EDGE;
    default: return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  }
}

}  // namespace

VkCompareOp CompareOp(COMPARISON_FUNC f) {
  switch (f) {
    case COMPARISON_NEVER: return VK_COMPARE_OP_NEVER;
    case COMPARISON_LESS: return VK_COMPARE_OP_LESS;
    case COMPARISON_EQUAL: return VK_COMPARE_OP_EQUAL;
    case COMPARISON_LESS_EQUAL: return VK_COMPARE_OP_LESS_OR_EQUAL;
    case COMPARISON_GREATER: return VK_COMPARE_OP_GREATER;
    case COMPARISON_NOT_EQUAL: return VK_COMPARE_OP_NOT_EQUAL;
    case COMPARISON_GREATER_EQUAL: return VK_COMPARE_OP_GREATER_OR_EQUAL;
    default: return VK_COMPARE_OP_ALWAYS;
  }
}

std::unique_ptr<VkSamplerObj> CreateSamplerObj(VulkanDevice* dev, SamplerState& sampler) {
  const char* call = "CreateSamplerState";
  std::string object = DescribeObject(&sampler);
  const SAMPLER_DESC& d = sampler.GetDesc();
  auto s = std::make_unique<VkSamplerObj>();
  s->dev = dev;

  VkSamplerCreateInfo ci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  bool aniso = FilterIsAnisotropic(d.Filter);
  ci.magFilter = aniso || FilterMagLinear(d.Filter) ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
  ci.minFilter = aniso || FilterMinLinear(d.Filter) ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
  ci.mipmapMode = aniso || FilterMipLinear(d.Filter) ? VK_SAMPLER_MIPMAP_MODE_LINEAR : VK_SAMPLER_MIPMAP_MODE_NEAREST;
  ci.addressModeU = AddressMode(d.AddressU);
  ci.addressModeV = AddressMode(d.AddressV);
  ci.addressModeW = AddressMode(d.AddressW);
  const VkPhysicalDeviceLimits& lim = dev->props.limits;
  ci.mipLodBias = std::clamp(d.MipLODBias, -lim.maxSamplerLodBias, lim.maxSamplerLodBias);
  if (aniso && d.MaxAnisotropy > 1 && dev->feat.anisotropy) {
    ci.anisotropyEnable = VK_TRUE;
    ci.maxAnisotropy = std::min(float(d.MaxAnisotropy), lim.maxSamplerAnisotropy);
  }
  if (FilterIsComparison(d.Filter)) {
    ci.compareEnable = VK_TRUE;
    ci.compareOp = CompareOp(d.ComparisonFunc);
  }
  // D3D11 clamps the computed LOD to [MinLOD, MaxLOD] and then to the view's mips, so a negative
  // MinLOD behaves as 0 and FLT_MAX as "no clamp".
  ci.minLod = std::clamp(d.MinLOD, 0.0f, VK_LOD_CLAMP_NONE);
  ci.maxLod = std::clamp(d.MaxLOD, ci.minLod, VK_LOD_CLAMP_NONE);

  VkSamplerReductionModeCreateInfo reduction{VK_STRUCTURE_TYPE_SAMPLER_REDUCTION_MODE_CREATE_INFO};
  uint32_t red = FilterReduction(d.Filter);
  const void** tail = &ci.pNext;
  if (red >= 2) {
    if (!dev->feat.samplerMinmax) Throw(ErrorId::NOT_SUPPORTED, call, object, "min/max reduction filters need samplerFilterMinmax, which this device lacks");
    reduction.reductionMode = red == 2 ? VK_SAMPLER_REDUCTION_MODE_MIN : VK_SAMPLER_REDUCTION_MODE_MAX;
    *tail = &reduction;
    tail = &reduction.pNext;
  }

  VkSamplerCustomBorderColorCreateInfoEXT custom{VK_STRUCTURE_TYPE_SAMPLER_CUSTOM_BORDER_COLOR_CREATE_INFO_EXT};
  bool usesBorder = d.AddressU == TEXTURE_ADDRESS_BORDER || d.AddressV == TEXTURE_ADDRESS_BORDER || d.AddressW == TEXTURE_ADDRESS_BORDER;
  const float* c = d.BorderColor;
  auto is = [&](float r, float g, float b, float a) { return c[0] == r && c[1] == g && c[2] == b && c[3] == a; };
  if (!usesBorder || is(0, 0, 0, 0)) {
    ci.borderColor = VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK;
  } else if (is(0, 0, 0, 1)) {
    ci.borderColor = VK_BORDER_COLOR_FLOAT_OPAQUE_BLACK;
  } else if (is(1, 1, 1, 1)) {
    ci.borderColor = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
  } else {
    if (!dev->feat.customBorderColor)
      Throw(ErrorId::NOT_SUPPORTED, call, object, "BorderColor (" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " + std::to_string(c[2]) + ", " +
                                                    std::to_string(c[3]) + ") needs VK_EXT_custom_border_color; only (0,0,0,0), (0,0,0,1) and (1,1,1,1) work here");
    ci.borderColor = VK_BORDER_COLOR_FLOAT_CUSTOM_EXT;
    for (int i = 0; i < 4; ++i) custom.customBorderColor.float32[i] = c[i];
    custom.format = VK_FORMAT_UNDEFINED;
    *tail = &custom;
    tail = &custom.pNext;
  }
  Check(vkCreateSampler(dev->device, &ci, nullptr, &s->sampler), call, object, "vkCreateSampler");
  dev->Name(VK_OBJECT_TYPE_SAMPLER, uint64_t(s->sampler), object);
  return s;
}

VkSamplerObj::~VkSamplerObj() {
  VulkanDevice* d = dev;
  VkSampler smp = sampler;
  d->Defer(lastUse, [d, smp] { vkDestroySampler(d->device, smp, nullptr); });
}

}  // namespace sp::vk
