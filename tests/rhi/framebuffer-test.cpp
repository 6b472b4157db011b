// Output-merger bindings: several render targets with gaps, render-target views of one array
// slice, mip or 3D slice, clears of exactly a view's subresources, sRGB encoding on write and on
// clear, and MSAA mechanics (typeless resolve, sample counts). Per-sample loads through sample
// masks and resolve averaging are conformance probes (eval/conformance/probes/resource-msaa.cpp).
#include <cmath>

#include "rhi-test-util.h"

namespace sp::test {
namespace {

class FramebufferTest : public BackendTest {};

const char* kShaders = R"(
cbuffer Color : register(b0) { float4 color; };
float4 VSFull(uint id : SV_VertexID) : SV_Position {
  float2 p = float2((id << 1) & 2, id & 2);
  return float4(p * float2(2, -2) + float2(-1, 1), 0, 1);
}
float4 PSColor(float4 p : SV_Position) : SV_Target { return color; }
struct Three { float4 a : SV_Target0; float4 b : SV_Target1; float4 c : SV_Target2; };
Three PSThree(float4 p : SV_Position) { Three o; o.a = float4(1, 0, 0, 1); o.b = float4(0, 1, 0, 1); o.c = float4(0, 0, 1, 1); return o; }
)";

class Fullscreen {
 public:
  Fullscreen(Device& dev) {
    vs = dev.CreateVertexShader(CompileHlsl(kShaders, "vs_5_0", "VSFull"));
    ps = dev.CreatePixelShader(CompileHlsl(kShaders, "ps_5_0", "PSColor"));
    cb = MakeBuffer(dev, BIND_CONSTANT_BUFFER, nullptr, 16);
  }
  void Draw(DeviceContext& ctx, const float color[4], PixelShader* shader = nullptr) {
    ctx.UpdateSubresource(cb.get(), 0, nullptr, color, 0, 0);
    ctx.VSSetShader(vs.get());
    ctx.PSSetShader(shader ? shader : ps.get());
    ctx.PSSetConstantBuffers(0, {cb.get()});
    ctx.IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    ctx.Draw(3, 0);
  }
  Ref<VertexShader> vs;
  Ref<PixelShader> ps;
  Ref<Buffer> cb;
};

TEST_P(FramebufferTest, RenderTargetSlotsWithGaps) {
  const uint32_t W = 4, H = 4;
  Target t0 = MakeTarget(device(), W, H, FORMAT_R8G8B8A8_UNORM), t2 = MakeTarget(device(), W, H, FORMAT_R8G8B8A8_UNORM);
  Fullscreen fs(device());
  Ref<PixelShader> three = device().CreatePixelShader(CompileHlsl(kShaders, "ps_5_0", "PSThree"));
  const float zero[4] = {0, 0, 0, 0};
  ctx().ClearRenderTargetView(t0.rtv.get(), zero);
  ctx().ClearRenderTargetView(t2.rtv.get(), zero);
  RenderTargetView* rtvs[] = {t0.rtv.get(), nullptr, t2.rtv.get()};
  ctx().OMSetRenderTargets(3, rtvs, nullptr);
  SetViewport(ctx(), W, H);
  fs.Draw(ctx(), zero, three.get());
  std::vector<uint8_t> a = ReadTexture(device(), ctx(), t0.texture.get()), c = ReadTexture(device(), ctx(), t2.texture.get());
  EXPECT_EQ(a[0], 255);
  EXPECT_EQ(a[1], 0);
  EXPECT_EQ(a[2], 0);
  EXPECT_EQ(c[0], 0);
  EXPECT_EQ(c[1], 0);
  EXPECT_EQ(c[2], 255);
}

// Draws and clears through views of one (slice, mip) touch only that subresource; a view of
// several slices clears all of them.
TEST_P(FramebufferTest, ArraySliceAndMipViews) {
  const uint32_t W = 8, H = 8, Slices = 3, Mips = 3;
  Ref<Texture2D> tex = MakeTexture2D(device(), W, H, FORMAT_R32_FLOAT, BIND_RENDER_TARGET, nullptr, Mips, Slices);
  Fullscreen fs(device());
  auto rtvOf = [&](uint32_t mip, uint32_t first, uint32_t count) {
    RENDER_TARGET_VIEW_DESC d;
    d.Format = FORMAT_R32_FLOAT;
    d.ViewDimension = RTV_DIMENSION_TEXTURE2DARRAY;
    d.Texture2DArray = {mip, first, count};
    return device().CreateRenderTargetView(tex.get(), &d);
  };
  for (uint32_t mip = 0; mip < Mips; ++mip) {
    Ref<RenderTargetView> all = rtvOf(mip, 0, Slices);
    const float v[4] = {float(mip + 1), 0, 0, 0};
    ctx().ClearRenderTargetView(all.get(), v);  // every slice of this mip
  }
  Ref<RenderTargetView> slice1mip1 = rtvOf(1, 1, 1);
  RenderTargetView* rtvs[] = {slice1mip1.get()};
  ctx().OMSetRenderTargets(1, rtvs, nullptr);
  SetViewport(ctx(), W / 2, H / 2);
  const float drawn[4] = {42, 0, 0, 0};
  fs.Draw(ctx(), drawn);
  ctx().OMSetRenderTargets(0, nullptr, nullptr);
  Ref<RenderTargetView> slice2mip0 = rtvOf(0, 2, 1);
  const float cleared[4] = {-7, 0, 0, 0};
  ctx().ClearRenderTargetView(slice2mip0.get(), cleared);
  for (uint32_t slice = 0; slice < Slices; ++slice)
    for (uint32_t mip = 0; mip < Mips; ++mip) {
      std::vector<float> px = ReadTextureAs<float>(device(), ctx(), tex.get(), CalcSubresource(mip, slice, Mips));
      float expect = float(mip + 1);
      if (slice == 1 && mip == 1) expect = 42;
      if (slice == 2 && mip == 0) expect = -7;
      for (float v : px) ASSERT_EQ(v, expect) << "slice " << slice << " mip " << mip;
    }
}

TEST_P(FramebufferTest, Texture3DSliceViews) {
  const uint32_t W = 4, H = 4, D = 4;
  TEXTURE3D_DESC td;
  td.Width = W;
  td.Height = H;
  td.Depth = D;
  td.Format = FORMAT_R32_FLOAT;
  td.BindFlags = BIND_RENDER_TARGET;
  Ref<Texture3D> tex = device().CreateTexture3D(td);
  Ref<RenderTargetView> all = device().CreateRenderTargetView(tex.get());
  RENDER_TARGET_VIEW_DESC d;
  d.Format = FORMAT_R32_FLOAT;
  d.ViewDimension = RTV_DIMENSION_TEXTURE3D;
  d.Texture3D = {0, 2, 1};
  Ref<RenderTargetView> slice2 = device().CreateRenderTargetView(tex.get(), &d);
  const float one[4] = {1, 0, 0, 0};
  ctx().ClearRenderTargetView(all.get(), one);
  Fullscreen fs(device());
  RenderTargetView* rtvs[] = {slice2.get()};
  ctx().OMSetRenderTargets(1, rtvs, nullptr);
  SetViewport(ctx(), W, H);
  const float five[4] = {5, 0, 0, 0};
  fs.Draw(ctx(), five);
  td.BindFlags = 0;
  td.Usage = USAGE_STAGING;
  td.CPUAccessFlags = CPU_ACCESS_READ;
  Ref<Texture3D> staging = device().CreateTexture3D(td);
  ctx().CopyResource(staging.get(), tex.get());
  MAPPED_SUBRESOURCE m;
  ASSERT_TRUE(ctx().Map(staging.get(), 0, MAP_READ, 0, &m));
  for (uint32_t z = 0; z < D; ++z)
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x) {
        float v;
        std::memcpy(&v, static_cast<const uint8_t*>(m.pData) + z * m.DepthPitch + y * m.RowPitch + x * 4, 4);
        ASSERT_EQ(v, z == 2 ? 5.0f : 1.0f) << x << "," << y << "," << z;
      }
  ctx().Unmap(staging.get(), 0);
}

// sRGB views encode on write and on clear; a UNORM view of the same TYPELESS texture sees the
// encoded bytes. Blending happens in linear space.
TEST_P(FramebufferTest, SrgbEncodesOnWriteAndClear) {
  const uint32_t W = 4, H = 2;
  Ref<Texture2D> tex = MakeTexture2D(device(), W, H, FORMAT_R8G8B8A8_TYPELESS, BIND_RENDER_TARGET | BIND_SHADER_RESOURCE);
  RENDER_TARGET_VIEW_DESC d;
  d.Format = FORMAT_R8G8B8A8_UNORM_SRGB;
  d.ViewDimension = RTV_DIMENSION_TEXTURE2D;
  Ref<RenderTargetView> srgb = device().CreateRenderTargetView(tex.get(), &d);
  auto encode = [](double linear) {
    double s = linear <= 0.0031308 ? linear * 12.92 : 1.055 * std::pow(linear, 1 / 2.4) - 0.055;
    return int(std::lround(s * 255));
  };
  const float clear[4] = {0.5f, 0.25f, 0.0f, 0.5f};
  ctx().ClearRenderTargetView(srgb.get(), clear);
  std::vector<uint8_t> px = ReadTexture(device(), ctx(), tex.get());
  EXPECT_NEAR(px[0], encode(0.5), 1);
  EXPECT_NEAR(px[1], encode(0.25), 1);
  EXPECT_EQ(px[2], 0);
  EXPECT_NEAR(px[3], 128, 1);  // alpha is linear
  // Additive blend of 0.25 onto 0.5: linear 0.75, encoded.
  BLEND_DESC bd;
  bd.RenderTarget[0] = {true, BLEND_ONE, BLEND_ONE, BLEND_OP_ADD, BLEND_ONE, BLEND_ZERO, BLEND_OP_ADD, COLOR_WRITE_ENABLE_ALL};
  Ref<BlendState> add = device().CreateBlendState(bd);
  Fullscreen fs(device());
  RenderTargetView* rtvs[] = {srgb.get()};
  ctx().OMSetRenderTargets(1, rtvs, nullptr);
  ctx().OMSetBlendState(add.get(), nullptr, 0xffffffff);
  SetViewport(ctx(), W, H);
  const float quarter[4] = {0.25f, 0.25f, 0.25f, 1.0f};
  fs.Draw(ctx(), quarter);
  px = ReadTexture(device(), ctx(), tex.get());
  EXPECT_NEAR(px[0], encode(0.75), 1);
  EXPECT_NEAR(px[1], encode(0.5), 1);
  EXPECT_NEAR(px[2], encode(0.25), 1);
  EXPECT_EQ(px[3], 255);
}

// Resolving a TYPELESS multisampled texture through a typed format.
TEST_P(FramebufferTest, ResolveTypelessThroughFormat) {
  if (!device().CheckMultisampleQualityLevels(FORMAT_R8G8B8A8_UNORM, 4)) GTEST_SKIP() << "no 4x MSAA for R8G8B8A8_UNORM";
  const uint32_t W = 4, H = 4;
  Ref<Texture2D> ms = MakeTexture2D(device(), W, H, FORMAT_R8G8B8A8_TYPELESS, BIND_RENDER_TARGET, nullptr, 1, 1, 4);
  RENDER_TARGET_VIEW_DESC d;
  d.Format = FORMAT_R8G8B8A8_UNORM;
  d.ViewDimension = RTV_DIMENSION_TEXTURE2DMS;
  Ref<RenderTargetView> rtv = device().CreateRenderTargetView(ms.get(), &d);
  const float c[4] = {1.0f, 0.5f, 0.0f, 1.0f};
  ctx().ClearRenderTargetView(rtv.get(), c);
  Ref<Texture2D> resolved = MakeTexture2D(device(), W, H, FORMAT_R8G8B8A8_TYPELESS, BIND_SHADER_RESOURCE);
  ctx().ResolveSubresource(resolved.get(), 0, ms.get(), 0, FORMAT_R8G8B8A8_UNORM);
  std::vector<uint8_t> px = ReadTexture(device(), ctx(), resolved.get());
  for (uint32_t i = 0; i < W * H; ++i) {
    EXPECT_EQ(px[i * 4 + 0], 255);
    EXPECT_EQ(px[i * 4 + 1], 128);
    EXPECT_EQ(px[i * 4 + 2], 0);
    EXPECT_EQ(px[i * 4 + 3], 255);
  }
}

// CheckMultisampleQualityLevels tells exactly which counts exist: those create textures that
// really have that many samples, the others fail to create.
TEST_P(FramebufferTest, MultisampleCountsAreReportedExactly) {
  const char* cs = R"(
Texture2DMS<float4> ms : register(t0);
RWStructuredBuffer<uint> output : register(u0);
[numthreads(1, 1, 1)] void main() { uint w, h, n; ms.GetDimensions(w, h, n); output[0] = n; }
)";
  Ref<ComputeShader> shader = device().CreateComputeShader(CompileHlsl(cs, "cs_5_0", "main"));
  for (FORMAT f : {FORMAT_R8G8B8A8_UNORM, FORMAT_R32_FLOAT}) {
    for (uint32_t n : {2u, 4u, 8u}) {
      const bool reported = device().CheckMultisampleQualityLevels(f, n) > 0;
      Ref<Texture2D> tex;
      try {
        tex = MakeTexture2D(device(), 4, 4, f, BIND_RENDER_TARGET | BIND_SHADER_RESOURCE, nullptr, 1, 1, n);
      } catch (const Error& e) {
        EXPECT_FALSE(reported) << n << "x " << FormatName(f) << " is reported but fails: " << e.what();
        EXPECT_EQ(e.id(), ErrorId::FORMAT_UNSUPPORTED);
        continue;
      }
      ASSERT_TRUE(reported) << n << "x " << FormatName(f) << " creates but is not reported";
      Ref<ShaderResourceView> srv = device().CreateShaderResourceView(tex.get());
      UavBuffer out = MakeUavBuffer(device(), 1, 4);
      ctx().CSSetShader(shader.get());
      ctx().CSSetShaderResources(0, {srv.get()});
      ctx().CSSetUnorderedAccessViews(0, {out.uav.get()});
      ctx().Dispatch(1, 1, 1);
      EXPECT_EQ(ReadBufferAs<uint32_t>(device(), ctx(), out.buffer.get())[0], n) << FormatName(f);
    }
  }
}

// A read-only depth-stencil view may stay bound while shaders sample the same depth texture (a
// depth-tested pass that also reads depth, as soft-shadow and fog passes do).
TEST_P(FramebufferTest, ReadOnlyDepthWhileSampled) {
  const uint32_t W = 8, H = 4;
  Ref<Texture2D> depth = MakeTexture2D(device(), W, H, FORMAT_R32_TYPELESS, BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE);
  DEPTH_STENCIL_VIEW_DESC dd;
  dd.Format = FORMAT_D32_FLOAT;
  dd.ViewDimension = DSV_DIMENSION_TEXTURE2D;
  Ref<DepthStencilView> writable = device().CreateDepthStencilView(depth.get(), &dd);
  dd.Flags = DSV_READ_ONLY_DEPTH;
  Ref<DepthStencilView> readOnly = device().CreateDepthStencilView(depth.get(), &dd);
  SHADER_RESOURCE_VIEW_DESC sd;
  sd.Format = FORMAT_R32_FLOAT;
  sd.ViewDimension = SRV_DIMENSION_TEXTURE2D;
  sd.Texture2D = {0, 1};
  Ref<ShaderResourceView> srv = device().CreateShaderResourceView(depth.get(), &sd);
  ctx().ClearDepthStencilView(writable.get(), CLEAR_DEPTH, 0.5f, 0);
  const char* ps = R"(
Texture2D<float> depth : register(t0);
float4 main(float4 p : SV_Position) : SV_Target { return depth.Load(int3(p.xy, 0)) + 1; }
)";
  Ref<PixelShader> shader = device().CreatePixelShader(CompileHlsl(ps, "ps_5_0", "main"));
  Target t = MakeTarget(device(), W, H, FORMAT_R32_FLOAT);
  const float zero[4] = {0, 0, 0, 0};
  ctx().ClearRenderTargetView(t.rtv.get(), zero);
  RenderTargetView* rtvs[] = {t.rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, readOnly.get());
  ctx().PSSetShaderResources(0, {srv.get()});
  Ref<ShaderResourceView> bound;
  ctx().PSGetShaderResources(0, 1, &bound);
  ASSERT_EQ(bound, srv) << "a read-only DSV must not unbind the SRV";
  SetViewport(ctx(), W, H);
  ctx().PSSetShader(shader.get());
  RectDrawer rect(device());
  rect.Draw(ctx(), 0, 0, 4, float(H), W, H, 0.25f);  // passes LESS against 0.5
  rect.Draw(ctx(), 4, 0, 8, float(H), W, H, 0.75f);  // fails
  std::vector<float> px = ReadTextureAs<float>(device(), ctx(), t.texture.get());
  for (uint32_t x = 0; x < W; ++x) EXPECT_EQ(px[x], x < 4 ? 1.5f : 0.0f) << x;
}

// A depth-stencil view of one array slice clears only that slice.
TEST_P(FramebufferTest, DepthClearOfOneSlice) {
  const uint32_t W = 4, H = 4;
  Ref<Texture2D> depth = MakeTexture2D(device(), W, H, FORMAT_R32_TYPELESS, BIND_DEPTH_STENCIL, nullptr, 1, 3);
  DEPTH_STENCIL_VIEW_DESC all;
  all.Format = FORMAT_D32_FLOAT;
  all.ViewDimension = DSV_DIMENSION_TEXTURE2DARRAY;
  all.Texture2DArray = {0, 0, 3};
  Ref<DepthStencilView> dsvAll = device().CreateDepthStencilView(depth.get(), &all);
  DEPTH_STENCIL_VIEW_DESC one = all;
  one.Texture2DArray = {0, 1, 1};
  Ref<DepthStencilView> dsvOne = device().CreateDepthStencilView(depth.get(), &one);
  ctx().ClearDepthStencilView(dsvAll.get(), CLEAR_DEPTH, 0.75f, 0);
  ctx().ClearDepthStencilView(dsvOne.get(), CLEAR_DEPTH, 0.125f, 0);
  for (uint32_t s = 0; s < 3; ++s) {
    std::vector<float> z = ReadTextureAs<float>(device(), ctx(), depth.get(), s);
    for (float v : z) ASSERT_EQ(v, s == 1 ? 0.125f : 0.75f) << "slice " << s;
  }
}

SP_INSTANTIATE_BACKEND_TESTS(FramebufferTest);

}  // namespace
}  // namespace sp::test
