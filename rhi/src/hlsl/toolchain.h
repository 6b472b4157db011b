// Internal stages of the HLSL toolchain (see sp/hlsl/compiler.h for the pipeline).
#pragma once
#include <sp/hlsl/compiler.h>

#include "shader-bindings.h"

#include <string>
#include <vector>

namespace spirv_cross {
class Compiler;
struct SPIRType;
}  // namespace spirv_cross

namespace sp::hlsl {

// Toolchain revision: part of every cache key. Bump it when a stage changes its output.
inline constexpr const char* kToolchainRevision = "sp-hlsl-21";

// Reflection from SPIR-V that still carries SPV_GOOGLE_hlsl_functionality1 decorations
// (semantics, counter buffers). Throws CompileError for bindings outside ShadowPort's scheme.
ShaderReflection Reflect(const std::vector<uint32_t>& spirv, ShaderStage stage, const std::string& entry,
                         const std::string& sourceName);

// D3D (fxc) cbuffer packing, which glslang's HLSL offsets do not fully follow: fxc packs the
// member after a matrix, an array or a struct into the unused tail of its last 16-byte register
// (a float after a float3x3 lands at +44, after float[3] at +36). Offsets are relative to the
// struct; `rowMajorSpirv` is the member's SPIR-V RowMajor decoration (HLSL column_major).
uint32_t D3DTypeSize(const spirv_cross::Compiler& c, uint32_t typeId, bool rowMajorSpirv);
std::vector<uint32_t> D3DMemberOffsets(const spirv_cross::Compiler& c, const spirv_cross::SPIRType& structType);

// The cbuffer repacking rule (target-cbuffer.cpp), shared by both targets: the copies from a
// D3D11-packed buffer into block `blockType` laid out by `layout`. Std140 also writes the std140
// offsets and strides into c's decorations when the layouts differ.
enum class BlockLayout { Std140, SpirvDecorations };
struct CBufferCopyTable {
  bool identity = true;  // the layouts agree: bind the buffer as it is
  uint32_t size = 0;     // bytes of the target's block
  std::vector<CBufferCopyRange> ranges;
};
CBufferCopyTable D3DCBufferCopyTable(spirv_cross::Compiler& c, uint32_t blockType, BlockLayout layout);

// The GLSL target (target-glsl.cpp): GLSL 4.50 for OpenGL from the final SPIR-V, with GL binding
// points assigned per stage, cbuffers whose D3D packing std140 cannot express rewritten to std140
// (and a repack table), and for pixel shaders writing SV_Target1 the dual-source variant.
struct GlslOutput {
  std::string glsl;
  detail::GlslProducts products;
};
GlslOutput CrossCompileToGlsl(const std::vector<uint32_t>& spirv, const ShaderReflection& reflection,
                              const std::string& sourceName);

// The SPIR-V target (target-spirv.cpp): what the Vulkan backend needs besides the SPIR-V itself.
detail::SpirvProducts MakeSpirvProducts(const std::vector<uint32_t>& spirv, const ShaderReflection& reflection,
                                        const std::string& sourceName);

// GL binding bases per stage: one program pipeline holds VS and PS programs, whose bindings must
// not collide in GL's per-context binding tables.
struct GlStageBases {
  uint32_t textureUnit, uniformBlock, storageBlock;
};
GlStageBases GlBasesForStage(ShaderStage stage);
inline constexpr uint32_t kGlUavCounterBase = 8;  // storage-block binding of uN's counter: 8 + N

// glslang's preprocessor alone: defines applied, includes inlined, #line directives naming the
// user's files, before the D3D11 compatibility rewrites. sp::fx reads effect blocks from it.
// Throws CompileError.
std::string PreprocessOnly(std::string_view source, const std::string& fileName, const CompileOptions& options);

// "" when `flags` is a valid combination of COMPILE_* bits, else the reason it is not.
std::string CheckCompileFlags(uint32_t flags);

// fnv-1a 64 over bytes, for cache keys and include dependencies.
uint64_t Hash64(const void* data, size_t size, uint64_t seed = 1469598103934665603ull);
std::string HexHash(uint64_t h);

}  // namespace sp::hlsl
