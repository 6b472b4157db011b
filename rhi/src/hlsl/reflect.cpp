// Reflection read from SPIR-V with SPIRV-Cross: cbuffers (D3D packing), resources and their
// registers, input/output signatures (HLSL semantics from SPV_GOOGLE_hlsl_functionality1) and the
// compute thread-group size.
#include <cctype>
#include <spirv_cross/spirv_cross.hpp>

#include "spirv-edit.h"
#include "toolchain.h"

namespace sp::hlsl {
namespace {

using spirv_cross::SPIRType;

[[noreturn]] void Fail(const std::string& source, const std::string& msg) {
  throw CompileError("Reflect", source, {{source, 0, msg}}, msg);
}

ComponentType ComponentOf(SPIRType::BaseType t) {
  switch (t) {
    case SPIRType::Float:
    case SPIRType::Half:
    case SPIRType::Double: return ComponentType::Float;
    case SPIRType::UInt:
    case SPIRType::Boolean: return ComponentType::UInt;
    case SPIRType::Int: return ComponentType::SInt;
    default: return ComponentType::Unknown;
  }
}

void SplitSemantic(const std::string& full, std::string* name, uint32_t* index) {
  size_t end = full.size();
  while (end > 0 && std::isdigit(static_cast<unsigned char>(full[end - 1]))) --end;
  *name = full.substr(0, end);
  for (char& c : *name) c = char(std::toupper(static_cast<unsigned char>(c)));
  *index = end < full.size() ? uint32_t(std::stoul(full.substr(end))) : 0;
}

SRV_DIMENSION DimensionOf(const SPIRType& t) {
  const auto& im = t.image;
  switch (im.dim) {
    case spv::Dim1D: return im.arrayed ? SRV_DIMENSION_TEXTURE1DARRAY : SRV_DIMENSION_TEXTURE1D;
    case spv::Dim2D:
      if (im.ms) return im.arrayed ? SRV_DIMENSION_TEXTURE2DMSARRAY : SRV_DIMENSION_TEXTURE2DMS;
      return im.arrayed ? SRV_DIMENSION_TEXTURE2DARRAY : SRV_DIMENSION_TEXTURE2D;
    case spv::Dim3D: return SRV_DIMENSION_TEXTURE3D;
    case spv::DimCube: return im.arrayed ? SRV_DIMENSION_TEXTURECUBEARRAY : SRV_DIMENSION_TEXTURECUBE;
    case spv::DimBuffer: return SRV_DIMENSION_BUFFER;
    default: return SRV_DIMENSION_UNKNOWN;
  }
}

// HLSL spelling of a cbuffer member's type. glslang stores HLSL floatRxC as R SPIR-V "columns"
// of C components, with the majorness decoration inverted.
std::string HlslTypeName(const spirv_cross::Compiler& c, uint32_t typeId, bool rowMajorSpirv) {
  const SPIRType& t = c.get_type(typeId);
  std::string base;
  switch (t.basetype) {
    case SPIRType::Float: base = "float"; break;
    case SPIRType::Int: base = "int"; break;
    case SPIRType::UInt: base = "uint"; break;
    case SPIRType::Boolean: base = "bool"; break;
    case SPIRType::Half: base = "half"; break;
    case SPIRType::Double: base = "double"; break;
    case SPIRType::Struct: base = "struct " + c.get_name(t.self); break;
    default: base = "?"; break;
  }
  if (t.basetype != SPIRType::Struct) {
    if (t.columns > 1) {
      base = std::string(rowMajorSpirv ? "column_major " : "row_major ") + base + std::to_string(t.columns) + "x" + std::to_string(t.vecsize);
    } else if (t.vecsize > 1) {
      base += std::to_string(t.vecsize);
    }
  }
  for (size_t i = t.array.size(); i-- > 0;) base += "[" + std::to_string(t.array[i]) + "]";
  return base;
}

// Size a member occupies under D3D packing (no padding after the last used component).
uint32_t D3DSize(const spirv_cross::Compiler& c, const SPIRType& structType, uint32_t member) {
  const SPIRType& t = c.get_type(structType.member_types[member]);
  uint32_t elem;
  if (t.basetype == SPIRType::Struct) {
    const SPIRType* bp = &t;
    while (!bp->array.empty() && bp->parent_type) bp = &c.get_type(bp->parent_type);
    const SPIRType& base = *bp;
    uint32_t n = uint32_t(base.member_types.size());
    elem = n ? c.type_struct_member_offset(base, n - 1) + D3DSize(c, base, n - 1) : 0;
  } else if (t.columns > 1) {
    bool rowMajor = c.has_member_decoration(structType.self, member, spv::DecorationRowMajor);
    uint32_t vectors = rowMajor ? t.vecsize : t.columns;
    uint32_t comps = rowMajor ? t.columns : t.vecsize;
    elem = (vectors - 1) * 16 + comps * 4;
  } else {
    elem = t.vecsize * 4;
  }
  uint32_t count = 1;
  for (uint32_t dim : t.array) count *= dim;
  if (count <= 1) return elem;
  uint32_t stride = c.type_struct_member_array_stride(structType, member);
  return (count - 1) * stride + elem;
}

}  // namespace

ShaderReflection Reflect(const std::vector<uint32_t>& spirv, ShaderStage stage, const std::string& entry, const std::string& sourceName) {
  spirv_cross::Compiler c(spirv);
  ShaderReflection r;
  r.stage = stage;
  r.entryPoint = entry;
  if (stage == ShaderStage::Compute) {
    spirv_cross::SPIREntryPoint& ep = c.get_entry_point(c.get_entry_points_and_stages()[0].name, spv::ExecutionModelGLCompute);
    r.threadGroupSize = {ep.workgroup_size.x, ep.workgroup_size.y, ep.workgroup_size.z};
  }
  spirv_cross::ShaderResources res = c.get_shader_resources();
  const uint32_t set = vkbind::SetForStage(stage);

  auto registerOf = [&](uint32_t id, uint32_t base, uint32_t count, const char* what) {
    uint32_t binding = c.get_decoration(id, spv::DecorationBinding);
    if (c.get_decoration(id, spv::DecorationDescriptorSet) != set || binding < base || binding >= base + count)
      Fail(sourceName, std::string(what) + " '" + c.get_name(id) + "' landed outside its register range (binding " + std::to_string(binding) +
                           "); use register() within the D3D11 limits");
    return binding - base;
  };

  for (const auto& ub : res.uniform_buffers) {
    CBufferInfo cb;
    cb.name = c.get_name(ub.base_type_id);
    if (cb.name.empty()) cb.name = ub.name;
    cb.registerIndex = registerOf(ub.id, vkbind::kConstantBuffer, COMMONSHADER_CONSTANT_BUFFER_API_SLOT_COUNT, "cbuffer");
    cb.vkSet = set;
    cb.vkBinding = vkbind::kConstantBuffer + cb.registerIndex;
    const SPIRType& t = c.get_type(ub.base_type_id);
    uint32_t end = 0;
    for (uint32_t i = 0; i < t.member_types.size(); ++i) {
      CBufferMember m;
      m.name = c.get_member_name(t.self, i);
      m.offset = c.type_struct_member_offset(t, i);
      m.size = D3DSize(c, t, i);
      m.typeName = HlslTypeName(c, t.member_types[i], c.has_member_decoration(t.self, i, spv::DecorationRowMajor));
      end = std::max(end, m.offset + m.size);
      cb.members.push_back(std::move(m));
    }
    cb.size = (end + 15) / 16 * 16;
    r.cbuffers.push_back(std::move(cb));
  }

  std::set<uint32_t> comparison = ComparisonSamplerVariables(spirv);
  for (const auto& s : res.separate_samplers) {
    ShaderResourceBinding b;
    b.name = s.name;
    b.registerClass = RegisterClass::Sampler;
    b.registerIndex = registerOf(s.id, vkbind::kSampler, COMMONSHADER_SAMPLER_SLOT_COUNT, "sampler");
    b.type = comparison.count(s.id) ? ShaderResourceType::ComparisonSampler : ShaderResourceType::Sampler;
    b.vkSet = set;
    b.vkBinding = vkbind::kSampler + b.registerIndex;
    r.resources.push_back(b);
  }
  for (const auto& img : res.separate_images) {
    const SPIRType& t = c.get_type(img.type_id);
    ShaderResourceBinding b;
    b.name = img.name;
    b.registerClass = RegisterClass::ShaderResource;
    b.registerIndex = registerOf(img.id, vkbind::kShaderResource, COMMONSHADER_INPUT_RESOURCE_SLOT_COUNT, "texture");
    b.dimension = DimensionOf(t);
    b.type = b.dimension == SRV_DIMENSION_BUFFER ? ShaderResourceType::TypedBuffer : ShaderResourceType::Texture;
    b.returnType = ComponentOf(c.get_type(t.image.type).basetype);
    b.vkSet = set;
    b.vkBinding = vkbind::kShaderResource + b.registerIndex;
    if (!t.array.empty()) Fail(sourceName, "texture arrays of objects ('" + img.name + "[]') are not supported; use Texture2DArray");
    r.resources.push_back(b);
  }
  for (const auto& img : res.storage_images) {
    const SPIRType& t = c.get_type(img.type_id);
    ShaderResourceBinding b;
    b.name = img.name;
    b.registerClass = RegisterClass::UnorderedAccess;
    b.registerIndex = registerOf(img.id, vkbind::kUnorderedAccess, PS_CS_UAV_REGISTER_COUNT, "RW texture");
    b.dimension = DimensionOf(t);
    b.type = b.dimension == SRV_DIMENSION_BUFFER ? ShaderResourceType::RWTypedBuffer : ShaderResourceType::RWTexture;
    b.returnType = ComponentOf(c.get_type(t.image.type).basetype);
    b.vkSet = set;
    b.vkBinding = vkbind::kUnorderedAccess + b.registerIndex;
    r.resources.push_back(b);
  }
  // Counter buffers first, so their owners can be flagged as append/consume.
  std::set<uint32_t> countedRegisters;
  for (const auto& sb : res.storage_buffers) {
    uint32_t binding = c.get_decoration(sb.id, spv::DecorationBinding);
    if (binding >= vkbind::kUavCounter && binding < vkbind::kUavCounter + PS_CS_UAV_REGISTER_COUNT) countedRegisters.insert(binding - vkbind::kUavCounter);
  }
  for (const auto& sb : res.storage_buffers) {
    uint32_t binding = c.get_decoration(sb.id, spv::DecorationBinding);
    ShaderResourceBinding b;
    b.name = c.get_name(sb.id).empty() ? sb.name : c.get_name(sb.id);
    b.vkSet = set;
    b.vkBinding = binding;
    const SPIRType& t = c.get_type(sb.base_type_id);
    if (!t.member_types.empty()) {
      const SPIRType& arr = c.get_type(t.member_types[0]);
      if (!arr.array.empty()) b.structureStride = c.type_struct_member_array_stride(t, 0);
    }
    if (binding >= vkbind::kUavCounter) {
      b.registerClass = RegisterClass::UnorderedAccess;
      b.registerIndex = registerOf(sb.id, vkbind::kUavCounter, PS_CS_UAV_REGISTER_COUNT, "UAV counter");
      b.type = ShaderResourceType::UavCounter;
      b.structureStride = 0;
    } else if (binding >= vkbind::kUnorderedAccess) {
      b.registerClass = RegisterClass::UnorderedAccess;
      b.registerIndex = registerOf(sb.id, vkbind::kUnorderedAccess, PS_CS_UAV_REGISTER_COUNT, "RW buffer");
      b.type = ShaderResourceType::RWStructuredBuffer;
      b.appendConsume = countedRegisters.count(b.registerIndex) > 0;
    } else {
      b.registerClass = RegisterClass::ShaderResource;
      b.registerIndex = registerOf(sb.id, vkbind::kShaderResource, COMMONSHADER_INPUT_RESOURCE_SLOT_COUNT, "buffer");
      b.type = ShaderResourceType::StructuredBuffer;
    }
    b.dimension = SRV_DIMENSION_BUFFER;
    r.resources.push_back(b);
  }

  auto signature = [&](const spirv_cross::SmallVector<spirv_cross::Resource>& vars, bool builtin, std::vector<SignatureElement>& out) {
    for (const auto& v : vars) {
      SignatureElement e;
      std::string sem = c.get_decoration_string(v.id, spv::DecorationHlslSemanticGOOGLE);
      if (sem.empty()) sem = v.name;
      SplitSemantic(sem, &e.semanticName, &e.semanticIndex);
      const SPIRType& t = c.get_type(v.type_id);
      e.componentType = ComponentOf(t.basetype);
      e.componentCount = t.vecsize;
      e.systemValue = builtin || e.semanticName.rfind("SV_", 0) == 0;
      e.location = c.get_decoration(v.id, spv::DecorationLocation);
      // SV_Target is a location output, not a SPIR-V built-in, but D3D calls it a system value.
      if (e.semanticName == "SV_TARGET") e.systemValue = false;
      out.push_back(e);
    }
  };
  signature(res.stage_inputs, false, r.inputs);
  signature(res.stage_outputs, false, r.outputs);
  spirv_cross::SmallVector<spirv_cross::Resource> builtinIns, builtinOuts;
  for (const auto& b : res.builtin_inputs) builtinIns.push_back(b.resource);
  for (const auto& b : res.builtin_outputs) builtinOuts.push_back(b.resource);
  signature(builtinIns, true, r.inputs);
  signature(builtinOuts, true, r.outputs);
  return r;
}

}  // namespace sp::hlsl
