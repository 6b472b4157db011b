// Copies between the depth and colour members of one TYPELESS family: a texture created with
// BIND_DEPTH_STENCIL is stored as a depth format, its twin without it as a colour format, and
// D3D11 copies between them bit for bit (CopyResource and whole-subresource
// CopySubresourceRegion). Values are the D3D11 encodings of the cleared and drawn depths.
#include "rhi-test-util.h"

namespace sp::test {
namespace {

class DepthCopyTest : public BackendTest {
 protected:
  // Clears the DSV to `clear` and draws the left half at `drawn` (depth test ALWAYS).
  void ClearAndDraw(DepthStencilView* dsv, uint32_t w, uint32_t h, float clear, float drawn) {
    if (!rect_) rect_ = std::make_unique<RectDrawer>(device());
    DEPTH_STENCIL_DESC dd;
    dd.DepthFunc = COMPARISON_ALWAYS;
    ds_ = device().CreateDepthStencilState(dd);
    ctx().ClearDepthStencilView(dsv, CLEAR_DEPTH, clear, 0);
    ctx().OMSetRenderTargets(0, nullptr, dsv);
    ctx().OMSetDepthStencilState(ds_.get(), 0);
    ctx().PSSetShader(nullptr);
    SetViewport(ctx(), float(w), float(h));
    rect_->Draw(ctx(), 0, 0, float(w) / 2, float(h), float(w), float(h), drawn);
    ctx().OMSetRenderTargets(0, nullptr, nullptr);
  }
  std::unique_ptr<RectDrawer> rect_;
  Ref<DepthStencilState> ds_;
};

TEST_P(DepthCopyTest, D32ToColourAndBack) {
  const uint32_t W = 8, H = 4;
  Ref<Texture2D> depth = MakeTexture2D(device(), W, H, FORMAT_R32_TYPELESS, BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE);
  DEPTH_STENCIL_VIEW_DESC dd;
  dd.Format = FORMAT_D32_FLOAT;
  dd.ViewDimension = DSV_DIMENSION_TEXTURE2D;
  Ref<DepthStencilView> dsv = device().CreateDepthStencilView(depth.get(), &dd);
  ClearAndDraw(dsv.get(), W, H, 0.25f, 0.75f);
  std::vector<float> expect(W * H);
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) expect[y * W + x] = x < W / 2 ? 0.75f : 0.25f;

  Ref<Texture2D> colour = MakeTexture2D(device(), W, H, FORMAT_R32_TYPELESS, BIND_SHADER_RESOURCE | BIND_RENDER_TARGET);
  ctx().CopyResource(colour.get(), depth.get());
  EXPECT_EQ(ReadTextureAs<float>(device(), ctx(), colour.get()), expect);

  // And back into a second depth texture, through CopySubresourceRegion with a null box.
  Ref<Texture2D> depth2 = MakeTexture2D(device(), W, H, FORMAT_R32_TYPELESS, BIND_DEPTH_STENCIL);
  ctx().CopySubresourceRegion(depth2.get(), 0, 0, 0, 0, colour.get(), 0, nullptr);
  EXPECT_EQ(ReadTextureAs<float>(device(), ctx(), depth2.get()), expect);

  // The copy is usable as a depth buffer: LESS against 0.5 passes only where 0.75 was not drawn.
  Ref<DepthStencilView> dsv2 = device().CreateDepthStencilView(depth2.get(), &dd);
  Target t = MakeTarget(device(), W, H, FORMAT_R32_FLOAT);
  const float zero[4] = {0, 0, 0, 0};
  ctx().ClearRenderTargetView(t.rtv.get(), zero);
  DEPTH_STENCIL_DESC less;
  Ref<DepthStencilState> lessState = device().CreateDepthStencilState(less);
  const char* ps = "float4 main(float4 p : SV_Position) : SV_Target { return 1; }";
  Ref<PixelShader> one = device().CreatePixelShader(CompileHlsl(ps, "ps_5_0", "main"));
  RenderTargetView* rtvs[] = {t.rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, dsv2.get());
  ctx().OMSetDepthStencilState(lessState.get(), 0);
  ctx().PSSetShader(one.get());
  rect_->Draw(ctx(), 0, 0, float(W), float(H), float(W), float(H), 0.5f);
  std::vector<float> hits = ReadTextureAs<float>(device(), ctx(), t.texture.get());
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) EXPECT_EQ(hits[y * W + x], x < W / 2 ? 1.0f : 0.0f) << x << ", " << y;
}

TEST_P(DepthCopyTest, D16ArraySliceToColourSlice) {
  const uint32_t W = 4, H = 4;
  Ref<Texture2D> depth = MakeTexture2D(device(), W, H, FORMAT_R16_TYPELESS, BIND_DEPTH_STENCIL, nullptr, 1, 3);
  DEPTH_STENCIL_VIEW_DESC dd;
  dd.Format = FORMAT_D16_UNORM;
  dd.ViewDimension = DSV_DIMENSION_TEXTURE2DARRAY;
  dd.Texture2DArray = {0, 2, 1};
  Ref<DepthStencilView> slice2 = device().CreateDepthStencilView(depth.get(), &dd);
  ClearAndDraw(slice2.get(), W, H, 0.25f, 0.625f);
  Ref<Texture2D> colour = MakeTexture2D(device(), W, H, FORMAT_R16_TYPELESS, BIND_SHADER_RESOURCE, nullptr, 1, 2);
  ctx().CopySubresourceRegion(colour.get(), CalcSubresource(0, 1, 1), 0, 0, 0, depth.get(), CalcSubresource(0, 2, 1), nullptr);
  // D3D11 UNORM encoding: round(d * 65535); 0.25 -> 16384 (16383.75), 0.625 -> 40959 (40959.375).
  std::vector<uint16_t> got = ReadTextureAs<uint16_t>(device(), ctx(), colour.get(), 1);
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) EXPECT_EQ(got[y * W + x], x < W / 2 ? 40959 : 16384) << x << ", " << y;
}

SP_INSTANTIATE_BACKEND_TESTS(DepthCopyTest);

}  // namespace
}  // namespace sp::test
