// SV_RenderTargetArrayIndex / SV_ViewportArrayIndex written by a vertex shader (no device): glslang
// declares the EXT capability, the SPIR-V validates for the Vulkan versions the backend targets,
// and the GLSL requires GL_ARB_shader_viewport_layer_array, without which GLSL 4.50 has no
// gl_Layer in a vertex shader.
#include <gtest/gtest.h>

#include <spirv-tools/libspirv.hpp>

#include "backend-test.h"

namespace sp::test {
namespace {

const char* kLayerVs = R"(
cbuffer Layers : register(b0) { float4x4 viewProj[6]; uint4 layerOf[6]; };
struct VSOut { float4 pos : SV_Position; uint layer : SV_RenderTargetArrayIndex; uint viewport : SV_ViewportArrayIndex; };
VSOut VSMain(float3 pos : POSITION, uint instance : SV_InstanceID) {
  VSOut o;
  uint layer = layerOf[instance].x;
  o.pos = mul(viewProj[layer], float4(pos, 1.0));
  o.layer = layer;
  o.viewport = 0;
  return o;
}
)";

bool DeclaresCapability(const std::vector<uint32_t>& spirv, uint32_t capability) {
  for (size_t i = 5; i < spirv.size();) {
    uint32_t words = spirv[i] >> 16, op = spirv[i] & 0xffff;
    if (words == 0) break;
    if (op == 17 /* OpCapability */ && words == 2 && spirv[i + 1] == capability) return true;
    i += words;
  }
  return false;
}

TEST(HlslVertexArrayIndex, CompilesToTheLayerCapabilityAndTheGlExtension) {
  ShaderBytecode vs = CompileHlsl(kLayerVs, "vs_5_0", "VSMain");
  bool layer = false, viewport = false;
  for (const SignatureElement& o : vs.reflection.outputs) {
    layer |= o.semanticName == "SV_RENDERTARGETARRAYINDEX" && o.systemValue;
    viewport |= o.semanticName == "SV_VIEWPORTARRAYINDEX" && o.systemValue;
  }
  EXPECT_TRUE(layer);
  EXPECT_TRUE(viewport);
  const uint32_t kShaderViewportIndexLayerEXT = 5254;
  EXPECT_TRUE(DeclaresCapability(vs.spirv, kShaderViewportIndexLayerEXT));
  // The toolchain validated for Vulkan 1.1 (+ the extension); the backend runs Vulkan 1.3.
  for (spv_target_env env : {SPV_ENV_VULKAN_1_1, SPV_ENV_VULKAN_1_2, SPV_ENV_VULKAN_1_3}) {
    spvtools::SpirvTools tools(env);
    std::string log;
    tools.SetMessageConsumer([&](spv_message_level_t, const char*, const spv_position_t&, const char* m) { log += m; });
    EXPECT_TRUE(tools.Validate(vs.spirv)) << "target env " << int(env) << ": " << log;
  }
  EXPECT_NE(vs.glsl.find("#extension GL_ARB_shader_viewport_layer_array : require"), std::string::npos) << vs.glsl;
  EXPECT_NE(vs.glsl.find("gl_Layer = "), std::string::npos) << vs.glsl;
  EXPECT_NE(vs.glsl.find("gl_ViewportIndex = "), std::string::npos) << vs.glsl;
}

// Shaders that do not write them get no extension line (older GL drivers lack it).
TEST(HlslVertexArrayIndex, OtherShadersDoNotRequireTheExtension) {
  ShaderBytecode vs = CompileShaderFile("common/depth-only.hlsl", "vs_5_0", "VSMain");
  EXPECT_EQ(vs.glsl.find("GL_ARB_shader_viewport_layer_array"), std::string::npos) << vs.glsl;
  ShaderBytecode layered = CompileShaderFile("common/depth-layered.hlsl", "vs_5_0", "VSMain");
  EXPECT_NE(layered.glsl.find("GL_ARB_shader_viewport_layer_array"), std::string::npos) << layered.glsl;
}

}  // namespace
}  // namespace sp::test
