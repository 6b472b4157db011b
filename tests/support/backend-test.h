// Fixture for tests that run on both backends. Every test gets a fresh device with Vulkan
// validation layers / GL debug output on; any validation error or GL error fails the test.
#pragma once
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <optional>
#include <sp/rhi/rhi.h>

#include "gpu-util.h"
#include <string>
#include <vector>

namespace sp::test {

class BackendTest : public ::testing::TestWithParam<Backend> {
 protected:
  void SetUp() override;
  void TearDown() override;

  Device& device() { return *device_; }
  DeviceContext& ctx() { return *device_->GetImmediateContext(); }
  Backend backend() const { return GetParam(); }

  // Errors reported by the backend's validation during the test (cleared by TearDown).
  std::vector<std::string> validationMessages;
  // Set by tests that provoke driver messages on purpose.
  bool expectValidationErrors = false;
  // Lets a suite change the device it gets (a display to present to, ...) before SetUp creates it.
  virtual void ConfigureDevice(DeviceDesc&) {}

 private:
  Ref<Device> device_;
};

// Sets (or, with nullopt, unsets) an environment variable for the life of the object.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, std::optional<std::string> value);
  ~ScopedEnv();
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

// Name printer so tests read "Vulkan" / "OpenGL" / "Null" instead of 0 / 1 / 2.
std::string BackendTestName(Backend b);
std::string BackendParamName(const ::testing::TestParamInfo<Backend>& info);

#define SP_INSTANTIATE_BACKEND_TESTS(Suite) \
  INSTANTIATE_TEST_SUITE_P(Backends, Suite, ::testing::Values(::sp::Backend::Vulkan, ::sp::Backend::OpenGL), ::sp::test::BackendParamName)

// For suites that only check what the core accepts and refuses (error ids, messages, warnings,
// bound state), never pixels: they run on the null backend as well, which needs no driver.
#define SP_INSTANTIATE_VALIDATION_TESTS(Suite)                                                                              \
  INSTANTIATE_TEST_SUITE_P(Backends, Suite, ::testing::Values(::sp::Backend::Vulkan, ::sp::Backend::OpenGL, ::sp::Backend::Null), \
                           ::sp::test::BackendParamName)

// Compiles HLSL given inline (cached in the build tree).
ShaderBytecode CompileHlsl(const std::string& source, const std::string& target, const std::string& entry,
                           const std::vector<hlsl::Define>& defines = {});
// Compiles a file from shaders-hlsl/ (path relative to it).
ShaderBytecode CompileShaderFile(const std::string& relativePath, const std::string& target, const std::string& entry,
                                 const std::vector<hlsl::Define>& defines = {});
std::filesystem::path ShaderDir();
std::filesystem::path TestShaderCacheDir();  // build/test-output/shader-cache: tests never write to $HOME
std::filesystem::path TestOutputDir();  // build/test-output/<suite>/<test>, created on demand

// Readback and creation helpers (eval/conformance/gpu-util.h), shared with the conformance probes.
using gpu::MakeBuffer;
using gpu::MakeTexture2D;
using gpu::ReadAs;
using gpu::ReadBuffer;
using gpu::ReadTexture;

// Writes an RGBA8 PNG (for diffs and failure artefacts).
void WritePng(const std::filesystem::path& path, uint32_t w, uint32_t h, const uint8_t* rgba);

// Compares two RGBA8 images; on mismatch writes a, b and a heat map of |a-b| next to each other
// under TestOutputDir() and returns the number of pixels differing by more than `tolerance`.
size_t CompareImages(const std::string& name, uint32_t w, uint32_t h, const uint8_t* a, const uint8_t* b, int tolerance = 0);

}  // namespace sp::test
