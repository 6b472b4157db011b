// Fixed-function state with D3D11's rules: depth clipping and clamping, depth test and write
// mask, stencil per face, independent blending and write masks, blend factor, dual-source
// blending, and depth bias by D3D11's formula. Winding, culling, viewport and scissor are
// conformance probes (eval/conformance/probes/raster-*.cpp).
#include <cmath>

#include "rhi-test-util.h"

namespace sp::test {
namespace {

const char* kShaders = R"(
cbuffer Color : register(b0) { float4 color; float4 color1; };
float4 VSMain(float3 p : POSITION) : SV_Position { return float4(p, 1); }
float4 PSColor(float4 p : SV_Position) : SV_Target { return color; }
struct Two { float4 a : SV_Target0; float4 b : SV_Target1; };
Two PSTwo(float4 p : SV_Position) { Two o; o.a = color; o.b = color1; return o; }
)";

struct Vertex {
  float x, y, z;
};

class StateTest : public BackendTest {
 protected:
  void SetUp() override {
    BackendTest::SetUp();
    ShaderBytecode vsb = CompileHlsl(kShaders, "vs_5_0", "VSMain");
    vs_ = device().CreateVertexShader(vsb);
    INPUT_ELEMENT_DESC el{"POSITION", 0, FORMAT_R32G32B32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0};
    layout_ = device().CreateInputLayout(&el, 1, vsb);
    colorPs_ = device().CreatePixelShader(CompileHlsl(kShaders, "ps_5_0", "PSColor"));
    constants_ = MakeBuffer(device(), BIND_CONSTANT_BUFFER, nullptr, 32);
  }

  // Draws triangles given in pixel coordinates (y down) of a w x h target, z in NDC.
  void DrawPixels(const std::vector<Vertex>& pixels, float w, float h, PRIMITIVE_TOPOLOGY topology = PRIMITIVE_TOPOLOGY_TRIANGLELIST) {
    std::vector<Vertex> ndc;
    for (const Vertex& v : pixels) ndc.push_back({v.x / w * 2 - 1, 1 - v.y / h * 2, v.z});
    Ref<Buffer> vb = MakeBuffer(device(), BIND_VERTEX_BUFFER, ndc.data(), uint32_t(ndc.size() * sizeof(Vertex)));
    Buffer* vbs[] = {vb.get()};
    uint32_t stride = sizeof(Vertex), offset = 0;
    ctx().IASetVertexBuffers(0, 1, vbs, &stride, &offset);
    ctx().IASetInputLayout(layout_.get());
    ctx().IASetPrimitiveTopology(topology);
    ctx().VSSetShader(vs_.get());
    ctx().Draw(uint32_t(ndc.size()), 0);
  }

  void SetColor(float r, float g, float b, float a, std::array<float, 4> c1 = {0, 0, 0, 0}) {
    float c[8] = {r, g, b, a, c1[0], c1[1], c1[2], c1[3]};
    ctx().UpdateSubresource(constants_.get(), 0, nullptr, c, 0, 0);
    ctx().PSSetConstantBuffers(0, {constants_.get()});
  }

  Ref<VertexShader> vs_;
  Ref<InputLayout> layout_;
  Ref<PixelShader> colorPs_;
  Ref<Buffer> constants_;
};

// DepthClipEnable = FALSE keeps geometry beyond the far plane and clamps its depth to the
// viewport's MaxDepth; with clipping on it is dropped.
TEST_P(StateTest, DepthClipAndViewportClamp) {
  const uint32_t W = 8, H = 8;
  Target t = MakeTarget(device(), W, H, FORMAT_R8G8B8A8_UNORM);
  Ref<Texture2D> depth = MakeTexture2D(device(), W, H, FORMAT_D32_FLOAT, BIND_DEPTH_STENCIL);
  Ref<DepthStencilView> dsv = device().CreateDepthStencilView(depth.get());
  DEPTH_STENCIL_DESC dd;
  dd.DepthFunc = COMPARISON_ALWAYS;
  Ref<DepthStencilState> ds = device().CreateDepthStencilState(dd);
  for (bool clip : {true, false}) {
    RASTERIZER_DESC rd;
    rd.CullMode = CULL_NONE;
    rd.DepthClipEnable = clip;
    Ref<RasterizerState> rs = device().CreateRasterizerState(rd);
    const float zero[4] = {0, 0, 0, 0};
    ctx().ClearRenderTargetView(t.rtv.get(), zero);
    ctx().ClearDepthStencilView(dsv.get(), CLEAR_DEPTH, 0.25f, 0);
    RenderTargetView* rtvs[] = {t.rtv.get()};
    ctx().OMSetRenderTargets(1, rtvs, dsv.get());
    ctx().OMSetDepthStencilState(ds.get(), 0);
    ctx().RSSetState(rs.get());
    SetViewport(ctx(), W, H, 0.0f, 0.5f);
    ctx().PSSetShader(colorPs_.get());
    SetColor(1, 0, 0, 1);
    std::vector<Vertex> beyondFar = {{0, 0, 1.5f}, {16, 0, 1.5f}, {0, 16, 1.5f}};
    DrawPixels(beyondFar, W, H);
    std::vector<uint8_t> px = ReadTexture(device(), ctx(), t.texture.get());
    std::vector<float> z = ReadTextureAs<float>(device(), ctx(), depth.get());
    EXPECT_EQ(px[0], clip ? 0 : 255) << "clip " << clip;
    EXPECT_EQ(z[0], clip ? 0.25f : 0.5f) << "clip " << clip;
  }
}

TEST_P(StateTest, DepthTestAndWriteMask) {
  const uint32_t W = 8, H = 4;
  Target t = MakeTarget(device(), W, H, FORMAT_R32G32B32A32_FLOAT);
  Ref<Texture2D> depth = MakeTexture2D(device(), W, H, FORMAT_D32_FLOAT, BIND_DEPTH_STENCIL);
  Ref<DepthStencilView> dsv = device().CreateDepthStencilView(depth.get());
  DEPTH_STENCIL_DESC noWrite;
  noWrite.DepthWriteMask = DEPTH_WRITE_MASK_ZERO;
  Ref<DepthStencilState> readOnly = device().CreateDepthStencilState(noWrite);
  const float zero[4] = {0, 0, 0, 0};
  ctx().ClearRenderTargetView(t.rtv.get(), zero);
  ctx().ClearDepthStencilView(dsv.get(), CLEAR_DEPTH, 1.0f, 0);
  RenderTargetView* rtvs[] = {t.rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, dsv.get());
  SetViewport(ctx(), W, H);
  ctx().PSSetShader(colorPs_.get());
  // Default state: LESS, writes. Left half at 0.5, then the whole target at 0.75: the right
  // half gets 0.75, the left keeps 0.5.
  SetColor(1, 0, 0, 1);
  DrawPixels({{0, 0, 0.5f}, {4, 0, 0.5f}, {4, 4, 0.5f}, {0, 0, 0.5f}, {4, 4, 0.5f}, {0, 4, 0.5f}}, W, H);
  SetColor(0, 1, 0, 1);
  DrawPixels({{0, 0, 0.75f}, {8, 0, 0.75f}, {8, 4, 0.75f}, {0, 0, 0.75f}, {8, 4, 0.75f}, {0, 4, 0.75f}}, W, H);
  // No depth writes: colour passes the test at 0.25 but depth stays.
  ctx().OMSetDepthStencilState(readOnly.get(), 0);
  SetColor(0, 0, 1, 1);
  DrawPixels({{6, 0, 0.25f}, {8, 0, 0.25f}, {8, 4, 0.25f}, {6, 0, 0.25f}, {8, 4, 0.25f}, {6, 4, 0.25f}}, W, H);
  std::vector<float> c = ReadTextureAs<float>(device(), ctx(), t.texture.get());
  std::vector<float> z = ReadTextureAs<float>(device(), ctx(), depth.get());
  for (uint32_t x = 0; x < W; ++x) {
    float expectZ = x < 4 ? 0.5f : 0.75f;
    EXPECT_EQ(z[x], expectZ) << x;
    if (x < 4) EXPECT_EQ(c[x * 4 + 0], 1.0f) << x;
    else if (x < 6) EXPECT_EQ(c[x * 4 + 1], 1.0f) << x;
    else EXPECT_EQ(c[x * 4 + 2], 1.0f) << x;
  }
}

// Front faces increment, back faces replace with the reference; then an EQUAL test with a read
// mask selects pixels. Stencil is read back through a D24S8 staging copy in D3D's packing.
TEST_P(StateTest, StencilPerFaceAndReadMask) {
  const uint32_t W = 16, H = 4;
  Target t = MakeTarget(device(), W, H, FORMAT_R8G8B8A8_UNORM);
  Ref<Texture2D> depth = MakeTexture2D(device(), W, H, FORMAT_D24_UNORM_S8_UINT, BIND_DEPTH_STENCIL);
  Ref<DepthStencilView> dsv = device().CreateDepthStencilView(depth.get());
  RASTERIZER_DESC rd;
  rd.CullMode = CULL_NONE;
  Ref<RasterizerState> rs = device().CreateRasterizerState(rd);
  DEPTH_STENCIL_DESC write;
  write.DepthEnable = false;
  write.StencilEnable = true;
  write.FrontFace = {STENCIL_OP_KEEP, STENCIL_OP_KEEP, STENCIL_OP_INCR_SAT, COMPARISON_ALWAYS};
  write.BackFace = {STENCIL_OP_KEEP, STENCIL_OP_KEEP, STENCIL_OP_REPLACE, COMPARISON_ALWAYS};
  Ref<DepthStencilState> writeState = device().CreateDepthStencilState(write);
  DEPTH_STENCIL_DESC test = write;
  test.StencilReadMask = 0x0f;
  test.StencilWriteMask = 0;
  test.FrontFace = {STENCIL_OP_KEEP, STENCIL_OP_KEEP, STENCIL_OP_KEEP, COMPARISON_EQUAL};
  test.BackFace = test.FrontFace;
  Ref<DepthStencilState> testState = device().CreateDepthStencilState(test);

  const float zero[4] = {0, 0, 0, 0};
  ctx().ClearRenderTargetView(t.rtv.get(), zero);
  ctx().ClearDepthStencilView(dsv.get(), CLEAR_DEPTH | CLEAR_STENCIL, 1.0f, 3);
  RenderTargetView* rtvs[] = {t.rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, dsv.get());
  ctx().RSSetState(rs.get());
  SetViewport(ctx(), W, H);
  ctx().PSSetShader(colorPs_.get());
  SetColor(0, 0, 0, 0);
  ctx().OMSetDepthStencilState(writeState.get(), 0xf5);
  // Columns 0-3: two clockwise (front) quads -> 3 + 2 = 5. Columns 4-7: one counter-clockwise
  // (back) quad -> 0xf5. Columns 8-15: untouched, 3.
  std::vector<Vertex> front = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 0, 0}, {4, 4, 0}, {0, 4, 0}};
  DrawPixels(front, W, H);
  DrawPixels(front, W, H);
  DrawPixels({{4, 0, 0}, {8, 4, 0}, {8, 0, 0}, {4, 0, 0}, {4, 4, 0}, {8, 4, 0}}, W, H);
  // Colour where (stencil & 0x0f) == (0x05 & 0x0f): columns 0-7.
  ctx().OMSetDepthStencilState(testState.get(), 0x05);
  SetColor(1, 1, 1, 1);
  DrawPixels({{0, 0, 0}, {16, 0, 0}, {16, 4, 0}, {0, 0, 0}, {16, 4, 0}, {0, 4, 0}}, W, H);

  std::vector<uint32_t> ds = ReadTextureAs<uint32_t>(device(), ctx(), depth.get());
  std::vector<uint8_t> px = ReadTexture(device(), ctx(), t.texture.get());
  for (uint32_t x = 0; x < W; ++x) {
    uint32_t stencil = ds[x] >> 24, d = ds[x] & 0xffffff;
    uint32_t expect = x < 4 ? 5 : x < 8 ? 0xf5 : 3;
    EXPECT_EQ(stencil, expect) << x;
    EXPECT_EQ(d, 0xffffffu) << x;  // depth 1.0 in the low 24 bits
    EXPECT_EQ(px[x * 4], x < 8 ? 255 : 0) << x;
  }
}

TEST_P(StateTest, IndependentBlendWriteMaskAndBlendFactor) {
  const uint32_t W = 4, H = 4;
  Target a = MakeTarget(device(), W, H, FORMAT_R32G32B32A32_FLOAT), b = MakeTarget(device(), W, H, FORMAT_R32G32B32A32_FLOAT);
  Ref<PixelShader> two = device().CreatePixelShader(CompileHlsl(kShaders, "ps_5_0", "PSTwo"));
  BLEND_DESC bd;
  bd.IndependentBlendEnable = true;
  // RT0: src * blendFactor + dst * (1 - srcAlpha); RT1: src - dst, green and alpha masked off.
  bd.RenderTarget[0] = {true, BLEND_BLEND_FACTOR, BLEND_INV_SRC_ALPHA, BLEND_OP_ADD, BLEND_ONE, BLEND_ONE, BLEND_OP_MAX, COLOR_WRITE_ENABLE_ALL};
  bd.RenderTarget[1] = {true, BLEND_ONE, BLEND_ONE, BLEND_OP_SUBTRACT, BLEND_ONE, BLEND_ZERO, BLEND_OP_ADD,
                        COLOR_WRITE_ENABLE_RED | COLOR_WRITE_ENABLE_BLUE};
  Ref<BlendState> blend = device().CreateBlendState(bd);
  const float da[4] = {0.5f, 0.25f, 1.0f, 0.75f}, db[4] = {0.125f, 0.5f, 0.25f, 0.5f};
  ctx().ClearRenderTargetView(a.rtv.get(), da);
  ctx().ClearRenderTargetView(b.rtv.get(), db);
  RenderTargetView* rtvs[] = {a.rtv.get(), b.rtv.get()};
  ctx().OMSetRenderTargets(2, rtvs, nullptr);
  const float factor[4] = {0.5f, 2.0f, 0.25f, 1.0f};
  ctx().OMSetBlendState(blend.get(), factor, 0xffffffff);
  SetViewport(ctx(), W, H);
  ctx().PSSetShader(two.get());
  const float s0[4] = {1.0f, 0.5f, 0.25f, 0.25f}, s1[4] = {1.0f, 1.0f, 1.0f, 1.0f};
  SetColor(s0[0], s0[1], s0[2], s0[3], {s1[0], s1[1], s1[2], s1[3]});
  DrawPixels({{0, 0, 0}, {8, 0, 0}, {0, 8, 0}}, W, H);
  std::vector<float> pa = ReadTextureAs<float>(device(), ctx(), a.texture.get());
  std::vector<float> pb = ReadTextureAs<float>(device(), ctx(), b.texture.get());
  for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(pa[c], s0[c] * factor[c] + da[c] * (1 - s0[3])) << c;
  EXPECT_FLOAT_EQ(pa[3], std::max(s0[3], da[3]));
  EXPECT_FLOAT_EQ(pb[0], s1[0] - db[0]);
  EXPECT_FLOAT_EQ(pb[1], db[1]);  // masked
  EXPECT_FLOAT_EQ(pb[2], s1[2] - db[2]);
  EXPECT_FLOAT_EQ(pb[3], db[3]);  // masked
}

// SV_Target1 is the second source of target 0's blend (D3D11 dual-source blending).
TEST_P(StateTest, DualSourceBlending) {
  const uint32_t W = 4, H = 4;
  Target t = MakeTarget(device(), W, H, FORMAT_R32G32B32A32_FLOAT);
  Ref<PixelShader> two = device().CreatePixelShader(CompileHlsl(kShaders, "ps_5_0", "PSTwo"));
  BLEND_DESC bd;
  bd.RenderTarget[0] = {true, BLEND_ONE, BLEND_SRC1_COLOR, BLEND_OP_ADD, BLEND_ONE, BLEND_INV_SRC1_ALPHA, BLEND_OP_ADD, COLOR_WRITE_ENABLE_ALL};
  Ref<BlendState> blend = device().CreateBlendState(bd);
  const float dst[4] = {0.5f, 0.5f, 0.5f, 0.5f};
  ctx().ClearRenderTargetView(t.rtv.get(), dst);
  RenderTargetView* rtvs[] = {t.rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, nullptr);
  ctx().OMSetBlendState(blend.get(), nullptr, 0xffffffff);
  SetViewport(ctx(), W, H);
  ctx().PSSetShader(two.get());
  const float s0[4] = {0.25f, 0.125f, 0.0f, 0.25f}, s1[4] = {1.0f, 0.5f, 0.25f, 0.75f};
  SetColor(s0[0], s0[1], s0[2], s0[3], {s1[0], s1[1], s1[2], s1[3]});
  DrawPixels({{0, 0, 0}, {8, 0, 0}, {0, 8, 0}}, W, H);
  std::vector<float> p = ReadTextureAs<float>(device(), ctx(), t.texture.get());
  for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(p[c], s0[c] + dst[c] * s1[c]) << c;
  EXPECT_FLOAT_EQ(p[3], s0[3] + dst[3] * (1 - s1[3]));
}

// D3D11's depth bias: UNORM r = 1/(2^n - 1) per unit, D32_FLOAT 2^(e - 23) at the primitive's
// largest |z|; slope term SlopeScaledDepthBias * max(|dz/dx|, |dz/dy|); optional clamp; never on
// lines. Compared within a fraction of a unit (the rasterizer's interpolation and rounding).
TEST_P(StateTest, DepthBiasFollowsD3DFormula) {
  const uint32_t W = 16, H = 16;
  struct Fmt {
    FORMAT format;
    uint32_t bits;
  };
  const Fmt formats[] = {{FORMAT_D16_UNORM, 16}, {FORMAT_D24_UNORM_S8_UINT, 24}, {FORMAT_D32_FLOAT, 32}};
  for (const Fmt& f : formats) {
    Ref<Texture2D> depth = MakeTexture2D(device(), W, H, f.format, BIND_DEPTH_STENCIL);
    Ref<DepthStencilView> dsv = device().CreateDepthStencilView(depth.get());
    DEPTH_STENCIL_DESC dd;
    dd.DepthFunc = COMPARISON_ALWAYS;
    Ref<DepthStencilState> ds = device().CreateDepthStencilState(dd);
    auto read = [&](uint32_t x, uint32_t y) -> double {
      std::vector<uint8_t> raw = ReadTexture(device(), ctx(), depth.get());
      size_t i = y * W + x;
      if (f.bits == 16) return ReadAs<uint16_t>(raw)[i] / 65535.0;
      if (f.bits == 24) return (ReadAs<uint32_t>(raw)[i] & 0xffffff) / 16777215.0;
      return ReadAs<float>(raw)[i];
    };
    auto render = [&](int32_t bias, float slope, float clamp, const std::vector<Vertex>& tri, PRIMITIVE_TOPOLOGY topo) {
      RASTERIZER_DESC rd;
      rd.CullMode = CULL_NONE;
      rd.DepthBias = bias;
      rd.SlopeScaledDepthBias = slope;
      rd.DepthBiasClamp = clamp;
      Ref<RasterizerState> rs = device().CreateRasterizerState(rd);
      ctx().ClearDepthStencilView(dsv.get(), CLEAR_DEPTH, 0.0f, 0);
      ctx().OMSetRenderTargets(0, nullptr, dsv.get());
      ctx().OMSetDepthStencilState(ds.get(), 0);
      ctx().RSSetState(rs.get());
      SetViewport(ctx(), W, H);
      ctx().PSSetShader(nullptr);
      DrawPixels(tri, W, H, topo);
    };
    const double unit = f.bits == 32 ? std::ldexp(1.0, -1 - 23) : 1.0 / (std::ldexp(1.0, int(f.bits)) - 1);  // z = 0.5
    const double tolerance = f.bits == 32 ? 2 * unit : 1.01 * unit;
    const std::vector<Vertex> flat = {{0, 0, 0.5f}, {32, 0, 0.5f}, {0, 32, 0.5f}};
    render(0, 0, 0, flat, PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    double base = read(4, 4);
    EXPECT_NEAR(base, 0.5, tolerance) << FormatName(f.format);
    render(100, 0, 0, flat, PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    EXPECT_NEAR(read(4, 4) - base, 100 * unit, tolerance) << FormatName(f.format) << " constant bias";
    render(100, 0, float(40 * unit), flat, PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    EXPECT_NEAR(read(4, 4) - base, 40 * unit, tolerance) << FormatName(f.format) << " clamped bias";
    // z rises by 1/64 per pixel in x (NDC 0.25 .. 0.75 across 32 pixels): slope term 2 * 1/64.
    const std::vector<Vertex> sloped = {{0, 0, 0.25f}, {32, 0, 0.75f}, {0, 32, 0.25f}};
    render(0, 0, 0, sloped, PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    double slopeBase = read(4, 4);
    render(0, 2.0f, 0, sloped, PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    EXPECT_NEAR(read(4, 4) - slopeBase, 2.0 / 64, 2 * tolerance) << FormatName(f.format) << " slope bias";
    // Lines are never biased.
    render(0, 0, 0, {{0, 4.5f, 0.5f}, {16, 4.5f, 0.5f}}, PRIMITIVE_TOPOLOGY_LINELIST);
    double lineBase = read(8, 4);
    render(1000, 4.0f, 0, {{0, 4.5f, 0.5f}, {16, 4.5f, 0.5f}}, PRIMITIVE_TOPOLOGY_LINELIST);
    EXPECT_EQ(read(8, 4), lineBase) << FormatName(f.format) << " line";
  }
}

// Vertex input: integer and normalized formats, offsets, per-instance data with step rates 1
// and 2, and step rate 0 (the data never advances), with StartInstanceLocation.
// D3D11 rasterizes nothing into a viewport of zero width or height; the rule lives in the core
// (DeviceContext's draw), so both backends skip the draw, and the state it carried reaches the
// next draw with a real viewport. (A draw with no viewport set at all is refused by validation.)
TEST_P(StateTest, EmptyViewportDrawsNothing) {
  const uint32_t W = 8, H = 4;
  Target t = MakeTarget(device(), W, H, FORMAT_R32G32B32A32_FLOAT);
  const float zero[4] = {0, 0, 0, 0};
  ctx().ClearRenderTargetView(t.rtv.get(), zero);
  RenderTargetView* rtvs[] = {t.rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, nullptr);
  ctx().PSSetShader(colorPs_.get());
  SetColor(1, 0, 0, 1);
  const std::vector<Vertex> all = {{0, 0, 0.5f}, {8, 0, 0.5f}, {8, 4, 0.5f}, {0, 0, 0.5f}, {8, 4, 0.5f}, {0, 4, 0.5f}};
  VIEWPORT flat{0, 0, float(W), 0, 0, 1}, thin{0, 0, 0, float(H), 0, 1};
  ctx().RSSetViewports(1, &flat);
  DrawPixels(all, W, H);
  ctx().RSSetViewports(1, &thin);
  DrawPixels(all, W, H);
  std::vector<float> c = ReadTextureAs<float>(device(), ctx(), t.texture.get());
  for (uint32_t i = 0; i < W * H; ++i) EXPECT_EQ(c[i * 4], 0.0f) << "pixel " << i << " drawn through an empty viewport";
  SetViewport(ctx(), W, H);
  DrawPixels(all, W, H);
  c = ReadTextureAs<float>(device(), ctx(), t.texture.get());
  for (uint32_t i = 0; i < W * H; ++i) EXPECT_EQ(c[i * 4], 1.0f) << "pixel " << i;
  EXPECT_EQ(device().ValidationErrorCount(), 0u) << device().LastValidationError();
}

TEST_P(StateTest, VertexFormatsAndInstancing) {
  const char* src = R"(
struct V { float4 pos : SV_Position; nointerpolation float4 color : COLOR; };
V VSMain(float2 corner : POSITION, uint2 ids : IDS, float4 tint : TINT, float4 fixedTint : FIXED, uint inst : SV_InstanceID) {
  V v;
  v.pos = float4((corner.x + inst + 0.5) / 8 * 2 - 1, 0, 0, 1);
  v.color = float4(ids.x, ids.y, tint.x * 255, fixedTint.y * 255);
  return v;
}
float4 PSMain(V v) : SV_Target { return v.color; }
)";
  const uint32_t W = 8;
  ShaderBytecode vsb = CompileHlsl(src, "vs_5_0", "VSMain");
  Ref<VertexShader> vs = device().CreateVertexShader(vsb);
  Ref<PixelShader> ps = device().CreatePixelShader(CompileHlsl(src, "ps_5_0", "PSMain"));
  INPUT_ELEMENT_DESC el[] = {{"POSITION", 0, FORMAT_R32G32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0},
                             {"IDS", 0, FORMAT_R16G16_UINT, 1, 4, INPUT_PER_INSTANCE_DATA, 1},
                             {"TINT", 0, FORMAT_R8G8B8A8_UNORM, 2, 0, INPUT_PER_INSTANCE_DATA, 2},
                             {"FIXED", 0, FORMAT_R8G8B8A8_UNORM, 3, 0, INPUT_PER_INSTANCE_DATA, 0}};
  Ref<InputLayout> layout = device().CreateInputLayout(el, 4, vsb);
  const float corner[2] = {0, 0};
  struct Ids {
    uint16_t pad[2];
    uint16_t id[2];
  };
  std::vector<Ids> ids;
  for (uint16_t i = 0; i < 8; ++i) ids.push_back({{9, 9}, {uint16_t(i * 3), uint16_t(100 + i)}});
  std::vector<uint8_t> tints;
  for (uint8_t i = 0; i < 8; ++i) tints.insert(tints.end(), {uint8_t(10 * i), 0, 0, 0});
  // Bound at offset 4; element StartInstanceLocation (2) holds 77 in .y, element 0 a decoy.
  const uint8_t fixed[16] = {0, 0, 0, 0, 0, 33, 0, 0, 0, 0, 0, 0, 0, 77, 0, 0};
  Ref<Buffer> b0 = MakeBuffer(device(), BIND_VERTEX_BUFFER, corner, sizeof(corner));
  Ref<Buffer> b1 = MakeBuffer(device(), BIND_VERTEX_BUFFER, ids.data(), uint32_t(ids.size() * sizeof(Ids)));
  Ref<Buffer> b2 = MakeBuffer(device(), BIND_VERTEX_BUFFER, tints.data(), uint32_t(tints.size()));
  Ref<Buffer> b3 = MakeBuffer(device(), BIND_VERTEX_BUFFER, fixed, sizeof(fixed));
  Target t = MakeTarget(device(), W, 1, FORMAT_R32G32B32A32_FLOAT);
  RenderTargetView* rtvs[] = {t.rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, nullptr);
  SetViewport(ctx(), W, 1);
  Buffer* vbs[] = {b0.get(), b1.get(), b2.get(), b3.get()};
  const uint32_t strides[] = {8, sizeof(Ids), 4, 4}, offsets[] = {0, 0, 0, 4};
  ctx().IASetVertexBuffers(0, 4, vbs, strides, offsets);
  ctx().IASetInputLayout(layout.get());
  ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_POINTLIST);
  ctx().VSSetShader(vs.get());
  ctx().PSSetShader(ps.get());
  ctx().DrawInstanced(1, 6, 0, 2);  // instances 0..5, per-instance data from element 2 on
  std::vector<float> px = ReadTextureAs<float>(device(), ctx(), t.texture.get());
  for (uint32_t x = 0; x < 6; ++x) {
    // D3D11: element = StartInstanceLocation + instance / step rate.
    uint32_t idElem = 2 + x, tintElem = 2 + x / 2;
    EXPECT_EQ(px[x * 4 + 0], float(idElem * 3)) << x;
    EXPECT_EQ(px[x * 4 + 1], float(100 + idElem)) << x;
    EXPECT_NEAR(px[x * 4 + 2], float(10 * tintElem), 1e-3) << x;
    EXPECT_NEAR(px[x * 4 + 3], 77.0f, 1e-3) << x;
  }
}

SP_INSTANTIATE_BACKEND_TESTS(StateTest);

// What the core refuses, without drawing: these run on the null backend too.
class StateValidationTest : public BackendTest {};

// One policy for a device without depth-bias clamping, in the core: a non-zero DepthBiasClamp is
// refused when the state is made (GL used to refuse it at draw time, Vulkan to drop the clamp).
TEST_P(StateValidationTest, DepthBiasClampWithoutTheCapabilityIsRefusedWhenTheStateIsMade) {
  EXPECT_TRUE(device().Info().depthBiasClamp) << "Mesa's drivers clamp depth bias";
  DeviceDesc dd;
  dd.backend = backend();
  dd.disableDepthBiasClamp = true;
  Ref<Device> dev = CreateDevice(dd);
  EXPECT_FALSE(dev->Info().depthBiasClamp);
  RASTERIZER_DESC rd;
  rd.DepthBias = 100;
  rd.SlopeScaledDepthBias = 1.0f;
  EXPECT_NO_THROW(dev->CreateRasterizerState(rd));  // no clamp asked: fine
  rd.DepthBiasClamp = 0.25f;
  try {
    dev->CreateRasterizerState(rd);
    ADD_FAILURE() << "expected SP_NOT_SUPPORTED";
  } catch (const Error& e) {
    EXPECT_EQ(e.id(), ErrorId::NOT_SUPPORTED) << e.what();
    EXPECT_NE(std::string(e.what()).find("DepthBiasClamp"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("RasterizerState"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(device().CreateRasterizerState(rd));  // the normal device has it
}

SP_INSTANTIATE_VALIDATION_TESTS(StateValidationTest);

}  // namespace
}  // namespace sp::test
