// What D3D11 code asks of fxc: Shader Model 4 targets, fxc's compile flags (-Zpr/-Zpc packing,
// -WX, the accepted no-ops) and the cache keys they make. No device needed.
#include <gtest/gtest.h>

#include <fstream>

#include "backend-test.h"

namespace sp::test {
namespace {

namespace fs = std::filesystem;

// tests/hlsl/data in the source tree (SHADOWPORT_SHADER_DIR is <source>/shaders-hlsl).
fs::path DataDir() { return fs::path(SHADOWPORT_SHADER_DIR).parent_path() / "tests" / "hlsl" / "data"; }

std::string ReadText(const fs::path& p) {
  std::ifstream f(p);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

hlsl::CompileOptions Options(const std::string& target, const std::string& entry, uint32_t flags = 0) {
  hlsl::CompileOptions o;
  o.target = target;
  o.entryPoint = entry;
  o.flags1 = flags;
  o.useCache = false;
  return o;
}

// One entry point per stage, so each SM4 target has something of its stage to compile.
const char* kStages = R"(
cbuffer C : register(b0) { float4x4 world; float4 tint; };
Texture2D<float4> tex : register(t0);
SamplerState smp : register(s0);
RWStructuredBuffer<float4> outBuf : register(u0);
struct VSOut { float4 pos : SV_Position; float2 uv : TEXCOORD0; };
VSOut VSMain(float3 p : POSITION, float2 uv : TEXCOORD0) { VSOut o; o.pos = mul(float4(p, 1), world); o.uv = uv; return o; }
float4 PSMain(VSOut i) : SV_Target { return tex.Sample(smp, i.uv) * tint; }
[numthreads(8, 1, 1)] void CSMain(uint3 id : SV_DispatchThreadID) { outBuf[id.x] = tint * float(id.x); }
[maxvertexcount(3)] void GSMain(triangle VSOut input[3], inout TriangleStream<VSOut> stream) {
  for (int i = 0; i < 3; ++i) stream.Append(input[i]);
}
)";

TEST(FxcCompat, ShaderModel4TargetsCompileAsTheirShaderModel5Twin) {
  struct Case {
    const char* sm4;
    const char* sm5;
    const char* entry;
  };
  const Case cases[] = {
      {"vs_4_0", "vs_5_0", "VSMain"}, {"vs_4_1", "vs_5_0", "VSMain"}, {"ps_4_0", "ps_5_0", "PSMain"}, {"ps_4_1", "ps_5_0", "PSMain"},
      {"cs_4_0", "cs_5_0", "CSMain"}, {"cs_4_1", "cs_5_0", "CSMain"}, {"gs_4_0", "gs_5_0", "GSMain"}, {"gs_4_1", "gs_5_0", "GSMain"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.sm4);
    ShaderStage stage;
    ASSERT_TRUE(hlsl::ParseTarget(c.sm4, &stage));
    ShaderBytecode a = hlsl::CompileSource(kStages, "sm4.hlsl", Options(c.sm4, c.entry));
    ShaderBytecode b = hlsl::CompileSource(kStages, "sm4.hlsl", Options(c.sm5, c.entry));
    EXPECT_EQ(a.stage, b.stage);
    EXPECT_FALSE(a.spirv.empty());
    EXPECT_EQ(a.spirv, b.spirv);
    EXPECT_EQ(a.glsl, b.glsl);
    EXPECT_EQ(a.ReflectionJson(), b.ReflectionJson());
  }
}

TEST(FxcCompat, UnknownTargetsAreNamedWithTheValidOnes) {
  for (const char* target : {"ps_3_0", "vs_2_0", "lib_6_3", "tx_1_0", "ps_6_0", "hs_5_0", "ps_5_1", ""}) {
    SCOPED_TRACE(target);
    ShaderStage stage;
    EXPECT_FALSE(hlsl::ParseTarget(target, &stage));
    try {
      hlsl::CompileSource(kStages, "targets.hlsl", Options(target, "PSMain"));
      ADD_FAILURE() << "expected a compile error";
    } catch (const hlsl::CompileError& e) {
      std::string what = e.what();
      EXPECT_EQ(e.id(), ErrorId::SHADER_COMPILE_FAILED);
      EXPECT_NE(what.find("targets.hlsl: error: unknown target '" + std::string(target) + "'"), std::string::npos) << what;
      EXPECT_NE(what.find("vs_4_0, vs_4_1, vs_5_0, ps_4_0, ps_4_1, ps_5_0, cs_4_0, cs_4_1, cs_5_0"), std::string::npos) << what;
    }
  }
  try {
    hlsl::CompileSource(kStages, "targets.hlsl", Options("ps_3_0", "PSMain"));
  } catch (const hlsl::CompileError& e) {
    EXPECT_NE(std::string(e.what()).find("Direct3D 9"), std::string::npos) << e.what();
  }
}

const CBufferMember* Member(const ShaderBytecode& b, const std::string& name) {
  for (const CBufferMember& m : b.reflection.cbuffers.at(0).members)
    if (m.name == name) return &m;
  return nullptr;
}

// fxc's packing: a float4x3 is 3 registers column_major (48 bytes) and 4 rows of float3
// row_major (3 * 16 + 12 = 60 bytes); the next scalar packs into the tail of the last register.
TEST(FxcCompat, PackMatrixFlagsSetTheDefaultPackingAsFxc) {
  std::string src = ReadText(DataDir() / "packing.hlsl");
  ShaderBytecode def = hlsl::CompileSource(src, "packing.hlsl", Options("cs_5_0", "main"));
  ShaderBytecode zpc = hlsl::CompileSource(src, "packing.hlsl", Options("cs_5_0", "main", hlsl::COMPILE_PACK_MATRIX_COLUMN_MAJOR));
  ShaderBytecode zpr = hlsl::CompileSource(src, "packing.hlsl", Options("cs_5_0", "main", hlsl::COMPILE_PACK_MATRIX_ROW_MAJOR));
  for (const ShaderBytecode* b : {&def, &zpc}) {
    EXPECT_EQ(Member(*b, "n")->size, 48u);
    EXPECT_EQ(Member(*b, "n")->typeName, "column_major float4x3");
    EXPECT_EQ(Member(*b, "tail")->offset, 112u);
  }
  EXPECT_EQ(def.spirv, zpc.spirv);  // column_major is HLSL's default
  EXPECT_EQ(Member(zpr, "m")->typeName, "row_major float4x4");
  EXPECT_EQ(Member(zpr, "n")->typeName, "row_major float4x3");
  EXPECT_EQ(Member(zpr, "n")->size, 60u);
  EXPECT_EQ(Member(zpr, "tail")->offset, 124u);
  // Explicit qualifiers win over the flag, in both directions.
  for (const ShaderBytecode* b : {&def, &zpr}) {
    EXPECT_EQ(Member(*b, "c")->typeName, "column_major float4x3");
    EXPECT_EQ(Member(*b, "c")->offset, 128u);
    EXPECT_EQ(Member(*b, "c")->size, 48u);
    EXPECT_EQ(Member(*b, "r")->typeName, "row_major float3x4");
    EXPECT_EQ(Member(*b, "r")->offset, 176u);
    EXPECT_EQ(b->reflection.cbuffers[0].size, 224u);
  }
  // So does a pack_matrix pragma in the source, after the flag.
  ShaderBytecode pragma = hlsl::CompileSource("#pragma pack_matrix(column_major)\n" + src, "packing.hlsl",
                                              Options("cs_5_0", "main", hlsl::COMPILE_PACK_MATRIX_ROW_MAJOR));
  EXPECT_EQ(Member(pragma, "n")->typeName, "column_major float4x3");
  EXPECT_EQ(Member(pragma, "tail")->offset, 112u);
}

TEST(FxcCompat, ConflictingAndUnknownFlagsAreRefused) {
  const uint32_t bad[] = {hlsl::COMPILE_PACK_MATRIX_ROW_MAJOR | hlsl::COMPILE_PACK_MATRIX_COLUMN_MAJOR,
                          hlsl::COMPILE_AVOID_FLOW_CONTROL | hlsl::COMPILE_PREFER_FLOW_CONTROL, 1u << 16, 1u << 30};
  const char* expect[] = {"exclude each other", "exclude each other", "unknown compile flags 0x10000", "unknown compile flags 0x40000000"};
  for (int i = 0; i < 4; ++i) {
    try {
      hlsl::CompileSource(kStages, "flags.hlsl", Options("ps_5_0", "PSMain", bad[i]));
      ADD_FAILURE() << "expected an error for flags " << bad[i];
    } catch (const hlsl::CompileError& e) {
      EXPECT_NE(std::string(e.what()).find(expect[i]), std::string::npos) << e.what();
    }
  }
}

// Flags that only steer fxc's code generation are accepted and change nothing.
TEST(FxcCompat, CodeGenerationFlagsAreAcceptedWithoutEffect) {
  ShaderBytecode plain = hlsl::CompileSource(kStages, "noop.hlsl", Options("ps_5_0", "PSMain"));
  const uint32_t noops[] = {hlsl::COMPILE_DEBUG,
                            hlsl::COMPILE_SKIP_VALIDATION,
                            hlsl::COMPILE_SKIP_OPTIMIZATION,
                            hlsl::COMPILE_PARTIAL_PRECISION,
                            hlsl::COMPILE_AVOID_FLOW_CONTROL,
                            hlsl::COMPILE_PREFER_FLOW_CONTROL,
                            hlsl::COMPILE_ENABLE_STRICTNESS,
                            hlsl::COMPILE_ENABLE_BACKWARDS_COMPATIBILITY,
                            hlsl::COMPILE_IEEE_STRICTNESS,
                            hlsl::COMPILE_OPTIMIZATION_LEVEL0,
                            hlsl::COMPILE_OPTIMIZATION_LEVEL2,
                            hlsl::COMPILE_OPTIMIZATION_LEVEL3,
                            hlsl::COMPILE_RESOURCES_MAY_ALIAS,
                            hlsl::COMPILE_ALL_RESOURCES_BOUND,
                            hlsl::COMPILE_NO_PRESHADER,
                            hlsl::COMPILE_ENABLE_STRICTNESS | hlsl::COMPILE_WARNINGS_ARE_ERRORS | hlsl::COMPILE_OPTIMIZATION_LEVEL3};
  for (uint32_t f : noops) {
    SCOPED_TRACE(f);
    ShaderBytecode b = hlsl::CompileSource(kStages, "noop.hlsl", Options("ps_5_0", "PSMain", f));
    EXPECT_EQ(b.spirv, plain.spirv);
    EXPECT_EQ(b.glsl, plain.glsl);
  }
  // Strict mode must not break valid SM5 code: every shader of the project's own set compiles.
  for (const char* entry : {"VSMain", "PSMain", "CSMain"}) {
    std::string target = std::string(entry[0] == 'V' ? "vs" : entry[0] == 'P' ? "ps" : "cs") + "_5_0";
    EXPECT_NO_THROW(hlsl::CompileSource(kStages, "strict.hlsl", Options(target, entry, hlsl::COMPILE_ENABLE_STRICTNESS)));
  }
}

TEST(FxcCompat, WarningsAreReportedAndFailUnderWX) {
  fs::path file = DataDir() / "warning.hlsl";
  std::vector<hlsl::Diagnostic> warnings;
  ShaderBytecode b = hlsl::CompileFile(file, Options("vs_5_0", "main"), &warnings);
  EXPECT_FALSE(b.spirv.empty());
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0].line, 3);
  EXPECT_NE(warnings[0].message.find("unrecognized attribute"), std::string::npos) << warnings[0].message;
  EXPECT_NE(hlsl::FormatDiagnostics(warnings, "warning").find("warning.hlsl:3: warning: "), std::string::npos);
  try {
    hlsl::CompileFile(file, Options("vs_5_0", "main", hlsl::COMPILE_WARNINGS_ARE_ERRORS));
    FAIL() << "-WX must turn the warning into an error";
  } catch (const hlsl::CompileError& e) {
    std::string what = e.what();
    EXPECT_NE(what.find("warning.hlsl:3: error: "), std::string::npos) << what;
    EXPECT_NE(what.find("-WX"), std::string::npos) << what;
  }
  // fxc's loop and switch hints are valid D3D11 HLSL: no warning, so -WX passes.
  const char* hints = R"(
RWStructuredBuffer<uint> o : register(u0);
[numthreads(1, 1, 1)] void main(uint3 id : SV_DispatchThreadID) {
  [fastopt] for (uint i = 0; i < 4; ++i) o[i] = i;
  [allow_uav_condition] for (uint j = 0; j < o[0]; ++j) o[j + 4] = j;
  [forcecase] switch (id.x) { case 0: o[8] = 1; break; default: break; }
  [call] switch (id.y) { case 0: o[9] = 1; break; default: break; }
})";
  std::vector<hlsl::Diagnostic> none;
  EXPECT_NO_THROW(hlsl::CompileSource(hints, "hints.hlsl", Options("cs_5_0", "main", hlsl::COMPILE_WARNINGS_ARE_ERRORS), &none));
  EXPECT_TRUE(none.empty());
}

size_t CountEntries(const fs::path& dir) {
  size_t n = 0;
  if (fs::exists(dir))
    for (const fs::directory_entry& e : fs::directory_iterator(dir)) n += e.path().extension() == ".json";
  return n;
}

// The cache key holds the flags that change the output; flags without effect share the entry,
// and a cached shader's warnings still fail a later -WX compile.
TEST(FxcCompat, CacheKeysFollowTheFlagsThatChangeTheOutput) {
  fs::path dir = fs::path(SHADOWPORT_TEST_OUTPUT_DIR) / "fxc-flag-cache";
  fs::remove_all(dir);
  std::string src = ReadText(DataDir() / "packing.hlsl");
  auto compile = [&](const std::string& target, uint32_t flags) {
    hlsl::CompileOptions o = Options(target, "main", flags);
    o.useCache = true;
    o.cacheDir = dir;
    return hlsl::CompileSource(src, "cache-flags.hlsl", o);
  };
  hlsl::CacheStats s0 = hlsl::GetCacheStats();
  ShaderBytecode plain = compile("cs_5_0", 0);
  EXPECT_EQ(CountEntries(dir), 1u);
  compile("cs_4_0", hlsl::COMPILE_SKIP_OPTIMIZATION | hlsl::COMPILE_DEBUG | hlsl::COMPILE_OPTIMIZATION_LEVEL3 |
                        hlsl::COMPILE_PREFER_FLOW_CONTROL | hlsl::COMPILE_ENABLE_STRICTNESS | hlsl::COMPILE_IEEE_STRICTNESS);
  EXPECT_EQ(CountEntries(dir), 1u);
  hlsl::CacheStats s1 = hlsl::GetCacheStats();
  EXPECT_EQ(s1.misses, s0.misses + 1);
  EXPECT_EQ(s1.hits, s0.hits + 1);
  ShaderBytecode zpr = compile("cs_5_0", hlsl::COMPILE_PACK_MATRIX_ROW_MAJOR);
  EXPECT_EQ(CountEntries(dir), 2u);
  EXPECT_NE(zpr.spirv, plain.spirv);
  EXPECT_EQ(Member(zpr, "tail")->offset, 124u);
  compile("cs_5_0", hlsl::COMPILE_PACK_MATRIX_COLUMN_MAJOR);
  EXPECT_EQ(CountEntries(dir), 3u);
  EXPECT_EQ(hlsl::GetCacheStats().misses, s1.misses + 2);

  // Warnings are stored with the entry: the second compile is a cache hit and still fails.
  hlsl::CompileOptions o = Options("vs_5_0", "main");
  o.useCache = true;
  o.cacheDir = dir;
  std::vector<hlsl::Diagnostic> warnings;
  hlsl::CompileFile(DataDir() / "warning.hlsl", o, &warnings);
  EXPECT_EQ(warnings.size(), 1u);
  hlsl::CacheStats s2 = hlsl::GetCacheStats();
  warnings.clear();
  hlsl::CompileFile(DataDir() / "warning.hlsl", o, &warnings);
  EXPECT_EQ(warnings.size(), 1u);
  o.flags1 = hlsl::COMPILE_WARNINGS_ARE_ERRORS;
  EXPECT_THROW(hlsl::CompileFile(DataDir() / "warning.hlsl", o), hlsl::CompileError);
  EXPECT_EQ(hlsl::GetCacheStats().misses, s2.misses);
  EXPECT_EQ(hlsl::GetCacheStats().hits, s2.hits + 2);
}

}  // namespace
}  // namespace sp::test
