// Multisampled resources at 4x: Texture2DMS.Load of every colour and depth sample,
// ResolveSubresource of colour, and a depth "resolve" done in a shader (D3D11 cannot resolve depth
// with ResolveSubresource).
// - Colour: four draws with sample masks 1, 2, 4, 8 write a different known value into each
//   sample, so Load(p, s) must return exactly the value written to sample s (tolerance 0 codes).
// - Depth: one draw of a sloped plane; D3D11 evaluates depth at each sample's standard position
//   ((-2,-6), (6,-2), (-6,2), (2,6) / 16), so sample s holds the plane there. Plane values are
//   exact in float32; the tolerance is 2 ulp for the rasterizer's interpolation (as the depth clip
//   probes).
// - ResolveSubresource averages the samples; D3D11 does not fix the rounding of the average, so
//   UNORM may differ by 1 LSB from the exact mean, float by 1 ulp.
#include <algorithm>
#include <cmath>

#include "render-helpers.h"

namespace sp::conformance {
namespace {

const char* kGroup = "Resources";
constexpr uint32_t W = 16, H = 8;

const char* kDrawPS = R"(
cbuffer Pass : register(b0) { uint sampleIndex; uint3 pad; };
// An 8-bit code per channel that differs per pixel, channel and sample.
uint4 Codes(float2 p, uint s) { uint2 q = uint2(p); return (q.x * 17 + q.y * 29 + s * 61 + uint4(0, 13, 101, 211)) % 256; }
float4 PSCodes(float4 p : SV_Position) : SV_Target { return float4(Codes(p.xy, sampleIndex)) / 255.0; }
// Float values that are exact in float32 and in their average.
float4 PSFloats(float4 p : SV_Position) : SV_Target { return float4(Codes(p.xy, sampleIndex)) / 64.0 - 1.0; }
)";

const char* kLoadColourCS = R"(
Texture2DMS<float4> colour : register(t0);
RWStructuredBuffer<float4> output : register(u0);
[numthreads(64, 1, 1)] void main(uint3 i : SV_DispatchThreadID) {
  uint pixel = i.x / 4;
  output[i.x] = colour.Load(int2(pixel % 16, pixel / 16), i.x % 4);
}
)";

const char* kLoadDepthCS = R"(
Texture2DMS<float> depth : register(t0);
RWStructuredBuffer<float4> output : register(u0);
[numthreads(64, 1, 1)] void main(uint3 i : SV_DispatchThreadID) {
  uint pixel = i.x / 4;
  output[i.x] = float4(depth.Load(int2(pixel % 16, pixel / 16), i.x % 4), 0, 0, 0);
}
)";

const char* kResolveDepthPS = R"(
Texture2DMS<float> depth : register(t0);
struct Resolved { float minimum : SV_Target0; float maximum : SV_Target1; float first : SV_Target2; };
Resolved main(float4 p : SV_Position) {
  Resolved o;
  int2 q = int2(p.xy);
  o.first = depth.Load(q, 0);
  o.minimum = o.first;
  o.maximum = o.first;
  [unroll] for (int s = 1; s < 4; ++s) {
    float d = depth.Load(q, s);
    o.minimum = min(o.minimum, d);
    o.maximum = max(o.maximum, d);
  }
  return o;
}
)";

uint32_t Code(uint32_t x, uint32_t y, uint32_t s, uint32_t c) {
  const uint32_t off[4] = {0, 13, 101, 211};
  return (x * 17 + y * 29 + s * 61 + off[c]) % 256;
}

// A 4x colour texture whose sample s holds the pixel shader `entry` run with sampleIndex = s.
Ref<Texture2D> DrawPerSample(Device& device, FORMAT format, const char* entry) {
  DeviceContext& ctx = *device.GetImmediateContext();
  Ref<Texture2D> ms = gpu::MakeTexture2D(device, W, H, format, BIND_RENDER_TARGET | BIND_SHADER_RESOURCE, nullptr, 1, 1, 4);
  Ref<RenderTargetView> rtv = device.CreateRenderTargetView(ms.get());
  Ref<PixelShader> ps = device.CreatePixelShader(gpu::CompileInline(kDrawPS, "conformance/msaa-draw.hlsl", "ps_5_0", entry));
  Ref<Buffer> cb = gpu::MakeBuffer(device, BIND_CONSTANT_BUFFER, nullptr, 16);
  const float zero[4] = {0, 0, 0, 0};
  ctx.ClearRenderTargetView(rtv.get(), zero);
  RenderTargetView* rtvs[] = {rtv.get()};
  ctx.OMSetRenderTargets(1, rtvs, nullptr);
  VIEWPORT vp{0, 0, float(W), float(H), 0, 1};
  ctx.RSSetViewports(1, &vp);
  ctx.PSSetShader(ps.get());
  ctx.PSSetConstantBuffers(0, {cb.get()});
  PixelDrawer drawer(device);
  for (uint32_t s = 0; s < 4; ++s) {
    uint32_t c[4] = {s, 0, 0, 0};
    ctx.UpdateSubresource(cb.get(), 0, nullptr, c, 0, 0);
    ctx.OMSetBlendState(nullptr, nullptr, 1u << s);
    drawer.Draw(ctx, {{0, 0}, {2.0 * W, 0}, {0, 2.0 * H}}, W, H);
  }
  ctx.OMSetBlendState(nullptr, nullptr, 0xffffffffu);
  ctx.OMSetRenderTargets(0, nullptr, nullptr);
  return ms;
}

// The sloped depth plane of the depth probes, in window pixels.
double Plane(double x, double y) { return 0.25 + x / 64 + y / 32; }

// A 4x R32_TYPELESS depth texture holding the plane, drawn through a D32_FLOAT DSV.
Ref<Texture2D> DrawDepthPlane(Device& device) {
  DeviceContext& ctx = *device.GetImmediateContext();
  Ref<Texture2D> tex = gpu::MakeTexture2D(device, W, H, FORMAT_R32_TYPELESS, BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE, nullptr, 1, 1, 4);
  DEPTH_STENCIL_VIEW_DESC dd;
  dd.Format = FORMAT_D32_FLOAT;
  dd.ViewDimension = DSV_DIMENSION_TEXTURE2DMS;
  Ref<DepthStencilView> dsv = device.CreateDepthStencilView(tex.get(), &dd);
  DEPTH_STENCIL_DESC ds;
  ds.DepthFunc = COMPARISON_ALWAYS;
  Ref<DepthStencilState> state = device.CreateDepthStencilState(ds);
  ctx.ClearDepthStencilView(dsv.get(), CLEAR_DEPTH, 1.0f, 0);
  ctx.OMSetRenderTargets(0, nullptr, dsv.get());
  ctx.OMSetDepthStencilState(state.get(), 0);
  VIEWPORT vp{0, 0, float(W), float(H), 0, 1};
  ctx.RSSetViewports(1, &vp);
  ctx.PSSetShader(nullptr);
  const double X = 2.0 * W, Y = 2.0 * H;
  PixelDrawer(device).Draw(ctx, {{0, 0, float(Plane(0, 0))}, {X, 0, float(Plane(X, 0))}, {0, Y, float(Plane(0, Y))}}, W, H);
  ctx.OMSetRenderTargets(0, nullptr, nullptr);
  return tex;
}

double SamplePlane(uint32_t x, uint32_t y, int s) { return Plane(x + 0.5 + kStandard4x[s][0] / 16.0, y + 0.5 + kStandard4x[s][1] / 16.0); }

bool Has4x(Device& device, FORMAT f) { return device.CheckMultisampleQualityLevels(f, 4) > 0; }

}  // namespace

SP_PROBE(kGroup, "Texture2DMS.Load reads each colour sample (4x)",
         "after draws with sample masks 1, 2, 4, 8, Load(p, s) returns exactly what was written to sample s") {
  if (!Has4x(device, FORMAT_R8G8B8A8_UNORM)) return Unsupported("the driver has no 4x MSAA for R8G8B8A8_UNORM");
  Ref<Texture2D> ms = DrawPerSample(device, FORMAT_R8G8B8A8_UNORM, "PSCodes");
  Ref<ShaderResourceView> srv = device.CreateShaderResourceView(ms.get());
  std::vector<std::array<float, 4>> r = RunCompute(device, kLoadColourCS, "conformance/msaa-load-colour.hlsl", W * H * 4, {srv.get()}, {}, W * H * 4 / 64);
  double worst = 0;
  std::string detail;
  for (uint32_t i = 0; i < W * H * 4; ++i)
    for (uint32_t c = 0; c < 4; ++c) {
      uint32_t x = i / 4 % W, y = i / 4 / W, s = i % 4;
      double e = std::abs(double(r[i][c]) * 255.0 - Code(x, y, s, c));
      if (e > worst) {
        worst = e;
        detail = "pixel (" + std::to_string(x) + "," + std::to_string(y) + ") sample " + std::to_string(s) + " channel " + std::to_string(c) + ": " +
                 std::to_string(r[i][c] * 255.0) + ", written " + std::to_string(Code(x, y, s, c));
      }
    }
  // Load returns code / 255; 0.01 LSB only absorbs the float division (the code itself is exact).
  return Within(worst, 0.01, "LSB", detail);
}

SP_PROBE(kGroup, "Texture2DMS.Load reads each depth sample (4x R32_TYPELESS, D32_FLOAT DSV, R32_FLOAT SRV)",
         "a sloped plane drawn through a 4x D32_FLOAT view holds in sample s the plane at sample s's standard position") {
  if (!Has4x(device, FORMAT_D32_FLOAT)) return Unsupported("the driver has no 4x MSAA for D32_FLOAT");
  Ref<Texture2D> tex = DrawDepthPlane(device);
  Ref<ShaderResourceView> srv = MakeSrv(device, tex.get(), FORMAT_R32_FLOAT, SRV_DIMENSION_TEXTURE2DMS);
  std::vector<std::array<float, 4>> r = RunCompute(device, kLoadDepthCS, "conformance/msaa-load-depth.hlsl", W * H * 4, {srv.get()}, {}, W * H * 4 / 64);
  double worst = 0;
  std::string detail;
  for (uint32_t i = 0; i < W * H * 4; ++i) {
    uint32_t x = i / 4 % W, y = i / 4 / W;
    int s = int(i % 4);
    double expected = SamplePlane(x, y, s);
    double e = std::abs(r[i][0] - expected) / FloatUlp(expected);
    if (e > worst) {
      worst = e;
      detail = "pixel (" + std::to_string(x) + "," + std::to_string(y) + ") sample " + std::to_string(s) + ": " + std::to_string(r[i][0]) + ", D3D11 " +
               std::to_string(expected) + " (pixel centre " + std::to_string(Plane(x + 0.5, y + 0.5)) + ")";
    }
  }
  return Within(worst, 2.0, "ulp", detail);
}

SP_PROBE(kGroup, "ResolveSubresource averages 4 colour samples (R8G8B8A8_UNORM, R32G32B32A32_FLOAT)",
         "the resolved texel is the mean of the four samples: within 1 LSB for UNORM, 1 ulp for float") {
  DeviceContext& ctx = *device.GetImmediateContext();
  double worstUnorm = 0, worstFloat = 0;
  std::string detail;
  for (FORMAT f : {FORMAT_R8G8B8A8_UNORM, FORMAT_R32G32B32A32_FLOAT}) {
    if (!Has4x(device, f)) return Unsupported(std::string("the driver has no 4x MSAA for ") + std::string(FormatName(f)));
    bool unorm = f == FORMAT_R8G8B8A8_UNORM;
    Ref<Texture2D> ms = DrawPerSample(device, f, unorm ? "PSCodes" : "PSFloats");
    Ref<Texture2D> resolved = gpu::MakeTexture2D(device, W, H, f, BIND_SHADER_RESOURCE);
    ctx.ResolveSubresource(resolved.get(), 0, ms.get(), 0, f);
    std::vector<uint8_t> raw = gpu::ReadTexture(device, ctx, resolved.get());
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x)
        for (uint32_t c = 0; c < 4; ++c) {
          double mean = 0;
          for (uint32_t s = 0; s < 4; ++s) mean += unorm ? Code(x, y, s, c) : Code(x, y, s, c) / 64.0 - 1.0;
          mean /= 4;
          double got, e;
          if (unorm) {
            got = raw[(y * W + x) * 4 + c];
            e = std::abs(got - mean);
            worstUnorm = std::max(worstUnorm, e);
          } else {
            got = gpu::ReadAs<float>(raw)[(y * W + x) * 4 + c];
            e = std::abs(got - mean) / FloatUlp(std::abs(mean));
            worstFloat = std::max(worstFloat, e);
          }
          if (e > 1.0 && detail.empty())
            detail = std::string(FormatName(f)) + " pixel (" + std::to_string(x) + "," + std::to_string(y) + ") channel " + std::to_string(c) + ": " +
                     std::to_string(got) + ", mean of the samples " + std::to_string(mean);
        }
  }
  if (worstFloat > 1.0) return Fail(detail, worstFloat, "ulp", 1.0);
  return Within(worstUnorm, 1.0, "LSB", detail);
}

SP_PROBE(kGroup, "depth resolve in a shader: min, max and sample 0 of 4x depth",
         "a pixel shader loading the four depth samples writes their min, max and sample 0 to single-sampled R32_FLOAT targets") {
  if (!Has4x(device, FORMAT_D32_FLOAT)) return Unsupported("the driver has no 4x MSAA for D32_FLOAT");
  DeviceContext& ctx = *device.GetImmediateContext();
  Ref<Texture2D> tex = DrawDepthPlane(device);
  Ref<ShaderResourceView> srv = MakeSrv(device, tex.get(), FORMAT_R32_FLOAT, SRV_DIMENSION_TEXTURE2DMS);
  Ref<PixelShader> ps = device.CreatePixelShader(gpu::CompileInline(kResolveDepthPS, "conformance/msaa-resolve-depth.hlsl", "ps_5_0", "main"));
  Ref<Texture2D> targets[3];
  Ref<RenderTargetView> rtvs[3];
  for (int i = 0; i < 3; ++i) {
    targets[i] = gpu::MakeTexture2D(device, W, H, FORMAT_R32_FLOAT, BIND_RENDER_TARGET);
    rtvs[i] = device.CreateRenderTargetView(targets[i].get());
  }
  RenderTargetView* bound[] = {rtvs[0].get(), rtvs[1].get(), rtvs[2].get()};
  ctx.OMSetRenderTargets(3, bound, nullptr);
  ctx.OMSetDepthStencilState(nullptr, 0);
  VIEWPORT vp{0, 0, float(W), float(H), 0, 1};
  ctx.RSSetViewports(1, &vp);
  ctx.PSSetShaderResources(0, {srv.get()});
  ctx.PSSetShader(ps.get());
  PixelDrawer(device).Draw(ctx, {{0, 0}, {2.0 * W, 0}, {0, 2.0 * H}}, W, H);
  const char* names[3] = {"min", "max", "sample 0"};
  double worst = 0;
  std::string detail;
  for (int i = 0; i < 3; ++i) {
    std::vector<float> got = gpu::ReadAs<float>(gpu::ReadTexture(device, ctx, targets[i].get()));
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x) {
        double v[4];
        for (int s = 0; s < 4; ++s) v[s] = SamplePlane(x, y, s);
        double expected = i == 0 ? *std::min_element(v, v + 4) : i == 1 ? *std::max_element(v, v + 4) : v[0];
        double e = std::abs(got[y * W + x] - expected) / FloatUlp(expected);
        if (e > worst) {
          worst = e;
          detail = std::string(names[i]) + " at pixel (" + std::to_string(x) + "," + std::to_string(y) + "): " + std::to_string(got[y * W + x]) +
                   ", D3D11 " + std::to_string(expected);
        }
      }
  }
  return Within(worst, 2.0, "ulp", detail);
}

}  // namespace sp::conformance
