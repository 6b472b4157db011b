// The HLSL toolchain on its own (no device): reflection, bindings, GL repacking, errors, cache.
#include <gtest/gtest.h>

#include <fstream>

#include "backend-test.h"
// The GL binding tables and Vulkan binding offsets are internal to the library (rhi/src).
#include "shader-bindings.h"

namespace sp::test {
namespace {

namespace fs = std::filesystem;

const char* kLit = R"(
cbuffer Camera : register(b0) { float4x4 viewProj; float bias; float3 lightDir; };
Texture2D<float> shadowMap : register(t0);
Texture2D<float4> albedo : register(t1);
SamplerComparisonState shadowSampler : register(s0);
SamplerState linearSampler : register(s1);
struct VSIn { float3 pos : POSITION; float3 normal : NORMAL; float2 uv : TEXCOORD0; };
struct VSOut { float4 pos : SV_Position; float3 normal : NORMAL; float2 uv : TEXCOORD0; };
VSOut VSMain(VSIn i) { VSOut o; o.pos = mul(float4(i.pos, 1), viewProj); o.normal = i.normal * lightDir + bias; o.uv = i.uv; return o; }
float4 PSMain(VSOut i) : SV_Target {
  float s = 0;
  [unroll] for (int x = -1; x <= 1; ++x) s += shadowMap.SampleCmpLevelZero(shadowSampler, i.uv, bias, int2(x, 0));
  return albedo.Sample(linearSampler, i.uv) * s + albedo.Load(int3(0, 0, 0));
}
)";

TEST(HlslToolchain, ReflectsRegistersAndSignature) {
  ShaderBytecode vs = CompileHlsl(kLit, "vs_5_0", "VSMain");
  ASSERT_EQ(vs.stage, ShaderStage::Vertex);
  ASSERT_EQ(vs.reflection.cbuffers.size(), 1u);
  const CBufferInfo& cb = vs.reflection.cbuffers[0];
  EXPECT_EQ(cb.name, "Camera");
  EXPECT_EQ(cb.registerIndex, 0u);
  ASSERT_EQ(cb.members.size(), 3u);
  EXPECT_EQ(cb.members[0].offset, 0u);
  EXPECT_EQ(cb.members[1].offset, 64u);   // bias
  EXPECT_EQ(cb.members[2].offset, 68u);   // float3 packed after a float, as fxc does
  EXPECT_EQ(cb.members[2].size, 12u);
  EXPECT_EQ(cb.size, 80u);
  ASSERT_NE(vs.reflection.FindInput("POSITION", 0), nullptr);
  ASSERT_NE(vs.reflection.FindInput("TEXCOORD", 0), nullptr);
  EXPECT_EQ(vs.reflection.FindInput("TEXCOORD", 0)->componentCount, 2u);

  ShaderBytecode ps = CompileHlsl(kLit, "ps_5_0", "PSMain");
  const ShaderResourceBinding* smp = ps.reflection.FindResource(RegisterClass::Sampler, 0);
  ASSERT_NE(smp, nullptr);
  EXPECT_EQ(smp->type, ShaderResourceType::ComparisonSampler);
  EXPECT_EQ(ps.reflection.FindResource(RegisterClass::Sampler, 1)->type, ShaderResourceType::Sampler);
  const ShaderResourceBinding* tex = ps.reflection.FindResource(RegisterClass::ShaderResource, 1);
  ASSERT_NE(tex, nullptr);
  EXPECT_EQ(tex->dimension, SRV_DIMENSION_TEXTURE2D);
  EXPECT_EQ(tex->vkSet, 1u);
  EXPECT_EQ(tex->vkBinding, vkbind::kShaderResource + 1);
}

TEST(HlslToolchain, GlslGetsCombinedSamplersAndStd140Repack) {
  ShaderBytecode vs = CompileHlsl(kLit, "vs_5_0", "VSMain");
  // float3 at offset 68 cannot be expressed in std140: the block is repacked.
  const GlBinding* ubo = nullptr;
  for (const GlBinding& b : detail::GlBindingsOf(vs))
    if (b.kind == GlBindingKind::UniformBlock) ubo = &b;
  ASSERT_NE(ubo, nullptr);
  ASSERT_FALSE(ubo->repack.empty());
  EXPECT_EQ(ubo->glBlockSize, 96u);
  // lightDir: D3D offset 68 -> std140 offset 80
  bool found = false;
  for (const GlCopyRange& r : ubo->repack) found |= (r.src == 68 && r.dst == 80 && r.size == 12);
  EXPECT_TRUE(found);

  ShaderBytecode ps = CompileHlsl(kLit, "ps_5_0", "PSMain");
  int combined = 0, loads = 0;
  for (const GlBinding& b : detail::GlBindingsOf(ps)) {
    if (b.kind != GlBindingKind::CombinedSampler) continue;
    ++combined;
    if (b.samplerRegister < 0) ++loads;
    EXPECT_GE(b.glBinding, 16u);  // pixel-stage texture units
  }
  EXPECT_EQ(combined, 3);  // shadow+cmp, albedo+linear, albedo+dummy (Load)
  EXPECT_EQ(loads, 1);
  EXPECT_NE(ps.glsl.find("textureLodOffset"), std::string::npos) << ps.glsl;
}

TEST(HlslToolchain, ErrorNamesFileAndLine) {
  const char* bad = "float4 main() : SV_Target {\n  return undefinedThing;\n}\n";
  try {
    CompileHlsl(bad, "ps_5_0", "main");
    FAIL() << "expected a compile error";
  } catch (const hlsl::CompileError& e) {
    ASSERT_FALSE(e.diagnostics().empty());
    EXPECT_EQ(e.diagnostics()[0].line, 2);
    EXPECT_NE(std::string(e.what()).find(":2: error:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("undefinedThing"), std::string::npos) << e.what();
  }
}

// Invalid HLSL that crashes glslang's parser (a global declaration list going on with a struct
// type: glslang 11 segfaults in growGlobalUniformBlock; found by fuzz/fx-effect-fuzz.cpp). The
// parser runs in a child process, so the crash is a CompileError naming the file and the line
// (bisected), the caller lives on, and the next compile works.
TEST(HlslToolchain, ParserCrashIsACompileErrorNotACrash) {
  const char* crashes = "struct S { float4 p; };\nfloat4 a, S i;\nfloat4 main() : SV_Target { return a; }\n";
  try {
    CompileHlsl(crashes, "ps_5_0", "main");
    FAIL() << "expected a compile error";
  } catch (const hlsl::CompileError& e) {
    std::string what = e.what();
    EXPECT_NE(what.find("crashed with signal"), std::string::npos) << what;
    EXPECT_NE(what.find("glslang"), std::string::npos) << what;
    ASSERT_FALSE(e.diagnostics().empty());
    // The line it crashed on, found by bisecting the source.
    EXPECT_EQ(e.diagnostics()[0].line, 2) << what;
  }
  EXPECT_NO_THROW(CompileHlsl("float4 main() : SV_Target { return 1; }", "ps_5_0", "main"));
}

TEST(HlslToolchain, IncludesAndDefinesWorkLikeFxc) {
  fs::path dir = fs::path(SHADOWPORT_TEST_OUTPUT_DIR) / "include-test";
  fs::create_directories(dir / "sub");
  std::ofstream(dir / "sub" / "common.hlsli") << "#include \"values.hlsli\"\nfloat4 Color() { return float4(VALUE, 0, 0, 1); }\n";
  std::ofstream(dir / "sub" / "values.hlsli") << "#ifndef VALUE\n#define VALUE 0.25\n#endif\n";
  std::ofstream(dir / "main.hlsl") << "#include \"sub/common.hlsli\"\nfloat4 main() : SV_Target { return Color() * SCALE; }\n";
  hlsl::CompileOptions o;
  o.target = "ps_5_0";
  o.defines = {{"SCALE", "2"}};
  o.useCache = false;
  ShaderBytecode b = hlsl::CompileFile(dir / "main.hlsl", o);
  EXPECT_NE(b.glsl.find("0.5"), std::string::npos) << b.glsl;  // 0.25 * 2 folded

  // An error inside an included file names that file and line.
  std::ofstream(dir / "sub" / "values.hlsli") << "#define VALUE 0.25\nfloat broken = ;\n";
  try {
    hlsl::CompileFile(dir / "main.hlsl", o);
    FAIL() << "expected a compile error";
  } catch (const hlsl::CompileError& e) {
    ASSERT_FALSE(e.diagnostics().empty());
    EXPECT_NE(e.diagnostics()[0].file.find("values.hlsli"), std::string::npos) << e.what();
    EXPECT_EQ(e.diagnostics()[0].line, 2) << e.what();
  }
}

TEST(HlslToolchain, SecondCompileHitsTheCache) {
  fs::path cache = fs::path(SHADOWPORT_TEST_OUTPUT_DIR) / "cache-test";
  fs::remove_all(cache);
  hlsl::CompileOptions o;
  o.target = "ps_5_0";
  o.entryPoint = "PSMain";
  o.cacheDir = cache;
  hlsl::CacheStats before = hlsl::GetCacheStats();
  ShaderBytecode a = hlsl::CompileSource(kLit, "cache-test.hlsl", o);
  hlsl::CacheStats mid = hlsl::GetCacheStats();
  ShaderBytecode b = hlsl::CompileSource(kLit, "cache-test.hlsl", o);
  hlsl::CacheStats after = hlsl::GetCacheStats();
  EXPECT_EQ(mid.misses, before.misses + 1);
  EXPECT_EQ(after.misses, mid.misses);  // nothing compiled the second time
  EXPECT_EQ(after.hits, mid.hits + 1);
  EXPECT_EQ(a.spirv, b.spirv);
  EXPECT_EQ(a.glsl, b.glsl);
  EXPECT_EQ(a.ReflectionJson(), b.ReflectionJson());
}

TEST(HlslToolchain, BlobRoundTrips) {
  ShaderBytecode a = CompileHlsl(kLit, "ps_5_0", "PSMain");
  std::vector<uint8_t> blob = a.Serialize();
  ShaderBytecode b = ShaderBytecode::Deserialize(blob.data(), blob.size());
  EXPECT_EQ(a.spirv, b.spirv);
  EXPECT_EQ(a.glsl, b.glsl);
  EXPECT_EQ(a.ReflectionJson(), b.ReflectionJson());
  blob[0] ^= 0xff;
  EXPECT_THROW(ShaderBytecode::Deserialize(blob.data(), blob.size()), Error);
}

TEST(HlslToolchain, ComputeResourcesAndAppendCounters) {
  const char* cs = R"(
StructuredBuffer<float4> input : register(t2);
RWTexture2D<float4> outputImage : register(u0);
RWStructuredBuffer<uint> counters : register(u1);
AppendStructuredBuffer<uint> appended : register(u4);
groupshared uint gsData[64];
[numthreads(8, 8, 1)] void main(uint3 id : SV_DispatchThreadID, uint gi : SV_GroupIndex) {
  gsData[gi] = 0; GroupMemoryBarrierWithGroupSync(); InterlockedAdd(gsData[0], 1); GroupMemoryBarrierWithGroupSync();
  outputImage[id.xy] = input[id.x];
  InterlockedMax(counters[0], gsData[0]);
  appended.Append(id.x);
}
)";
  ShaderBytecode b = CompileHlsl(cs, "cs_5_0", "main");
  EXPECT_EQ(b.reflection.threadGroupSize, (std::array<uint32_t, 3>{8, 8, 1}));
  const ShaderResourceBinding* app = b.reflection.FindResource(RegisterClass::UnorderedAccess, 4);
  ASSERT_NE(app, nullptr);
  EXPECT_TRUE(app->appendConsume);
  bool counter = false;
  for (const ShaderResourceBinding& r : b.reflection.resources)
    if (r.type == ShaderResourceType::UavCounter) {
      counter = true;
      EXPECT_EQ(r.registerIndex, 4u);
      EXPECT_EQ(r.vkBinding, vkbind::kUavCounter + 4);
    }
  EXPECT_TRUE(counter);
  EXPECT_EQ(b.reflection.FindResource(RegisterClass::ShaderResource, 2)->structureStride, 16u);
}

}  // namespace
}  // namespace sp::test
