// The GLSL target: SPIR-V -> GLSL 4.50 and everything else the OpenGL backend needs, made once at
// compile time (and cached with it), so the backend only creates programs.
//
// GL differs from D3D/Vulkan in three ways that matter here:
//  - textures and samplers are combined: each (texture, sampler) pair a shader uses becomes one
//    sampler uniform with its own texture unit, and Load/texelFetch get a dummy sampler;
//  - uniform blocks follow std140, which cannot express every HLSL cbuffer packing (a float3 right
//    after a float, a float after a float3x3, arrays of structs whose size std140 rounds up).
//    Such blocks are given std140 offsets here, and the GL backend repacks the D3D-laid-out buffer
//    into that layout with the copy table of the shared rule (target-cbuffer.cpp);
//  - dual-source blending reads the output at location 0 index 1, which D3D's SV_Target1 is not:
//    the variant is cross-compiled from SPIR-V with that decoration (spirv-edit.cpp).
#include <algorithm>
#include <spirv_cross/spirv_glsl.hpp>

#include "spirv-edit.h"
#include "toolchain.h"

namespace sp::hlsl {
namespace {


[[noreturn]] void Fail(const std::string& source, const std::string& msg) {
  throw CompileError("CrossCompileToGlsl", source, {{source, 0, msg}}, msg);
}

// OpAtomicSMin/SMax on unsigned integer memory (made by FixAtomicOperandTypes).
bool HasSignedAtomicOnUnsignedWords(const std::vector<uint32_t>& spirv) {
  std::vector<uint32_t> unsignedInts;
  for (size_t i = 5; i < spirv.size();) {
    uint32_t wc = spirv[i] >> 16;
    if (wc == 0) break;
    spv::Op op = spv::Op(spirv[i] & 0xffff);
    if (op == spv::OpTypeInt && wc >= 4 && spirv[i + 3] == 0) unsignedInts.push_back(spirv[i + 1]);
    if ((op == spv::OpAtomicSMin || op == spv::OpAtomicSMax) && wc >= 3 &&
        std::find(unsignedInts.begin(), unsignedInts.end(), spirv[i + 1]) != unsignedInts.end())
      return true;
    i += wc;
  }
  return false;
}

// With the extension, Mesa makes gl_Layer and gl_ViewportIndex members of the vertex stage's
// gl_PerVertex, and a redeclared gl_PerVertex (SPIRV-Cross writes one for separable programs)
// hides every member it does not list; SPIRV-Cross lists only the SPIR-V block's members.
void DeclareLayerOutputsInPerVertex(std::string& glsl) {
  const std::string block = "out gl_PerVertex\n{\n";
  size_t at = glsl.find(block);
  if (at == std::string::npos) return;
  size_t end = glsl.find('}', at);
  for (const char* name : {"gl_Layer", "gl_ViewportIndex"}) {
    std::string member = std::string("    int ") + name + ";\n";
    if (glsl.find(std::string(name) + " =") == std::string::npos || glsl.substr(at, end - at).find(name) != std::string::npos) continue;
    glsl.insert(at + block.size(), member);
    end += member.size();
  }
}

}  // namespace

GlStageBases GlBasesForStage(ShaderStage stage) {
  switch (stage) {
    case ShaderStage::Vertex: return {0, 0, 16};
    case ShaderStage::Pixel: return {16, 14, 32};
    case ShaderStage::Geometry: return {32, 28, 48};
    case ShaderStage::Compute: return {0, 0, 16};
  }
  return {0, 0, 16};
}

namespace {

GlslOutput CrossCompileOne(const std::vector<uint32_t>& spirv, const ShaderReflection& refl, const std::string& sourceName) {
  GlslOutput out;
  try {
    spirv_cross::CompilerGLSL c(spirv);
    spirv_cross::CompilerGLSL::Options o = c.get_common_options();
    o.version = 450;
    o.es = false;
    o.vulkan_semantics = false;
    o.separate_shader_objects = true;
    o.enable_420pack_extension = true;
    // glslang maps SV_InstanceID to InstanceIndex, which counts from the draw's first instance;
    // D3D's SV_InstanceID, like GL's gl_InstanceID, does not include StartInstanceLocation.
    o.vertex.support_nonzero_base_instance = false;
    c.set_common_options(o);
    // SPIRV-Cross writes gl_Layer / gl_ViewportIndex in a vertex shader without the extension
    // that declares them there in GLSL 4.50, so the GL driver would reject the shader.
    bool layerOutputs = false;
    if (refl.stage == ShaderStage::Vertex)
      for (spv::Capability cap : c.get_declared_capabilities())
        layerOutputs |= cap == spv::CapabilityShaderViewportIndexLayerEXT || cap == spv::CapabilityShaderLayer || cap == spv::CapabilityShaderViewportIndex;
    if (layerOutputs) c.require_extension("GL_ARB_shader_viewport_layer_array");

    GlStageBases bases = GlBasesForStage(refl.stage);
    spirv_cross::ShaderResources res = c.get_shader_resources();

    // Uniform blocks: std140 where needed, bindings per stage.
    for (const auto& ub : res.uniform_buffers) {
      uint32_t reg = c.get_decoration(ub.id, spv::DecorationBinding) - vkbind::kConstantBuffer;
      GlBinding b;
      b.kind = GlBindingKind::UniformBlock;
      b.glBinding = bases.uniformBlock + reg;
      b.registerClass = RegisterClass::ConstantBuffer;
      b.registerIndex = reg;
      CBufferCopyTable std140 = D3DCBufferCopyTable(c, ub.base_type_id, BlockLayout::Std140);
      if (!std140.identity) {
        b.repack = std::move(std140.ranges);
        b.glBlockSize = std140.size;
      }
      c.set_decoration(ub.id, spv::DecorationBinding, b.glBinding);
      c.unset_decoration(ub.id, spv::DecorationDescriptorSet);
      out.products.bindings.push_back(std::move(b));
    }

    // Storage blocks: UAV buffers keep their register (D3D shares u# between PS and CS), their
    // counters sit at kGlUavCounterBase + N, read-only t# buffers get a per-stage range.
    uint32_t nextStorage = bases.storageBlock;
    for (const auto& sb : res.storage_buffers) {
      uint32_t binding = c.get_decoration(sb.id, spv::DecorationBinding);
      GlBinding b;
      b.kind = GlBindingKind::StorageBlock;
      if (binding >= vkbind::kUavCounter) {
        b.registerClass = RegisterClass::UnorderedAccess;
        b.registerIndex = binding - vkbind::kUavCounter;
        b.uavCounter = true;
        b.glBinding = kGlUavCounterBase + b.registerIndex;
      } else if (binding >= vkbind::kUnorderedAccess) {
        b.registerClass = RegisterClass::UnorderedAccess;
        b.registerIndex = binding - vkbind::kUnorderedAccess;
        b.glBinding = b.registerIndex;
      } else {
        b.registerClass = RegisterClass::ShaderResource;
        b.registerIndex = binding - vkbind::kShaderResource;
        if (nextStorage >= bases.storageBlock + 16) Fail(sourceName, "more than 16 structured/byte-address buffers in one stage");
        b.glBinding = nextStorage++;
      }
      c.set_decoration(sb.id, spv::DecorationBinding, b.glBinding);
      c.unset_decoration(sb.id, spv::DecorationDescriptorSet);
      out.products.bindings.push_back(std::move(b));
    }

    for (const auto& img : res.storage_images) {
      GlBinding b;
      b.kind = GlBindingKind::Image;
      b.registerClass = RegisterClass::UnorderedAccess;
      b.registerIndex = c.get_decoration(img.id, spv::DecorationBinding) - vkbind::kUnorderedAccess;
      b.glBinding = b.registerIndex;
      c.set_decoration(img.id, spv::DecorationBinding, b.glBinding);
      c.unset_decoration(img.id, spv::DecorationDescriptorSet);
      out.products.bindings.push_back(std::move(b));
    }

    // Combined image-samplers, one texture unit each.
    c.build_dummy_sampler_for_combined_images();
    c.build_combined_image_samplers();
    uint32_t unit = bases.textureUnit;
    for (const spirv_cross::CombinedImageSampler& cis : c.get_combined_image_samplers()) {
      GlBinding b;
      b.kind = GlBindingKind::CombinedSampler;
      b.registerClass = RegisterClass::ShaderResource;
      b.registerIndex = c.get_decoration(cis.image_id, spv::DecorationBinding) - vkbind::kShaderResource;
      uint32_t sb = c.get_decoration(cis.sampler_id, spv::DecorationBinding);
      bool dummy = !c.has_decoration(cis.sampler_id, spv::DecorationBinding) || sb < vkbind::kSampler;
      b.samplerRegister = dummy ? -1 : int32_t(sb - vkbind::kSampler);
      if (unit >= bases.textureUnit + 16) Fail(sourceName, "more than 16 texture/sampler pairs in one stage (GL_MAX_TEXTURE_IMAGE_UNITS minimum)");
      b.glBinding = unit++;
      c.set_decoration(cis.combined_id, spv::DecorationBinding, b.glBinding);
      c.set_name(cis.combined_id, "sp_" + c.get_name(cis.image_id) + (dummy ? std::string("_load") : "_" + c.get_name(cis.sampler_id)));
      out.products.bindings.push_back(std::move(b));
    }
    // Typed buffers (Buffer<T>) are only ever fetched: SPIRV-Cross declares them as samplerBuffer
    // without a combined sampler, so they need a texture unit of their own.
    for (const auto& img : res.separate_images) {
      if (c.get_type(img.type_id).image.dim != spv::DimBuffer) continue;
      GlBinding b;
      b.kind = GlBindingKind::CombinedSampler;
      b.registerClass = RegisterClass::ShaderResource;
      b.registerIndex = c.get_decoration(img.id, spv::DecorationBinding) - vkbind::kShaderResource;
      b.samplerRegister = -1;
      if (unit >= bases.textureUnit + 16) Fail(sourceName, "more than 16 texture/sampler pairs in one stage (GL_MAX_TEXTURE_IMAGE_UNITS minimum)");
      b.glBinding = unit++;
      c.set_decoration(img.id, spv::DecorationBinding, b.glBinding);
      c.unset_decoration(img.id, spv::DecorationDescriptorSet);
      out.products.bindings.push_back(std::move(b));
    }
    out.glsl = c.compile();
    if (layerOutputs) DeclareLayerOutputsInPerVertex(out.glsl);
    if (HasSignedAtomicOnUnsignedWords(spirv)) {
      // GLSL's atomicMin/atomicMax compare with the signedness of the memory, here the uint words
      // of a RWByteAddressBuffer, so D3D11's signed int overloads cannot be expressed. The
      // Vulkan bytecode is right; the GL driver rejects this GLSL when the shader is created.
      size_t eol = out.glsl.find('\n');
      out.glsl.insert(eol == std::string::npos ? out.glsl.size() : eol + 1,
                      "#error InterlockedMin/InterlockedMax with an int value on a RWByteAddressBuffer compare signed in D3D11, which GLSL cannot "
                      "express on the buffer's uint words\n");
    }
  } catch (const spirv_cross::CompilerError& e) {
    std::string what = e.what();
    if (what.find("cannot be expressed as any of std430") != std::string::npos)
      Fail(sourceName, "a structured buffer's element has members at offsets that neither GLSL std430 nor Vulkan without scalar layout can "
                       "express (D3D11's 4-byte packed layout, e.g. a float2 or float3 after a float); reorder the members largest first or "
                       "pad them to their natural alignment (SPIRV-Cross: " + what + ")");
    Fail(sourceName, "SPIRV-Cross: " + what);
  }
  return out;
}

}  // namespace

GlslOutput CrossCompileToGlsl(const std::vector<uint32_t>& spirv, const ShaderReflection& refl, const std::string& sourceName) {
  GlslOutput out = CrossCompileOne(spirv, refl, sourceName);
  if (refl.stage == ShaderStage::Pixel)
    for (const SignatureElement& o : refl.outputs)
      if (o.semanticName == "SV_TARGET" && o.semanticIndex == 1) out.products.dualSourceGlsl = CrossCompileOne(DualSourceVariant(spirv), refl, sourceName).glsl;
  return out;
}

}  // namespace sp::hlsl
