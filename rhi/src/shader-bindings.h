// How D3D registers become Vulkan and OpenGL bindings (private to the library: the toolchain
// writes these tables, the backends follow them, the core reads them to learn how a shader uses a
// texture). Applications see only ShaderBytecode's opaque GL layout handle and the reflection.
#pragma once
#include <cstdint>
#include <vector>

#include <sp/rhi/shader.h>

namespace sp {

// One descriptor set per stage (VS 0, PS 1, GS 2; CS 0), and within it a fixed offset per
// register class so b0, t0, s0 and u0 never collide.
namespace vkbind {
inline constexpr uint32_t kConstantBuffer = 0;     // b0..b13  -> 0..13
inline constexpr uint32_t kShaderResource = 16;    // t0..t127 -> 16..143
inline constexpr uint32_t kSampler = 144;          // s0..s15  -> 144..159
inline constexpr uint32_t kUnorderedAccess = 160;  // u0..u7 -> 160..167
inline constexpr uint32_t kUavCounter = 168;       // hidden counters of append/consume UAVs
inline uint32_t SetForStage(ShaderStage s) { return s == ShaderStage::Compute ? 0u : uint32_t(s); }
}  // namespace vkbind

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

namespace detail {

// What ShaderBytecode::glLayout points at.
struct GlProgramLayout {
  std::vector<GlBinding> bindings;
};

// The GL binding table of a shader (empty when it has none).
const std::vector<GlBinding>& GlBindingsOf(const ShaderBytecode& bytecode);
void SetGlBindings(ShaderBytecode& bytecode, std::vector<GlBinding> bindings);

// Whether the shader reads texture register tN through a comparison sampler (SampleCmp,
// GatherCmp): the combined samplers of the GL table name each (texture, sampler) pair.
bool TextureIsCompared(const ShaderBytecode& bytecode, uint32_t textureRegister);

}  // namespace detail
}  // namespace sp
