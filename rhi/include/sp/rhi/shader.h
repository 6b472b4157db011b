// Compiled shaders ("bytecode"), their reflection, shader objects and input layouts.
//
// A ShaderBytecode is what D3DCompile gives a D3D11 program: one object per HLSL entry point and
// target, usable on either backend. It carries the legalised, validated SPIR-V (Vulkan), the
// GLSL 4.50 produced from it by SPIRV-Cross (OpenGL), and reflection read from the SPIR-V.
// Compile with sp::hlsl::Compile (sp/hlsl/compiler.h).
#pragma once
#include <array>
#include <string>
#include <vector>
#include <sp/rhi/common.h>
#include <sp/rhi/format.h>
#include <sp/rhi/view.h>

namespace sp {

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

// How D3D registers become Vulkan bindings: one descriptor set per stage (VS 0, PS 1, GS 2;
// CS 0), and within it a fixed offset per register class so b0, t0, s0 and u0 never collide.
namespace vkbind {
inline constexpr uint32_t kConstantBuffer = 0;  // b0..b13  -> 0..13
inline constexpr uint32_t kShaderResource = 16; // t0..t127 -> 16..143
inline constexpr uint32_t kSampler = 144;       // s0..s15  -> 144..159
inline constexpr uint32_t kUnorderedAccess = 160;  // u0..u7 -> 160..167
inline constexpr uint32_t kUavCounter = 168;       // hidden counters of append/consume UAVs
inline uint32_t SetForStage(ShaderStage s) { return s == ShaderStage::Compute ? 0u : uint32_t(s); }
}  // namespace vkbind

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

// OpenGL has one namespace of texture units, image units, uniform-buffer and storage-buffer
// bindings per program; SPIRV-Cross's GLSL uses combined samplers. This table, written by the
// compiler, tells the GL backend where each D3D binding goes.
enum class GlBindingKind : uint8_t { CombinedSampler, UniformBlock, StorageBlock, Image };

struct GlCopyRange {
  uint32_t src = 0, dst = 0, size = 0;  // bytes
};

struct GlBinding {
  GlBindingKind kind = GlBindingKind::CombinedSampler;
  uint32_t glBinding = 0;        // texture unit / image unit / UBO or SSBO binding point
  RegisterClass registerClass = RegisterClass::ShaderResource;
  uint32_t registerIndex = 0;    // tN, bN or uN
  int32_t samplerRegister = -1;  // sN for combined samplers; -1 = no sampler (Load, texelFetch)
  bool uavCounter = false;       // storage block holding the hidden counter of uN
  // Uniform blocks whose D3D packing std140 cannot express are compiled with std140 offsets;
  // the GL backend copies these ranges from the D3D-packed buffer into a std140 copy. Empty when
  // the layouts agree (the buffer is bound directly).
  uint32_t glBlockSize = 0;
  std::vector<GlCopyRange> repack;
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
  std::vector<GlBinding> glBindings;
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
