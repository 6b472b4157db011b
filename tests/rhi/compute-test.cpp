// Unordered access with D3D11's guarantees: UAV writes of a dispatch or draw are visible to every
// later command (sampling, indirect arguments, copies), append/consume counters with initial
// counts and CopyStructureCount, pixel-shader UAVs, UAV clears, and indirect draws and dispatches
// whose arguments a compute shader wrote.
#include <algorithm>

#include "rhi-test-util.h"

namespace sp::test {
namespace {

class ComputeTest : public BackendTest {};

Ref<UnorderedAccessView> TextureUav(Device& dev, Texture2D* tex, FORMAT fmt, uint32_t slices = 0) {
  UNORDERED_ACCESS_VIEW_DESC d;
  d.Format = fmt;
  if (slices) {
    d.ViewDimension = UAV_DIMENSION_TEXTURE2DARRAY;
    d.Texture2DArray = {0, 0, slices};
  } else {
    d.ViewDimension = UAV_DIMENSION_TEXTURE2D;
  }
  return dev.CreateUnorderedAccessView(tex, &d);
}

// A dispatch writes a texture array through a UAV; a draw right after samples it.
TEST_P(ComputeTest, DispatchWritesThenDrawSamples) {
  const uint32_t W = 8, H = 8, S = 2;
  Ref<Texture2D> tex = MakeTexture2D(device(), W, H, FORMAT_R32_FLOAT, BIND_UNORDERED_ACCESS | BIND_SHADER_RESOURCE, nullptr, 1, S);
  Ref<UnorderedAccessView> uav = TextureUav(device(), tex.get(), FORMAT_R32_FLOAT, S);
  Ref<ShaderResourceView> srv = device().CreateShaderResourceView(tex.get());
  const char* cs = R"(
RWTexture2DArray<float> target : register(u0);
[numthreads(8, 8, 1)] void main(uint3 id : SV_DispatchThreadID) { target[id] = id.x + id.y * 8 + id.z * 100; }
)";
  const char* ps = R"(
Texture2DArray<float> src : register(t0);
float4 main(float4 p : SV_Position) : SV_Target { return src.Load(int4(p.xy, 1, 0)); }
)";
  Ref<ComputeShader> c = device().CreateComputeShader(CompileHlsl(cs, "cs_5_0", "main"));
  Ref<PixelShader> p = device().CreatePixelShader(CompileHlsl(ps, "ps_5_0", "main"));
  ctx().CSSetShader(c.get());
  ctx().CSSetUnorderedAccessViews(0, {uav.get()});
  ctx().Dispatch(1, 1, S);
  ctx().CSSetUnorderedAccessViews(0, {nullptr});
  Target t = MakeTarget(device(), W, H, FORMAT_R32_FLOAT);
  RectDrawer rect(device());
  RenderTargetView* rtvs[] = {t.rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, nullptr);
  SetViewport(ctx(), W, H);
  ctx().PSSetShader(p.get());
  ctx().PSSetShaderResources(0, {srv.get()});
  rect.Draw(ctx(), 0, 0, W, H, W, H);
  std::vector<float> px = ReadTextureAs<float>(device(), ctx(), t.texture.get());
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) ASSERT_EQ(px[y * W + x], float(x + y * 8 + 100)) << x << "," << y;
  std::vector<float> slice0 = ReadTextureAs<float>(device(), ctx(), tex.get(), 0);
  EXPECT_EQ(slice0[9], 9.0f);
}

// Append with an initial count, consume, and CopyStructureCount of the hidden counter.
TEST_P(ComputeTest, AppendConsumeAndStructureCount) {
  UavBuffer appendBuf = MakeUavBuffer(device(), 64, 4, BUFFER_UAV_FLAG_APPEND);
  UavBuffer consumed = MakeUavBuffer(device(), 64, 4);
  const char* append = R"(
AppendStructuredBuffer<uint> items : register(u0);
[numthreads(32, 1, 1)] void main(uint3 id : SV_DispatchThreadID) { if (id.x % 3 == 0) items.Append(1000 + id.x); }
)";
  const char* consume = R"(
ConsumeStructuredBuffer<uint> items : register(u0);
RWStructuredBuffer<uint> output : register(u1);
[numthreads(4, 1, 1)] void main(uint3 id : SV_DispatchThreadID) { output[id.x] = items.Consume(); }
)";
  Ref<ComputeShader> a = device().CreateComputeShader(CompileHlsl(append, "cs_5_0", "main"));
  Ref<ComputeShader> c = device().CreateComputeShader(CompileHlsl(consume, "cs_5_0", "main"));
  ctx().CSSetShader(a.get());
  UnorderedAccessView* uavs[] = {appendBuf.uav.get()};
  const uint32_t initial[] = {5};
  ctx().CSSetUnorderedAccessViews(0, 1, uavs, initial);
  ctx().Dispatch(1, 1, 1);  // 11 appends (0, 3, ..., 30) after 5 existing elements
  Ref<Buffer> count = MakeBuffer(device(), BIND_SHADER_RESOURCE, nullptr, 16, RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS);
  ctx().CopyStructureCount(count.get(), 4, appendBuf.uav.get());
  std::vector<uint32_t> n = ReadBufferAs<uint32_t>(device(), ctx(), count.get());
  EXPECT_EQ(n[1], 16u);
  std::vector<uint32_t> items = ReadBufferAs<uint32_t>(device(), ctx(), appendBuf.buffer.get());
  std::vector<uint32_t> appended(items.begin() + 5, items.begin() + 16);
  std::sort(appended.begin(), appended.end());
  for (uint32_t i = 0; i < 11; ++i) EXPECT_EQ(appended[i], 1000 + i * 3);

  // Consume 4 from the top (the counter keeps its value across bindings: -1 keeps it).
  ctx().CSSetShader(c.get());
  UnorderedAccessView* both[] = {appendBuf.uav.get(), consumed.uav.get()};
  const uint32_t keep[] = {0xffffffffu, 0xffffffffu};
  ctx().CSSetUnorderedAccessViews(0, 2, both, keep);
  ctx().Dispatch(1, 1, 1);
  ctx().CopyStructureCount(count.get(), 8, appendBuf.uav.get());
  n = ReadBufferAs<uint32_t>(device(), ctx(), count.get());
  EXPECT_EQ(n[2], 12u);
  std::vector<uint32_t> out = ReadBufferAs<uint32_t>(device(), ctx(), consumed.buffer.get());
  std::vector<uint32_t> got(out.begin(), out.begin() + 4), expect(items.begin() + 12, items.begin() + 16);
  std::sort(got.begin(), got.end());
  std::sort(expect.begin(), expect.end());
  EXPECT_EQ(got, expect);
}

// A compute shader writes draw and dispatch arguments; the indirect calls use them at once.
TEST_P(ComputeTest, IndirectArgumentsWrittenByCompute) {
  const uint32_t W = 8, H = 1;
  BUFFER_DESC ad;
  ad.ByteWidth = 64;
  ad.BindFlags = BIND_UNORDERED_ACCESS;
  ad.MiscFlags = RESOURCE_MISC_DRAWINDIRECT_ARGS;
  Ref<Buffer> args = device().CreateBuffer(ad);
  UNORDERED_ACCESS_VIEW_DESC ud;
  ud.Format = FORMAT_R32_UINT;
  ud.ViewDimension = UAV_DIMENSION_BUFFER;
  ud.Buffer = {0, 16, 0};
  Ref<UnorderedAccessView> argsUav = device().CreateUnorderedAccessView(args.get(), &ud);
  const char* writer = R"(
RWBuffer<uint> args : register(u0);
[numthreads(1, 1, 1)] void main() {
  // DrawIndexedInstancedIndirect at 0: 3 indices, 2 instances, start index 3, base vertex 0, start instance 0
  args[0] = 3; args[1] = 2; args[2] = 3; args[3] = 0; args[4] = 0;
  // DispatchIndirect at 32: 3 x 1 x 1 groups
  args[8] = 3; args[9] = 1; args[10] = 1;
  // DrawInstancedIndirect at 48: 1 vertex, 1 instance, start vertex 7, start instance 0
  args[12] = 1; args[13] = 1; args[14] = 7; args[15] = 0;
}
)";
  const char* counter = R"(
RWStructuredBuffer<uint> hits : register(u0);
[numthreads(4, 1, 1)] void main(uint3 id : SV_DispatchThreadID) { InterlockedAdd(hits[id.x], 1); }
)";
  // Points at pixel x = vertex id (index) + 2 * instance.
  const char* draw = R"(
struct V { float4 pos : SV_Position; float v : VALUE; };
V VSMain(uint id : SV_VertexID, uint inst : SV_InstanceID) {
  V o;
  o.pos = float4((id + 2 * inst + 0.5) / 8 * 2 - 1, 0, 0, 1);
  o.v = 10 + id + 100 * inst;
  return o;
}
float4 PSMain(V v) : SV_Target { return v.v; }
)";
  Ref<ComputeShader> w = device().CreateComputeShader(CompileHlsl(writer, "cs_5_0", "main"));
  Ref<ComputeShader> c = device().CreateComputeShader(CompileHlsl(counter, "cs_5_0", "main"));
  Ref<VertexShader> vs = device().CreateVertexShader(CompileHlsl(draw, "vs_5_0", "VSMain"));
  Ref<PixelShader> ps = device().CreatePixelShader(CompileHlsl(draw, "ps_5_0", "PSMain"));
  ctx().CSSetShader(w.get());
  ctx().CSSetUnorderedAccessViews(0, {argsUav.get()});
  ctx().Dispatch(1, 1, 1);
  ctx().CSSetUnorderedAccessViews(0, {nullptr});

  UavBuffer hits = MakeUavBuffer(device(), 16, 4);
  ctx().CSSetShader(c.get());
  ctx().CSSetUnorderedAccessViews(0, {hits.uav.get()});
  ctx().DispatchIndirect(args.get(), 32);
  std::vector<uint32_t> h = ReadBufferAs<uint32_t>(device(), ctx(), hits.buffer.get());
  for (uint32_t i = 0; i < 16; ++i) EXPECT_EQ(h[i], i < 12 ? 1u : 0u) << i;

  // Index buffer bound with an offset: indices from byte 8 on are 0..5.
  const uint32_t indices[] = {99, 99, 0, 1, 2, 3, 4, 5};
  Ref<Buffer> ib = MakeBuffer(device(), BIND_INDEX_BUFFER, indices, sizeof(indices));
  Target t = MakeTarget(device(), W, H, FORMAT_R32_FLOAT);
  const float zero[4] = {0, 0, 0, 0};
  ctx().ClearRenderTargetView(t.rtv.get(), zero);
  RenderTargetView* rtvs[] = {t.rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, nullptr);
  SetViewport(ctx(), W, H);
  ctx().VSSetShader(vs.get());
  ctx().PSSetShader(ps.get());
  ctx().IASetInputLayout(nullptr);
  ctx().IASetIndexBuffer(ib.get(), FORMAT_R32_UINT, 8);
  ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_POINTLIST);
  ctx().DrawIndexedInstancedIndirect(args.get(), 0);  // indices 3, 4, 5 (start 3), instances 0 and 1
  ctx().DrawInstancedIndirect(args.get(), 48);       // vertex 7
  std::vector<float> px = ReadTextureAs<float>(device(), ctx(), t.texture.get());
  // Instance 0: vertices 3, 4, 5 at x 3..5; instance 1 at x 5..7 (later, so it wins at x 5);
  // the second draw's vertex 7 overwrites x 7.
  std::vector<float> expect = {0, 0, 0, 13, 14, 113, 114, 17};
  for (uint32_t x = 0; x < W; ++x) EXPECT_EQ(px[x], expect[x]) << x;
}

// Pixel shaders write UAVs bound next to render targets (OMSetRenderTargetsAndUnorderedAccessViews).
TEST_P(ComputeTest, PixelShaderUavs) {
  const uint32_t W = 8, H = 4;
  const char* ps = R"(
RWStructuredBuffer<uint> counts : register(u1);
RWTexture2D<uint> ids : register(u2);
float4 main(float4 p : SV_Position) : SV_Target {
  InterlockedAdd(counts[0], 1);
  ids[uint2(p.xy)] = uint(p.x) + uint(p.y) * 100;
  return 1;
}
)";
  Ref<PixelShader> p = device().CreatePixelShader(CompileHlsl(ps, "ps_5_0", "main"));
  Target t = MakeTarget(device(), W, H, FORMAT_R8G8B8A8_UNORM);
  UavBuffer counts = MakeUavBuffer(device(), 4, 4);
  Ref<Texture2D> ids = MakeTexture2D(device(), W, H, FORMAT_R32_UINT, BIND_UNORDERED_ACCESS);
  Ref<UnorderedAccessView> idsUav = TextureUav(device(), ids.get(), FORMAT_R32_UINT);
  RectDrawer rect(device());
  RenderTargetView* rtvs[] = {t.rtv.get()};
  UnorderedAccessView* uavs[] = {counts.uav.get(), idsUav.get()};
  ctx().OMSetRenderTargetsAndUnorderedAccessViews(1, rtvs, nullptr, 1, 2, uavs, nullptr);
  SetViewport(ctx(), W, H);
  ctx().PSSetShader(p.get());
  rect.Draw(ctx(), 0, 0, W, H, W, H);
  rect.Draw(ctx(), 0, 0, 2, 2, W, H);
  ctx().OMSetRenderTargets(0, nullptr, nullptr);
  EXPECT_EQ(ReadBufferAs<uint32_t>(device(), ctx(), counts.buffer.get())[0], W * H + 4);
  std::vector<uint32_t> v = ReadTextureAs<uint32_t>(device(), ctx(), ids.get());
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) EXPECT_EQ(v[y * W + x], x + y * 100);
}

// ClearUnorderedAccessViewFloat converts; ClearUnorderedAccessViewUint writes raw low bits.
TEST_P(ComputeTest, UavClears) {
  Ref<Texture2D> f = MakeTexture2D(device(), 4, 4, FORMAT_R16G16B16A16_FLOAT, BIND_UNORDERED_ACCESS);
  Ref<Texture2D> u = MakeTexture2D(device(), 4, 4, FORMAT_R8G8B8A8_UNORM, BIND_UNORDERED_ACCESS);
  Ref<Texture2D> r = MakeTexture2D(device(), 4, 4, FORMAT_R32_FLOAT, BIND_UNORDERED_ACCESS);
  const float fv[4] = {0.5f, -2.0f, 1024.0f, 0.25f};
  ctx().ClearUnorderedAccessViewFloat(TextureUav(device(), f.get(), FORMAT_R16G16B16A16_FLOAT).get(), fv);
  const float uf[4] = {0.5f, 2.0f, -1.0f, 0.2f};
  ctx().ClearUnorderedAccessViewFloat(TextureUav(device(), u.get(), FORMAT_R8G8B8A8_UNORM).get(), uf);
  const uint32_t bits[4] = {0x3f800000u, 7, 8, 9};  // R32_FLOAT: the bits of 1.0f
  ctx().ClearUnorderedAccessViewUint(TextureUav(device(), r.get(), FORMAT_R32_FLOAT).get(), bits);
  std::vector<uint16_t> hf = ReadTextureAs<uint16_t>(device(), ctx(), f.get());
  EXPECT_EQ(hf[0], 0x3800);  // 0.5 as half
  EXPECT_EQ(hf[1], 0xc000);  // -2
  EXPECT_EQ(hf[2], 0x6400);  // 1024
  EXPECT_EQ(hf[3], 0x3400);  // 0.25
  std::vector<uint8_t> ub = ReadTexture(device(), ctx(), u.get());
  EXPECT_EQ(ub[0], 128);
  EXPECT_EQ(ub[1], 255);
  EXPECT_EQ(ub[2], 0);
  EXPECT_EQ(ub[3], 51);
  std::vector<float> rf = ReadTextureAs<float>(device(), ctx(), r.get());
  for (float v : rf) EXPECT_EQ(v, 1.0f);
  const uint32_t raw[4] = {0x12345678u, 0x11, 0x22, 0x33};
  ctx().ClearUnorderedAccessViewUint(TextureUav(device(), u.get(), FORMAT_R8G8B8A8_UNORM).get(), raw);
  ub = ReadTexture(device(), ctx(), u.get());
  EXPECT_EQ(ub[0], 0x78);  // low 8 bits of each value
  EXPECT_EQ(ub[1], 0x11);
  EXPECT_EQ(ub[2], 0x22);
  EXPECT_EQ(ub[3], 0x33);

  // Structured: every element gets values[0]. Typed buffer: per-channel low bits.
  UavBuffer s = MakeUavBuffer(device(), 8, 8);
  const uint32_t sv[4] = {0xdeadbeefu, 1, 2, 3};
  ctx().ClearUnorderedAccessViewUint(s.uav.get(), sv);
  for (uint32_t v : ReadBufferAs<uint32_t>(device(), ctx(), s.buffer.get())) EXPECT_EQ(v, 0xdeadbeefu);
  Ref<Buffer> typed = MakeBuffer(device(), BIND_UNORDERED_ACCESS, nullptr, 64);
  UNORDERED_ACCESS_VIEW_DESC td;
  td.Format = FORMAT_R16G16_UINT;
  td.ViewDimension = UAV_DIMENSION_BUFFER;
  td.Buffer = {4, 8, 0};
  Ref<UnorderedAccessView> typedUav = device().CreateUnorderedAccessView(typed.get(), &td);
  const uint32_t tv[4] = {0x10005, 0x20007, 0, 0};
  ctx().ClearUnorderedAccessViewUint(typedUav.get(), tv);
  std::vector<uint16_t> tb = ReadBufferAs<uint16_t>(device(), ctx(), typed.get());
  for (uint32_t i = 0; i < 16; ++i) {
    bool inView = i >= 4 && i < 12;
    EXPECT_EQ(tb[i * 2], inView ? 5 : 0) << i;
    EXPECT_EQ(tb[i * 2 + 1], inView ? 7 : 0) << i;
  }
}

SP_INSTANTIATE_BACKEND_TESTS(ComputeTest);

}  // namespace
}  // namespace sp::test
