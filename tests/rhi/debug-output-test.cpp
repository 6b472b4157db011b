// What reaches the message callback: nothing at all for a correct draw (Mesa's GL ES 3.1
// portability note about pipelines whose pixel shader reads a subset of the vertex outputs is the
// one driver message dropped), while real driver errors still arrive. Also: the shaders the
// device compiles for itself go to DeviceDesc::shaderCacheDir.
#include <GL/glcorearb.h>

#include "rhi-test-util.h"

extern "C" void glEnable(GLenum cap);  // from libOpenGL, which the GL backend links

namespace sp::test {
namespace {

// The vertex shader writes two varyings, the pixel shader reads one: valid in D3D11 and desktop
// GL, not an exact interface match in the sense of OpenGL ES 3.1.
const char* kSubsetInterface = R"(
struct VOut { float4 pos : SV_Position; float2 uv : TEXCOORD0; float4 extra : TEXCOORD1; };
VOut VSMain(uint id : SV_VertexID) {
  VOut o;
  o.uv = float2((id << 1) & 2, id & 2);
  o.pos = float4(o.uv.x * 2 - 1, 1 - o.uv.y * 2, 0.5, 1);  // clockwise: front-facing
  o.extra = o.pos;
  return o;
}
struct PIn { float4 pos : SV_Position; float2 uv : TEXCOORD0; };
float4 PSMain(PIn v) : SV_Target { return float4(v.uv, 0, 1); }
)";

class DebugOutputTest : public BackendTest {
 protected:
  void CaptureAll() {
    device().SetMessageCallback([this](MessageSeverity s, std::string_view t) {
      messages.emplace_back(std::string(s == MessageSeverity::Error ? "error: " : s == MessageSeverity::Warning ? "warning: " : "info: ") +
                            std::string(t));
    });
  }
  std::vector<std::string> messages;
};

TEST_P(DebugOutputTest, CorrectDrawReportsNothing) {
  Ref<VertexShader> vs = device().CreateVertexShader(CompileHlsl(kSubsetInterface, "vs_5_0", "VSMain"));
  Ref<PixelShader> ps = device().CreatePixelShader(CompileHlsl(kSubsetInterface, "ps_5_0", "PSMain"));
  Target t = MakeTarget(device(), 8, 8, FORMAT_R8G8B8A8_UNORM);
  CaptureAll();
  for (int frame = 0; frame < 2; ++frame) {
    RenderTargetView* rtvs[] = {t.rtv.get()};
    ctx().OMSetRenderTargets(1, rtvs, nullptr);
    SetViewport(ctx(), 8, 8);
    ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    ctx().VSSetShader(vs.get());
    ctx().PSSetShader(ps.get());
    ctx().Draw(3, 0);
    ReadTexture(device(), ctx(), t.texture.get());
    ctx().ClearState();
  }
  for (const std::string& m : messages) ADD_FAILURE() << m;
}

TEST_P(DebugOutputTest, DriverErrorsStillArrive) {
  if (backend() != Backend::OpenGL) GTEST_SKIP() << "provokes a GL error with a raw GL call; Vulkan has no public handle to misuse";
  CaptureAll();
  expectValidationErrors = true;
  // The device's context is current on this thread; an invalid enum is a GL_INVALID_ENUM error.
  glEnable(0x1234);
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_EQ(messages[0].rfind("error: GL error", 0), 0u) << messages[0];
  EXPECT_EQ(device().ValidationErrorCount(), 1u);
}

TEST_P(DebugOutputTest, DeviceShadersGoToShaderCacheDir) {
  std::filesystem::path dir = TestOutputDir() / "device-cache";
  std::filesystem::remove_all(dir);
  DeviceDesc dd;
  dd.backend = backend();
  dd.shaderCacheDir = dir;
  dd.messageCallback = [this](MessageSeverity s, std::string_view t) {
    if (s == MessageSeverity::Error) validationMessages.emplace_back(t);
  };
  Ref<Device> dev = CreateDevice(dd);
  // The depth-bias calibration compiled its shader into the directory.
  size_t files = 0;
  if (std::filesystem::exists(dir))
    for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) files += e.is_regular_file();
  EXPECT_GT(files, 0u) << dir;
  dev.reset();
}

SP_INSTANTIATE_BACKEND_TESTS(DebugOutputTest);

}  // namespace
}  // namespace sp::test
