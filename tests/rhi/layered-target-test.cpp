// Layered rendering: a vertex shader writing SV_RenderTargetArrayIndex into a DSV over all six
// slices of a TextureCube (DSV_DIMENSION_TEXTURE2DARRAY), one instanced draw for all of them;
// the capability as DeviceInfo reports it; the refusals when a device lacks it or the bound
// target is not layered.
#include "rhi-test-util.h"

namespace sp::test {
namespace {

class LayeredTargetTest : public BackendTest {};

// Instance i draws into layer layerOf[i] a band of the top rows, (layer + 1) * 2 rows tall, at depth
// (layer + 1) / 8: each layer's picture differs from every other's, so a face written to the
// wrong layer, or to layer 0 only, shows.
const char* kShaders = R"(
cbuffer Layers : register(b0) { uint4 layerOf[6]; };
struct VSOut { float4 pos : SV_Position; uint layer : SV_RenderTargetArrayIndex; };
VSOut VSBand(uint id : SV_VertexID, uint instance : SV_InstanceID) {
  VSOut o;
  uint layer = layerOf[instance].x;
  float2 corner = float2(id == 1 || id == 2 || id == 4 ? 1.0 : 0.0, id == 2 || id == 4 || id == 5 ? 1.0 : 0.0);
  float bottom = 1.0 - 2.0 * float(layer + 1) / 6.0;
  o.pos = float4(corner.x * 2.0 - 1.0, lerp(1.0, bottom, corner.y), float(layer + 1) / 8.0, 1.0);
  o.layer = layer;
  return o;
}
float4 VSNoLayer(uint id : SV_VertexID) : SV_Position { return float4(0, 0, 0.5, 1); }
)";

constexpr uint32_t kSize = 12;  // rows per face: layer l covers rows [0, 2 (l + 1))

struct LayeredDepth {
  Ref<Texture2D> cube;
  Ref<DepthStencilView> all, face0;
};

LayeredDepth MakeLayeredDepth(Device& dev) {
  LayeredDepth d;
  d.cube = MakeTexture2D(dev, kSize, kSize, FORMAT_R32_TYPELESS, BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE, nullptr, 1, 6, 1, RESOURCE_MISC_TEXTURECUBE);
  DEPTH_STENCIL_VIEW_DESC dv;
  dv.Format = FORMAT_D32_FLOAT;
  dv.ViewDimension = DSV_DIMENSION_TEXTURE2DARRAY;
  dv.Texture2DArray = {0, 0, 6};
  d.all = dev.CreateDepthStencilView(d.cube.get(), &dv);
  dv.Texture2DArray = {0, 0, 1};
  d.face0 = dev.CreateDepthStencilView(d.cube.get(), &dv);
  return d;
}

TEST_P(LayeredTargetTest, TheSoftwareDriversOfferTheVertexShaderArrayIndex) {
  if (device().Info().deviceName.find("llvmpipe") == std::string::npos) GTEST_SKIP() << "checked on Mesa's lavapipe/llvmpipe only";
  EXPECT_TRUE(device().Info().vsRenderTargetArrayIndex) << device().Info().apiVersion;
}

// One instanced draw fills all six faces; expected depths from the band geometry above.
TEST_P(LayeredTargetTest, OneInstancedDrawWritesEachInstanceIntoItsOwnCubeFace) {
  if (!device().Info().vsRenderTargetArrayIndex) GTEST_SKIP() << "device lacks vsRenderTargetArrayIndex";
  LayeredDepth d = MakeLayeredDepth(device());
  Ref<VertexShader> vs = device().CreateVertexShader(CompileHlsl(kShaders, "vs_5_0", "VSBand"));
  // Instances in a scrambled order, so the layer comes from the list, not from the instance id.
  const uint32_t order[6] = {3, 0, 5, 1, 4, 2};
  uint32_t layers[6][4] = {};
  for (int i = 0; i < 6; ++i) layers[i][0] = order[i];
  Ref<Buffer> cb = MakeBuffer(device(), BIND_CONSTANT_BUFFER, layers, sizeof(layers));
  ctx().OMSetRenderTargets(0, nullptr, d.all.get());
  ctx().ClearDepthStencilView(d.all.get(), CLEAR_DEPTH, 1.0f, 0);
  SetViewport(ctx(), kSize, kSize);
  ctx().VSSetShader(vs.get());
  ctx().PSSetShader(nullptr);
  ctx().VSSetConstantBuffers(0, {cb.get()});
  ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  ctx().DrawInstanced(6, 6, 0, 0);
  ctx().OMSetRenderTargets(0, nullptr, nullptr);
  int wrong = 0;
  for (uint32_t face = 0; face < 6; ++face) {
    std::vector<float> got = ReadTextureAs<float>(device(), ctx(), d.cube.get(), face);
    ASSERT_EQ(got.size(), size_t(kSize) * kSize);
    for (uint32_t y = 0; y < kSize; ++y)
      for (uint32_t x = 0; x < kSize; ++x) {
        float expected = y < 2 * (face + 1) ? float(face + 1) / 8.0f : 1.0f;
        float g = got[y * kSize + x];
        if (g != expected && ++wrong <= 5) ADD_FAILURE() << "face " << face << " texel " << x << "," << y << ": " << g << ", expected " << expected;
      }
  }
  EXPECT_EQ(wrong, 0);
}

SP_INSTANTIATE_BACKEND_TESTS(LayeredTargetTest);

// What the core refuses, without drawing: these run on the null backend too.
class LayeredTargetValidationTest : public BackendTest {};

// Without the capability the shader is refused at creation, naming what is missing.
TEST_P(LayeredTargetValidationTest, ADeviceWithoutTheCapabilityRefusesTheShader) {
  DeviceDesc dd;
  dd.backend = backend();
  dd.disableVsRenderTargetArrayIndex = true;
  Ref<Device> dev = CreateDevice(dd);
  EXPECT_FALSE(dev->Info().vsRenderTargetArrayIndex);
  try {
    dev->CreateVertexShader(CompileHlsl(kShaders, "vs_5_0", "VSBand"));
    ADD_FAILURE() << "expected SP_NOT_SUPPORTED";
  } catch (const Error& e) {
    EXPECT_EQ(e.id(), ErrorId::NOT_SUPPORTED) << e.what();
    EXPECT_NE(std::string(e.what()).find("SV_RenderTargetArrayIndex"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("vsRenderTargetArrayIndex"), std::string::npos) << e.what();
  }
  // A vertex shader without the output is still fine there.
  EXPECT_NO_THROW(dev->CreateVertexShader(CompileHlsl(kShaders, "vs_5_0", "VSNoLayer")));
  EXPECT_EQ(dev->ValidationErrorCount(), 0u) << dev->LastValidationError();
}

// Drawing with the index into a single-slice view is refused: D3D11 would send an out-of-range
// index to slice 0, Vulkan leaves it undefined.
TEST_P(LayeredTargetValidationTest, WritingTheIndexIntoASingleSliceViewIsAnError) {
  if (!device().Info().vsRenderTargetArrayIndex) GTEST_SKIP() << "device lacks vsRenderTargetArrayIndex";
  LayeredDepth d = MakeLayeredDepth(device());
  Ref<VertexShader> vs = device().CreateVertexShader(CompileHlsl(kShaders, "vs_5_0", "VSBand"));
  uint32_t layers[6][4] = {};
  Ref<Buffer> cb = MakeBuffer(device(), BIND_CONSTANT_BUFFER, layers, sizeof(layers));
  ctx().OMSetRenderTargets(0, nullptr, d.face0.get());
  SetViewport(ctx(), kSize, kSize);
  ctx().VSSetShader(vs.get());
  ctx().VSSetConstantBuffers(0, {cb.get()});
  ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  try {
    ctx().DrawInstanced(6, 1, 0, 0);
    ADD_FAILURE() << "expected SP_OUTPUT_MISMATCH";
  } catch (const Error& e) {
    EXPECT_EQ(e.id(), ErrorId::OUTPUT_MISMATCH) << e.what();
    EXPECT_NE(std::string(e.what()).find("one array slice"), std::string::npos) << e.what();
  }
}

SP_INSTANTIATE_VALIDATION_TESTS(LayeredTargetValidationTest);

}  // namespace
}  // namespace sp::test
