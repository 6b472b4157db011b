#include "backend-test.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

#include <algorithm>
#include <cstdlib>

namespace sp::test {

std::string BackendParamName(const ::testing::TestParamInfo<Backend>& info) { return BackendTestName(info.param); }

std::string BackendTestName(Backend b) {
  switch (b) {
    case Backend::Vulkan: return "Vulkan";
    case Backend::OpenGL: return "OpenGL";
    case Backend::Null: return "Null";
  }
  return "Unknown";
}

void BackendTest::SetUp() {
  DeviceDesc desc;
  desc.backend = GetParam();
  desc.debug = true;
  desc.shaderCacheDir = TestShaderCacheDir();
  desc.messageCallback = [this](MessageSeverity s, std::string_view text) {
    if (s == MessageSeverity::Error) validationMessages.emplace_back(text);
  };
  ConfigureDevice(desc);
  device_ = CreateDevice(desc);
}

void BackendTest::TearDown() {
  if (device_) {
    device_->GetImmediateContext()->ClearState();
    device_->GetImmediateContext()->WaitIdle();
  }
  device_.reset();
  if (!expectValidationErrors) {
    for (const std::string& m : validationMessages) ADD_FAILURE() << "validation error: " << m;
  }
}

std::filesystem::path ShaderDir() {
  if (const char* e = std::getenv("SHADOWPORT_SHADER_DIR"); e && *e) return e;
  return SHADOWPORT_SHADER_DIR;
}

std::filesystem::path TestShaderCacheDir() { return std::filesystem::path(SHADOWPORT_TEST_OUTPUT_DIR) / "shader-cache"; }

std::filesystem::path TestOutputDir() {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string suite = info ? info->test_suite_name() : "unknown";
  std::string name = info ? info->name() : "unknown";
  std::replace(suite.begin(), suite.end(), '/', '_');
  std::replace(name.begin(), name.end(), '/', '_');
  std::filesystem::path p = std::filesystem::path(SHADOWPORT_TEST_OUTPUT_DIR) / suite / name;
  std::filesystem::create_directories(p);
  return p;
}

static hlsl::CompileOptions TestOptions(const std::string& target, const std::string& entry, const std::vector<hlsl::Define>& defines) {
  hlsl::CompileOptions o;
  o.target = target;
  o.entryPoint = entry;
  o.defines = defines;
  o.includeDirs = {ShaderDir()};
  o.cacheDir = TestShaderCacheDir();
  return o;
}

ShaderBytecode CompileHlsl(const std::string& source, const std::string& target, const std::string& entry, const std::vector<hlsl::Define>& defines) {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = std::string("inline/") + (info ? info->test_suite_name() : "test") + ".hlsl";
  std::replace(name.begin(), name.end(), '/', '_');
  return hlsl::CompileSource(source, name, TestOptions(target, entry, defines));
}

ShaderBytecode CompileShaderFile(const std::string& rel, const std::string& target, const std::string& entry, const std::vector<hlsl::Define>& defines) {
  return hlsl::CompileFile(ShaderDir() / rel, TestOptions(target, entry, defines));
}

void WritePng(const std::filesystem::path& path, uint32_t w, uint32_t h, const uint8_t* rgba) {
  std::filesystem::create_directories(path.parent_path());
  stbi_write_png(path.string().c_str(), int(w), int(h), 4, rgba, int(w * 4));
}

size_t CompareImages(const std::string& name, uint32_t w, uint32_t h, const uint8_t* a, const uint8_t* b, int tolerance) {
  size_t bad = 0;
  std::vector<uint8_t> heat(size_t(w) * h * 4);
  for (size_t i = 0; i < size_t(w) * h; ++i) {
    int diff = 0;
    for (int c = 0; c < 4; ++c) diff = std::max(diff, std::abs(int(a[i * 4 + c]) - int(b[i * 4 + c])));
    if (diff > tolerance) ++bad;
    uint8_t v = uint8_t(std::min(255, diff * 8));
    heat[i * 4 + 0] = v;
    heat[i * 4 + 1] = diff > tolerance ? 0 : v;
    heat[i * 4 + 2] = 0;
    heat[i * 4 + 3] = 255;
  }
  if (bad) {
    std::filesystem::path dir = TestOutputDir();
    WritePng(dir / (name + "-a.png"), w, h, a);
    WritePng(dir / (name + "-b.png"), w, h, b);
    WritePng(dir / (name + "-diff.png"), w, h, heat.data());
  }
  return bad;
}

ScopedEnv::ScopedEnv(const char* name, std::optional<std::string> value) : name_(name) {
  if (const char* old = std::getenv(name)) old_ = old;
  if (value) setenv(name, value->c_str(), 1);
  else unsetenv(name);
}

ScopedEnv::~ScopedEnv() {
  if (old_) setenv(name_, old_->c_str(), 1);
  else unsetenv(name_);
}

}  // namespace sp::test
