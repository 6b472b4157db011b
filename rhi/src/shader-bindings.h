// How D3D registers become Vulkan and OpenGL bindings, and everything else a backend needs from a
// shader (private to the library: the toolchain's target modules, rhi/src/hlsl/target-*.cpp,
// write these products at compile time, the backends only create modules and programs from them,
// the core reads them to learn how a shader uses a texture). Applications see only
// ShaderBytecode's opaque `targets` handle and the reflection.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <sp/rhi/shader.h>
#include <sp/rhi/state.h>

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

// A cbuffer whose D3D11 packing the target's block layout cannot express is bound as a copy:
// these byte ranges go from the D3D-packed buffer to the target's layout (one rule for both
// targets, rhi/src/hlsl/target-cbuffer.cpp).
struct CBufferCopyRange {
  uint32_t src = 0, dst = 0, size = 0;  // bytes
};
using GlCopyRange = CBufferCopyRange;

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

// Vulkan: a cbuffer whose SPIR-V block layout differs from D3D11's packing (fxc places the member
// after a matrix, array or struct in its last register's tail; SPIR-V block rules cannot).
struct CBufferRepack {
  uint32_t reg = 0;   // bN
  uint32_t size = 0;  // bytes of the SPIR-V block
  std::vector<CBufferCopyRange> ranges;
};

// A texture and a sampler used together, and how: D3D11 lets any texture be filtered and compared,
// Vulkan only formats with the matching features (checked at draw time).
struct SampledPair {
  uint32_t textureReg = 0, samplerReg = 0;
  bool filtered = false;  // Sample* without comparison
  bool compared = false;  // SampleCmp*, GatherCmp*
};

// Which SPIR-V a Vulkan module is made from: the variants differ by D3D11 rules Vulkan needs
// spelled out (rhi/src/hlsl/target-spirv.cpp).
struct SpirvVariant {
  bool instanceFromZero = false;  // SV_InstanceID counts from 0 (needs shaderDrawParameters)
  bool pointSize = false;         // writes PointSize = 1 (point-list draws)
  bool dualSource = false;        // SV_Target1 at location 0 index 1 (SRC1 blend factors)
};

// Whether a blend reads the pixel shader's second output (SRC1 factors): D3D11's dual-source
// blending, which only render target 0 may use. Pixel shaders writing SV_Target1 come with a
// variant for each target that makes it target 0's second source (SpirvFor, GlslProducts).
inline bool BlendReadsSource1(const RENDER_TARGET_BLEND_DESC& rt) {
  auto src1 = [](BLEND b) { return b == BLEND_SRC1_COLOR || b == BLEND_INV_SRC1_COLOR || b == BLEND_SRC1_ALPHA || b == BLEND_INV_SRC1_ALPHA; };
  return src1(rt.SrcBlend) || src1(rt.DestBlend) || src1(rt.SrcBlendAlpha) || src1(rt.DestBlendAlpha);
}

namespace detail {

// What the Vulkan backend gets (rhi/src/hlsl/target-spirv.cpp). A variant left empty is the same
// code as the one it derives from.
struct SpirvProducts {
  std::string entryPoint;
  std::vector<CBufferRepack> repacks;
  std::vector<SampledPair> sampledPairs;
  std::vector<uint32_t> instanceFromZero;           // vertex shaders reading SV_InstanceID
  std::vector<uint32_t> pointSize;                  // vertex shaders
  std::vector<uint32_t> pointSizeInstanceFromZero;  // vertex shaders reading SV_InstanceID
  std::vector<uint32_t> dualSource;                 // pixel shaders writing SV_Target1
};

// What the GL backend gets besides ShaderBytecode::glsl (rhi/src/hlsl/target-glsl.cpp).
struct GlslProducts {
  std::vector<GlBinding> bindings;
  std::string dualSourceGlsl;  // pixel shaders writing SV_Target1: SV_Target1 at location 0 index 1
};

// Every target's products (ShaderBytecode::targets).
struct TargetProducts {
  SpirvProducts spirv;
  GlslProducts gl;
};

const TargetProducts& TargetsOf(const ShaderBytecode& bytecode);  // empty products when none
void SetTargets(ShaderBytecode& bytecode, TargetProducts products);

// The code of a Vulkan module for `variant` (falls back along the variants left empty).
const std::vector<uint32_t>& SpirvFor(const ShaderBytecode& bytecode, SpirvVariant variant);

// The GL binding table of a shader (empty when it has none).
const std::vector<GlBinding>& GlBindingsOf(const ShaderBytecode& bytecode);

// Whether the shader reads texture register tN through a comparison sampler (SampleCmp,
// GatherCmp): the combined samplers of the GL table name each (texture, sampler) pair.
bool TextureIsCompared(const ShaderBytecode& bytecode, uint32_t textureRegister);

}  // namespace detail
}  // namespace sp
