// Small, targeted edits of SPIR-V binaries that spirv-opt does not offer. Each exists because a
// D3D11 rule or a driver requirement is not met by glslang's output as is.
#pragma once
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "shader-bindings.h"

namespace sp::hlsl {

// After loop unrolling and constant propagation, texel offsets of [unroll]ed loops are constants
// but still use the Offset image operand, which Vulkan allows only on gathers. Turn them into
// ConstOffset (the operand glslang would have emitted for a literal offset).
void ConstOffsetsFromConstants(std::vector<uint32_t>& spirv);

// glslang places the hidden counter of an Append/ConsumeStructuredBuffer at the next free binding,
// which can be another register's. Move each counter to `counterBase + (binding - uavBase)`.
void RemapCounterBindings(std::vector<uint32_t>& spirv, uint32_t uavBase, uint32_t counterBase);

// glslang gives a texture used with both a SamplerComparisonState and a SamplerState two
// variables (a depth and a non-depth image) and applies the texture binding shift to only one:
// the other keeps the bare register number (and set 0). Give it its twin's binding and set.
void ShiftUnshiftedTextureBindings(std::vector<uint32_t>& spirv, uint32_t textureBase);

// Variables (by result id) of samplers that feed a depth-comparison instruction: HLSL's
// SamplerComparisonState, which SPIR-V does not distinguish by type.
std::set<uint32_t> ComparisonSamplerVariables(const std::vector<uint32_t>& spirv);

// Storage images are compiled without a format (D3D binds any compatible UAV format to a
// RWTexture2D<float4>). Images that are read or used atomically need one; D3D11 allows typed UAV
// loads only from R32_FLOAT/UINT/SINT, so give those R32f/R32ui/R32i.
void SetFormatOfReadImages(std::vector<uint32_t>& spirv);

// Variables (by result id) of storage images that are only written (no read, no atomics).
std::set<uint32_t> WriteOnlyImageVariables(const std::vector<uint32_t>& spirv);

// glslang 12 translates GatherCmp and GatherCmpRed without an offset into an OpImageDrefGather
// that also passes the reference as a Bias operand, which SPIR-V allows only on implicit-LOD
// sampling (D3D11's gather4_c has no bias). Remove Bias from every gather, and the AMD extension
// and capability glslang declares for it.
void DropBiasFromGathers(std::vector<uint32_t>& spirv);

// Atomics on RWByteAddressBuffer get their value and comparator operands with the HLSL
// argument's type (int for literals and int arguments), which SPIR-V rejects: bitcast them to the
// word type, and make the int overloads of InterlockedMin/Max compare signed as in D3D11.
void FixAtomicOperandTypes(std::vector<uint32_t>& spirv);

// Rewrites OpDot, matrix products, length, normalize, distance and lerp (FMix) into explicit scalar and
// component-wise multiplies and adds in a fixed order, so that the Vulkan and GL drivers compute
// bit-identical results (see spirv-arith.cpp).
void LowerDotAndMatrixProducts(std::vector<uint32_t>& spirv);

// HLSL's component-wise intrinsics take matrices (abs(m), saturate(m), max(m, n), lerp(a, b, s));
// glslang emits the GLSL.std.450 instruction on the matrix type, which SPIR-V allows only on
// scalars and vectors. Applies each to the matrix column by column. Runs before legalisation.
void SplitMatrixIntrinsics(std::vector<uint32_t>& spirv);

// For the SPIR-V target (target-spirv.cpp): the entry point's name, and variants of a module for
// D3D11 rules Vulkan needs spelled out. A variant that would not differ is returned unchanged.
std::string EntryPointName(const std::vector<uint32_t>& spirv);
// D3D's dual-source blending reads SV_Target1 as the second source of target 0; Vulkan needs that
// output at location 0, index 1, which the HLSL front end cannot declare.
std::vector<uint32_t> DualSourceVariant(const std::vector<uint32_t>& spirv);
// D3D11 draws points one pixel wide; Vulkan reads PointSize, which must then be written.
std::vector<uint32_t> WritePointSizeVariant(const std::vector<uint32_t>& spirv);
// D3D11's SV_InstanceID counts from 0 whatever StartInstanceLocation is; InstanceIndex includes
// the base instance, so subtract BaseInstance (shaderDrawParameters).
std::vector<uint32_t> InstanceIdFromZeroVariant(const std::vector<uint32_t>& spirv);
// Each (texture, sampler) pair the shader samples with, and whether filtered and/or compared;
// registers are bindings minus the given bases.
std::vector<SampledPair> SampledPairs(const std::vector<uint32_t>& spirv, uint32_t textureBase, uint32_t samplerBase);

}  // namespace sp::hlsl
