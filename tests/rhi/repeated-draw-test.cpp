// Draws that repeat with nothing rebound: the core keeps the last draw's validation and the Vulkan
// backend keeps a stage's descriptor set (moving only dynamic offsets) while no state changed, so
// the per-draw cost stays near a raw API's. These tests hold both short cuts to D3D11's results:
// every draw still sees the data written before it, and every state change is checked again.
#include <array>
#include <optional>

#include "rhi-test-util.h"

namespace sp::test {
namespace {

class RepeatedDrawTest : public BackendTest {};
class RepeatedDrawValidationTest : public BackendTest {};

// Strip i of 8 comes from the vertex ids Draw(4, 4 * i) generates: no vertex-shader bindings.
const char* kStripVS = R"(
float4 main(uint id : SV_VertexID) : SV_Position {
  float strip = float(id / 4u);
  float x = (strip + float(id & 1u)) / 4.0 - 1.0;
  float y = (id & 2u) ? -1.0 : 1.0;  // clockwise: front-facing under the default state
  return float4(x, y, 0.5, 1.0);
}
)";

// A dynamic cbuffer (dynamic offset on Vulkan) and a dynamic structured buffer (its range is in
// the descriptor set), renamed between draws in turn.
const char* kSumPS = R"(
cbuffer Color : register(b0) { float4 color; };
StructuredBuffer<float4> extra : register(t0);
float4 main(float4 p : SV_Position) : SV_Target { return color + extra[0]; }
)";

Ref<Buffer> DynamicBuffer(Device& dev, uint32_t size, uint32_t bind, uint32_t misc = 0, uint32_t stride = 0) {
  BUFFER_DESC d;
  d.ByteWidth = size;
  d.Usage = USAGE_DYNAMIC;
  d.BindFlags = bind;
  d.CPUAccessFlags = CPU_ACCESS_WRITE;
  d.MiscFlags = misc;
  d.StructureByteStride = stride;
  return dev.CreateBuffer(d);
}

void WriteDiscard(DeviceContext& ctx, Buffer* b, const float (&v)[4]) {
  MAPPED_SUBRESOURCE m;
  ASSERT_TRUE(ctx.Map(b, 0, MAP_WRITE_DISCARD, 0, &m));
  std::memcpy(m.pData, v, sizeof(v));
  ctx.Unmap(b, 0);
}

// The fixed part of every pass here: one target, its viewport, strips, the two shaders.
void BindPass(DeviceContext& ctx, const Target& t, uint32_t w, uint32_t h, VertexShader* vs, PixelShader* ps) {
  RenderTargetView* rtvs[] = {t.rtv.get()};
  ctx.OMSetRenderTargets(1, rtvs, nullptr);
  SetViewport(ctx, float(w), float(h));
  ctx.IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLESTRIP);
  ctx.VSSetShader(vs);
  ctx.PSSetShader(ps);
}

TEST_P(RepeatedDrawTest, EveryDrawSeesTheBuffersWrittenBeforeItWithNothingRebound) {
  const uint32_t W = 32, H = 4;
  Target t = MakeTarget(device(), W, H, FORMAT_R32G32B32A32_FLOAT);
  Ref<VertexShader> vs = device().CreateVertexShader(CompileHlsl(kStripVS, "vs_5_0", "main"));
  Ref<PixelShader> ps = device().CreatePixelShader(CompileHlsl(kSumPS, "ps_5_0", "main"));
  Ref<Buffer> cb = DynamicBuffer(device(), 16, BIND_CONSTANT_BUFFER);
  Ref<Buffer> sb = DynamicBuffer(device(), 16, BIND_SHADER_RESOURCE, RESOURCE_MISC_BUFFER_STRUCTURED, 16);
  Ref<ShaderResourceView> srv = device().CreateShaderResourceView(sb.get());
  float color[4] = {0, 0, 0, 1}, extra[4] = {0, 0, 0, 0};
  WriteDiscard(ctx(), cb.get(), color);
  WriteDiscard(ctx(), sb.get(), extra);
  BindPass(ctx(), t, W, H, vs.get(), ps.get());
  ctx().PSSetConstantBuffers(0, {cb.get()});
  ctx().PSSetShaderResources(0, {srv.get()});
  // Even strips rename only the cbuffer, odd ones only the structured buffer, strip 7 neither.
  std::vector<std::array<float, 4>> expected;
  for (uint32_t i = 0; i < 8; ++i) {
    if (i < 7 && i % 2 == 0) {
      color[0] = float(i + 1);
      WriteDiscard(ctx(), cb.get(), color);
    } else if (i < 7) {
      extra[1] = float(10 * i);
      WriteDiscard(ctx(), sb.get(), extra);
    }
    ctx().Draw(4, 4 * i);
    expected.push_back({color[0] + extra[0], color[1] + extra[1], color[2] + extra[2], color[3] + extra[3]});
  }
  std::vector<float> px = ReadTextureAs<float>(device(), ctx(), t.texture.get());
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x)
      for (uint32_t c = 0; c < 4; ++c) ASSERT_EQ(px[(y * W + x) * 4 + c], expected[x / 4][c]) << "pixel " << x << "," << y << " channel " << c;
}

const char* kTexturePS = R"(
Texture2D tex : register(t0);
SamplerState smp : register(s0);
float4 main(float4 p : SV_Position) : SV_Target { return tex.Sample(smp, float2(0.5, 0.5)); }
)";

const char* kFillCS = R"(
RWStructuredBuffer<uint> outBuf : register(u0);
[numthreads(1, 1, 1)] void main(uint3 id : SV_DispatchThreadID) { outBuf[0] = 7; }
)";

// A dynamic vertex buffer renamed before every draw, nothing rebound: each strip is drawn where the
// vertices written before its draw put it.
TEST_P(RepeatedDrawTest, ARenamedVertexBufferIsReadAtItsNewPlace) {
  const uint32_t W = 32, H = 4;
  Target t = MakeTarget(device(), W, H, FORMAT_R32G32B32A32_FLOAT);
  Ref<VertexShader> vs = device().CreateVertexShader(CompileHlsl(R"(
float4 main(float2 p : POSITION) : SV_Position { return float4(p, 0.5, 1.0); }
)",
                                                                 "vs_5_0", "main"));
  Ref<PixelShader> ps = device().CreatePixelShader(CompileHlsl(R"(
cbuffer Color : register(b0) { float4 color; };
float4 main(float4 p : SV_Position) : SV_Target { return color; }
)",
                                                               "ps_5_0", "main"));
  const ShaderBytecode& vsCode = vs->Bytecode();
  INPUT_ELEMENT_DESC el[] = {{"POSITION", 0, FORMAT_R32G32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0}};
  Ref<InputLayout> layout = device().CreateInputLayout(el, 1, vsCode);
  Ref<Buffer> vb = DynamicBuffer(device(), 32, BIND_VERTEX_BUFFER);
  Ref<Buffer> cb = DynamicBuffer(device(), 16, BIND_CONSTANT_BUFFER);
  BindPass(ctx(), t, W, H, vs.get(), ps.get());
  ctx().IASetInputLayout(layout.get());
  Buffer* vbs[] = {vb.get()};
  uint32_t stride = 8, offset = 0;
  ctx().IASetVertexBuffers(0, 1, vbs, &stride, &offset);
  ctx().PSSetConstantBuffers(0, {cb.get()});
  for (uint32_t i = 0; i < 8; ++i) {
    float x0 = float(i) / 4.0f - 1.0f, x1 = float(i + 1) / 4.0f - 1.0f;
    float quad[8] = {x0, 1, x1, 1, x0, -1, x1, -1};
    MAPPED_SUBRESOURCE m;
    ASSERT_TRUE(ctx().Map(vb.get(), 0, MAP_WRITE_DISCARD, 0, &m));
    std::memcpy(m.pData, quad, sizeof(quad));
    ctx().Unmap(vb.get(), 0);
    const float color[4] = {float(i + 1), 0, 0, 1};
    WriteDiscard(ctx(), cb.get(), color);
    ctx().Draw(4, 0);
  }
  std::vector<float> px = ReadTextureAs<float>(device(), ctx(), t.texture.get());
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) ASSERT_EQ(px[(y * W + x) * 4], float(x / 4 + 1)) << "pixel " << x << "," << y;
}

// Work between draws changes GL state behind the pipeline state: a depth clear binds a
// framebuffer and switches depth writes on, a resolve switches the scissor test off and opens the
// colour mask, a dispatch binds a compute program. A draw with nothing rebound still draws with its
// own state. Strips 0-3 lie inside the scissor; each strip is drawn three times (after the clear,
// the resolve, the dispatch) with additive blending, red and green only, depth test LESS without
// depth writes after its depth was cleared to 1: (3, 3, 0, 0) inside, untouched outside.
TEST_P(RepeatedDrawTest, WorkBetweenDrawsDoesNotChangeTheNextDrawsState) {
  const uint32_t W = 32, H = 4;
  const FORMAT rgba32 = FORMAT_R32G32B32A32_FLOAT;
  Target t = MakeTarget(device(), W, H, rgba32);
  Ref<Texture2D> depth = MakeTexture2D(device(), W, H, FORMAT_D32_FLOAT, BIND_DEPTH_STENCIL);
  Ref<DepthStencilView> dsv = device().CreateDepthStencilView(depth.get());
  Ref<Texture2D> ms = MakeTexture2D(device(), W, H, rgba32, BIND_RENDER_TARGET, nullptr, 1, 1, 4);
  Ref<Texture2D> resolved = MakeTexture2D(device(), W, H, rgba32, 0);
  Ref<VertexShader> vs = device().CreateVertexShader(CompileHlsl(kStripVS, "vs_5_0", "main"));
  Ref<PixelShader> ps = device().CreatePixelShader(CompileHlsl(R"(
float4 main(float4 p : SV_Position) : SV_Target { return float4(1, 1, 1, 1); }
)",
                                                               "ps_5_0", "main"));
  Ref<ComputeShader> cs = device().CreateComputeShader(CompileHlsl(kFillCS, "cs_5_0", "main"));
  UavBuffer u = MakeUavBuffer(device(), 1, 4);
  RASTERIZER_DESC rd;
  rd.ScissorEnable = true;
  Ref<RasterizerState> scissored = device().CreateRasterizerState(rd);
  DEPTH_STENCIL_DESC dd;
  dd.DepthWriteMask = DEPTH_WRITE_MASK_ZERO;
  Ref<DepthStencilState> noWrite = device().CreateDepthStencilState(dd);
  BLEND_DESC bd;
  bd.RenderTarget[0] = {true, BLEND_ONE, BLEND_ONE, BLEND_OP_ADD, BLEND_ONE, BLEND_ONE, BLEND_OP_ADD, COLOR_WRITE_ENABLE_RED | COLOR_WRITE_ENABLE_GREEN};
  Ref<BlendState> add = device().CreateBlendState(bd);
  const float zero[4] = {0, 0, 0, 0};
  ctx().ClearRenderTargetView(t.rtv.get(), zero);
  RenderTargetView* rtvs[] = {t.rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, dsv.get());
  SetViewport(ctx(), float(W), float(H));
  const RECT inside{0, 0, int32_t(W / 2), int32_t(H)};
  ctx().RSSetScissorRects(1, &inside);
  ctx().RSSetState(scissored.get());
  ctx().OMSetDepthStencilState(noWrite.get(), 0);
  ctx().OMSetBlendState(add.get(), nullptr, 0xffffffffu);
  ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLESTRIP);
  ctx().VSSetShader(vs.get());
  ctx().PSSetShader(ps.get());
  ctx().CSSetShader(cs.get());
  ctx().CSSetUnorderedAccessViews(0, {u.uav.get()});
  for (uint32_t i = 0; i < 8; ++i) {
    ctx().ClearDepthStencilView(dsv.get(), CLEAR_DEPTH, 1.0f, 0);
    ctx().Draw(4, 4 * i);
    ctx().ResolveSubresource(resolved.get(), 0, ms.get(), 0, rgba32);
    ctx().Draw(4, 4 * i);
    ctx().Dispatch(1, 1, 1);
    ctx().Draw(4, 4 * i);
  }
  std::vector<float> px = ReadTextureAs<float>(device(), ctx(), t.texture.get());
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      const float v = x < W / 2 ? 3.0f : 0.0f;
      const float want[4] = {v, v, 0, 0};
      for (uint32_t c = 0; c < 4; ++c) ASSERT_EQ(px[(y * W + x) * 4 + c], want[c]) << "pixel " << x << "," << y << " channel " << c;
    }
  EXPECT_EQ(ReadBufferAs<uint32_t>(device(), ctx(), u.buffer.get())[0], 7u);
}

// A depth-only pass (a shadow map's): the clear binds the pass's own framebuffer, so only the depth
// write mask it switched on differs. Drawn with depth writes off, the depth stays at the cleared 1.
TEST_P(RepeatedDrawTest, ADepthClearDoesNotTurnDepthWritesOnForTheNextDraw) {
  const uint32_t W = 32, H = 4;
  Ref<Texture2D> depth = MakeTexture2D(device(), W, H, FORMAT_D32_FLOAT, BIND_DEPTH_STENCIL);
  Ref<DepthStencilView> dsv = device().CreateDepthStencilView(depth.get());
  Ref<VertexShader> vs = device().CreateVertexShader(CompileHlsl(kStripVS, "vs_5_0", "main"));
  DEPTH_STENCIL_DESC dd;
  dd.DepthWriteMask = DEPTH_WRITE_MASK_ZERO;
  Ref<DepthStencilState> noWrite = device().CreateDepthStencilState(dd);
  ctx().OMSetRenderTargets(0, nullptr, dsv.get());
  SetViewport(ctx(), float(W), float(H));
  ctx().OMSetDepthStencilState(noWrite.get(), 0);
  ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLESTRIP);
  ctx().VSSetShader(vs.get());
  ctx().PSSetShader(nullptr);
  for (uint32_t i = 0; i < 8; ++i) {
    ctx().ClearDepthStencilView(dsv.get(), CLEAR_DEPTH, 1.0f, 0);
    ctx().Draw(4, 4 * i);
  }
  std::vector<float> d = ReadTextureAs<float>(device(), ctx(), depth.get());
  for (uint32_t p = 0; p < W * H; ++p) ASSERT_EQ(d[p], 1.0f) << "pixel " << p % W << "," << p / W;
}

// Targets switched between draws with nothing else in between (no clear, copy or barrier ends the
// pass): each draw lands in the targets bound for it. Two targets of one format and one of another,
// so both the pass (Vulkan keeps it open while the targets did not change) and the pipeline (its
// identity keeps the targets' part between target changes) must follow the switch.
TEST_P(RepeatedDrawTest, TargetsSwitchedBetweenDrawsReceiveTheirOwnDraws) {
  const uint32_t W = 32, H = 4;
  Target targets[3] = {MakeTarget(device(), W, H, FORMAT_R32G32B32A32_FLOAT), MakeTarget(device(), W, H, FORMAT_R32G32B32A32_FLOAT),
                       MakeTarget(device(), W, H, FORMAT_R32_FLOAT)};
  Ref<VertexShader> vs = device().CreateVertexShader(CompileHlsl(kStripVS, "vs_5_0", "main"));
  Ref<PixelShader> ps = device().CreatePixelShader(CompileHlsl(R"(
float4 main(float4 p : SV_Position) : SV_Target { return float4(1, 1, 1, 1); }
)",
                                                               "ps_5_0", "main"));
  const float zero[4] = {0, 0, 0, 0};
  for (Target& t : targets) ctx().ClearRenderTargetView(t.rtv.get(), zero);
  BindPass(ctx(), targets[0], W, H, vs.get(), ps.get());
  // Two rounds over the three targets first, so every target is already an attachment when the
  // strips are drawn: no layout barrier is left to close the pass at a switch.
  for (uint32_t round = 0; round < 2; ++round)
    for (Target& t : targets) {
      RenderTargetView* rtvs[] = {t.rtv.get()};
      ctx().OMSetRenderTargets(1, rtvs, nullptr);
      ctx().Draw(0, 0);
    }
  // Strip i goes to target i % 3.
  for (uint32_t i = 0; i < 8; ++i) {
    RenderTargetView* rtvs[] = {targets[i % 3].rtv.get()};
    ctx().OMSetRenderTargets(1, rtvs, nullptr);
    ctx().Draw(4, 4 * i);
  }
  for (uint32_t k = 0; k < 3; ++k) {
    const uint32_t channels = k == 2 ? 1 : 4;
    std::vector<float> px = ReadTextureAs<float>(device(), ctx(), targets[k].texture.get());
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x) {
        const float want = (x / 4) % 3 == k ? 1.0f : 0.0f;
        for (uint32_t c = 0; c < channels; ++c)
          ASSERT_EQ(px[(y * W + x) * channels + c], want) << "target " << k << " pixel " << x << "," << y << " channel " << c;
      }
  }
}

// The id of the error the call throws, or none.
template <class F>
std::optional<ErrorId> ErrorOf(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.id();
  }
  return std::nullopt;
}

// After a draw that passed, a draw with a state change in between is checked again: a wrong view,
// an indexed draw without an index buffer, a dispatch whose UAV changed while a draw ran between.
TEST_P(RepeatedDrawValidationTest, AChangeAfterADrawThatPassedIsCheckedAgain) {
  Target t = MakeTarget(device(), 8, 8, FORMAT_R8G8B8A8_UNORM);
  Ref<VertexShader> vs = device().CreateVertexShader(CompileHlsl(kStripVS, "vs_5_0", "main"));
  Ref<PixelShader> ps = device().CreatePixelShader(CompileHlsl(kTexturePS, "ps_5_0", "main"));
  Ref<Texture2D> tex = MakeTexture2D(device(), 4, 4, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE);
  Ref<ShaderResourceView> srv = device().CreateShaderResourceView(tex.get());
  Ref<Texture2D> uintTex = MakeTexture2D(device(), 4, 4, FORMAT_R8G8B8A8_UINT, BIND_SHADER_RESOURCE);
  Ref<ShaderResourceView> uintSrv = device().CreateShaderResourceView(uintTex.get());
  Ref<SamplerState> smp = device().CreateSamplerState(SAMPLER_DESC{});
  BindPass(ctx(), t, 8, 8, vs.get(), ps.get());
  ctx().PSSetShaderResources(0, {srv.get()});
  ctx().PSSetSamplers(0, {smp.get()});
  EXPECT_EQ(ErrorOf([&] { ctx().Draw(4, 0); }), std::nullopt);
  EXPECT_EQ(ErrorOf([&] { ctx().Draw(4, 0); }), std::nullopt);
  ctx().PSSetShaderResources(0, {uintSrv.get()});  // a UINT view where the shader reads float
  EXPECT_EQ(ErrorOf([&] { ctx().Draw(4, 0); }), ErrorId::RESOURCE_TYPE_MISMATCH);
  ctx().PSSetShaderResources(0, {srv.get()});
  EXPECT_EQ(ErrorOf([&] { ctx().Draw(4, 0); }), std::nullopt);
  // Same state, but indexed: whether a draw is indexed is part of what was checked.
  EXPECT_EQ(ErrorOf([&] { ctx().DrawIndexed(4, 0, 0); }), ErrorId::DRAW_STATE_INVALID);
  EXPECT_EQ(ErrorOf([&] { ctx().Draw(4, 0); }), std::nullopt);

  Ref<ComputeShader> cs = device().CreateComputeShader(CompileHlsl(kFillCS, "cs_5_0", "main"));
  UavBuffer good = MakeUavBuffer(device(), 4, 4);
  Ref<Texture2D> uavTex = MakeTexture2D(device(), 4, 4, FORMAT_R32_UINT, BIND_UNORDERED_ACCESS);
  Ref<UnorderedAccessView> texUav = device().CreateUnorderedAccessView(uavTex.get());
  ctx().CSSetShader(cs.get());
  ctx().CSSetUnorderedAccessViews(0, {good.uav.get()});
  EXPECT_EQ(ErrorOf([&] { ctx().Dispatch(1, 1, 1); }), std::nullopt);
  ctx().CSSetUnorderedAccessViews(0, {texUav.get()});  // a texture where the shader has a structured buffer
  EXPECT_EQ(ErrorOf([&] { ctx().Draw(4, 0); }), std::nullopt);  // the draw must not hide the change from the dispatch
  EXPECT_EQ(ErrorOf([&] { ctx().Dispatch(1, 1, 1); }), ErrorId::RESOURCE_TYPE_MISMATCH);
  ctx().CSSetUnorderedAccessViews(0, {good.uav.get()});
  EXPECT_EQ(ErrorOf([&] { ctx().Dispatch(1, 1, 1); }), std::nullopt);
  ctx().CSSetUnorderedAccessViews(0, {nullptr});
}

// After a draw that passed, only the rules reading what changed run again: each kind of change
// still finds its error (vertex input, shader interface, render-target kind, scissor).
TEST_P(RepeatedDrawValidationTest, EachKindOfChangeIsCheckedAgain) {
  Target t = MakeTarget(device(), 8, 8, FORMAT_R8G8B8A8_UNORM);
  Target uintTarget = MakeTarget(device(), 8, 8, FORMAT_R8G8B8A8_UINT);
  const char* vsSource = R"(
struct V { float4 p : SV_Position; float4 c : COLOR0; };
V main(float2 p : POSITION) { V v; v.p = float4(p, 0.5, 1.0); v.c = 1; return v; }
)";
  ShaderBytecode vsCode = CompileHlsl(vsSource, "vs_5_0", "main");
  Ref<VertexShader> vs = device().CreateVertexShader(vsCode);
  Ref<PixelShader> ps = device().CreatePixelShader(CompileHlsl(R"(
float4 main(float4 p : SV_Position, float4 c : COLOR0) : SV_Target { return c; }
)",
                                                               "ps_5_0", "main"));
  Ref<PixelShader> psTexcoord = device().CreatePixelShader(CompileHlsl(R"(
float4 main(float4 p : SV_Position, float2 uv : TEXCOORD0) : SV_Target { return float4(uv, 0, 1); }
)",
                                                                       "ps_5_0", "main"));
  INPUT_ELEMENT_DESC el[] = {{"POSITION", 0, FORMAT_R32G32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0}};
  Ref<InputLayout> layout = device().CreateInputLayout(el, 1, vsCode);
  const float quad[8] = {-1, 1, 1, 1, -1, -1, 1, -1};
  Ref<Buffer> vb = MakeBuffer(device(), BIND_VERTEX_BUFFER, quad, sizeof(quad));
  RASTERIZER_DESC rd;
  rd.ScissorEnable = true;
  Ref<RasterizerState> scissored = device().CreateRasterizerState(rd);
  RenderTargetView* rtvs[] = {t.rtv.get()};
  RenderTargetView* uintRtvs[] = {uintTarget.rtv.get()};
  Buffer* vbs[] = {vb.get()};
  Buffer* noVbs[] = {nullptr};
  uint32_t stride = 8, offset = 0;
  ctx().OMSetRenderTargets(1, rtvs, nullptr);
  SetViewport(ctx(), 8, 8);
  ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLESTRIP);
  ctx().IASetInputLayout(layout.get());
  ctx().IASetVertexBuffers(0, 1, vbs, &stride, &offset);
  ctx().VSSetShader(vs.get());
  ctx().PSSetShader(ps.get());
  auto draw = [&] { return ErrorOf([&] { ctx().Draw(4, 0); }); };
  EXPECT_EQ(draw(), std::nullopt);
  ctx().IASetVertexBuffers(0, 1, noVbs, &stride, &offset);
  EXPECT_EQ(draw(), ErrorId::DRAW_STATE_INVALID);
  ctx().IASetVertexBuffers(0, 1, vbs, &stride, &offset);
  EXPECT_EQ(draw(), std::nullopt);
  ctx().PSSetShader(psTexcoord.get());
  EXPECT_EQ(draw(), ErrorId::SHADER_INTERFACE_MISMATCH);
  ctx().PSSetShader(ps.get());
  EXPECT_EQ(draw(), std::nullopt);
  ctx().OMSetRenderTargets(1, uintRtvs, nullptr);
  EXPECT_EQ(draw(), ErrorId::RESOURCE_TYPE_MISMATCH);
  ctx().OMSetRenderTargets(1, rtvs, nullptr);
  EXPECT_EQ(draw(), std::nullopt);
  ctx().RSSetState(scissored.get());
  EXPECT_EQ(draw(), ErrorId::DRAW_STATE_INVALID);
  ctx().RSSetState(nullptr);
  EXPECT_EQ(draw(), std::nullopt);
}

// D3D11 warns at every draw that reads past the end of a too-small cbuffer, repeated draws too.
TEST_P(RepeatedDrawValidationTest, ATooSmallCbufferWarnsAtEveryDraw) {
  std::vector<std::string> warnings;
  device().SetMessageCallback([&](MessageSeverity s, std::string_view text) {
    if (s == MessageSeverity::Warning && text.find("is smaller than cbuffer") != std::string_view::npos) warnings.emplace_back(text);
    if (s == MessageSeverity::Error) validationMessages.emplace_back(text);
  });
  Target t = MakeTarget(device(), 8, 8, FORMAT_R8G8B8A8_UNORM);
  Ref<VertexShader> vs = device().CreateVertexShader(CompileHlsl(kStripVS, "vs_5_0", "main"));
  Ref<PixelShader> ps = device().CreatePixelShader(CompileHlsl(R"(
cbuffer Big : register(b0) { float4 a; float4 b; };
float4 main(float4 p : SV_Position) : SV_Target { return a + b; }
)",
                                                               "ps_5_0", "main"));
  Ref<Buffer> small = MakeBuffer(device(), BIND_CONSTANT_BUFFER, nullptr, 16);
  BindPass(ctx(), t, 8, 8, vs.get(), ps.get());
  ctx().PSSetConstantBuffers(0, {small.get()});
  for (int i = 0; i < 3; ++i) ctx().Draw(4, 0);
  EXPECT_EQ(warnings.size(), 3u);
}

SP_INSTANTIATE_BACKEND_TESTS(RepeatedDrawTest);
SP_INSTANTIATE_VALIDATION_TESTS(RepeatedDrawValidationTest);

}  // namespace
}  // namespace sp::test
