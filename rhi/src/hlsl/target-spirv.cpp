// The SPIR-V target: everything the Vulkan backend needs about a shader, made once at compile
// time (and cached with it), so the backend only creates modules.
//  - cbuffers whose D3D11 packing the SPIR-V block cannot express get a copy table (the shared
//    rule in target-cbuffer.cpp, destination read from glslang's decorations);
//  - the (texture, sampler) pairs sampled, so draws can check the format's features;
//  - variants of the module for D3D11 rules: SV_Target1 as location 0 index 1 for dual-source
//    blending, SV_InstanceID from 0, PointSize = 1 for point lists (spirv-edit.cpp).
#include <spirv_cross/spirv_cross.hpp>

#include "spirv-edit.h"
#include "toolchain.h"

namespace sp::hlsl {
namespace {

// A variant equal to the code it derives from is stored empty (detail::SpirvFor falls back).
std::vector<uint32_t> IfDifferent(std::vector<uint32_t> variant, const std::vector<uint32_t>& from) {
  if (variant == from) variant.clear();
  return variant;
}

}  // namespace

detail::SpirvProducts MakeSpirvProducts(const std::vector<uint32_t>& spirv, const ShaderReflection& refl, const std::string& sourceName) {
  detail::SpirvProducts p;
  p.entryPoint = EntryPointName(spirv);
  try {
    spirv_cross::Compiler c(spirv);
    for (const auto& ub : c.get_shader_resources().uniform_buffers) {
      CBufferCopyTable t = D3DCBufferCopyTable(c, ub.base_type_id, BlockLayout::SpirvDecorations);
      if (t.identity) continue;
      p.repacks.push_back({c.get_decoration(ub.id, spv::DecorationBinding) - vkbind::kConstantBuffer, t.size, std::move(t.ranges)});
    }
  } catch (const spirv_cross::CompilerError& e) {
    std::string msg = std::string("the cbuffer layout of this shader cannot be read: ") + e.what();
    throw CompileError("Compile", sourceName, {{sourceName, 0, msg}}, msg);
  }
  p.sampledPairs = SampledPairs(spirv, vkbind::kShaderResource, vkbind::kSampler);
  if (refl.stage == ShaderStage::Vertex) {
    p.instanceFromZero = IfDifferent(InstanceIdFromZeroVariant(spirv), spirv);
    p.pointSize = IfDifferent(WritePointSizeVariant(spirv), spirv);
    if (!p.instanceFromZero.empty()) p.pointSizeInstanceFromZero = IfDifferent(WritePointSizeVariant(p.instanceFromZero), p.instanceFromZero);
  }
  if (refl.stage == ShaderStage::Pixel)
    for (const SignatureElement& o : refl.outputs)
      if (o.semanticName == "SV_TARGET" && o.semanticIndex == 1) p.dualSource = IfDifferent(DualSourceVariant(spirv), spirv);
  return p;
}

}  // namespace sp::hlsl
