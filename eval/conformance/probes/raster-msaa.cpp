// 4x MSAA rasterization at D3D11's standard sample positions (-2,-6), (6,-2), (-6,2), (2,6) in
// 1/16 pixel from the pixel centre (D3D11 functional spec, "Multisample Standard Sample
// Patterns"): each sample is covered by the top-left rule applied at its own position. In D3D10.1
// and later MultisampleEnable no longer affects triangles (it only picks the line algorithm), so
// coverage is per sample whatever its value. Samples are read back one by one with
// Texture2DMS.Load. Vertices lie on the 1/16 grid (within D3D11's 8 sub-pixel bits), several edges
// pass exactly through sample positions so the tie rule is exercised; coverage is exact, the
// tolerance is 0 samples.
#include "render-helpers.h"

namespace sp::conformance {
namespace {

const char* kGroup = "Rasterization";
constexpr uint32_t W = 32, H = 16;

using Tri = std::array<PixelVertex, 3>;

const char* kLoadCS = R"(
Texture2DMS<float> ms : register(t0);
RWStructuredBuffer<float4> output : register(u0);
[numthreads(64, 1, 1)] void main(uint3 i : SV_DispatchThreadID) {
  uint pixel = i.x / 4, s = i.x % 4;
  output[i.x] = float4(ms.Load(int2(pixel % 32, pixel / 32), s), 0, 0, 0);
}
)";

const char* kShaders = R"(
float4 PSCount(float4 p : SV_Position) : SV_Target { return float4(1, 0, 0, 0); }
// SV_Coverage in an input struct (a scalar parameter works too: the toolchain rewrites it into one,
// since glslang 12 does not connect it).
struct CoverageIn { float4 p : SV_Position; uint coverage : SV_Coverage; };
float4 PSCoverage(CoverageIn i) : SV_Target { return float4(i.coverage, 0, 0, 0); }
float4 PSSampleIndex(float4 p : SV_Position, uint s : SV_SampleIndex) : SV_Target { return float4(s + 1, 0, 0, 0); }
)";

// Triangles on the left half share edges (each sample covered once); the right half is a fan
// around a vertex placed on sample 0 of pixel (24, 8).
std::vector<Tri> Mesh() {
  const PixelVertex a{1.375, 1.625}, b{14.625, 2.125}, c{13.875, 14.375}, d{2.125, 13.625}, m{8.125, 7.875};
  std::vector<Tri> tris = {{{a, b, m}}, {{b, c, m}}, {{c, d, m}}, {{d, a, m}}};
  const PixelVertex hub{24.5 - 2.0 / 16, 8.5 - 6.0 / 16};
  const PixelVertex ring[] = {{18.375, 2.125}, {24.375, 1.625}, {30.625, 2.5}, {30.125, 8.625}, {29.875, 14.375}, {24.625, 14.125}, {18.5, 13.875}, {17.875, 8.125}};
  for (int i = 0; i < 8; ++i) tris.push_back({{hub, ring[i], ring[(i + 1) % 8]}});
  // A sliver whose vertical edges pass through sample 0 (x - 2/16) and sample 1 (x + 6/16) of
  // their columns, away from the mesh (rows 0 and 15 are left free by the shapes above).
  tris.push_back({{{3.375, 0.0}, {10.875, 0.0}, {3.375, 1.0}}});
  tris.push_back({{{20.875, 15.0}, {27.375, 15.0}, {27.375, 16.0}}});
  return tris;
}

bool Covers(const Tri& t, uint32_t x, uint32_t y, int s) {
  return D3DCovers({t[0].x, t[0].y}, {t[1].x, t[1].y}, {t[2].x, t[2].y}, x + 0.5 + kStandard4x[s][0] / 16.0, y + 0.5 + kStandard4x[s][1] / 16.0);
}

enum class Output { Count, Coverage, SampleIndex };

// Draws the mesh into a 4x R32_FLOAT target and returns every sample (pixel-major, 4 per pixel).
std::vector<float> DrawSamples(Device& device, Output what, bool multisampleEnable) {
  DeviceContext& ctx = *device.GetImmediateContext();
  Ref<Texture2D> ms = gpu::MakeTexture2D(device, W, H, FORMAT_R32_FLOAT, BIND_RENDER_TARGET | BIND_SHADER_RESOURCE, nullptr, 1, 1, 4);
  Ref<RenderTargetView> rtv = device.CreateRenderTargetView(ms.get());
  Ref<ShaderResourceView> srv = device.CreateShaderResourceView(ms.get());
  const char* entry = what == Output::Count ? "PSCount" : what == Output::Coverage ? "PSCoverage" : "PSSampleIndex";
  Ref<PixelShader> ps = device.CreatePixelShader(gpu::CompileInline(kShaders, "conformance/msaa-raster.hlsl", "ps_5_0", entry));
  BLEND_DESC bd;
  bd.RenderTarget[0].BlendEnable = what == Output::Count;
  bd.RenderTarget[0].SrcBlend = BLEND_ONE;
  bd.RenderTarget[0].DestBlend = BLEND_ONE;
  Ref<BlendState> blend = device.CreateBlendState(bd);
  RASTERIZER_DESC rd;
  rd.CullMode = CULL_NONE;
  rd.MultisampleEnable = multisampleEnable;
  Ref<RasterizerState> rs = device.CreateRasterizerState(rd);
  const float zero[4] = {0, 0, 0, 0};
  ctx.ClearRenderTargetView(rtv.get(), zero);
  RenderTargetView* rtvs[] = {rtv.get()};
  ctx.OMSetRenderTargets(1, rtvs, nullptr);
  ctx.OMSetBlendState(blend.get(), nullptr, 0xffffffffu);
  ctx.RSSetState(rs.get());
  VIEWPORT vp{0, 0, float(W), float(H), 0, 1};
  ctx.RSSetViewports(1, &vp);
  ctx.PSSetShader(ps.get());
  std::vector<PixelVertex> flat;
  for (const Tri& t : Mesh()) flat.insert(flat.end(), t.begin(), t.end());
  PixelDrawer(device).Draw(ctx, flat, W, H);
  ctx.OMSetRenderTargets(0, nullptr, nullptr);
  std::vector<std::array<float, 4>> r = RunCompute(device, kLoadCS, "conformance/msaa-load.hlsl", W * H * 4, {srv.get()}, {}, W * H * 4 / 64);
  std::vector<float> out;
  for (auto& v : r) out.push_back(v[0]);
  return out;
}

Result Compare(const std::vector<float>& got, const std::vector<float>& expected, const char* what) {
  int wrong = 0;
  std::string detail;
  for (size_t i = 0; i < expected.size(); ++i) {
    if (got[i] == expected[i]) continue;
    if (++wrong <= 3)
      detail += std::string(detail.empty() ? "" : "; ") + "pixel (" + std::to_string(i / 4 % W) + "," + std::to_string(i / 4 / W) + ") sample " +
                std::to_string(i % 4) + ": " + what + " " + std::to_string(got[i]) + ", D3D11 " + std::to_string(expected[i]);
  }
  if (wrong) return Fail(std::to_string(wrong) + " samples differ from D3D11's standard-pattern coverage; " + detail, wrong, "samples", 0);
  return Pass(0, "samples", 0);
}

Result CheckCoverage(Device& device, bool multisampleEnable) {
  if (!device.CheckMultisampleQualityLevels(FORMAT_R32_FLOAT, 4)) return Unsupported("the driver has no 4x MSAA for R32_FLOAT");
  std::vector<float> got = DrawSamples(device, Output::Count, multisampleEnable);
  std::vector<float> expected(W * H * 4, 0.0f);
  for (const Tri& t : Mesh())
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x)
        for (int s = 0; s < 4; ++s)
          if (Covers(t, x, y, s)) expected[(y * W + x) * 4 + s] += 1;
  return Compare(got, expected, "hits");
}

}  // namespace

SP_PROBE(kGroup, "MSAA 4x: per-sample coverage at the standard positions",
         "each of 4 samples is covered by the top-left rule at (-2,-6), (6,-2), (-6,2), (2,6)/16; shared edges cover each sample once") {
  return CheckCoverage(device, false);
}

SP_PROBE(kGroup, "MSAA 4x: MultisampleEnable TRUE does not change triangle coverage",
         "since D3D10.1 MultisampleEnable only selects the line algorithm; triangles stay multisampled") {
  return CheckCoverage(device, true);
}

SP_PROBE(kGroup, "MSAA 4x: SV_Coverage is the primitive's sample mask",
         "the pixel shader's SV_Coverage input has bit s set exactly when the triangle covers sample s of the pixel") {
  if (!device.CheckMultisampleQualityLevels(FORMAT_R32_FLOAT, 4)) return Unsupported("the driver has no 4x MSAA for R32_FLOAT");
  std::vector<float> got = DrawSamples(device, Output::Coverage, false);
  std::vector<float> expected(W * H * 4, 0.0f);
  for (const Tri& t : Mesh())
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x) {
        uint32_t mask = 0;
        for (int s = 0; s < 4; ++s) mask |= Covers(t, x, y, s) ? 1u << s : 0u;
        for (int s = 0; s < 4; ++s)
          if (mask & (1u << s)) expected[(y * W + x) * 4 + s] = float(mask);
      }
  return Compare(got, expected, "SV_Coverage");
}

SP_PROBE(kGroup, "MSAA 4x: SV_SampleIndex runs the pixel shader per sample",
         "a pixel shader reading SV_SampleIndex runs once per covered sample and writes only that sample") {
  if (!device.CheckMultisampleQualityLevels(FORMAT_R32_FLOAT, 4)) return Unsupported("the driver has no 4x MSAA for R32_FLOAT");
  std::vector<float> got = DrawSamples(device, Output::SampleIndex, false);
  std::vector<float> expected(W * H * 4, 0.0f);
  for (const Tri& t : Mesh())
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x)
        for (int s = 0; s < 4; ++s)
          if (Covers(t, x, y, s)) expected[(y * W + x) * 4 + s] = float(s + 1);
  return Compare(got, expected, "SV_SampleIndex + 1");
}

SP_PROBE(kGroup, "MSAA 4x: Texture2DMS.GetSamplePosition returns the standard positions",
         "GetSamplePosition(s) of a 4x texture is (-2,-6), (6,-2), (-6,2), (2,6) / 16") {
  if (!device.CheckMultisampleQualityLevels(FORMAT_R32_FLOAT, 4)) return Unsupported("the driver has no 4x MSAA for R32_FLOAT");
  Ref<Texture2D> ms = gpu::MakeTexture2D(device, 4, 4, FORMAT_R32_FLOAT, BIND_RENDER_TARGET | BIND_SHADER_RESOURCE, nullptr, 1, 1, 4);
  Ref<ShaderResourceView> srv = device.CreateShaderResourceView(ms.get());
  const char* cs = R"(
Texture2DMS<float> ms : register(t0);
RWStructuredBuffer<float4> output : register(u0);
[numthreads(4, 1, 1)] void main(uint3 i : SV_DispatchThreadID) { output[i.x] = float4(ms.GetSamplePosition(i.x), 0, 0); }
)";
  std::vector<std::array<float, 4>> r = RunCompute(device, cs, "conformance/sample-position.hlsl", 4, {srv.get()});
  double worst = 0;
  std::string detail;
  for (int s = 0; s < 4; ++s) {
    double e = std::max(std::abs(r[s][0] - kStandard4x[s][0] / 16.0), std::abs(r[s][1] - kStandard4x[s][1] / 16.0));
    if (e > worst) {
      worst = e;
      detail = "sample " + std::to_string(s) + ": (" + std::to_string(r[s][0]) + ", " + std::to_string(r[s][1]) + ")";
    }
  }
  return Within(worst, 0.0, "pixels", detail);
}

}  // namespace sp::conformance
