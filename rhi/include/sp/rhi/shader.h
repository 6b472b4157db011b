// Compiled shaders ("bytecode"), their reflection, shader objects and input layouts.
//
// A ShaderBytecode is what D3DCompile gives a D3D11 program: one object per HLSL entry point and
// target, usable on either backend. It carries the legalised, validated SPIR-V (Vulkan), the
// GLSL 4.50 produced from it by SPIRV-Cross (OpenGL), and reflection read from the SPIR-V.
// Compile with sp::hlsl::Compile (sp/hlsl/compiler.h).
#pragma once
#include <array>
#include <memory>
#include <string>
#include <vector>
#include <sp/rhi/common.h>
#include <sp/rhi/format.h>
#include <sp/rhi/view.h>

namespace sp {

namespace detail {
struct TargetProducts;
}  // namespace detail

enum class ShaderStage : uint8_t { Vertex = 0, Pixel = 1, Geometry = 2, Compute = 3 };
inline constexpr uint32_t SHADER_STAGE_COUNT = 4;
const char* ShaderStageName(ShaderStage s);    // "vertex"
const char* ShaderStagePrefix(ShaderStage s);  // "VS", "PS", "GS", "CS" (as in VSSetShader)

// D3D11 register counts per stage (D3D11_COMMONSHADER_*_SLOT_COUNT, D3D11_PS_CS_UAV_REGISTER_COUNT).
inline constexpr uint32_t COMMONSHADER_CONSTANT_BUFFER_API_SLOT_COUNT = 14;
inline constexpr uint32_t COMMONSHADER_INPUT_RESOURCE_SLOT_COUNT = 128;
inline constexpr uint32_t COMMONSHADER_SAMPLER_SLOT_COUNT = 16;
inline constexpr uint32_t PS_CS_UAV_REGISTER_COUNT = 8;
inline constexpr uint32_t IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT = 32;
inline constexpr uint32_t VIEWPORT_AND_SCISSORRECT_OBJECT_COUNT_PER_PIPELINE = 16;

enum class RegisterClass : uint8_t { ConstantBuffer /*b*/, ShaderResource /*t*/, Sampler /*s*/, UnorderedAccess /*u*/ };
char RegisterClassLetter(RegisterClass c);  // 'b', 't', 's', 'u'

// What HLSL declared in a register (D3D_SHADER_INPUT_TYPE, split by what the backends need).
enum class ShaderResourceType : uint8_t {
  ConstantBuffer,
  Texture,             // Texture1D/2D/3D/Cube[Array], Texture2DMS[Array]
  TypedBuffer,         // Buffer<T>
  StructuredBuffer,
  ByteAddressBuffer,
  Sampler,
  ComparisonSampler,
  RWTexture,
  RWTypedBuffer,
  RWStructuredBuffer,  // also AppendStructuredBuffer / ConsumeStructuredBuffer
  RWByteAddressBuffer,
  UavCounter,          // hidden counter buffer of an append/consume UAV (same register)
};
const char* ShaderResourceTypeName(ShaderResourceType t);

enum class ComponentType : uint8_t { Float, UInt, SInt, Unknown };

struct ShaderResourceBinding {
  std::string name;
  RegisterClass registerClass = RegisterClass::ShaderResource;
  uint32_t registerIndex = 0;  // the N of tN
  ShaderResourceType type = ShaderResourceType::Texture;
  SRV_DIMENSION dimension = SRV_DIMENSION_UNKNOWN;  // textures and buffers, as D3D reflection
  ComponentType returnType = ComponentType::Float;  // texel type of textures/typed buffers
  uint32_t structureStride = 0;                     // structured buffers
  bool appendConsume = false;                       // RWStructuredBuffer used with Append/Consume
  // Where the register is on Vulkan (descriptor set per stage, a fixed offset per register
  // class), for reading SPIR-V disassembly; the RHI binds by register.
  uint32_t vkSet = 0, vkBinding = 0;
};

struct CBufferMember {
  std::string name;
  std::string typeName;  // "float3", "float4x4", "row_major float4x4", "struct Cascade[4]"
  uint32_t offset = 0;   // bytes, D3D packing
  uint32_t size = 0;     // bytes, D3D packing (a float3x3 is 44)
};

struct CBufferInfo {
  std::string name;
  uint32_t registerIndex = 0;
  uint32_t size = 0;  // bytes used by the declared members (D3D reflection's Size, rounded to 16)
  std::vector<CBufferMember> members;
  uint32_t vkSet = 0, vkBinding = 0;
};

struct SignatureElement {
  std::string semanticName;  // upper case, without index: "TEXCOORD"
  uint32_t semanticIndex = 0;
  uint32_t location = 0;     // SPIR-V / GLSL location
  ComponentType componentType = ComponentType::Float;
  uint32_t componentCount = 4;
  bool systemValue = false;  // SV_*: no location
};

struct ShaderReflection {
  ShaderStage stage = ShaderStage::Vertex;
  std::string entryPoint;
  std::array<uint32_t, 3> threadGroupSize{0, 0, 0};  // compute
  std::vector<CBufferInfo> cbuffers;
  std::vector<ShaderResourceBinding> resources;  // t, s, u registers (and counters)
  std::vector<SignatureElement> inputs;
  std::vector<SignatureElement> outputs;

  const CBufferInfo* FindCBuffer(uint32_t registerIndex) const;
  const ShaderResourceBinding* FindResource(RegisterClass cls, uint32_t registerIndex) const;
  const SignatureElement* FindInput(std::string_view semantic, uint32_t index) const;
};

struct ShaderBytecode {
  ShaderStage stage = ShaderStage::Vertex;
  std::string sourceName;        // "shaders-hlsl/basic/lit.hlsl:PSMain", for messages
  std::vector<uint32_t> spirv;   // Vulkan (SPIR-V 1.3, legalised, validated; VS flips y)
  std::string glsl;              // OpenGL (GLSL 4.50 core)
  // What each backend needs besides the code (GL binding table, Vulkan module variants, cbuffer
  // repacking, dual-source variants): written once by the toolchain's per-target modules,
  // opaque to applications (Serialize and ReflectionJson include it).
  std::shared_ptr<const detail::TargetProducts> targets;
  ShaderReflection reflection;

  bool empty() const { return spirv.empty(); }
  // One blob (for files, caches and the void*/size overloads of Create*Shader).
  std::vector<uint8_t> Serialize() const;
  static ShaderBytecode Deserialize(const void* data, size_t size);  // throws sp::Error
  std::string ReflectionJson() const;                                 // hlslc's out.json
};

enum INPUT_CLASSIFICATION : uint32_t { INPUT_PER_VERTEX_DATA = 0, INPUT_PER_INSTANCE_DATA = 1 };
inline constexpr uint32_t APPEND_ALIGNED_ELEMENT = 0xffffffffu;

struct INPUT_ELEMENT_DESC {
  const char* SemanticName = nullptr;
  uint32_t SemanticIndex = 0;
  FORMAT Format = FORMAT_UNKNOWN;
  uint32_t InputSlot = 0;
  uint32_t AlignedByteOffset = APPEND_ALIGNED_ELEMENT;
  INPUT_CLASSIFICATION InputSlotClass = INPUT_PER_VERTEX_DATA;
  uint32_t InstanceDataStepRate = 0;
};

// An input element resolved against the vertex shader's signature.
struct VertexAttribute {
  uint32_t location = 0;
  FORMAT format = FORMAT_UNKNOWN;
  uint32_t slot = 0;
  uint32_t offset = 0;  // APPEND_ALIGNED_ELEMENT resolved
  bool perInstance = false;
  uint32_t stepRate = 0;
  // The semantic it was matched by (upper case), so a draw can tell a layout made for another
  // vertex shader whose inputs sit at the same locations.
  std::string semanticName;
  uint32_t semanticIndex = 0;
};

class InputLayout : public Object {
 public:
  const std::vector<VertexAttribute>& Attributes() const { return attributes_; }
  const char* TypeName() const override { return "InputLayout"; }

 protected:
  friend class Device;
  InputLayout(Device* device, std::vector<VertexAttribute> attributes)
      : Object(device), attributes_(std::move(attributes)) {}

 private:
  std::vector<VertexAttribute> attributes_;
};

class Shader : public Object {
 public:
  ShaderStage Stage() const { return bytecode_.stage; }
  const ShaderBytecode& Bytecode() const { return bytecode_; }
  const ShaderReflection& Reflection() const { return bytecode_.reflection; }

 protected:
  friend class Device;
  Shader(Device* device, ShaderBytecode bytecode) : Object(device), bytecode_(std::move(bytecode)) {}
  std::string DescribeShape() const override { return bytecode_.sourceName; }

 private:
  ShaderBytecode bytecode_;
};

class VertexShader : public Shader {
 public:
  const char* TypeName() const override { return "VertexShader"; }

 protected:
  friend class Device;
  using Shader::Shader;
};

class PixelShader : public Shader {
 public:
  const char* TypeName() const override { return "PixelShader"; }

 protected:
  friend class Device;
  using Shader::Shader;
};

class GeometryShader : public Shader {
 public:
  const char* TypeName() const override { return "GeometryShader"; }

 protected:
  friend class Device;
  using Shader::Shader;
};

class ComputeShader : public Shader {
 public:
  const char* TypeName() const override { return "ComputeShader"; }

 protected:
  friend class Device;
  using Shader::Shader;
};

}  // namespace sp
