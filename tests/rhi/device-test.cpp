// Bring-up: the device starts with validation on, and clears and readback work. D3D11's
// rasterization rules and render-then-sample orientation are conformance probes
// (eval/conformance/probes/raster-*.cpp).
#include "backend-test.h"

namespace sp::test {
namespace {

class DeviceTest : public BackendTest {};

TEST_P(DeviceTest, ComesUpWithValidationAndCalibratedBias) {
  const DeviceInfo& info = device().Info();
  EXPECT_EQ(info.backend, backend());
  EXPECT_FALSE(info.apiVersion.empty());
  EXPECT_FALSE(info.deviceName.empty());
  EXPECT_TRUE(info.validationEnabled) << "validation layers / GL debug output must be on in tests";
  EXPECT_GT(info.timestampFrequency, 0u);
  // The calibration measured the driver's unit; on any driver the scale is positive and sane.
  for (float s : {info.depthBiasScaleD16, info.depthBiasScaleD24, info.depthBiasScaleD32}) {
    EXPECT_GT(s, 0.05f);
    EXPECT_LT(s, 20.0f);
  }
  EXPECT_NE(device().GetImmediateContext(), nullptr);
}

TEST_P(DeviceTest, ClearRenderTargetAndReadBack) {
  Ref<Texture2D> tex = MakeTexture2D(device(), 8, 4, FORMAT_R8G8B8A8_UNORM, BIND_RENDER_TARGET);
  Ref<RenderTargetView> rtv = device().CreateRenderTargetView(tex.get());
  const float color[4] = {1.0f, 0.5f, 0.0f, 0.25f};
  ctx().ClearRenderTargetView(rtv.get(), color);
  std::vector<uint8_t> px = ReadTexture(device(), ctx(), tex.get());
  ASSERT_EQ(px.size(), 8u * 4 * 4);
  for (size_t i = 0; i < px.size(); i += 4) {
    EXPECT_EQ(px[i + 0], 255);
    EXPECT_EQ(px[i + 1], 128);  // D3D: round(0.5 * 255)
    EXPECT_EQ(px[i + 2], 0);
    EXPECT_EQ(px[i + 3], 64);
  }
}

TEST_P(DeviceTest, UploadAndReadBackKeepMemoryLayout) {
  std::vector<uint32_t> data(16 * 8);
  for (uint32_t i = 0; i < data.size(); ++i) data[i] = i * 2654435761u;
  Ref<Texture2D> tex = MakeTexture2D(device(), 16, 8, FORMAT_R32_UINT, BIND_SHADER_RESOURCE, data.data());
  std::vector<uint32_t> back = ReadAs<uint32_t>(ReadTexture(device(), ctx(), tex.get()));
  EXPECT_EQ(back, data);
}

SP_INSTANTIATE_BACKEND_TESTS(DeviceTest);

}  // namespace
}  // namespace sp::test
