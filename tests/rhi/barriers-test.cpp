// D3D11 hides every barrier: successive dispatches and draws that write and read the same
// resources must see each other's results in call order. These chains are where a backend that
// forgets a barrier (or a layout transition, or restarting a render pass) gives stale data.
// Expected values are computed on the CPU from the call sequence.
#include <numeric>

#include "rhi-test-util.h"

namespace sp::test {
namespace {

class BarriersTest : public BackendTest {};

// Each dispatch reads the previous one's output through the same UAV (read-modify-write) and a
// second buffer through an SRV that the previous dispatch wrote as a UAV.
TEST_P(BarriersTest, DispatchChainsSeeEachOthersWrites) {
  const char* src = R"(
cbuffer Step : register(b0) { uint step; uint3 pad; };
RWStructuredBuffer<uint> acc : register(u0);
RWStructuredBuffer<uint> copyOut : register(u1);
StructuredBuffer<uint> copyIn : register(t0);
[numthreads(64, 1, 1)] void main(uint i : SV_DispatchThreadID) {
  acc[i] = acc[i] * 3 + step + copyIn[i];
  copyOut[i] = acc[i] & 0xff;
}
)";
  const uint32_t N = 256;
  Ref<ComputeShader> cs = device().CreateComputeShader(CompileHlsl(src, "cs_5_0", "main"));
  UavBuffer acc = MakeUavBuffer(device(), N, 4);
  UavBuffer ping = MakeUavBuffer(device(), N, 4), pong = MakeUavBuffer(device(), N, 4);
  Ref<ShaderResourceView> pingSrv = device().CreateShaderResourceView(ping.buffer.get());
  Ref<ShaderResourceView> pongSrv = device().CreateShaderResourceView(pong.buffer.get());
  Ref<Buffer> cb = MakeBuffer(device(), BIND_CONSTANT_BUFFER, nullptr, 16);
  std::vector<uint32_t> cpuAcc(N, 0), cpuPing(N, 0), cpuPong(N, 0);
  ctx().CSSetShader(cs.get());
  ctx().CSSetConstantBuffers(0, {cb.get()});
  for (uint32_t step = 1; step <= 12; ++step) {
    uint32_t c[4] = {step, 0, 0, 0};
    ctx().UpdateSubresource(cb.get(), 0, nullptr, c, 0, 0);
    bool even = step % 2 == 0;
    // Reads the buffer written last step, writes the other one (rebinding swaps roles).
    ctx().CSSetShaderResources(0, {nullptr});
    ctx().CSSetUnorderedAccessViews(0, {acc.uav.get(), even ? ping.uav.get() : pong.uav.get()});
    ctx().CSSetShaderResources(0, {even ? pongSrv.get() : pingSrv.get()});
    ctx().Dispatch(N / 64, 1, 1);
    std::vector<uint32_t>& in = even ? cpuPong : cpuPing;
    std::vector<uint32_t>& out = even ? cpuPing : cpuPong;
    for (uint32_t i = 0; i < N; ++i) {
      cpuAcc[i] = cpuAcc[i] * 3 + step + in[i];
      out[i] = cpuAcc[i] & 0xff;
    }
  }
  ctx().CSSetShaderResources(0, {nullptr});
  ctx().CSSetUnorderedAccessViews(0, {nullptr, nullptr});
  EXPECT_EQ(ReadBufferAs<uint32_t>(device(), ctx(), acc.buffer.get()), cpuAcc);
  EXPECT_EQ(ReadBufferAs<uint32_t>(device(), ctx(), ping.buffer.get()), cpuPing);
  EXPECT_EQ(ReadBufferAs<uint32_t>(device(), ctx(), pong.buffer.get()), cpuPong);
}

// GPU-driven drawing: a compute pass writes the vertex positions, the indices and the indirect
// arguments; the draw consumes all three right away. Then the compute pass overwrites them and
// the second draw must see the new data.
TEST_P(BarriersTest, ComputeWrittenVertexIndexAndArgumentBuffers) {
  const uint32_t W = 16, H = 1;
  const char* gen = R"(
cbuffer Params : register(b0) { uint first; uint count; uint value; uint pad; };
RWByteAddressBuffer verts : register(u0);
RWBuffer<uint> indices : register(u1);
RWBuffer<uint> args : register(u2);
[numthreads(16, 1, 1)] void main(uint i : SV_DispatchThreadID) {
  // Vertex i: x at pixel (first + i) centre, value in the second float.
  float x = (first + i + 0.5) / 16.0 * 2.0 - 1.0;
  verts.Store2(i * 8, uint2(asuint(x), asuint(float(value + i))));
  // Indices in reverse order, so a stale index buffer would be noticed.
  indices[i] = 15 - i;
  if (i == 0) { args[0] = count; args[1] = 1; args[2] = 16 - count; args[3] = 0; args[4] = 0; }
}
)";
  const char* draw = R"(
struct V { float4 pos : SV_Position; nointerpolation float v : VALUE; };
V VSMain(float2 p : POSITION) { V o; o.pos = float4(p.x, 0, 0, 1); o.v = p.y; return o; }
float4 PSMain(V v) : SV_Target { return v.v; }
)";
  BUFFER_DESC vd;
  vd.ByteWidth = 16 * 8;
  vd.BindFlags = BIND_VERTEX_BUFFER | BIND_UNORDERED_ACCESS;
  vd.MiscFlags = RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS;
  Ref<Buffer> vb = device().CreateBuffer(vd);
  UNORDERED_ACCESS_VIEW_DESC ud;
  ud.Format = FORMAT_R32_TYPELESS;
  ud.ViewDimension = UAV_DIMENSION_BUFFER;
  ud.Buffer = {0, 32, BUFFER_UAV_FLAG_RAW};
  Ref<UnorderedAccessView> vbUav = device().CreateUnorderedAccessView(vb.get(), &ud);
  BUFFER_DESC id;
  id.ByteWidth = 16 * 4;
  id.BindFlags = BIND_INDEX_BUFFER | BIND_UNORDERED_ACCESS;
  Ref<Buffer> ib = device().CreateBuffer(id);
  ud.Format = FORMAT_R32_UINT;
  ud.Buffer = {0, 16, 0};
  Ref<UnorderedAccessView> ibUav = device().CreateUnorderedAccessView(ib.get(), &ud);
  BUFFER_DESC ad;
  ad.ByteWidth = 32;
  ad.BindFlags = BIND_UNORDERED_ACCESS;
  ad.MiscFlags = RESOURCE_MISC_DRAWINDIRECT_ARGS;
  Ref<Buffer> args = device().CreateBuffer(ad);
  ud.Buffer = {0, 8, 0};
  Ref<UnorderedAccessView> argsUav = device().CreateUnorderedAccessView(args.get(), &ud);

  Ref<ComputeShader> cs = device().CreateComputeShader(CompileHlsl(gen, "cs_5_0", "main"));
  ShaderBytecode vsb = CompileHlsl(draw, "vs_5_0", "VSMain");
  Ref<VertexShader> vs = device().CreateVertexShader(vsb);
  Ref<PixelShader> ps = device().CreatePixelShader(CompileHlsl(draw, "ps_5_0", "PSMain"));
  INPUT_ELEMENT_DESC el{"POSITION", 0, FORMAT_R32G32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0};
  Ref<InputLayout> layout = device().CreateInputLayout(&el, 1, vsb);
  Ref<Buffer> params = MakeBuffer(device(), BIND_CONSTANT_BUFFER, nullptr, 16);
  Target t = MakeTarget(device(), W, H, FORMAT_R32_FLOAT);
  const float zero[4] = {0, 0, 0, 0};
  ctx().ClearRenderTargetView(t.rtv.get(), zero);

  auto generateAndDraw = [&](uint32_t first, uint32_t count, uint32_t value) {
    uint32_t p[4] = {first, count, value, 0};
    ctx().UpdateSubresource(params.get(), 0, nullptr, p, 0, 0);
    // Unbind from the input assembler before binding for output, as a D3D11 program does.
    Buffer* none = nullptr;
    uint32_t zeroU = 0;
    ctx().IASetVertexBuffers(0, 1, &none, &zeroU, &zeroU);
    ctx().IASetIndexBuffer(nullptr, FORMAT_R32_UINT, 0);
    ctx().CSSetShader(cs.get());
    ctx().CSSetConstantBuffers(0, {params.get()});
    ctx().CSSetUnorderedAccessViews(0, {vbUav.get(), ibUav.get(), argsUav.get()});
    ctx().Dispatch(1, 1, 1);
    ctx().CSSetUnorderedAccessViews(0, {nullptr, nullptr, nullptr});
    RenderTargetView* rtvs[] = {t.rtv.get()};
    ctx().OMSetRenderTargets(1, rtvs, nullptr);
    SetViewport(ctx(), W, H);
    uint32_t stride = 8, offset = 0;
    Buffer* vbs[] = {vb.get()};
    ctx().IASetVertexBuffers(0, 1, vbs, &stride, &offset);
    ctx().IASetIndexBuffer(ib.get(), FORMAT_R32_UINT, 0);
    ctx().IASetInputLayout(layout.get());
    ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_POINTLIST);
    ctx().VSSetShader(vs.get());
    ctx().PSSetShader(ps.get());
    ctx().DrawIndexedInstancedIndirect(args.get(), 0);
  };
  // Indices from 16 - count on are 15 - (16 - count) .. 0, i.e. vertices count-1 .. 0.
  generateAndDraw(0, 4, 100);   // pixels 0..3 = 100..103
  generateAndDraw(8, 6, 500);   // pixels 8..13 = 500..505
  std::vector<float> px = ReadTextureAs<float>(device(), ctx(), t.texture.get());
  std::vector<float> expect(W, 0.0f);
  for (uint32_t i = 0; i < 4; ++i) expect[i] = float(100 + i);
  for (uint32_t i = 0; i < 6; ++i) expect[8 + i] = float(500 + i);
  EXPECT_EQ(px, expect);
}

// A pixel shader accumulates into a UAV texture draw after draw (each draw reads what the one
// before wrote), while render-target output continues in the same render pass.
TEST_P(BarriersTest, PixelShaderUavReadModifyWriteAcrossDraws) {
  const uint32_t W = 8, H = 8;
  const char* ps = R"(
cbuffer K : register(b0) { uint k; uint3 pad; };
RWTexture2D<uint> acc : register(u1);
float4 main(float4 p : SV_Position) : SV_Target {
  uint2 xy = uint2(p.xy);
  acc[xy] = acc[xy] * 2 + k;
  return float4(k, 0, 0, 1);
}
)";
  RectDrawer rect(device());
  Ref<PixelShader> shader = device().CreatePixelShader(CompileHlsl(ps, "ps_5_0", "main"));
  Ref<Texture2D> accTex = MakeTexture2D(device(), W, H, FORMAT_R32_UINT, BIND_UNORDERED_ACCESS | BIND_SHADER_RESOURCE);
  Ref<UnorderedAccessView> accUav = device().CreateUnorderedAccessView(accTex.get());
  Target t = MakeTarget(device(), W, H, FORMAT_R32_FLOAT);
  Ref<Buffer> cb = MakeBuffer(device(), BIND_CONSTANT_BUFFER, nullptr, 16);
  RenderTargetView* rtvs[] = {t.rtv.get()};
  UnorderedAccessView* uavs[] = {accUav.get()};
  ctx().OMSetRenderTargetsAndUnorderedAccessViews(1, rtvs, nullptr, 1, 1, uavs, nullptr);
  SetViewport(ctx(), W, H);
  ctx().PSSetShader(shader.get());
  ctx().PSSetConstantBuffers(0, {cb.get()});
  std::vector<uint32_t> expect(W * H, 0);
  std::vector<float> color(W * H, 0.0f);
  for (uint32_t k = 1; k <= 6; ++k) {
    uint32_t c[4] = {k, 0, 0, 0};
    ctx().UpdateSubresource(cb.get(), 0, nullptr, c, 0, 0);
    float x0 = float(k % 3), y0 = float(k % 2);
    rect.Draw(ctx(), x0, y0, x0 + 5, y0 + 6, W, H);
    for (uint32_t y = uint32_t(y0); y < uint32_t(y0) + 6; ++y)
      for (uint32_t x = uint32_t(x0); x < uint32_t(x0) + 5; ++x) {
        expect[y * W + x] = expect[y * W + x] * 2 + k;
        color[y * W + x] = float(k);
      }
  }
  ctx().OMSetRenderTargets(0, nullptr, nullptr);
  EXPECT_EQ(ReadTextureAs<uint32_t>(device(), ctx(), accTex.get()), expect);
  EXPECT_EQ(ReadTextureAs<float>(device(), ctx(), t.texture.get()), color);
}

// Render to a texture, sample it into a second one, render into the first again and sample it
// again: every switch between output and input is a layout change between render passes.
TEST_P(BarriersTest, PingPongRenderTargets) {
  const uint32_t W = 8, H = 8;
  const char* src = R"(
Texture2D<float> prev : register(t0);
cbuffer K : register(b0) { float add; float3 pad; };
float4 Fill(float4 p : SV_Position) : SV_Target { return add + p.x; }
float4 Step(float4 p : SV_Position) : SV_Target { return prev.Load(int3(p.xy, 0)) * 2 + add; }
)";
  RectDrawer rect(device());
  Ref<PixelShader> fill = device().CreatePixelShader(CompileHlsl(src, "ps_5_0", "Fill"));
  Ref<PixelShader> step = device().CreatePixelShader(CompileHlsl(src, "ps_5_0", "Step"));
  Target a = MakeTarget(device(), W, H, FORMAT_R32_FLOAT, BIND_SHADER_RESOURCE);
  Target b = MakeTarget(device(), W, H, FORMAT_R32_FLOAT, BIND_SHADER_RESOURCE);
  Ref<ShaderResourceView> srvA = device().CreateShaderResourceView(a.texture.get());
  Ref<ShaderResourceView> srvB = device().CreateShaderResourceView(b.texture.get());
  Ref<Buffer> cb = MakeBuffer(device(), BIND_CONSTANT_BUFFER, nullptr, 16);
  SetViewport(ctx(), W, H);
  ctx().PSSetConstantBuffers(0, {cb.get()});
  auto setAdd = [&](float v) {
    float c[4] = {v, 0, 0, 0};
    ctx().UpdateSubresource(cb.get(), 0, nullptr, c, 0, 0);
  };
  RenderTargetView* ta[] = {a.rtv.get()};
  RenderTargetView* tb[] = {b.rtv.get()};
  std::vector<float> va(W * H), vb(W * H);
  ctx().OMSetRenderTargets(1, ta, nullptr);
  ctx().PSSetShader(fill.get());
  setAdd(1);
  rect.Draw(ctx(), 0, 0, W, H, W, H);
  for (uint32_t i = 0; i < W * H; ++i) va[i] = 1 + float(i % W) + 0.5f;
  for (int round = 0; round < 4; ++round) {
    bool toB = round % 2 == 0;
    ctx().OMSetRenderTargets(1, toB ? tb : ta, nullptr);
    ctx().PSSetShaderResources(0, {toB ? srvA.get() : srvB.get()});
    ctx().PSSetShader(step.get());
    setAdd(float(round));
    rect.Draw(ctx(), 0, 0, W, H, W, H);
    ctx().PSSetShaderResources(0, {nullptr});
    std::vector<float>& src0 = toB ? va : vb;
    std::vector<float>& dst0 = toB ? vb : va;
    for (uint32_t i = 0; i < W * H; ++i) dst0[i] = src0[i] * 2 + float(round);
  }
  EXPECT_EQ(ReadTextureAs<float>(device(), ctx(), a.texture.get()), va);
  EXPECT_EQ(ReadTextureAs<float>(device(), ctx(), b.texture.get()), vb);
}

// Copies, clears and updates between draws into the same target land in call order.
TEST_P(BarriersTest, TransfersInterleavedWithDraws) {
  const uint32_t W = 8, H = 4;
  const char* ps = "float4 main(float4 p : SV_Position) : SV_Target { return float4(0.25, 0.5, 0.75, 1); }";
  RectDrawer rect(device());
  Ref<PixelShader> shader = device().CreatePixelShader(CompileHlsl(ps, "ps_5_0", "main"));
  Target t = MakeTarget(device(), W, H, FORMAT_R8G8B8A8_UNORM);
  Ref<Texture2D> other = MakeTexture2D(device(), W, H, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE);
  // UNORM encodings (D3D11: round to nearest): 0.25 -> 64, 0.5 -> 128, 0.75 -> 191.
  const uint32_t kDrawn = 0xffbf8040u, kRed = 0xff0000ffu, kGreen = 0xff00ff00u, kBlue = 0xffff0000u;
  std::vector<uint32_t> expect(W * H);
  auto fill = [&](uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1, uint32_t v) {
    for (uint32_t y = y0; y < y1; ++y)
      for (uint32_t x = x0; x < x1; ++x) expect[y * W + x] = v;
  };
  RenderTargetView* rtvs[] = {t.rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, nullptr);
  SetViewport(ctx(), W, H);
  ctx().PSSetShader(shader.get());
  const float red[4] = {1, 0, 0, 1}, blue[4] = {0, 0, 1, 1};
  ctx().ClearRenderTargetView(t.rtv.get(), red);
  fill(0, 0, W, H, kRed);
  rect.Draw(ctx(), 0, 0, 4, 4, W, H);
  fill(0, 0, 4, 4, kDrawn);
  std::vector<uint32_t> green(4, kGreen);
  BOX box{6, 1, 0, 8, 3, 1};
  ctx().UpdateSubresource(t.texture.get(), 0, &box, green.data(), 8, 0);
  fill(6, 1, 8, 3, kGreen);
  rect.Draw(ctx(), 3, 2, 7, 4, W, H);
  fill(3, 2, 7, 4, kDrawn);
  ctx().CopyResource(other.get(), t.texture.get());
  std::vector<uint32_t> snapshot = expect;
  ctx().ClearRenderTargetView(t.rtv.get(), blue);
  fill(0, 0, W, H, kBlue);
  BOX right{4, 0, 0, 8, 4, 1};
  ctx().CopySubresourceRegion(t.texture.get(), 0, 4, 0, 0, other.get(), 0, &right);
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 4; x < W; ++x) expect[y * W + x] = snapshot[y * W + x];
  rect.Draw(ctx(), 0, 0, 1, 1, W, H);
  fill(0, 0, 1, 1, kDrawn);
  EXPECT_EQ(ReadTextureAs<uint32_t>(device(), ctx(), t.texture.get()), expect);
  EXPECT_EQ(ReadTextureAs<uint32_t>(device(), ctx(), other.get()), snapshot);
}

SP_INSTANTIATE_BACKEND_TESTS(BarriersTest);

}  // namespace
}  // namespace sp::test
