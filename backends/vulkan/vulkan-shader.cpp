// Shader objects: a VkShaderModule, the descriptor bindings read from reflection (one set per
// stage, see sp::vkbind) and their set layout. Everything else Vulkan-specific (cbuffer repacking,
// sampled pairs, the SPIR-V variants for dual-source blending, SV_InstanceID and point size) comes
// made with the bytecode (rhi/src/hlsl/target-spirv.cpp); modules of variants are created on
// first use.
#include <algorithm>

#include "vulkan-internal.h"

namespace sp::vk {
namespace {

VkDescriptorType DescriptorTypeOf(ShaderResourceType t) {
  switch (t) {
    case ShaderResourceType::ConstantBuffer: return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    case ShaderResourceType::Texture: return VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
    case ShaderResourceType::TypedBuffer: return VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
    case ShaderResourceType::Sampler:
    case ShaderResourceType::ComparisonSampler: return VK_DESCRIPTOR_TYPE_SAMPLER;
    case ShaderResourceType::RWTexture: return VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    case ShaderResourceType::RWTypedBuffer: return VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER;
    case ShaderResourceType::StructuredBuffer:
    case ShaderResourceType::ByteAddressBuffer:
    case ShaderResourceType::RWStructuredBuffer:
    case ShaderResourceType::RWByteAddressBuffer:
    case ShaderResourceType::UavCounter: return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  }
  return VK_DESCRIPTOR_TYPE_MAX_ENUM;
}

VkShaderStageFlags StageFlags(ShaderStage s) {
  switch (s) {
    case ShaderStage::Vertex: return VK_SHADER_STAGE_VERTEX_BIT;
    case ShaderStage::Pixel: return VK_SHADER_STAGE_FRAGMENT_BIT;
    case ShaderStage::Geometry: return VK_SHADER_STAGE_GEOMETRY_BIT;
    case ShaderStage::Compute: return VK_SHADER_STAGE_COMPUTE_BIT;
  }
  return 0;
}

VkShaderModule CreateModule(VulkanDevice* dev, const std::vector<uint32_t>& spirv, const char* call, const std::string& object) {
  VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  ci.codeSize = spirv.size() * 4;
  ci.pCode = spirv.data();
  VkShaderModule m;
  Check(vkCreateShaderModule(dev->device, &ci, nullptr, &m), call, object, "vkCreateShaderModule");
  return m;
}

}  // namespace

std::unique_ptr<VkShaderObj> CreateShaderObj(VulkanDevice* dev, Shader& shader) {
  const char* call = shader.Stage() == ShaderStage::Vertex  ? "CreateVertexShader"
                     : shader.Stage() == ShaderStage::Pixel ? "CreatePixelShader"
                                                             : "CreateComputeShader";
  std::string object = DescribeObject(&shader);
  const ShaderBytecode& bc = shader.Bytecode();
  auto s = std::make_unique<VkShaderObj>();
  s->dev = dev;
  s->owner = &shader;
  s->uid = shader.UniqueId();
  s->stage = shader.Stage();
  const detail::SpirvProducts& products = detail::TargetsOf(bc).spirv;
  if (products.entryPoint.empty())
    Throw(ErrorId::INVALID_ARGUMENT, call, object, "the bytecode carries no SPIR-V products for the Vulkan backend; compile it with this version of the toolchain");
  s->entry = products.entryPoint;
  const ShaderReflection& r = bc.reflection;
  // Dynamic, so that a WRITE_DISCARD rename only changes the offset given to vkCmdBindDescriptorSets
  // instead of costing a new set per draw; the limit counts the VS and PS sets of one layout together.
  VkDescriptorType cbType = r.cbuffers.size() <= dev->props.limits.maxDescriptorSetUniformBuffersDynamic / 2 ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC
                                                                                                            : VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  for (const CBufferInfo& cb : r.cbuffers)
    s->bindings.push_back({cb.vkBinding, cbType, RegisterClass::ConstantBuffer, cb.registerIndex, ShaderResourceType::ConstantBuffer});
  for (const ShaderResourceBinding& b : r.resources)
    s->bindings.push_back({b.vkBinding, DescriptorTypeOf(b.type), b.registerClass, b.registerIndex, b.type});
  std::sort(s->bindings.begin(), s->bindings.end(), [](const ShaderBinding& a, const ShaderBinding& b) { return a.binding < b.binding; });
  // A texture sampled both with and without comparison is two SPIR-V variables on one binding.
  s->bindings.erase(std::unique(s->bindings.begin(), s->bindings.end(), [](const ShaderBinding& a, const ShaderBinding& b) { return a.binding == b.binding; }),
                    s->bindings.end());
  for (const SignatureElement& o : r.outputs) {
    if (o.semanticName != "SV_TARGET") continue;
    s->writtenTargets |= 1u << o.location;
    if (o.location == 1) s->hasTarget1 = true;
  }
  s->repacks = products.repacks;
  s->sampledPairs = products.sampledPairs;
  // Non-dynamic uniform buffers (past the device's dynamic limit) hold a renamed cbuffer's offset.
  s->setKeptAcrossDraws = s->repacks.empty() && !s->bindings.empty() && cbType == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC;
  for (const ShaderBinding& b : s->bindings)
    s->rangeInSet |= b.type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER || b.type == VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER ||
                     b.type == VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER;
  s->setLayout = dev->SetLayout(s->bindings, StageFlags(s->stage));
  if (s->stage == ShaderStage::Compute) s->computeLayout = dev->PipelineLayout({s->setLayout});
  // D3D11's SV_InstanceID counts from 0 whatever StartInstanceLocation is; InstanceIndex does not.
  s->instanceFromZero = s->stage == ShaderStage::Vertex && dev->feat.drawParameters;
  s->module = CreateModule(dev, detail::SpirvFor(bc, {s->instanceFromZero, false, false}), call, object);
  dev->Name(VK_OBJECT_TYPE_SHADER_MODULE, uint64_t(s->module), object);
  return s;
}

VkShaderModule VkShaderObj::DualSourceModule() {
  if (!dualSourceModule) dualSourceModule = CreateModule(dev, detail::SpirvFor(owner->Bytecode(), {false, false, true}), "Draw", DescribeObject(owner));
  return dualSourceModule;
}

VkShaderModule VkShaderObj::PointSizeModule() {
  if (!pointSizeModule) pointSizeModule = CreateModule(dev, detail::SpirvFor(owner->Bytecode(), {instanceFromZero, true, false}), "Draw", DescribeObject(owner));
  return pointSizeModule;
}

VkShaderObj::~VkShaderObj() {
  // Modules are not referenced by command buffers; pipelines built from them are.
  vkDestroyShaderModule(dev->device, module, nullptr);
  if (dualSourceModule) vkDestroyShaderModule(dev->device, dualSourceModule, nullptr);
  if (pointSizeModule) vkDestroyShaderModule(dev->device, pointSizeModule, nullptr);
  dev->ForgetShader(uid);
}

}  // namespace sp::vk
