// The D3D11 compatibility pass (rhi/src/hlsl/compat/): each construct fxc accepts and glslang
// does not, rewritten and then run on both backends against values computed here from D3D11's
// rules; plus what each rewrite refuses, and that messages still name the user's lines.
#include <sp/rhi/helpers.h>

#include <fstream>

#include "../rhi/rhi-test-util.h"

namespace sp::test {
namespace {

hlsl::CompileOptions Options(const std::string& target = "cs_5_0") {
  hlsl::CompileOptions o;
  o.target = target;
  o.useCache = false;
  return o;
}

std::string Rewritten(const std::string& src, std::vector<std::string>* applied = nullptr) {
  return hlsl::Preprocess(src, "compat.hlsl", Options(), applied);
}

// The first diagnostic of a compile that must fail.
hlsl::Diagnostic FirstError(const std::string& src) {
  try {
    hlsl::CompileSource(src, "compat.hlsl", Options());
  } catch (const hlsl::CompileError& e) {
    if (!e.diagnostics().empty()) return e.diagnostics()[0];
    return {"", 0, e.what()};
  }
  ADD_FAILURE() << "expected a compile error";
  return {};
}

bool Contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// ---- each rewrite on its own (no device) --------------------------------------------------------

TEST(D3D11Compat, SourcesWithoutTheConstructsAreLeftAsTheyAre) {
  std::vector<std::string> applied;
  std::string src = "struct V { float4 p; float2 t; };\nstatic const V v[1] = { { float4(1, 2, 3, 4), float2(5, 6) } };\n"
                    "float4 f(float4x4 m) { float4 a = m._11; for (int i = 0; i < 2; ++i) a += i; return a; }\n";
  Rewritten(src, &applied);
  EXPECT_TRUE(applied.empty()) << applied[0];
}

TEST(D3D11Compat, MatrixSwizzlesBecomeHelperCalls) {
  std::vector<std::string> applied;
  std::string out = Rewritten("float3 f(float4x4 m) { m._m30_m31_m32 = 1; return m._11_21_31 + mul(m, m)._41_42_43; }", &applied);
  EXPECT_EQ(applied, std::vector<std::string>{"matrix-swizzle"});
  EXPECT_TRUE(Contains(out, "spcompat_mset_30_31_32(m, 1)")) << out;
  EXPECT_TRUE(Contains(out, "spcompat_mget_00_10_20(m)")) << out;
  EXPECT_TRUE(Contains(out, "spcompat_mget_30_31_32(mul(m, m))")) << out;
}

TEST(D3D11Compat, MatrixSwizzleRefusals) {
  hlsl::Diagnostic d = FirstError("float2 f(float4x4 m) {\n  m._11_22++;\n  return 0;\n}\n");
  EXPECT_EQ(d.file, "compat.hlsl");
  EXPECT_EQ(d.line, 2);
  EXPECT_TRUE(Contains(d.message, "++/-- on a matrix swizzle")) << d.message;
  d = FirstError("float4x4 g(); void f(float4x4 m) {\n\n  m._11_11 = float2(1, 2);\n}\n");
  EXPECT_EQ(d.line, 3);
  EXPECT_TRUE(Contains(d.message, "names an element twice")) << d.message;
}

TEST(D3D11Compat, ForLoopVariablesUsedAfterTheLoopMoveInFrontOfIt) {
  std::string out = Rewritten(
      "float f() {\n  float a = 0;\n  [unroll] for (int i = 0; i < 3; ++i) a += i;\n  for (int k = 0; k < 2; ++k) a += k;\n"
      "  a += i;\n  for (int i = 5; i < 6; ++i) a += i;\n  return a + i;\n}\n");
  EXPECT_TRUE(Contains(out, "int i = 0; [unroll]for(;i < 3;")) << out;
  EXPECT_TRUE(Contains(out, "for(int k = 0;")) << out;    // k is not used after its loop
  EXPECT_TRUE(Contains(out, "i = 5; for(;i < 6;")) << out;  // the second declaration assigns
  EXPECT_FALSE(Contains(out, "int i = 5")) << out;
  // A later loop declaring the same name takes over: the first one's variable is not used after it.
  out = Rewritten("float f() {\n  float a = 0;\n  for (int i = 0; i < 3; ++i) a += i;\n  for (int i = 5; i < 6; ++i) a += i;\n  return i;\n}\n");
  EXPECT_TRUE(Contains(out, "for(int i = 0;i < 3;")) << out;
  EXPECT_TRUE(Contains(out, "int i = 5; for(;i < 6;")) << out;
  hlsl::Diagnostic d = FirstError("float f(bool b) {\n  if (b)\n    for (int i = 0; i < 3; ++i) {}\n  return i;\n}\n");
  EXPECT_EQ(d.line, 3);
  EXPECT_TRUE(Contains(d.message, "put the loop in braces")) << d.message;
  d = FirstError("float f() {\n  for (int i = 0; i < 3; ++i) {}\n  float a = i;\n  for (uint i = 0; i < 3; ++i) {}\n  return a + i;\n}\n");
  EXPECT_EQ(d.line, 4);
  EXPECT_TRUE(Contains(d.message, "declared again in this for loop as 'uint'")) << d.message;
}

TEST(D3D11Compat, CbufferStaticsMoveOutAndArrayCastsListTheComponents) {
  std::vector<std::string> applied;
  std::string out = Rewritten("cbuffer C : register(b1) {\n  float4 packed[2];\n  static float s[8] = (float[8])packed;\n  float tail;\n};\n",
                              &applied);
  EXPECT_EQ(applied, (std::vector<std::string>{"cbuffer-static", "array-cast"}));
  EXPECT_TRUE(Contains(out, "static float s[8]={ packed[0].x, packed[0].y, packed[0].z, packed[0].w, packed[1].x, packed[1].y, "
                            "packed[1].z, packed[1].w };"))
      << out;
  EXPECT_TRUE(out.find("tail") < out.find("static float s")) << out;
  hlsl::Diagnostic d = FirstError("cbuffer C { float4 p[1]; };\nstatic float s[8] = (float[8])p;\n");
  EXPECT_EQ(d.line, 2);
  EXPECT_TRUE(Contains(d.message, "needs 8 components and 'p' has 4")) << d.message;
  d = FirstError("cbuffer C { float4 p[2]; };\nfloat f(int i) { return ((float[8])p)[i]; }\n");
  EXPECT_TRUE(Contains(d.message, "supported only as a declaration's initializer")) << d.message;
}

TEST(D3D11Compat, InitializerListsAreBracedLevelByLevel) {
  std::string out = Rewritten(
      "struct Vertex { float4 pos; float2 uv; };\n"
      "static const Vertex quad[2] = { { -1, -1, 1, 1 }, { 0, 1 },\n   { 1, 1, 1, 1 }, { 1, 0 } };\n"
      "static const Vertex flat[1] = { 1, 2, 3, 4, 5, 6 };\n");
  EXPECT_TRUE(Contains(out, "quad[2]= { { float4(- 1, - 1, 1, 1), float2(0, 1) }, { float4(1, 1, 1, 1), float2(1, 0) } }")) << out;
  EXPECT_TRUE(Contains(out, "flat[1]= { { float4(1, 2, 3, 4), float2(5, 6) } }")) << out;
  hlsl::Diagnostic d = FirstError("struct V { float4 p; float2 t; };\n\nstatic const V v[2] = { 1, 2, 3, 4, 5, 6, 7 };\n");
  EXPECT_EQ(d.line, 3);
  EXPECT_TRUE(Contains(d.message, "has 7 values; V[2] takes 12")) << d.message;
}

// A rewritten initializer spans two lines; glslang's message about a later line still names it.
TEST(D3D11Compat, MessagesAfterRewritesNameTheUsersLines) {
  hlsl::Diagnostic d = FirstError(
      "struct V { float4 p; float2 t; };\nstatic const V v[1] = { { 1, 2, 3, 4 },\n  { 5, 6 } };\n"
      "float4 f(float4x4 m) { return float4(m._11_22_33, 1); }\n\n[numthreads(1, 1, 1)] void main() { undefinedThing = 1; }\n");
  EXPECT_EQ(d.file, "compat.hlsl");
  EXPECT_EQ(d.line, 6);
  EXPECT_TRUE(Contains(d.message, "undefinedThing")) << d.message;
}

TEST(D3D11Compat, ObjectArrayRefusals) {
  hlsl::Diagnostic d = FirstError("Texture2D maps[2];\nfloat4 f() { return 0; }\n");
  EXPECT_EQ(d.line, 1);
  EXPECT_TRUE(Contains(d.message, "needs an explicit register")) << d.message;
  d = FirstError("Texture2D maps[2] : register(t0);\nfloat4 g(Texture2D t);\nfloat4 f() {\n  return g(maps);\n}\n");
  EXPECT_EQ(d.line, 4);
  EXPECT_TRUE(Contains(d.message, "can only be used element by element")) << d.message;
  d = FirstError("Texture2D maps[2] : register(t0);\nfloat4 g(Texture2D t[2]) { return 0; }\n");
  EXPECT_EQ(d.line, 2);
  EXPECT_TRUE(Contains(d.message, "an array of objects as a parameter ('t')")) << d.message;
  d = FirstError("Texture2D maps[2] : register(t0);\nfloat4 f(int i) {\n  uint w, h;\n  maps[i].GetDimensions(w, h);\n  return w;\n}\n");
  EXPECT_EQ(d.line, 4);
  EXPECT_TRUE(Contains(d.message, "can only call a method that returns a value")) << d.message;
}

// Windows-era includes: backslashes, and a case that differs from the file's name.
TEST(D3D11Compat, IncludesWithBackslashesAndAnotherCaseFindTheFile) {
  std::filesystem::path dir = TestOutputDir() / "windows-includes";
  std::filesystem::create_directories(dir / "Shared");
  {
    std::ofstream(dir / "Shared" / "Common.hlsli") << "float Twice(float x) { return 2 * x; }\n";
  }
  std::string src = "#include \"shared\\COMMON.hlsli\"\nRWStructuredBuffer<float> o : register(u0);\n"
                    "[numthreads(1, 1, 1)] void main() { o[0] = Twice(1); }\n";
  EXPECT_NO_THROW(hlsl::CompileSource(src, (dir / "main.hlsl").string(), Options()));
  hlsl::Diagnostic d = FirstError("#include \"shared\\Missing.hlsli\"\n");
  EXPECT_EQ(d.line, 1);
  EXPECT_TRUE(Contains(d.message, "shared\\Missing.hlsli")) << d.message;
}

// `#pragma once` includes a file once, as fxc does (glslang's preprocessor ignores it).
TEST(D3D11Compat, PragmaOnceIncludesAFileOnce) {
  std::filesystem::path dir = TestOutputDir() / "pragma-once";
  std::filesystem::create_directories(dir);
  {
    std::ofstream(dir / "once.hlsli") << "#pragma once\nfloat Twice(float x) { return 2 * x; }\n";
  }
  std::string src = "#include \"once.hlsli\"\n#include \"once.hlsli\"\nRWStructuredBuffer<float> o : register(u0);\n"
                    "[numthreads(1, 1, 1)] void main() { o[0] = Twice(1); }\n";
  hlsl::CompileOptions strict = Options();
  strict.flags1 = hlsl::COMPILE_WARNINGS_ARE_ERRORS;  // and glslang's warning about the pragma is not passed on
  EXPECT_NO_THROW(hlsl::CompileSource(src, (dir / "main.hlsl").string(), strict));
}

// glslang's recursive parser would overflow its stack; the pass stops first, with the line.
TEST(D3D11Compat, DeepNestingIsAnErrorNotACrash) {
  hlsl::Diagnostic d = FirstError("[numthreads(1, 1, 1)] void main() {\n  float x = " + std::string(10000, '(') + "1" +
                                  std::string(10000, ')') + ";\n}\n");
  EXPECT_EQ(d.line, 2);
  EXPECT_TRUE(Contains(d.message, "nested more than 512 levels")) << d.message;
}

TEST(D3D11Compat, TenThousandNestedBracesAreAnErrorNotACrash) {
  hlsl::Diagnostic d = FirstError("[numthreads(1, 1, 1)] void main() {\n" + std::string(10000, '{') + "\n" +
                                  std::string(10000, '}') + "\n}\n");
  EXPECT_GE(d.line, 2);
  EXPECT_TRUE(Contains(d.message, "nested more than 512 levels")) << d.message;
}

// Unbalanced brackets are refused before any rewrite reads the tokens, at the line of the bracket
// without a partner (an unmatched ']' in front of a for loop once sent the for-loop rewrite past
// the end of the tokens: found by fuzz/hlsl-preprocess-fuzz.cpp, its input is a seed there now).
TEST(D3D11Compat, UnbalancedBracketsAreRefusedWithTheirLine) {
  hlsl::Diagnostic d = FirstError("float4 main(float4 p : POSITION) : SV_Position\n{\n  ] for (int i = 0; i < 2; ++i) p += 1;\n  return p;\n}\n");
  EXPECT_EQ(d.line, 3);
  EXPECT_TRUE(Contains(d.message, "']' without a matching '['")) << d.message;
  d = FirstError("float4 main() : SV_Target {\n  return float4(1, 2, 3, 4;\n}\n");
  EXPECT_EQ(d.line, 2);
  EXPECT_TRUE(Contains(d.message, "'(' closed by '}'")) << d.message;
  d = FirstError("float4 main() : SV_Target {\n  return 1;\n");
  EXPECT_EQ(d.line, 1);
  EXPECT_TRUE(Contains(d.message, "'{' is never closed")) << d.message;
}

// ---- each construct executed on both backends ----------------------------------------------------

class D3D11CompatRun : public BackendTest {
 protected:
  // A triangle covering a 4x4 target (clockwise: D3D's front face), `ps` and `rt` bound; the
  // caller binds the pixel shader's resources and calls Draw(3, 0).
  void BindFullscreenPass(const Target& rt, PixelShader* ps) {
    if (!fullscreenVs_)
      fullscreenVs_ = device().CreateVertexShader(CompileHlsl(
          "float4 main(uint id : SV_VertexID) : SV_Position { return float4(id == 2 ? 3.0 : -1.0, id == 1 ? 3.0 : -1.0, 0, 1); }", "vs_5_0",
          "main"));
    RenderTargetView* rtvs[] = {rt.rtv.get()};
    ctx().OMSetRenderTargets(1, rtvs, nullptr);
    SetViewport(ctx(), 4, 4);
    ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    ctx().VSSetShader(fullscreenVs_.get());
    ctx().PSSetShader(ps);
  }

  // Runs `main` of a cs_5_0 source with cbuffer b0 = `constants` and u0 = `outputs` float4s.
  std::vector<float> Run(const std::string& src, const std::vector<float>& constants, uint32_t outputs) {
    Ref<ComputeShader> cs = device().CreateComputeShader(CompileHlsl(src, "cs_5_0", "main"));
    std::vector<float> cb = constants;
    cb.resize((cb.size() + 3) / 4 * 4 + (cb.empty() ? 4 : 0));
    Ref<Buffer> cbuf = MakeBuffer(device(), BIND_CONSTANT_BUFFER, cb.data(), uint32_t(cb.size() * 4));
    UavBuffer out = MakeUavBuffer(device(), outputs, 16);
    ctx().CSSetShader(cs.get());
    ctx().CSSetConstantBuffers(0, {cbuf.get()});
    ctx().CSSetUnorderedAccessViews(0, {out.uav.get()});
    ctx().Dispatch(1, 1, 1);
    ctx().CSSetUnorderedAccessViews(0, {nullptr});
    return ReadBufferAs<float>(device(), ctx(), out.buffer.get());
  }

 private:
  Ref<VertexShader> fullscreenVs_;
};

void ExpectRows(const std::vector<float>& got, const std::vector<std::vector<float>>& expect) {
  ASSERT_GE(got.size(), expect.size() * 4);
  for (size_t i = 0; i < expect.size(); ++i)
    for (size_t k = 0; k < 4; ++k) EXPECT_EQ(got[i * 4 + k], expect[i][k]) << "output[" << i << "]." << "xyzw"[k];
}

// D3D11 reads a row_major matrix row by row from its registers, a column_major one column by
// column; element (r, c) (one-based _rc, zero-based _mrc) is row r, column c either way.
TEST_P(D3D11CompatRun, MatrixSwizzlesReadAndWriteTheRightElements) {
  const char* src = R"(
cbuffer C : register(b0) { row_major float4x4 r; column_major float4x4 c; };
RWStructuredBuffer<float4> o : register(u0);
[numthreads(1, 1, 1)] void main() {
  o[0] = float4(r._11_21_31, r._14);
  o[1] = float4(c._m01_m12_m23, c._m30);
  o[2] = float4(r._41_42_43, 0);
  o[3] = c._44_33_22_11;
  float4x4 l = r;
  l._m30_m31_m32 = float3(100, 200, 300);
  l._11_22 += float2(5, 6);
  o[4] = l[3];
  o[5] = float4(l._11_22, l[0][0], l[1][1]);
  float3x3 small = (float3x3)c;
  o[6] = float4(small._m21_m12, 0, 0);
})";
  std::vector<float> cb(32);
  for (size_t i = 0; i < cb.size(); ++i) cb[i] = float(i + 1);
  auto R = [&](int row, int col) { return cb[size_t(row * 4 + col)]; };       // row_major at 0
  auto C = [&](int row, int col) { return cb[size_t(16 + col * 4 + row)]; };  // column_major at 64
  std::vector<float> got = Run(src, cb, 7);
  ExpectRows(got, {
                      {R(0, 0), R(1, 0), R(2, 0), R(0, 3)},
                      {C(0, 1), C(1, 2), C(2, 3), C(3, 0)},
                      {R(3, 0), R(3, 1), R(3, 2), 0},
                      {C(3, 3), C(2, 2), C(1, 1), C(0, 0)},
                      {100, 200, 300, R(3, 3)},
                      {R(0, 0) + 5, R(1, 1) + 6, R(0, 0) + 5, R(1, 1) + 6},
                      {C(2, 1), C(1, 2), 0, 0},
                  });
}

TEST_P(D3D11CompatRun, CbufferArrayCastReadsPackedFloatsInD3DOrder) {
  const char* src = R"(
cbuffer C : register(b0) {
  float4 packedFloats[2];
  int index;
  static float s[8] = (float[8])packedFloats;
  static float2 pairs[4] = (float2[4])packedFloats;
};
RWStructuredBuffer<float4> o : register(u0);
[numthreads(1, 1, 1)] void main() {
  o[0] = float4(s[0], s[3], s[4], s[7]);
  o[1] = float4(s[index], s[index + 1], pairs[index].y, pairs[3].x);
})";
  std::vector<float> cb = {10, 11, 12, 13, 14, 15, 16, 17, 0, 0, 0, 0};
  int index = 2;
  std::memcpy(&cb[8], &index, 4);
  ExpectRows(Run(src, cb, 2), {{10, 13, 14, 17}, {12, 13, 15, 16}});
}

TEST_P(D3D11CompatRun, InitializerListsFillMembersInOrder) {
  const char* src = R"(
struct Vertex { float4 pos; float2 uv; };
static const Vertex quad[6] = {
  { -1, -1, 0, 1 }, { 0, 1 },  { -1, 1, 0, 1 }, { 0, 0 },  { 1, 1, 0, 1 }, { 1, 0 },
  { -1, -1, 0, 1 }, { 0, 1 },  { 1, 1, 0, 1 }, { 1, 0 },   { 1, -1, 0, 1 }, { 1, 1 } };
static const Vertex flat[2] = { 1, 2, 3, 4, 5, 6,   7, 8, 9, 10, 11, 12 };
struct Light { float3 dir; float intensity; float4 color; };
cbuffer C : register(b0) { int pick; };
RWStructuredBuffer<float4> o : register(u0);
[numthreads(1, 1, 1)] void main() {
  Light l = { 0, -1, 0, 2.5, { 1, 0.5, 0.25, 1 } };
  float2 table[3] = { 1, 2, 3, 4, 5, 6 };
  o[0] = quad[pick].pos;
  o[1] = float4(quad[pick].uv, quad[5].uv);
  o[2] = flat[1].pos;
  o[3] = float4(flat[1].uv, flat[0].uv);
  o[4] = float4(l.dir, l.intensity);
  o[5] = l.color;
  o[6] = float4(table[pick], table[2]);
})";
  std::vector<float> cb(4, 0.0f);
  int pick = 1;
  std::memcpy(&cb[0], &pick, 4);
  ExpectRows(Run(src, cb, 7), {{-1, 1, 0, 1}, {0, 0, 1, 1}, {7, 8, 9, 10}, {11, 12, 5, 6}, {0, -1, 0, 2.5f}, {1, 0.5f, 0.25f, 1}, {3, 4, 5, 6}});
}

TEST_P(D3D11CompatRun, ForLoopVariableKeepsItsValueAfterTheLoop) {
  const char* src = R"(
cbuffer C : register(b0) { int stopAt; };
RWStructuredBuffer<float4> o : register(u0);
[numthreads(1, 1, 1)] void main() {
  float sum = 0;
  for (int i = 0; i < 10; ++i) {
    if (i == stopAt) break;
    sum += i;
  }
  o[0] = float4(i, sum, 0, 0);
  for (int i = 20; i < 23; i++) sum += 1;
  o[1] = float4(i, sum, 0, 0);
})";
  std::vector<float> cb(4, 0.0f);
  int stop = 4;
  std::memcpy(&cb[0], &stop, 4);
  ExpectRows(Run(src, cb, 2), {{4, 0 + 1 + 2 + 3, 0, 0}, {23, 6 + 3, 0, 0}});
}

// abs(m), saturate(m), max(m, n), lerp(a, b, s) on matrices: D3D applies them per component.
TEST_P(D3D11CompatRun, ComponentWiseIntrinsicsTakeMatrices) {
  const char* src = R"(
cbuffer C : register(b0) { row_major float2x4 a; row_major float2x4 b; };
RWStructuredBuffer<float4> o : register(u0);
[numthreads(1, 1, 1)] void main() {
  float2x4 s = saturate(a);
  float2x4 m = max(abs(a), b);
  float2x4 l = lerp(a, b, 0.25);
  o[0] = s[0]; o[1] = s[1];
  o[2] = m[0]; o[3] = m[1];
  o[4] = l[0]; o[5] = l[1];
})";
  std::vector<float> cb = {-2, -0.5f, 0.25f, 3, 1, 0, -4, 0.5f, /* b */ 1, 1, 1, 1, -1, 2, 2, 0};
  std::vector<std::vector<float>> expect(6, std::vector<float>(4));
  for (int i = 0; i < 8; ++i) {
    float x = cb[size_t(i)], y = cb[size_t(8 + i)];
    expect[size_t(i / 4)][size_t(i % 4)] = std::min(std::max(x, 0.0f), 1.0f);
    expect[size_t(2 + i / 4)][size_t(i % 4)] = std::max(std::abs(x), y);
    expect[size_t(4 + i / 4)][size_t(i % 4)] = x + 0.25f * (y - x);
  }
  ExpectRows(Run(src, cb, 6), expect);
}

// `uint coverage : SV_Coverage` as an entry parameter (glslang alone leaves it unconnected): a
// pixel fully covered by the triangle in a single-sampled target has coverage 1.
TEST_P(D3D11CompatRun, CoverageParameterReadsTheSampleMask) {
  const char* ps = "uint main(float4 pos : SV_Position, uint coverage : SV_Coverage) : SV_Target { return coverage + 10; }";
  Ref<PixelShader> p = device().CreatePixelShader(CompileHlsl(ps, "ps_5_0", "main"));
  Target rt = MakeTarget(device(), 4, 4, FORMAT_R32_UINT);
  BindFullscreenPass(rt, p.get());
  ctx().Draw(3, 0);
  for (uint32_t value : ReadTextureAs<uint32_t>(device(), ctx(), rt.texture.get())) EXPECT_EQ(value, 11u);
}

// Texture2D maps[3] : register(t1): one texture per register t1..t3, as PSSetShaderResources(1,
// 3, ...) binds them; elements read with constant and run-time indices, samplers from an array.
TEST_P(D3D11CompatRun, ArraysOfTexturesAndSamplersTakeOneRegisterPerElement) {
  const char* ps = R"(
Texture2D<float4> maps[3] : register(t1);
SamplerState samplers[2] : register(s0);
cbuffer C : register(b0) { int pick; };
float4 main(float4 pos : SV_Position) : SV_Target {
  float2 uv = pos.xy / 4;
  uint w, h;
  maps[2].GetDimensions(w, h);
  return float4(maps[0].Sample(samplers[1], uv).r, maps[pick].SampleLevel(samplers[0], uv, 0).r, maps[2].Load(int3(0, 0, 0)).r, w);
})";
  ShaderBytecode psCode = CompileHlsl(ps, "ps_5_0", "main");
  Ref<PixelShader> p = device().CreatePixelShader(psCode);
  std::vector<Ref<Texture2D>> textures;
  std::vector<Ref<ShaderResourceView>> views;
  for (int k = 0; k < 3; ++k) {
    std::vector<float> texels(size_t(2 + k) * (2 + k) * 4, float(10 * (k + 1)));  // maps[k] is (2+k)^2 texels of 10(k+1)
    textures.push_back(MakeTexture2D(device(), 2 + k, 2 + k, FORMAT_R32G32B32A32_FLOAT, BIND_SHADER_RESOURCE, texels.data()));
    views.push_back(device().CreateShaderResourceView(textures.back().get()));
  }
  CSAMPLER_DESC pointDesc(DEFAULT);
  pointDesc.Filter = FILTER_MIN_MAG_MIP_POINT;
  Ref<SamplerState> s0 = device().CreateSamplerState(pointDesc), s1 = device().CreateSamplerState(pointDesc);
  int pick = 1;
  std::vector<float> cb(4, 0.0f);
  std::memcpy(&cb[0], &pick, 4);
  Ref<Buffer> cbuf = MakeBuffer(device(), BIND_CONSTANT_BUFFER, cb.data(), 16);

  Target rt = MakeTarget(device(), 4, 4, FORMAT_R32G32B32A32_FLOAT);
  BindFullscreenPass(rt, p.get());
  ctx().PSSetShaderResources(1, {views[0].get(), views[1].get(), views[2].get()});
  ctx().PSSetSamplers(0, {s0.get(), s1.get()});
  ctx().PSSetConstantBuffers(0, {cbuf.get()});
  ctx().Draw(3, 0);
  std::vector<float> got = ReadTextureAs<float>(device(), ctx(), rt.texture.get());
  for (size_t px = 0; px < 16; ++px) {
    SCOPED_TRACE(px);
    EXPECT_EQ(got[px * 4 + 0], 10.0f);
    EXPECT_EQ(got[px * 4 + 1], 20.0f);  // maps[pick], pick = 1
    EXPECT_EQ(got[px * 4 + 2], 30.0f);
    EXPECT_EQ(got[px * 4 + 3], 4.0f);  // maps[2] is 4 texels wide
  }
}

// A Texture2DArray at t1 read in one pixel shader through a plain and a comparison sampler (a
// moment-map permutation and a PCF permutation in one): two SPIR-V variables at one register.
TEST_P(D3D11CompatRun, TextureArrayReadThroughAPlainAndAComparisonSampler) {
  const char* ps = R"(
Texture2D unusedAtT0 : register(t0);
Texture2DArray ShadowMap : register(t1);
SamplerState PointSampler : register(s0);
SamplerComparisonState CmpSampler : register(s1);
float4 main(float4 pos : SV_Position) : SV_Target {
  float2 uv = pos.xy / 4;
  return float4(ShadowMap.SampleLevel(PointSampler, float3(uv, 0), 0).r, ShadowMap.SampleLevel(PointSampler, float3(uv, 1), 0).r,
                ShadowMap.SampleCmpLevelZero(CmpSampler, float3(uv, 0), 0.5), ShadowMap.SampleCmpLevelZero(CmpSampler, float3(uv, 1), 0.5));
})";
  ShaderBytecode psCode = CompileHlsl(ps, "ps_5_0", "main");
  ASSERT_EQ(psCode.reflection.resources.size(), 3u);  // t1, s0, s1: t1 once
  Ref<PixelShader> p = device().CreatePixelShader(psCode);

  TEXTURE2D_DESC td = {4, 4, 1, 2, FORMAT_R32_TYPELESS, {1, 0}, USAGE_DEFAULT, BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE, 0, 0};
  Ref<Texture2D> map = device().CreateTexture2D(td);
  const float depths[2] = {0.25f, 0.75f};
  for (uint32_t slice = 0; slice < 2; ++slice) {
    CDEPTH_STENCIL_VIEW_DESC dd(map.get(), DSV_DIMENSION_TEXTURE2DARRAY, FORMAT_D32_FLOAT, 0, slice, 1);
    Ref<DepthStencilView> dsv = device().CreateDepthStencilView(map.get(), &dd);
    ctx().ClearDepthStencilView(dsv.get(), CLEAR_DEPTH, depths[slice], 0);
  }
  CSHADER_RESOURCE_VIEW_DESC sd(map.get(), SRV_DIMENSION_TEXTURE2DARRAY, FORMAT_R32_FLOAT);
  Ref<ShaderResourceView> srv = device().CreateShaderResourceView(map.get(), &sd);
  CSAMPLER_DESC pointDesc(DEFAULT);
  pointDesc.Filter = FILTER_MIN_MAG_MIP_POINT;
  CSAMPLER_DESC cmpDesc(DEFAULT);
  cmpDesc.Filter = FILTER_COMPARISON_MIN_MAG_MIP_POINT;
  cmpDesc.ComparisonFunc = COMPARISON_LESS_EQUAL;
  Ref<SamplerState> pointSampler = device().CreateSamplerState(pointDesc);
  Ref<SamplerState> cmpSampler = device().CreateSamplerState(cmpDesc);

  Target rt = MakeTarget(device(), 4, 4, FORMAT_R32G32B32A32_FLOAT);
  BindFullscreenPass(rt, p.get());
  ctx().PSSetShaderResources(1, {srv.get()});
  ctx().PSSetSamplers(0, {pointSampler.get(), cmpSampler.get()});
  ctx().Draw(3, 0);
  std::vector<float> got = ReadTextureAs<float>(device(), ctx(), rt.texture.get());
  // D3D11: SampleCmp returns 1 where reference <= texel (LESS_EQUAL): 0.5 <= 0.25 fails, 0.5 <= 0.75 passes.
  for (size_t px = 0; px < 16; ++px) {
    SCOPED_TRACE(px);
    EXPECT_EQ(got[px * 4 + 0], 0.25f);
    EXPECT_EQ(got[px * 4 + 1], 0.75f);
    EXPECT_EQ(got[px * 4 + 2], 0.0f);
    EXPECT_EQ(got[px * 4 + 3], 1.0f);
  }
}

SP_INSTANTIATE_BACKEND_TESTS(D3D11CompatRun);

}  // namespace
}  // namespace sp::test
