// Viewport and scissor orientation: D3D11 counts viewport and scissor rectangles from the top-left
// pixel of the render target (row 0 is the top row in memory), SV_Position in the pixel shader is
// the pixel centre (x + 0.5, y + 0.5) in render-target pixels (not relative to the viewport), and
// MinDepth/MaxDepth map NDC depth z to MinDepth + z * (MaxDepth - MinDepth). Coverage is exact
// (0 pixels); SV_Position.xy is exactly representable (0 abs error); the depth mapping is one
// float32 multiply and add, so 1 ulp (the ordering D3D11 leaves open: fused or not).
#include <algorithm>
#include <cmath>

#include "render-helpers.h"

namespace sp::conformance {
namespace {

const char* kGroup = "Rasterization";

const char* kShaders = R"(
cbuffer Color : register(b0) { float4 color; };
float4 PSColor(float4 p : SV_Position) : SV_Target { return color; }
float4 PSPosition(float4 p : SV_Position) : SV_Target { return p; }
)";

struct Fixture {
  Device& device;
  DeviceContext& ctx;
  Ref<Texture2D> target;
  Ref<RenderTargetView> rtv;
  Ref<PixelShader> color, position;
  Ref<Buffer> cb;
  PixelDrawer drawer;

  Fixture(Device& d, uint32_t w, uint32_t h, FORMAT f) : device(d), ctx(*d.GetImmediateContext()), drawer(d) {
    target = gpu::MakeTexture2D(d, w, h, f, BIND_RENDER_TARGET);
    rtv = d.CreateRenderTargetView(target.get());
    color = d.CreatePixelShader(gpu::CompileInline(kShaders, "conformance/viewport.hlsl", "ps_5_0", "PSColor"));
    position = d.CreatePixelShader(gpu::CompileInline(kShaders, "conformance/viewport.hlsl", "ps_5_0", "PSPosition"));
    cb = gpu::MakeBuffer(d, BIND_CONSTANT_BUFFER, nullptr, 16);
  }
  void Bind(DepthStencilView* dsv = nullptr) {
    RenderTargetView* rtvs[] = {rtv.get()};
    ctx.OMSetRenderTargets(1, rtvs, dsv);
  }
  void SetColor(float r, float g, float b, float a) {
    const float c[4] = {r, g, b, a};
    ctx.UpdateSubresource(cb.get(), 0, nullptr, c, 0, 0);
    ctx.PSSetConstantBuffers(0, {cb.get()});
    ctx.PSSetShader(color.get());
  }
  // A triangle that covers the whole viewport (NDC x, y in [-1, 3]).
  void DrawViewport(const VIEWPORT& vp, float z = 0.5f) {
    std::vector<PixelVertex> big = {{0, 0, z}, {2 * vp.Width, 0, z}, {0, 2 * vp.Height, z}};
    drawer.Draw(ctx, big, vp.Width, vp.Height);
  }
};

Ref<RasterizerState> Rasterizer(Device& device, bool scissor) {
  RASTERIZER_DESC rd;
  rd.CullMode = CULL_NONE;
  rd.ScissorEnable = scissor;
  return device.CreateRasterizerState(rd);
}

}  // namespace

SP_PROBE(kGroup, "viewport offset and scissor rectangle count from the top-left",
         "a draw lands in viewport (4,2,16,8) cut by scissor (10,0)-(30,6), rows counted from the top; clears ignore the scissor") {
  const uint32_t W = 32, H = 16;
  Fixture f(device, W, H, FORMAT_R8G8B8A8_UNORM);
  int wrong = 0;
  std::string detail;
  for (bool scissor : {true, false}) {
    Ref<RasterizerState> rs = Rasterizer(device, scissor);
    f.Bind();
    f.ctx.RSSetState(rs.get());
    VIEWPORT vp{4, 2, 16, 8, 0, 1};
    f.ctx.RSSetViewports(1, &vp);
    RECT sc{10, 0, 30, 6};
    f.ctx.RSSetScissorRects(1, &sc);
    const float blue[4] = {0, 0, 1, 1};
    f.ctx.ClearRenderTargetView(f.rtv.get(), blue);  // D3D11 clears the whole view whatever the scissor
    f.SetColor(1, 1, 1, 1);
    f.DrawViewport(vp);
    std::vector<uint8_t> px = gpu::ReadTexture(device, f.ctx, f.target.get());
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x) {
        bool inViewport = x >= 4 && x < 20 && y >= 2 && y < 10;
        bool inScissor = x >= 10 && x < 30 && y < 6;
        bool drawn = inViewport && (!scissor || inScissor);
        const uint8_t* p = &px[(y * W + x) * 4];
        if (p[0] != (drawn ? 255 : 0) || p[2] != 255) {
          if (++wrong <= 3)
            detail += std::string(detail.empty() ? "" : "; ") + "pixel (" + std::to_string(x) + "," + std::to_string(y) + ") " +
                      (p[2] != 255 ? "not cleared" : drawn ? "not drawn" : "drawn") + (scissor ? " (scissor on)" : " (scissor off)");
        }
      }
  }
  if (wrong) return Fail(std::to_string(wrong) + " wrong pixels: " + detail, wrong, "pixels", 0);
  return Pass(0, "pixels", 0);
}

SP_PROBE(kGroup, "viewport with a fractional origin",
         "TopLeftX/Y = (2.5, 1.25) shift the viewport transform by exactly that; coverage then follows the top-left rule") {
  const uint32_t W = 32, H = 32;
  Fixture f(device, W, H, FORMAT_R32_FLOAT);
  Ref<RasterizerState> rs = Rasterizer(device, false);
  const float zero[4] = {0, 0, 0, 0};
  f.ctx.ClearRenderTargetView(f.rtv.get(), zero);
  f.Bind();
  f.ctx.RSSetState(rs.get());
  VIEWPORT vp{2.5f, 1.25f, 16, 16, 0, 1};
  f.ctx.RSSetViewports(1, &vp);
  f.SetColor(1, 0, 0, 0);
  // Triangles well inside the viewport, in viewport pixels; on the target they are shifted by the
  // origin, which puts some of their edges exactly on pixel centres.
  std::vector<PixelVertex> tris = {{1, 1.25}, {13, 1.25}, {1, 13.25}, {14, 2.25}, {15, 14.25}, {3, 15.25}};
  f.drawer.Draw(f.ctx, tris, 16, 16);
  std::vector<float> got = gpu::ReadAs<float>(gpu::ReadTexture(device, f.ctx, f.target.get()));
  std::vector<float> expected(W * H, 0.0f);
  for (size_t t = 0; t < tris.size(); t += 3) {
    std::array<double, 2> v[3];
    for (int i = 0; i < 3; ++i) v[i] = {tris[t + i].x + vp.TopLeftX, tris[t + i].y + vp.TopLeftY};
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x)
        if (D3DCovers(v[0], v[1], v[2], x + 0.5, y + 0.5)) expected[y * W + x] = 1.0f;
  }
  std::string detail;
  int wrong = CountMismatches(got, expected, W, &detail, "coverage");
  if (wrong) return Fail(std::to_string(wrong) + " wrong pixels: " + detail, wrong, "pixels", 0);
  return Pass(0, "pixels", 0);
}

SP_PROBE(kGroup, "SV_Position is the pixel centre from the top-left",
         "with a viewport at (3,5) the pixel shader sees SV_Position.xy = (x + 0.5, y + 0.5) of the render target") {
  const uint32_t W = 32, H = 16;
  Fixture f(device, W, H, FORMAT_R32G32B32A32_FLOAT);
  Ref<RasterizerState> rs = Rasterizer(device, false);
  const float clear[4] = {-1, -1, -1, -1};
  f.ctx.ClearRenderTargetView(f.rtv.get(), clear);
  f.Bind();
  f.ctx.RSSetState(rs.get());
  VIEWPORT vp{3, 5, 16, 8, 0, 1};
  f.ctx.RSSetViewports(1, &vp);
  f.ctx.PSSetShader(f.position.get());
  f.DrawViewport(vp);
  std::vector<float> px = gpu::ReadAs<float>(gpu::ReadTexture(device, f.ctx, f.target.get()));
  double worst = 0;
  std::string detail;
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      const float* p = &px[(y * W + x) * 4];
      bool inside = x >= 3 && x < 19 && y >= 5 && y < 13;
      double e = inside ? std::max(std::abs(p[0] - (x + 0.5)), std::abs(p[1] - (y + 0.5))) : (p[0] == -1 ? 0 : 1e9);
      if (e > worst) {
        worst = e;
        detail = "pixel (" + std::to_string(x) + "," + std::to_string(y) + "): SV_Position (" + std::to_string(p[0]) + ", " + std::to_string(p[1]) + ")";
      }
    }
  return Within(worst, 0.0, "abs", detail);
}

SP_PROBE(kGroup, "render to texture then sample keeps the D3D11 orientation",
         "a target written with SV_Position-derived texels and sampled back at the same pixel returns the same texels; UV (0,0) is row 0") {
  const char* src = R"(
Texture2D<float4> input : register(t0);
SamplerState pointSampler : register(s0);
float4 VSMain(uint id : SV_VertexID) : SV_Position {
  float2 p = float2((id << 1) & 2, id & 2);
  return float4(p * float2(2, -2) + float2(-1, 1), 0, 1);
}
float4 Pattern(float4 p : SV_Position) : SV_Target { return float4(floor(p.x) / 255.0, floor(p.y) / 255.0, 0, 1); }
float4 Copy(float4 p : SV_Position) : SV_Target { return input.Sample(pointSampler, p.xy / float2(16, 8)); }
)";
  DeviceContext& ctx = *device.GetImmediateContext();
  Ref<VertexShader> vs = device.CreateVertexShader(gpu::CompileInline(src, "conformance/orientation.hlsl", "vs_5_0", "VSMain"));
  Ref<PixelShader> pattern = device.CreatePixelShader(gpu::CompileInline(src, "conformance/orientation.hlsl", "ps_5_0", "Pattern"));
  Ref<PixelShader> copy = device.CreatePixelShader(gpu::CompileInline(src, "conformance/orientation.hlsl", "ps_5_0", "Copy"));
  Ref<Texture2D> a = gpu::MakeTexture2D(device, 16, 8, FORMAT_R8G8B8A8_UNORM, BIND_RENDER_TARGET | BIND_SHADER_RESOURCE);
  Ref<Texture2D> b = gpu::MakeTexture2D(device, 16, 8, FORMAT_R8G8B8A8_UNORM, BIND_RENDER_TARGET);
  Ref<RenderTargetView> rtvA = device.CreateRenderTargetView(a.get());
  Ref<RenderTargetView> rtvB = device.CreateRenderTargetView(b.get());
  Ref<ShaderResourceView> srvA = device.CreateShaderResourceView(a.get());
  Ref<SamplerState> point = MakeSampler(device, FILTER_MIN_MAG_MIP_POINT);
  VIEWPORT vp{0, 0, 16, 8, 0, 1};
  ctx.RSSetViewports(1, &vp);
  ctx.IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  ctx.VSSetShader(vs.get());
  RenderTargetView* t1[] = {rtvA.get()};
  ctx.OMSetRenderTargets(1, t1, nullptr);
  ctx.PSSetShader(pattern.get());
  ctx.Draw(3, 0);
  RenderTargetView* t2[] = {rtvB.get()};
  ctx.OMSetRenderTargets(1, t2, nullptr);
  ctx.PSSetShader(copy.get());
  ctx.PSSetShaderResources(0, {srvA.get()});
  ctx.PSSetSamplers(0, {point.get()});
  ctx.Draw(3, 0);
  std::vector<uint8_t> pa = gpu::ReadTexture(device, ctx, a.get());
  std::vector<uint8_t> pb = gpu::ReadTexture(device, ctx, b.get());
  int wrong = 0;
  std::string detail;
  for (uint32_t y = 0; y < 8; ++y)
    for (uint32_t x = 0; x < 16; ++x) {
      size_t i = (y * 16 + x) * 4;
      bool ok = pa[i] == x && pa[i + 1] == y && pb[i] == pa[i] && pb[i + 1] == pa[i + 1];
      if (!ok && ++wrong <= 3)
        detail += " pixel (" + std::to_string(x) + "," + std::to_string(y) + ") rendered (" + std::to_string(pa[i]) + "," + std::to_string(pa[i + 1]) +
                  ") sampled (" + std::to_string(pb[i]) + "," + std::to_string(pb[i + 1]) + ")";
    }
  if (wrong) return Fail(std::to_string(wrong) + " wrong pixels:" + detail, wrong, "pixels", 0);
  return Pass(0, "pixels", 0);
}

SP_PROBE(kGroup, "viewport MinDepth/MaxDepth map depth",
         "NDC z lands at MinDepth + z * (MaxDepth - MinDepth) in the depth buffer and in SV_Position.z") {
  const uint32_t W = 32, H = 8;
  Fixture f(device, W, H, FORMAT_R32G32B32A32_FLOAT);
  Ref<Texture2D> depth = gpu::MakeTexture2D(device, W, H, FORMAT_D32_FLOAT, BIND_DEPTH_STENCIL);
  Ref<DepthStencilView> dsv = device.CreateDepthStencilView(depth.get());
  DEPTH_STENCIL_DESC dd;
  dd.DepthFunc = COMPARISON_ALWAYS;
  Ref<DepthStencilState> ds = device.CreateDepthStencilState(dd);
  Ref<RasterizerState> rs = Rasterizer(device, false);
  const float ranges[][2] = {{0.25f, 0.75f}, {0.1f, 0.3f}, {0.5f, 0.5f}, {0.0f, 1.0f}, {0.6f, 0.9f}};
  const float zs[] = {0.0f, 0.2f, 0.5f, 0.7f, 0.9f, 1.0f, 0.3333333f, 0.123456f};  // one constant-depth column band each
  double worst = 0;
  std::string detail;
  for (const auto& r : ranges) {
    f.ctx.ClearDepthStencilView(dsv.get(), CLEAR_DEPTH, 1.0f, 0);
    f.Bind(dsv.get());
    f.ctx.OMSetDepthStencilState(ds.get(), 0);
    f.ctx.RSSetState(rs.get());
    VIEWPORT vp{0, 0, float(W), float(H), r[0], r[1]};
    f.ctx.RSSetViewports(1, &vp);
    f.ctx.PSSetShader(f.position.get());
    std::vector<PixelVertex> bands;
    for (size_t i = 0; i < std::size(zs); ++i) {
      double x0 = 4.0 * i, x1 = x0 + 4;
      bands.insert(bands.end(), {{x0, 0, zs[i]}, {x1, 0, zs[i]}, {x0, double(H), zs[i]}, {x1, 0, zs[i]}, {x1, double(H), zs[i]}, {x0, double(H), zs[i]}});
    }
    f.drawer.Draw(f.ctx, bands, W, H);
    std::vector<float> z = gpu::ReadAs<float>(gpu::ReadTexture(device, f.ctx, depth.get()));
    std::vector<float> pos = gpu::ReadAs<float>(gpu::ReadTexture(device, f.ctx, f.target.get()));
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x) {
        // D3D11's float32 viewport transform; the 1 ulp tolerance covers a fused multiply-add.
        double expected = float(r[0] + float(zs[x / 4] * float(r[1] - r[0])));
        for (float got : {z[y * W + x], pos[(y * W + x) * 4 + 2]}) {
          double e = std::abs(got - expected) / FloatUlp(expected);
          if (e > worst) {
            worst = e;
            detail = "range [" + std::to_string(r[0]) + ", " + std::to_string(r[1]) + "], z " + std::to_string(zs[x / 4]) + ": got " +
                     std::to_string(got) + ", D3D11 " + std::to_string(expected);
          }
        }
      }
  }
  return Within(worst, 1.0, "ulp", detail);
}

SP_PROBE(kGroup, "several viewports: without SV_ViewportArrayIndex everything uses viewport 0",
         "with two viewports and two scissor rectangles set, a draw uses only viewport 0 and scissor 0") {
  const uint32_t W = 32, H = 16;
  Fixture f(device, W, H, FORMAT_R32_FLOAT);
  Ref<RasterizerState> rs = Rasterizer(device, true);
  const float zero[4] = {0, 0, 0, 0};
  f.ctx.ClearRenderTargetView(f.rtv.get(), zero);
  f.Bind();
  f.ctx.RSSetState(rs.get());
  VIEWPORT vps[2] = {{2, 1, 8, 8, 0, 1}, {16, 4, 16, 8, 0, 1}};
  f.ctx.RSSetViewports(2, vps);
  RECT scs[2] = {{0, 3, 32, 16}, {0, 0, 32, 16}};
  f.ctx.RSSetScissorRects(2, scs);
  f.SetColor(1, 0, 0, 0);
  f.DrawViewport(vps[0]);
  std::vector<float> got = gpu::ReadAs<float>(gpu::ReadTexture(device, f.ctx, f.target.get()));
  std::vector<float> expected(W * H, 0.0f);
  for (uint32_t y = 3; y < 9; ++y)
    for (uint32_t x = 2; x < 10; ++x) expected[y * W + x] = 1.0f;
  std::string detail;
  int wrong = CountMismatches(got, expected, W, &detail, "coverage");
  if (wrong) return Fail(std::to_string(wrong) + " wrong pixels: " + detail, wrong, "pixels", 0);
  return Pass(0, "pixels", 0);
}

}  // namespace sp::conformance
