// Bring-up and the basic D3D11 guarantees every other test relies on: the device starts with
// validation on, clears and readback work, rasterization follows D3D11's rules, and a texture
// rendered then sampled has the same memory layout on both backends.
#include <array>
#include <cmath>

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

// --- Rasterization: the D3D11 top-left rule, computed on the CPU.

struct Vec2 {
  double x, y;
};

// D3D11 coverage of pixel centres for a triangle given in pixel coordinates (y down), after
// putting it in clockwise order: inside if every edge function is > 0, or == 0 on a top or left
// edge.
bool D3DCovers(Vec2 a, Vec2 b, Vec2 c, double px, double py) {
  double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  if (area == 0) return false;
  if (area < 0) std::swap(b, c);
  Vec2 v[3] = {a, b, c};
  for (int i = 0; i < 3; ++i) {
    Vec2 p = v[i], q = v[(i + 1) % 3];
    double e = (q.x - p.x) * (py - p.y) - (q.y - p.y) * (px - p.x);
    bool top = q.y == p.y && q.x > p.x;
    bool left = q.y < p.y;
    if (e < 0 || (e == 0 && !top && !left)) return false;
  }
  return true;
}

const char* kPassThrough = R"(
float4 VSMain(float2 pos : POSITION) : SV_Position { return float4(pos, 0.5, 1); }
float4 PSMain(float4 p : SV_Position) : SV_Target { return float4(1, 0, 0, 0); }
)";

TEST_P(DeviceTest, TrianglesCoverExactlyTheD3D11Pixels) {
  const uint32_t W = 32, H = 32;
  // Pixel-space triangles with edges through pixel centres and shared edges, all vertices on
  // the 1/256 sub-pixel grid so snapping cannot change the answer.
  std::vector<std::array<Vec2, 3>> tris = {
      {{{2.5, 2.5}, {12.5, 2.5}, {2.5, 12.5}}},      // top and left edges on centres
      {{{12.5, 2.5}, {12.5, 12.5}, {2.5, 12.5}}},    // shares the diagonal with the first
      {{{16.0, 4.0}, {30.25, 9.5}, {18.75, 27.5}}},  // general position
      {{{20.5, 28.5}, {29.5, 28.5}, {29.5, 31.5}}},  // bottom-right region, horizontal top
  };
  std::vector<float> verts;
  for (auto& t : tris)
    for (Vec2 v : t) {
      verts.push_back(float(v.x / W * 2 - 1));
      verts.push_back(float(1 - v.y / H * 2));
    }
  Ref<Buffer> vb = MakeBuffer(device(), BIND_VERTEX_BUFFER, verts.data(), uint32_t(verts.size() * 4));
  ShaderBytecode vsb = CompileHlsl(kPassThrough, "vs_5_0", "VSMain");
  ShaderBytecode psb = CompileHlsl(kPassThrough, "ps_5_0", "PSMain");
  Ref<VertexShader> vs = device().CreateVertexShader(vsb);
  Ref<PixelShader> ps = device().CreatePixelShader(psb);
  INPUT_ELEMENT_DESC el{"POSITION", 0, FORMAT_R32G32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0};
  Ref<InputLayout> layout = device().CreateInputLayout(&el, 1, vsb);

  // Count hits per pixel with additive blending into R32_FLOAT: double hits show up as 2.
  Ref<Texture2D> target = MakeTexture2D(device(), W, H, FORMAT_R32_FLOAT, BIND_RENDER_TARGET);
  Ref<RenderTargetView> rtv = device().CreateRenderTargetView(target.get());
  BLEND_DESC bd;
  bd.RenderTarget[0].BlendEnable = true;
  bd.RenderTarget[0].SrcBlend = BLEND_ONE;
  bd.RenderTarget[0].DestBlend = BLEND_ONE;
  Ref<BlendState> blend = device().CreateBlendState(bd);
  RASTERIZER_DESC rd;
  rd.CullMode = CULL_NONE;
  Ref<RasterizerState> rs = device().CreateRasterizerState(rd);

  const float zero[4] = {0, 0, 0, 0};
  ctx().ClearRenderTargetView(rtv.get(), zero);
  RenderTargetView* rtvs[] = {rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, nullptr);
  ctx().OMSetBlendState(blend.get(), nullptr, 0xffffffff);
  ctx().RSSetState(rs.get());
  VIEWPORT vp{0, 0, float(W), float(H), 0, 1};
  ctx().RSSetViewports(1, &vp);
  ctx().IASetInputLayout(layout.get());
  ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  uint32_t stride = 8, offset = 0;
  Buffer* vbs[] = {vb.get()};
  ctx().IASetVertexBuffers(0, 1, vbs, &stride, &offset);
  ctx().VSSetShader(vs.get());
  ctx().PSSetShader(ps.get());
  ctx().Draw(uint32_t(verts.size() / 2), 0);

  std::vector<float> hits = ReadAs<float>(ReadTexture(device(), ctx(), target.get()));
  int mismatches = 0;
  for (uint32_t y = 0; y < H; ++y) {
    for (uint32_t x = 0; x < W; ++x) {
      int expected = 0;
      for (auto& t : tris) expected += D3DCovers(t[0], t[1], t[2], x + 0.5, y + 0.5) ? 1 : 0;
      float got = hits[y * W + x];
      if (got != float(expected)) {
        if (++mismatches < 10) ADD_FAILURE() << "pixel (" << x << ", " << y << "): covered " << got << " times, D3D11 rules say " << expected;
      }
    }
  }
  EXPECT_EQ(mismatches, 0);
}

// Render a pattern that depends on SV_Position, then sample the result in a second pass at the
// same pixel: row 0 must be the top on both backends, and UV (0,0) the first texel in memory.
TEST_P(DeviceTest, RenderToTextureThenSampleKeepsD3DOrientation) {
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
  ShaderBytecode vsb = CompileHlsl(src, "vs_5_0", "VSMain");
  Ref<VertexShader> vs = device().CreateVertexShader(vsb);
  Ref<PixelShader> pattern = device().CreatePixelShader(CompileHlsl(src, "ps_5_0", "Pattern"));
  Ref<PixelShader> copy = device().CreatePixelShader(CompileHlsl(src, "ps_5_0", "Copy"));
  Ref<Texture2D> a = MakeTexture2D(device(), 16, 8, FORMAT_R8G8B8A8_UNORM, BIND_RENDER_TARGET | BIND_SHADER_RESOURCE);
  Ref<Texture2D> b = MakeTexture2D(device(), 16, 8, FORMAT_R8G8B8A8_UNORM, BIND_RENDER_TARGET);
  Ref<RenderTargetView> rtvA = device().CreateRenderTargetView(a.get());
  Ref<RenderTargetView> rtvB = device().CreateRenderTargetView(b.get());
  Ref<ShaderResourceView> srvA = device().CreateShaderResourceView(a.get());
  SAMPLER_DESC sd;
  sd.Filter = FILTER_MIN_MAG_MIP_POINT;
  Ref<SamplerState> point = device().CreateSamplerState(sd);

  VIEWPORT vp{0, 0, 16, 8, 0, 1};
  ctx().RSSetViewports(1, &vp);
  ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  ctx().VSSetShader(vs.get());
  RenderTargetView* t1[] = {rtvA.get()};
  ctx().OMSetRenderTargets(1, t1, nullptr);
  ctx().PSSetShader(pattern.get());
  ctx().Draw(3, 0);

  RenderTargetView* t2[] = {rtvB.get()};
  ctx().OMSetRenderTargets(1, t2, nullptr);
  ctx().PSSetShader(copy.get());
  ctx().PSSetShaderResources(0, {srvA.get()});
  ctx().PSSetSamplers(0, {point.get()});
  ctx().Draw(3, 0);

  std::vector<uint8_t> pa = ReadTexture(device(), ctx(), a.get());
  std::vector<uint8_t> pb = ReadTexture(device(), ctx(), b.get());
  for (uint32_t y = 0; y < 8; ++y)
    for (uint32_t x = 0; x < 16; ++x) {
      size_t i = (y * 16 + x) * 4;
      // SV_Position is the pixel centre (x + 0.5, y + 0.5) with y = 0 at the top row in memory.
      EXPECT_EQ(pa[i + 0], x) << "x=" << x << " y=" << y;
      EXPECT_EQ(pa[i + 1], y) << "x=" << x << " y=" << y;
      EXPECT_EQ(pb[i + 0], pa[i + 0]);
      EXPECT_EQ(pb[i + 1], pa[i + 1]);
    }
}

SP_INSTANTIATE_BACKEND_TESTS(DeviceTest);

}  // namespace
}  // namespace sp::test
