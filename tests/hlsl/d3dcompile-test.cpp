// D3DCompile's shape: sp::hlsl::Compile / CompileFromFile with HRESULTs, Blob out-pointers,
// SHADER_MACRO arrays and fxc-style error blobs, written the way D3D11 samples call them.
#include <cstring>

#include "../rhi/rhi-test-util.h"

// As D3D samples define it.
#define SAFE_RELEASE(p) \
  do {                  \
    if (p) {            \
      (p)->Release();   \
      (p) = nullptr;    \
    }                   \
  } while (0)

namespace sp::test {
namespace {

namespace fs = std::filesystem;
using hlsl::Blob;
using hlsl::SHADER_MACRO;

// tests/hlsl/data in the source tree (SHADOWPORT_SHADER_DIR is <source>/shaders-hlsl).
fs::path DataDir() { return fs::path(SHADOWPORT_SHADER_DIR).parent_path() / "tests" / "hlsl" / "data"; }

std::string BlobText(Blob* b) {
  if (!b) return {};
  return std::string(static_cast<const char*>(b->GetBufferPointer()));
}

const char* kGood = R"(
RWStructuredBuffer<uint4> result : register(u0);
#ifndef EMPTY
#error EMPTY must be defined
#endif
[numthreads(1, 1, 1)] void CSMain() { result[0] = uint4(VALUE, OTHER EMPTY, 3, 4); }
)";

TEST(D3DCompile, CompilesWithMacrosIntoTheSerializedBytecode) {
  const SHADER_MACRO defines[] = {{"VALUE", "7"}, {"OTHER", "11"}, {"EMPTY", ""}, {nullptr, nullptr}};
  Blob* code = nullptr;
  Blob* errors = nullptr;
  HRESULT hr = hlsl::Compile(kGood, std::strlen(kGood), "d3dcompile-good.hlsl", defines, nullptr, "CSMain", "cs_4_0",
                             hlsl::COMPILE_ENABLE_STRICTNESS | hlsl::COMPILE_DEBUG, 0, &code, &errors);
  ASSERT_EQ(hr, S_OK) << BlobText(errors);
  ASSERT_NE(code, nullptr);
  EXPECT_EQ(errors, nullptr);  // no warnings
  ShaderBytecode b = ShaderBytecode::Deserialize(code->GetBufferPointer(), code->GetBufferSize());
  EXPECT_EQ(b.stage, ShaderStage::Compute);
  EXPECT_EQ(b.reflection.entryPoint, "CSMain");

  // Exactly what the throwing interface produces from the same input.
  hlsl::CompileOptions o;
  o.target = "cs_5_0";
  o.entryPoint = "CSMain";
  o.defines = {{"VALUE", "7"}, {"OTHER", "11"}, {"EMPTY", " "}};
  o.useCache = false;
  std::vector<uint8_t> direct = hlsl::CompileSource(kGood, "d3dcompile-good.hlsl", o).Serialize();
  ASSERT_EQ(code->GetBufferSize(), direct.size());
  EXPECT_EQ(std::memcmp(code->GetBufferPointer(), direct.data(), direct.size()), 0);

  EXPECT_EQ(code->AddRef(), 2u);
  EXPECT_EQ(code->Release(), 1u);
  SAFE_RELEASE(code);
  EXPECT_EQ(code, nullptr);
  SAFE_RELEASE(errors);
}

TEST(D3DCompile, ErrorsComeBackAsANullTerminatedBlob) {
  const char* bad = "float4 main() : SV_Target {\n  return undefinedThing;\n}\n";
  Blob* code = reinterpret_cast<Blob*>(uintptr_t(0x1234));  // must be overwritten with null
  Blob* errors = nullptr;
  HRESULT hr = hlsl::Compile(bad, std::strlen(bad), "d3dcompile-bad.hlsl", nullptr, nullptr, "main", "ps_4_0", 0, 0, &code, &errors);
  EXPECT_EQ(hr, E_FAIL);
  EXPECT_TRUE(FAILED(hr));
  EXPECT_EQ(code, nullptr);
  ASSERT_NE(errors, nullptr);
  std::string text = BlobText(errors);
  EXPECT_EQ(errors->GetBufferSize(), text.size() + 1);
  EXPECT_EQ(static_cast<const char*>(errors->GetBufferPointer())[errors->GetBufferSize() - 1], '\0');
  EXPECT_EQ(text.rfind("d3dcompile-bad.hlsl:2: error: ", 0), 0u) << text;
  EXPECT_NE(text.find("undefinedThing"), std::string::npos) << text;
  SAFE_RELEASE(errors);

  // Errors may be ignored, as D3D allows.
  hr = hlsl::Compile(bad, std::strlen(bad), "d3dcompile-bad.hlsl", nullptr, nullptr, "main", "ps_5_0", 0, 0, &code, nullptr);
  EXPECT_EQ(hr, E_FAIL);
  EXPECT_EQ(code, nullptr);

  // An unknown target fails like a compile error, naming the valid ones.
  hr = hlsl::Compile(bad, std::strlen(bad), "d3dcompile-bad.hlsl", nullptr, nullptr, "main", "ps_3_0", 0, 0, &code, &errors);
  EXPECT_EQ(hr, E_FAIL);
  EXPECT_NE(BlobText(errors).find("unknown target 'ps_3_0' (valid: vs_4_0"), std::string::npos) << BlobText(errors);
  SAFE_RELEASE(errors);
}

TEST(D3DCompile, WarningsComeBackInTheErrorBlobAndFailUnderWX) {
  Blob* code = nullptr;
  Blob* errors = nullptr;
  fs::path file = DataDir() / "warning.hlsl";
  HRESULT hr = hlsl::CompileFromFile(file, nullptr, hlsl::COMPILE_STANDARD_FILE_INCLUDE, "main", "vs_4_0", 0, 0, &code, &errors);
  EXPECT_EQ(hr, S_OK);
  ASSERT_NE(code, nullptr);
  ASSERT_NE(errors, nullptr);
  EXPECT_NE(BlobText(errors).find("warning.hlsl:3: warning: "), std::string::npos) << BlobText(errors);
  SAFE_RELEASE(code);
  SAFE_RELEASE(errors);
  hr = hlsl::CompileFromFile(file, nullptr, hlsl::COMPILE_STANDARD_FILE_INCLUDE, "main", "vs_4_0", hlsl::COMPILE_WARNINGS_ARE_ERRORS, 0,
                             &code, &errors);
  EXPECT_EQ(hr, E_FAIL);
  EXPECT_EQ(code, nullptr);
  EXPECT_NE(BlobText(errors).find("warning.hlsl:3: error: "), std::string::npos) << BlobText(errors);
  SAFE_RELEASE(errors);
}

TEST(D3DCompile, FromFileResolvesIncludesNextToTheFile) {
  Blob* code = nullptr;
  Blob* errors = nullptr;
  // A wide-character path, as D3DCompileFromFile takes.
  std::wstring wide = (DataDir() / "includes-header.hlsl").wstring();
  for (hlsl::Include* include : {hlsl::COMPILE_STANDARD_FILE_INCLUDE, static_cast<hlsl::Include*>(nullptr)}) {
    HRESULT hr = hlsl::CompileFromFile(wide.c_str(), nullptr, include, "main", "ps_4_1", 0, 0, &code, &errors);
    ASSERT_EQ(hr, S_OK) << BlobText(errors);
    ShaderBytecode b = ShaderBytecode::Deserialize(code->GetBufferPointer(), code->GetBufferSize());
    EXPECT_NE(b.glsl.find("0.75"), std::string::npos) << b.glsl;
    SAFE_RELEASE(code);
  }
  HRESULT hr = hlsl::CompileFromFile(DataDir() / "no-such-file.hlsl", nullptr, nullptr, "main", "ps_5_0", 0, 0, &code, &errors);
  EXPECT_TRUE(FAILED(hr));
  EXPECT_EQ(code, nullptr);
  EXPECT_NE(BlobText(errors).find("no-such-file.hlsl: error: cannot open the file"), std::string::npos) << BlobText(errors);
  SAFE_RELEASE(errors);
}

// The DirectX SDK samples' call: D3DX11CompileFromFile(file, NULL, NULL, entry, profile, flags,
// 0, NULL, &blob, &errors, NULL).
TEST(D3DCompile, X11CompileFromFileIsCompileFromFileWithoutAPump) {
  Blob* code = nullptr;
  Blob* errors = nullptr;
  HRESULT async = E_NOTIMPL;
  fs::path file = DataDir() / "includes-header.hlsl";
  HRESULT hr = hlsl::X11CompileFromFile(file, nullptr, nullptr, "main", "ps_4_0", hlsl::COMPILE_ENABLE_STRICTNESS, 0, nullptr,
                                        &code, &errors, &async);
  ASSERT_EQ(hr, S_OK) << BlobText(errors);
  EXPECT_EQ(async, S_OK);
  ASSERT_NE(code, nullptr);
  ShaderBytecode b = ShaderBytecode::Deserialize(code->GetBufferPointer(), code->GetBufferSize());
  EXPECT_EQ(b.stage, ShaderStage::Pixel);
  SAFE_RELEASE(code);
  SAFE_RELEASE(errors);
  // A thread pump would mean an asynchronous compile: refused, with the reason.
  auto* pump = reinterpret_cast<hlsl::X11ThreadPump*>(uintptr_t(16));
  hr = hlsl::X11CompileFromFile(file, nullptr, nullptr, "main", "ps_4_0", 0, 0, pump, &code, &errors, &async);
  EXPECT_EQ(hr, E_INVALIDARG);
  EXPECT_EQ(async, E_INVALIDARG);
  EXPECT_EQ(code, nullptr);
  EXPECT_NE(BlobText(errors).find("pPump must be null"), std::string::npos) << BlobText(errors);
  SAFE_RELEASE(errors);
  // A compile error is E_FAIL through both the return value and pHResult.
  hr = hlsl::X11CompileFromFile(DataDir() / "no-such-file.hlsl", nullptr, nullptr, "main", "ps_4_0", 0, 0, nullptr, &code, &errors, &async);
  EXPECT_TRUE(FAILED(hr));
  EXPECT_EQ(async, hr);
  SAFE_RELEASE(errors);
}

TEST(D3DCompile, BadArgumentsAreInvalidArg) {
  Blob* code = nullptr;
  Blob* errors = nullptr;
  size_t n = std::strlen(kGood);
  const SHADER_MACRO defines[] = {{"VALUE", "1"}, {"OTHER", "2"}, {"EMPTY", nullptr}, {nullptr, nullptr}};
  auto call = [&](const void* src, const char* target, uint32_t flags, hlsl::Include* include, Blob** out) {
    SAFE_RELEASE(errors);
    return hlsl::Compile(src, n, "args.hlsl", defines, include, "CSMain", target, flags, 0, out, &errors);
  };
  EXPECT_EQ(call(kGood, "cs_5_0", 0, nullptr, &code), S_OK) << BlobText(errors);
  SAFE_RELEASE(code);
  EXPECT_EQ(call(nullptr, "cs_5_0", 0, nullptr, &code), E_INVALIDARG);
  EXPECT_EQ(call(kGood, nullptr, 0, nullptr, &code), E_INVALIDARG);
  EXPECT_EQ(call(kGood, "cs_5_0", 0, nullptr, nullptr), E_INVALIDARG);
  EXPECT_EQ(call(kGood, "cs_5_0", 1u << 17, nullptr, &code), E_INVALIDARG);
  EXPECT_NE(BlobText(errors).find("unknown compile flags 0x20000"), std::string::npos) << BlobText(errors);
  EXPECT_EQ(call(kGood, "cs_5_0", hlsl::COMPILE_PACK_MATRIX_ROW_MAJOR | hlsl::COMPILE_PACK_MATRIX_COLUMN_MAJOR, nullptr, &code),
            E_INVALIDARG);
  // A handler of one's own (an ID3DInclude subclass) is not supported and says so.
  alignas(8) static char fakeHandler[16];
  EXPECT_EQ(call(kGood, "cs_5_0", 0, reinterpret_cast<hlsl::Include*>(fakeHandler), &code), E_INVALIDARG);
  EXPECT_NE(BlobText(errors).find("include handlers (ID3DInclude) are not supported"), std::string::npos) << BlobText(errors);
  EXPECT_EQ(code, nullptr);
  SAFE_RELEASE(errors);

  Blob* empty = nullptr;
  EXPECT_EQ(hlsl::CreateBlob(8, &empty), S_OK);
  ASSERT_NE(empty, nullptr);
  EXPECT_EQ(empty->GetBufferSize(), 8u);
  for (size_t i = 0; i < 8; ++i) EXPECT_EQ(static_cast<const uint8_t*>(empty->GetBufferPointer())[i], 0);
  SAFE_RELEASE(empty);
  EXPECT_EQ(hlsl::CreateBlob(8, nullptr), E_INVALIDARG);
}

// The code blob goes to Create*Shader(ptr, size) unchanged, as a D3D11 port passes it.
class D3DCompileTest : public BackendTest {};

TEST_P(D3DCompileTest, CodeBlobCreatesAWorkingShader) {
  const SHADER_MACRO defines[] = {{"VALUE", "7"}, {"OTHER", "11"}, {"EMPTY", nullptr}, {nullptr, nullptr}};
  Blob* code = nullptr;
  Blob* errors = nullptr;
  HRESULT hr = hlsl::Compile(kGood, std::strlen(kGood), "d3dcompile-good.hlsl", defines, nullptr, "CSMain", "cs_5_0", 0, 0, &code, &errors);
  ASSERT_TRUE(SUCCEEDED(hr)) << BlobText(errors);
  Ref<ComputeShader> cs = device().CreateComputeShader(code->GetBufferPointer(), code->GetBufferSize());
  SAFE_RELEASE(code);
  UavBuffer out = MakeUavBuffer(device(), 1, 16);
  ctx().CSSetShader(cs.get());
  ctx().CSSetUnorderedAccessViews(0, {out.uav.get()});
  ctx().Dispatch(1, 1, 1);
  ctx().CSSetUnorderedAccessViews(0, {nullptr});
  EXPECT_EQ(ReadBufferAs<uint32_t>(device(), ctx(), out.buffer.get()), (std::vector<uint32_t>{7, 11, 3, 4}));
}

SP_INSTANTIATE_BACKEND_TESTS(D3DCompileTest);

}  // namespace
}  // namespace sp::test
