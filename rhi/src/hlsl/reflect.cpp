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

}  // namespace

uint32_t D3DTypeSize(const spirv_cross::Compiler& c, uint32_t typeId, bool rowMajorSpirv) {
  const SPIRType& t = c.get_type(typeId);
  if (!t.array.empty()) {
    // Every element starts a register; the last one is not padded.
    uint32_t elem = D3DTypeSize(c, t.parent_type, rowMajorSpirv);
    return (t.array.back() - 1) * ((elem + 15) / 16 * 16) + elem;
  }
  if (t.basetype == SPIRType::Struct) {
    uint32_t n = uint32_t(t.member_types.size());
    if (!n) return 0;
    return D3DMemberOffsets(c, t).back() + D3DTypeSize(c, t.member_types[n - 1], c.has_member_decoration(t.self, n - 1, spv::DecorationRowMajor));
  }
  if (t.columns > 1) {
    uint32_t vectors = rowMajorSpirv ? t.vecsize : t.columns;
    uint32_t comps = rowMajorSpirv ? t.columns : t.vecsize;
    return (vectors - 1) * 16 + comps * 4;
  }
  return t.vecsize * 4;
}

std::vector<uint32_t> D3DMemberOffsets(const spirv_cross::Compiler& c, const SPIRType& structType) {
  std::vector<uint32_t> offsets;
  uint32_t cursor = 0;
  for (uint32_t i = 0; i < structType.member_types.size(); ++i) {
    const SPIRType& t = c.get_type(structType.member_types[i]);
    uint32_t size = D3DTypeSize(c, structType.member_types[i], c.has_member_decoration(structType.self, i, spv::DecorationRowMajor));
    bool startsRegister = !t.array.empty() || t.basetype == SPIRType::Struct || t.columns > 1;
    // Vectors and scalars never straddle a 16-byte register.
    if (startsRegister || (size && cursor / 16 != (cursor + size - 1) / 16)) cursor = (cursor + 15) / 16 * 16;
    offsets.push_back(cursor);
    cursor += size;
  }
  return offsets;
}

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
    std::vector<uint32_t> offsets = D3DMemberOffsets(c, t);
    for (uint32_t i = 0; i < t.member_types.size(); ++i) {
      CBufferMember m;
      m.name = c.get_member_name(t.self, i);
      m.offset = offsets[i];
      m.size = D3DTypeSize(c, t.member_types[i], c.has_member_decoration(t.self, i, spv::DecorationRowMajor));
      m.typeName = HlslTypeName(c, t.member_types[i], c.has_member_decoration(t.self, i, spv::DecorationRowMajor));
      end = std::max(end, m.offset + m.size);
      cb.members.push_back(std::move(m));
    }
    cb.size = (end + 15) / 16 * 16;
    r.cbuffers.push_back(std::move(cb));
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
    // A texture read through both a comparison and a plain sampler is two SPIR-V variables (depth
    // and non-depth image types) at one register: D3D11 sees one shader resource.
    bool twin = false;
    for (const ShaderResourceBinding& o : r.resources)
      twin |= o.registerClass == RegisterClass::ShaderResource && o.registerIndex == b.registerIndex;
    if (!twin) r.resources.push_back(b);
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
