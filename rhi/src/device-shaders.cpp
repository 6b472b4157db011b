// Shader objects and input layouts.
#include <sp/rhi/context.h>

#include <algorithm>
#include <cctype>

#include "validate.h"

namespace sp {

template <class T>
Ref<T> Device::CreateShaderOfStage(ShaderStage stage, const ShaderBytecode& bytecode, const char* call) {
  std::string obj = bytecode.sourceName.empty() ? std::string(ShaderStageName(stage)) + " shader" : bytecode.sourceName;
  if (bytecode.empty()) Fail(ErrorId::INVALID_ARGUMENT, call, obj, "the bytecode is empty");
  if (bytecode.stage != stage)
    Fail(ErrorId::SHADER_STAGE_MISMATCH, call, obj,
         std::string("the bytecode is a ") + ShaderStageName(bytecode.stage) + " shader, not a " + ShaderStageName(stage) + " shader");
  const char* arrayIndex = stage == ShaderStage::Vertex ? ArrayIndexOutput(bytecode.reflection) : nullptr;
  if (arrayIndex && !info_.vsRenderTargetArrayIndex)
    Fail(ErrorId::NOT_SUPPORTED, call, obj,
         std::string("the vertex shader writes ") + arrayIndex +
             ", which needs DeviceInfo::vsRenderTargetArrayIndex (D3D11: VPAndRTArrayIndexFromAnyShaderFeedingRasterizer; Vulkan: "
             "shaderOutputLayer/VK_EXT_shader_viewport_index_layer; GL: GL_ARB_shader_viewport_layer_array), which this " +
             BackendName(info_.backend) + " device lacks");
  Ref<T> s(new T(this, bytecode));
  s->backend_ = backend_->CreateShaderBackend(*s);
  return s;
}

Ref<VertexShader> Device::CreateVertexShader(const ShaderBytecode& b) {
  return CreateShaderOfStage<VertexShader>(ShaderStage::Vertex, b, "CreateVertexShader");
}
Ref<PixelShader> Device::CreatePixelShader(const ShaderBytecode& b) {
  return CreateShaderOfStage<PixelShader>(ShaderStage::Pixel, b, "CreatePixelShader");
}
Ref<ComputeShader> Device::CreateComputeShader(const ShaderBytecode& b) {
  return CreateShaderOfStage<ComputeShader>(ShaderStage::Compute, b, "CreateComputeShader");
}
Ref<GeometryShader> Device::CreateGeometryShader(const ShaderBytecode& b) {
  Fail(ErrorId::NOT_SUPPORTED, "CreateGeometryShader", b.sourceName,
       "geometry shaders are not supported yet (the y flip that matches D3D's orientation is done in the vertex stage)");
}
Ref<VertexShader> Device::CreateVertexShader(const void* data, size_t size) {
  return CreateVertexShader(ShaderBytecode::Deserialize(data, size));
}
Ref<PixelShader> Device::CreatePixelShader(const void* data, size_t size) {
  return CreatePixelShader(ShaderBytecode::Deserialize(data, size));
}
Ref<ComputeShader> Device::CreateComputeShader(const void* data, size_t size) {
  return CreateComputeShader(ShaderBytecode::Deserialize(data, size));
}

static std::string Upper(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::toupper(c)); });
  return s;
}

static bool FormatFeedsComponent(FORMAT f, ComponentType t) {
  switch (GetFormatInfo(f).kind) {
    case FormatKind::UInt: return t == ComponentType::UInt;
    case FormatKind::SInt: return t == ComponentType::SInt;
    case FormatKind::Float:
    case FormatKind::UNorm:
    case FormatKind::SNorm:
    case FormatKind::UNormSRGB: return t == ComponentType::Float;
    default: return false;
  }
}

Ref<InputLayout> Device::CreateInputLayout(const INPUT_ELEMENT_DESC* elements, uint32_t num, const ShaderBytecode& vs) {
  const char* call = "CreateInputLayout";
  std::string obj = "InputLayout for " + (vs.sourceName.empty() ? std::string("vertex shader") : vs.sourceName);
  if (vs.stage != ShaderStage::Vertex) Fail(ErrorId::SHADER_STAGE_MISMATCH, call, obj, "the bytecode is not a vertex shader");
  if (num > 32) Fail(ErrorId::INVALID_ARGUMENT, call, obj, "at most 32 input elements");
  if (num && !elements) Fail(ErrorId::INVALID_ARGUMENT, call, obj, "pInputElementDescs is null");

  std::vector<VertexAttribute> attrs;
  std::array<uint32_t, IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT> nextOffset{};
  for (uint32_t i = 0; i < num; ++i) {
    const INPUT_ELEMENT_DESC& e = elements[i];
    std::string el = "element[" + std::to_string(i) + "]";
    if (!e.SemanticName || !*e.SemanticName) Fail(ErrorId::INVALID_ARGUMENT, call, obj, el + " has no SemanticName");
    el += " (" + std::string(e.SemanticName) + std::to_string(e.SemanticIndex) + ")";
    if (e.InputSlot >= IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT) Fail(ErrorId::SLOT_OUT_OF_RANGE, call, obj, el + ": InputSlot must be < 32");
    if (!(backend_->FormatSupportBackend(e.Format) & FORMAT_SUPPORT_IA_VERTEX_BUFFER))
      Fail(ErrorId::FORMAT_UNSUPPORTED, call, obj, el + ": " + std::string(FormatName(e.Format)) + " is not a vertex format on this device");
    if (e.InputSlotClass == INPUT_PER_VERTEX_DATA && e.InstanceDataStepRate != 0)
      Fail(ErrorId::INVALID_DESC, call, obj, el + ": InstanceDataStepRate must be 0 for per-vertex data");
    if (e.InputSlotClass > INPUT_PER_INSTANCE_DATA) Fail(ErrorId::INVALID_DESC, call, obj, el + ": unknown InputSlotClass");
    uint32_t size = GetFormatInfo(e.Format).bytesPerElement;
    uint32_t offset = e.AlignedByteOffset == APPEND_ALIGNED_ELEMENT ? nextOffset[e.InputSlot] : e.AlignedByteOffset;
    if (offset % std::min(4u, size)) Fail(ErrorId::INVALID_DESC, call, obj, el + ": AlignedByteOffset must be aligned to min(4, element size)");
    nextOffset[e.InputSlot] = offset + size;
    for (uint32_t j = 0; j < i; ++j)
      if (Upper(elements[j].SemanticName) == Upper(e.SemanticName) && elements[j].SemanticIndex == e.SemanticIndex)
        Fail(ErrorId::INVALID_DESC, call, obj, el + " repeats the semantic of element[" + std::to_string(j) + "]");

    const SignatureElement* sig = vs.reflection.FindInput(Upper(e.SemanticName), e.SemanticIndex);
    if (!sig) continue;  // D3D11 allows elements the shader does not read
    if (!FormatFeedsComponent(e.Format, sig->componentType))
      Fail(ErrorId::INPUT_LAYOUT_MISMATCH, call, obj, el + ": format " + std::string(FormatName(e.Format)) +
                                                           " does not match the shader's input type (" +
                                                           (sig->componentType == ComponentType::Float ? "float" : sig->componentType == ComponentType::UInt ? "uint" : "int") + ")");
    VertexAttribute a;
    a.location = sig->location;
    a.format = e.Format;
    a.slot = e.InputSlot;
    a.offset = offset;
    a.perInstance = e.InputSlotClass == INPUT_PER_INSTANCE_DATA;
    a.stepRate = e.InstanceDataStepRate;
    a.semanticName = sig->semanticName;
    a.semanticIndex = sig->semanticIndex;
    attrs.push_back(a);
  }
  for (const SignatureElement& in : vs.reflection.inputs) {
    if (in.systemValue) continue;
    bool found = std::any_of(attrs.begin(), attrs.end(), [&](const VertexAttribute& a) { return a.location == in.location; });
    if (!found)
      Fail(ErrorId::INPUT_LAYOUT_MISMATCH, call, obj, "the vertex shader reads " + in.semanticName + std::to_string(in.semanticIndex) +
                                                          " but no input element provides it");
  }
  return Make<InputLayout>(std::move(attrs));
}

}  // namespace sp
