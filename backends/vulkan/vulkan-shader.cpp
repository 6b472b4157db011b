// Shader objects: a VkShaderModule, the descriptor bindings read from reflection (one set per
// stage, see sp::vkbind) and their set layout. Dual-source blending needs SV_Target1 at
// location 0 index 1, which the HLSL front end cannot express: that variant is patched here.
#include <algorithm>
#include <cstring>
#include <map>
#include <unordered_map>

#include "vulkan-internal.h"

namespace sp::vk {
namespace {

constexpr uint32_t kOpEntryPoint = 15, kOpDecorate = 71, kOpVariable = 59;
constexpr uint32_t kDecorationLocation = 30, kDecorationIndex = 32;
constexpr uint32_t kStorageOutput = 3;

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

std::string SpirvEntryPoint(const std::vector<uint32_t>& spirv) {
  for (size_t i = 5; i < spirv.size();) {
    uint32_t wc = spirv[i] >> 16, op = spirv[i] & 0xffff;
    if (wc == 0) break;
    if (op == kOpEntryPoint && wc > 3) {
      const char* name = reinterpret_cast<const char*>(&spirv[i + 3]);
      return std::string(name, strnlen(name, (wc - 3) * 4));
    }
    i += wc;
  }
  return "main";
}

std::vector<uint32_t> SpirvDualSource(const std::vector<uint32_t>& spirv) {
  std::vector<uint32_t> outputs;
  for (size_t i = 5; i < spirv.size();) {
    uint32_t wc = spirv[i] >> 16, op = spirv[i] & 0xffff;
    if (wc == 0) break;
    if (op == kOpVariable && wc >= 4 && spirv[i + 3] == kStorageOutput) outputs.push_back(spirv[i + 2]);
    i += wc;
  }
  std::vector<uint32_t> out(spirv.begin(), spirv.begin() + 5);
  for (size_t i = 5; i < spirv.size();) {
    uint32_t wc = spirv[i] >> 16, op = spirv[i] & 0xffff;
    if (wc == 0) break;
    bool target1 = op == kOpDecorate && wc == 4 && spirv[i + 2] == kDecorationLocation && spirv[i + 3] == 1 &&
                   std::find(outputs.begin(), outputs.end(), spirv[i + 1]) != outputs.end();
    if (target1) {
      out.insert(out.end(), {(4u << 16) | kOpDecorate, spirv[i + 1], kDecorationLocation, 0u});
      out.insert(out.end(), {(4u << 16) | kOpDecorate, spirv[i + 1], kDecorationIndex, 1u});
    } else {
      out.insert(out.end(), spirv.begin() + i, spirv.begin() + i + wc);
    }
    i += wc;
  }
  return out;
}

std::vector<uint32_t> SpirvWritePointSize(const std::vector<uint32_t>& in) {
  constexpr uint32_t kOpTypeFloat = 22, kOpTypePointer = 32, kOpConstant = 43, kOpFunction = 54, kOpLabel = 248;
  constexpr uint32_t kOpMemberDecorate = 72, kOpStore = 62, kOpLine = 8, kOpNoLine = 317;
  constexpr uint32_t kDecorationBuiltIn = 11, kBuiltInPointSize = 1, kOne = 0x3f800000;
  size_t entryIdx = 0, firstGlobal = 0, firstFunction = 0;
  uint32_t entryFn = 0, floatId = 0, ptrId = 0, oneId = 0;
  for (size_t i = 5; i < in.size();) {
    uint32_t wc = in[i] >> 16, op = in[i] & 0xffff;
    if (wc == 0) break;
    const uint32_t* w = &in[i];
    if (op == kOpEntryPoint && w[1] == 0 && !entryIdx) entryIdx = i, entryFn = w[2];
    if ((op == kOpDecorate && wc >= 4 && w[2] == kDecorationBuiltIn && w[3] == kBuiltInPointSize) ||
        (op == kOpMemberDecorate && wc >= 5 && w[3] == kDecorationBuiltIn && w[4] == kBuiltInPointSize))
      return in;  // the shader has its own PointSize
    if (op == kOpTypeFloat && w[2] == 32) floatId = w[1];
    if (op == kOpTypePointer && w[2] == kStorageOutput && floatId && w[3] == floatId) ptrId = w[1];
    if (op == kOpConstant && floatId && w[1] == floatId && w[3] == kOne) oneId = w[2];
    bool global = (op >= 19 && op <= 39) || (op >= 41 && op <= 52) || op == kOpVariable;
    if (global && !firstGlobal && !firstFunction) firstGlobal = i;
    if (op == kOpFunction && !firstFunction) firstFunction = i;
    i += wc;
  }
  if (!entryIdx || !firstGlobal || !firstFunction) return in;
  uint32_t bound = in[3];
  uint32_t var = bound++;
  std::vector<uint32_t> out(in.begin(), in.begin() + 5);
  bool inEntry = false, afterLabel = false, stored = false;
  for (size_t i = 5; i < in.size();) {
    uint32_t wc = in[i] >> 16, op = in[i] & 0xffff;
    if (wc == 0) break;
    if (i == firstGlobal) out.insert(out.end(), {(4u << 16) | kOpDecorate, var, kDecorationBuiltIn, kBuiltInPointSize});
    if (i == firstFunction) {
      if (!floatId) out.insert(out.end(), {(3u << 16) | kOpTypeFloat, floatId = bound++, 32u});
      if (!ptrId) out.insert(out.end(), {(4u << 16) | kOpTypePointer, ptrId = bound++, kStorageOutput, floatId});
      if (!oneId) out.insert(out.end(), {(4u << 16) | kOpConstant, floatId, oneId = bound++, kOne});
      out.insert(out.end(), {(4u << 16) | kOpVariable, ptrId, var, kStorageOutput});
    }
    if (op == kOpFunction) inEntry = in[i + 2] == entryFn;
    if (inEntry && afterLabel && !stored && op != kOpVariable && op != kOpLine && op != kOpNoLine) {
      out.insert(out.end(), {(3u << 16) | kOpStore, var, oneId});
      stored = true;
    }
    if (i == entryIdx) {
      out.push_back(((wc + 1) << 16) | op);
      out.insert(out.end(), in.begin() + i + 1, in.begin() + i + wc);
      out.push_back(var);
    } else {
      out.insert(out.end(), in.begin() + i, in.begin() + i + wc);
    }
    if (inEntry && op == kOpLabel) afterLabel = true;
    i += wc;
  }
  out[3] = bound;
  return out;
}

std::vector<uint32_t> SpirvInstanceIdFromZero(const std::vector<uint32_t>& in) {
  constexpr uint32_t kOpCapability = 17, kOpLoad = 61, kOpISub = 130;
  constexpr uint32_t kDecorationBuiltIn = 11, kBuiltInInstanceIndex = 43, kBuiltInBaseInstance = 4425, kCapabilityDrawParameters = 4427;
  uint32_t instVar = 0, ptrType = 0;
  for (size_t i = 5; i < in.size();) {
    uint32_t wc = in[i] >> 16, op = in[i] & 0xffff;
    if (wc == 0) break;
    if (op == kOpDecorate && wc >= 4 && in[i + 2] == kDecorationBuiltIn && in[i + 3] == kBuiltInInstanceIndex) instVar = in[i + 1];
    if (op == kOpDecorate && wc >= 4 && in[i + 2] == kDecorationBuiltIn && in[i + 3] == kBuiltInBaseInstance) return in;
    i += wc;
  }
  if (!instVar) return in;
  for (size_t i = 5; i < in.size();) {
    uint32_t wc = in[i] >> 16, op = in[i] & 0xffff;
    if (wc == 0) break;
    if (op == kOpVariable && in[i + 2] == instVar) ptrType = in[i + 1];
    i += wc;
  }
  uint32_t bound = in[3];
  uint32_t baseVar = bound++;
  std::vector<uint32_t> out(in.begin(), in.begin() + 5);
  out.insert(out.end(), {(2u << 16) | kOpCapability, kCapabilityDrawParameters});
  bool decorated = false;
  for (size_t i = 5; i < in.size();) {
    uint32_t wc = in[i] >> 16, op = in[i] & 0xffff;
    if (wc == 0) break;
    const uint32_t* w = &in[i];
    if (op == kOpEntryPoint) {
      out.push_back(((wc + 1) << 16) | op);
      out.insert(out.end(), w + 1, w + wc);
      out.push_back(baseVar);
    } else if (op == kOpLoad && w[3] == instVar) {
      uint32_t raw = bound++, base = bound++;
      out.insert(out.end(), {(4u << 16) | kOpLoad, w[1], raw, instVar});
      out.insert(out.end(), {(4u << 16) | kOpLoad, w[1], base, baseVar});
      out.insert(out.end(), {(5u << 16) | kOpISub, w[1], w[2], raw, base});
    } else {
      out.insert(out.end(), w, w + wc);
      if (op == kOpDecorate && w[1] == instVar && !decorated) {
        out.insert(out.end(), {(4u << 16) | kOpDecorate, baseVar, kDecorationBuiltIn, kBuiltInBaseInstance});
        decorated = true;
      }
      if (op == kOpVariable && w[2] == instVar) out.insert(out.end(), {(4u << 16) | kOpVariable, ptrType, baseVar, w[3]});
    }
    i += wc;
  }
  out[3] = bound;
  return out;
}

std::vector<SampledPair> SpirvSampledPairs(const std::vector<uint32_t>& spirv) {
  constexpr uint32_t kOpLoad = 61, kOpCopyObject = 83, kOpSampledImage = 86, kDecorationBinding = 33;
  std::unordered_map<uint32_t, uint32_t> binding, source;  // variable -> binding; loaded id -> variable
  std::unordered_map<uint32_t, std::pair<uint32_t, uint32_t>> sampled;  // OpSampledImage result -> (image var, sampler var)
  std::map<std::pair<uint32_t, uint32_t>, SampledPair> pairs;
  for (size_t i = 5; i < spirv.size();) {
    uint32_t wc = spirv[i] >> 16, op = spirv[i] & 0xffff;
    if (wc == 0) break;
    const uint32_t* w = &spirv[i];
    if (op == kOpDecorate && wc >= 4 && w[2] == kDecorationBinding) binding[w[1]] = w[3];
    if (op == kOpLoad && wc >= 4) source[w[2]] = source.count(w[3]) ? source[w[3]] : w[3];
    if (op == kOpCopyObject && wc >= 4 && source.count(w[3])) source[w[2]] = source[w[3]];
    if (op == kOpSampledImage && wc >= 5 && source.count(w[3]) && source.count(w[4])) sampled[w[2]] = {source[w[3]], source[w[4]]};
    // Sampling instructions take the sampled image as their third word.
    if (op >= 87 && op <= 97 && op != 95 && wc >= 4 && sampled.count(w[3])) {
      auto [img, smp] = sampled[w[3]];
      if (binding.count(img) && binding.count(smp)) {
        SampledPair& p = pairs[{binding[img], binding[smp]}];
        p.textureReg = binding[img] - vkbind::kShaderResource;
        p.samplerReg = binding[smp] - vkbind::kSampler;
        bool dref = op == 89 || op == 90 || op == 93 || op == 94 || op == 97;
        bool gather = op == 96 || op == 97;
        p.compared |= dref;
        p.filtered |= !dref && !gather;
      }
    }
    i += wc;
  }
  std::vector<SampledPair> out;
  for (auto& [k, p] : pairs) out.push_back(p);
  return out;
}

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
  s->entry = SpirvEntryPoint(bc.spirv);
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
  try {
    s->repacks = ComputeCBufferRepacks(bc.spirv);
  } catch (const std::exception& e) {
    Throw(ErrorId::NOT_SUPPORTED, call, object, std::string("the cbuffer layout of this shader cannot be read: ") + e.what());
  }
  s->sampledPairs = SpirvSampledPairs(bc.spirv);
  s->setLayout = dev->SetLayout(s->bindings, StageFlags(s->stage));
  if (s->stage == ShaderStage::Compute) s->computeLayout = dev->PipelineLayout({s->setLayout});
  // D3D11's SV_InstanceID counts from 0 whatever StartInstanceLocation is; InstanceIndex does not.
  s->spirv = s->stage == ShaderStage::Vertex && dev->feat.drawParameters ? SpirvInstanceIdFromZero(bc.spirv) : bc.spirv;
  s->module = CreateModule(dev, s->spirv, call, object);
  dev->Name(VK_OBJECT_TYPE_SHADER_MODULE, uint64_t(s->module), object);
  return s;
}

VkShaderModule VkShaderObj::DualSourceModule() {
  if (!dualSourceModule) dualSourceModule = CreateModule(dev, SpirvDualSource(spirv), "Draw", DescribeObject(owner));
  return dualSourceModule;
}

VkShaderModule VkShaderObj::PointSizeModule() {
  if (!pointSizeModule) pointSizeModule = CreateModule(dev, SpirvWritePointSize(spirv), "Draw", DescribeObject(owner));
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
