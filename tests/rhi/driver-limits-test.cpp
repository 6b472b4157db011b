// What the core cannot check because it depends on the driver: shader code the driver refuses,
// and buffer-view offsets below the driver's binding alignment, must give a clear sp::Error (or
// work correctly), never a crash or wrong data.
#include "rhi-test-util.h"

namespace sp::test {
namespace {

class DriverLimitsTest : public BackendTest {};

TEST_P(DriverLimitsTest, ShaderTheDriverRejectsIsACompileError) {
  if (backend() != Backend::OpenGL) GTEST_SKIP() << "corrupts the GLSL, which only the OpenGL backend reads";
  ShaderBytecode bc = CompileHlsl("float4 main(float4 p : SV_Position) : SV_Target { return p; }", "ps_5_0", "main");
  bc.glsl.replace(bc.glsl.find("void main()"), 11, "void main() { undeclared_identifier = 1; }\nvoid unused()");
  try {
    device().CreatePixelShader(bc);
    FAIL() << "the driver accepted broken GLSL";
  } catch (const Error& e) {
    EXPECT_EQ(e.id(), ErrorId::SHADER_COMPILE_FAILED);
    EXPECT_EQ(e.call(), "CreatePixelShader");
    EXPECT_NE(e.object().find(bc.sourceName), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("undeclared_identifier"), std::string::npos) << e.what();
  }
}

// A structured view starting 4 bytes into the buffer: either the driver binds it and the shader
// reads from there, or creating the view fails with NOT_SUPPORTED.
TEST_P(DriverLimitsTest, UnalignedStructuredViewIsRefusedOrCorrect) {
  std::vector<uint32_t> data(16);
  for (uint32_t i = 0; i < 16; ++i) data[i] = 100 + i;
  Ref<Buffer> buf = MakeBuffer(device(), BIND_SHADER_RESOURCE, data.data(), 64, RESOURCE_MISC_BUFFER_STRUCTURED, 4);
  SHADER_RESOURCE_VIEW_DESC sd;
  sd.Format = FORMAT_UNKNOWN;
  sd.ViewDimension = SRV_DIMENSION_BUFFER;
  sd.Buffer = {1, 8};
  Ref<ShaderResourceView> view;
  try {
    view = device().CreateShaderResourceView(buf.get(), &sd);
  } catch (const Error& e) {
    EXPECT_EQ(e.id(), ErrorId::NOT_SUPPORTED) << e.what();
    EXPECT_NE(std::string(e.what()).find("alignment"), std::string::npos) << e.what();
    return;
  }
  const char* cs = R"(
StructuredBuffer<uint> input : register(t0);
RWStructuredBuffer<uint> output : register(u0);
[numthreads(1, 1, 1)] void main() { output[0] = input[0]; output[1] = input[7]; }
)";
  Ref<ComputeShader> shader = device().CreateComputeShader(CompileHlsl(cs, "cs_5_0", "main"));
  UavBuffer out = MakeUavBuffer(device(), 2, 4);
  ctx().CSSetShader(shader.get());
  ctx().CSSetShaderResources(0, {view.get()});
  ctx().CSSetUnorderedAccessViews(0, {out.uav.get()});
  ctx().Dispatch(1, 1, 1);
  EXPECT_EQ(ReadBufferAs<uint32_t>(device(), ctx(), out.buffer.get()), (std::vector<uint32_t>{101, 108}));
}

// Two devices used in turn from one thread keep their own objects and state; an object that
// outlives its device is released with the device (with a warning) and can then be dropped.
TEST_P(DriverLimitsTest, TwoDevicesOnOneThread) {
  DeviceDesc desc;
  desc.backend = backend();
  std::vector<std::string> errors;
  desc.messageCallback = [&](MessageSeverity s, std::string_view text) {
    if (s == MessageSeverity::Error) errors.emplace_back(text);
  };
  Ref<Device> other = CreateDevice(desc);
  DeviceContext& ctx2 = *other->GetImmediateContext();
  Ref<Texture2D> a = MakeTexture2D(device(), 4, 4, FORMAT_R32_FLOAT, BIND_RENDER_TARGET);
  Ref<Texture2D> b = MakeTexture2D(*other, 4, 4, FORMAT_R32_FLOAT, BIND_RENDER_TARGET);
  Ref<RenderTargetView> ra = device().CreateRenderTargetView(a.get());
  Ref<RenderTargetView> rb = other->CreateRenderTargetView(b.get());
  for (int i = 0; i < 3; ++i) {
    const float va[4] = {float(i), 0, 0, 0}, vb[4] = {float(10 + i), 0, 0, 0};
    ctx().ClearRenderTargetView(ra.get(), va);
    ctx2.ClearRenderTargetView(rb.get(), vb);
    EXPECT_EQ(ReadTextureAs<float>(device(), ctx(), a.get())[5], float(i));
    EXPECT_EQ(ReadTextureAs<float>(*other, ctx2, b.get())[5], float(10 + i));
  }
  Ref<Texture2D> survivor = MakeTexture2D(*other, 4, 4, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE);
  rb.reset();
  b.reset();
  other.reset();
  survivor.reset();
  EXPECT_TRUE(errors.empty()) << errors.front();
  const float v[4] = {7, 0, 0, 0};
  ctx().ClearRenderTargetView(ra.get(), v);
  EXPECT_EQ(ReadTextureAs<float>(device(), ctx(), a.get())[0], 7.0f);
}

SP_INSTANTIATE_BACKEND_TESTS(DriverLimitsTest);

}  // namespace
}  // namespace sp::test
