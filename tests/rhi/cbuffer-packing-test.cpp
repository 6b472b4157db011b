// Constant buffers laid out with HLSL's packing rules, including the cases std140 cannot
// express (a float3 right after a float, a float right after a column_major float3x3 or an array,
// arrays of floats, row- and column-major matrices, arrays of structs). The buffer is filled on
// the CPU at the offsets the D3D11 packing rules give, read by a compute, vertex and pixel
// shader, and every member read must equal the value written there.
#include <map>

#include "rhi-test-util.h"

namespace sp::test {
namespace {

class CBufferPackingTest : public BackendTest {};

const char* kTricky = R"(
struct Item { float a; float3 b; float2 c; };
cbuffer Simple : register(b0) { float4 scaleBias; };
cbuffer Tricky : register(b2) {
  float f0;
  float3 v0;
  float2 v1;
  float f1;
  float3x3 m0;
  float f2;
  float arr[3];
  float f3;
  row_major float3x2 m1;
  float2 v2;
  float2x3 m2;
  float f4;
  Item items[2];
  float4 tail;
  row_major float4x4 m3;
};

static const uint kCount = 68;

float Value(uint i) {
  float v[kCount] = {
    f0, v0.x, v0.y, v0.z, v1.x, v1.y, f1,
    m0[0][0], m0[0][1], m0[0][2], m0[1][0], m0[1][1], m0[1][2], m0[2][0], m0[2][1], m0[2][2],
    f2, arr[0], arr[1], arr[2], f3,
    m1[0][0], m1[0][1], m1[1][0], m1[1][1], m1[2][0], m1[2][1],
    v2.x, v2.y,
    m2[0][0], m2[0][1], m2[0][2], m2[1][0], m2[1][1], m2[1][2],
    f4,
    items[0].a, items[0].b.x, items[0].b.y, items[0].b.z, items[0].c.x, items[0].c.y,
    items[1].a, items[1].b.x, items[1].b.y, items[1].b.z, items[1].c.x, items[1].c.y,
    tail.x, tail.y, tail.z, tail.w,
    m3[0][0], m3[0][1], m3[0][2], m3[0][3], m3[1][0], m3[1][1], m3[1][2], m3[1][3],
    m3[2][0], m3[2][1], m3[2][2], m3[2][3], m3[3][0], m3[3][1], m3[3][2], m3[3][3]};
  return v[i] * scaleBias.x + scaleBias.y;
}

RWStructuredBuffer<float> output : register(u0);
[numthreads(kCount, 1, 1)] void CSMain(uint i : SV_DispatchThreadID) { output[i] = Value(i); }

struct V { float4 pos : SV_Position; nointerpolation float value : VALUE; };
V VSMain(uint id : SV_VertexID) {
  V o;
  o.pos = float4((id + 0.5) / kCount * 2 - 1, 0, 0, 1);
  o.value = Value(id);
  return o;
}
float4 PSPassValue(V v) : SV_Target { return v.value; }

float4 VSFullscreen(uint id : SV_VertexID) : SV_Position {
  float2 p = float2((id << 1) & 2, id & 2);
  return float4(p * float2(2, -2) + float2(-1, 1), 0, 1);
}
float4 PSMain(float4 p : SV_Position) : SV_Target { return Value(uint(p.x)); }
)";

constexpr uint32_t kCount = 68;
constexpr uint32_t kTrickySize = 368;

// Where each value read by Value(i) lives in the buffer, by the D3D11 packing rules:
// members pack into the current 16-byte register when they fit, matrices, arrays and structs
// start a register, each array element (and matrix column, or row when row_major) takes one, and
// the next member may pack into the last one.
std::vector<uint32_t> D3DOffsets() {
  std::vector<uint32_t> o;
  auto add = [&](uint32_t base, uint32_t n) {
    for (uint32_t i = 0; i < n; ++i) o.push_back(base + 4 * i);
  };
  add(0, 1);   // f0
  add(4, 3);   // v0: a float3 right after a float
  add(16, 2);  // v1
  add(24, 1);  // f1
  for (uint32_t r = 0; r < 3; ++r)
    for (uint32_t c = 0; c < 3; ++c) o.push_back(32 + c * 16 + r * 4);  // m0, column_major: column c in register c
  add(76, 1);                                                        // f2 after the 44-byte float3x3
  for (uint32_t i = 0; i < 3; ++i) o.push_back(80 + i * 16);         // arr: one register per element
  add(116, 1);                                                       // f3 packed after arr[2]
  for (uint32_t r = 0; r < 3; ++r)
    for (uint32_t c = 0; c < 2; ++c) o.push_back(128 + r * 16 + c * 4);  // m1, row_major 3x2: row r in register r
  add(168, 2);                                                            // v2 after m1's last row (40 bytes)
  for (uint32_t r = 0; r < 2; ++r)
    for (uint32_t c = 0; c < 3; ++c) o.push_back(176 + c * 16 + r * 4);  // m2, column_major 2x3
  add(216, 1);                                                            // f4
  for (uint32_t item = 0; item < 2; ++item) {
    uint32_t base = 224 + item * 32;  // a struct element starts a register; Item is 24 bytes
    add(base, 1);
    add(base + 4, 3);
    add(base + 16, 2);
  }
  add(288, 4);  // tail
  for (uint32_t r = 0; r < 4; ++r)
    for (uint32_t c = 0; c < 4; ++c) o.push_back(304 + r * 16 + c * 4);  // m3, row_major
  return o;
}

struct TrickyData {
  std::vector<uint8_t> bytes = std::vector<uint8_t>(kTrickySize, 0);
  std::vector<float> expected;
};

// Distinct values at every member's D3D offset; the padding holds a poison value that would show
// up if a shader read from the wrong place.
TrickyData MakeData(float seed) {
  TrickyData d;
  for (uint32_t i = 0; i < kTrickySize; i += 4) {
    float poison = -1000.0f - float(i);
    std::memcpy(d.bytes.data() + i, &poison, 4);
  }
  std::vector<uint32_t> offsets = D3DOffsets();
  EXPECT_EQ(offsets.size(), kCount);
  for (uint32_t i = 0; i < offsets.size(); ++i) {
    float v = seed + float(i) * 1.5f;
    std::memcpy(d.bytes.data() + offsets[i], &v, 4);
    d.expected.push_back(v);
  }
  return d;
}

Ref<Buffer> SimpleConstants(Device& dev, float scale, float bias) {
  float v[4] = {scale, bias, 0, 0};
  return MakeBuffer(dev, BIND_CONSTANT_BUFFER, v, 16);
}

// The toolchain reflects the same offsets (guards the CPU layout above as well).
TEST_P(CBufferPackingTest, ReflectionMatchesD3DRules) {
  ShaderBytecode cs = CompileHlsl(kTricky, "cs_5_0", "CSMain");
  const CBufferInfo* cb = cs.reflection.FindCBuffer(2);
  ASSERT_NE(cb, nullptr);
  EXPECT_EQ(cb->size, kTrickySize);
  std::map<std::string, uint32_t> offsets;
  for (const CBufferMember& m : cb->members) offsets[m.name] = m.offset;
  EXPECT_EQ(offsets["v0"], 4u);
  EXPECT_EQ(offsets["m0"], 32u);
  EXPECT_EQ(offsets["f2"], 76u);
  EXPECT_EQ(offsets["arr"], 80u);
  EXPECT_EQ(offsets["f3"], 116u);
  EXPECT_EQ(offsets["m1"], 128u);
  EXPECT_EQ(offsets["v2"], 168u);
  EXPECT_EQ(offsets["m2"], 176u);
  EXPECT_EQ(offsets["f4"], 216u);
  EXPECT_EQ(offsets["items"], 224u);
  EXPECT_EQ(offsets["tail"], 288u);
  EXPECT_EQ(offsets["m3"], 304u);
}

TEST_P(CBufferPackingTest, ComputeShaderReadsEveryMember) {
  TrickyData data = MakeData(1.0f);
  Ref<Buffer> tricky = MakeBuffer(device(), BIND_CONSTANT_BUFFER, data.bytes.data(), kTrickySize);
  Ref<Buffer> simple = SimpleConstants(device(), 2.0f, 0.25f);
  Ref<ComputeShader> cs = device().CreateComputeShader(CompileHlsl(kTricky, "cs_5_0", "CSMain"));
  UavBuffer out = MakeUavBuffer(device(), kCount, 4);
  ctx().CSSetShader(cs.get());
  ctx().CSSetConstantBuffers(0, {simple.get(), nullptr, tricky.get()});
  ctx().CSSetUnorderedAccessViews(0, {out.uav.get()});
  ctx().Dispatch(1, 1, 1);
  std::vector<float> got = ReadBufferAs<float>(device(), ctx(), out.buffer.get());
  for (uint32_t i = 0; i < kCount; ++i) EXPECT_EQ(got[i], data.expected[i] * 2.0f + 0.25f) << "value " << i;
}

// Updating the buffer between dispatches (UpdateSubresource, then Map on a dynamic buffer) must
// be seen by the next dispatch, through whatever copy the backend makes of the buffer.
TEST_P(CBufferPackingTest, UpdatesBetweenDispatchesAreSeen) {
  TrickyData first = MakeData(1.0f), second = MakeData(500.0f), third = MakeData(-70.0f);
  Ref<Buffer> tricky = MakeBuffer(device(), BIND_CONSTANT_BUFFER, first.bytes.data(), kTrickySize);
  BUFFER_DESC dd;
  dd.ByteWidth = kTrickySize;
  dd.Usage = USAGE_DYNAMIC;
  dd.BindFlags = BIND_CONSTANT_BUFFER;
  dd.CPUAccessFlags = CPU_ACCESS_WRITE;
  Ref<Buffer> dynamic = device().CreateBuffer(dd);
  Ref<Buffer> simple = SimpleConstants(device(), 1.0f, 0.0f);
  Ref<ComputeShader> cs = device().CreateComputeShader(CompileHlsl(kTricky, "cs_5_0", "CSMain"));
  UavBuffer outs[3] = {MakeUavBuffer(device(), kCount, 4), MakeUavBuffer(device(), kCount, 4), MakeUavBuffer(device(), kCount, 4)};
  ctx().CSSetShader(cs.get());
  ctx().CSSetConstantBuffers(0, {simple.get(), nullptr, tricky.get()});
  ctx().CSSetUnorderedAccessViews(0, {outs[0].uav.get()});
  ctx().Dispatch(1, 1, 1);
  ctx().UpdateSubresource(tricky.get(), 0, nullptr, second.bytes.data(), 0, 0);
  ctx().CSSetUnorderedAccessViews(0, {outs[1].uav.get()});
  ctx().Dispatch(1, 1, 1);
  MAPPED_SUBRESOURCE m;
  ASSERT_TRUE(ctx().Map(dynamic.get(), 0, MAP_WRITE_DISCARD, 0, &m));
  std::memcpy(m.pData, third.bytes.data(), kTrickySize);
  ctx().Unmap(dynamic.get(), 0);
  ctx().CSSetConstantBuffers(2, {dynamic.get()});
  ctx().CSSetUnorderedAccessViews(0, {outs[2].uav.get()});
  ctx().Dispatch(1, 1, 1);
  const TrickyData* expected[3] = {&first, &second, &third};
  for (int k = 0; k < 3; ++k) {
    std::vector<float> got = ReadBufferAs<float>(device(), ctx(), outs[k].buffer.get());
    for (uint32_t i = 0; i < kCount; ++i) EXPECT_EQ(got[i], expected[k]->expected[i]) << "dispatch " << k << ", value " << i;
  }
}

TEST_P(CBufferPackingTest, VertexShaderReadsEveryMember) {
  TrickyData data = MakeData(3.0f);
  Ref<Buffer> tricky = MakeBuffer(device(), BIND_CONSTANT_BUFFER, data.bytes.data(), kTrickySize);
  Ref<Buffer> simple = SimpleConstants(device(), 1.0f, 0.5f);
  Ref<VertexShader> vs = device().CreateVertexShader(CompileHlsl(kTricky, "vs_5_0", "VSMain"));
  Ref<PixelShader> ps = device().CreatePixelShader(CompileHlsl(kTricky, "ps_5_0", "PSPassValue"));
  Target t = MakeTarget(device(), kCount, 1, FORMAT_R32_FLOAT);
  RenderTargetView* rtvs[] = {t.rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, nullptr);
  SetViewport(ctx(), float(kCount), 1);
  ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_POINTLIST);
  ctx().VSSetShader(vs.get());
  ctx().PSSetShader(ps.get());
  ctx().VSSetConstantBuffers(0, {simple.get(), nullptr, tricky.get()});
  ctx().Draw(kCount, 0);
  std::vector<float> got = ReadTextureAs<float>(device(), ctx(), t.texture.get());
  for (uint32_t i = 0; i < kCount; ++i) EXPECT_EQ(got[i], data.expected[i] + 0.5f) << "value " << i;
}

TEST_P(CBufferPackingTest, PixelShaderReadsEveryMember) {
  TrickyData data = MakeData(-20.0f);
  Ref<Buffer> tricky = MakeBuffer(device(), BIND_CONSTANT_BUFFER, data.bytes.data(), kTrickySize);
  Ref<Buffer> simple = SimpleConstants(device(), -1.0f, 0.0f);
  Ref<VertexShader> vs = device().CreateVertexShader(CompileHlsl(kTricky, "vs_5_0", "VSFullscreen"));
  Ref<PixelShader> ps = device().CreatePixelShader(CompileHlsl(kTricky, "ps_5_0", "PSMain"));
  Target t = MakeTarget(device(), kCount, 2, FORMAT_R32_FLOAT);
  RenderTargetView* rtvs[] = {t.rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, nullptr);
  SetViewport(ctx(), float(kCount), 2);
  ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  ctx().VSSetShader(vs.get());
  ctx().PSSetShader(ps.get());
  ctx().PSSetConstantBuffers(0, {simple.get(), nullptr, tricky.get()});
  ctx().Draw(3, 0);
  std::vector<float> got = ReadTextureAs<float>(device(), ctx(), t.texture.get());
  for (uint32_t y = 0; y < 2; ++y)
    for (uint32_t i = 0; i < kCount; ++i) EXPECT_EQ(got[y * kCount + i], -data.expected[i]) << "value " << i;
}

// D3D11 reads 0 for the part of a cbuffer beyond the end of the bound buffer (the core warns).
TEST_P(CBufferPackingTest, ShortBufferReadsZeroBeyondItsEnd) {
  TrickyData data = MakeData(7.0f);
  Ref<Buffer> tricky = MakeBuffer(device(), BIND_CONSTANT_BUFFER, data.bytes.data(), 128);  // up to and including f3
  Ref<Buffer> simple = SimpleConstants(device(), 1.0f, 0.0f);
  Ref<ComputeShader> cs = device().CreateComputeShader(CompileHlsl(kTricky, "cs_5_0", "CSMain"));
  UavBuffer out = MakeUavBuffer(device(), kCount, 4);
  ctx().CSSetShader(cs.get());
  ctx().CSSetConstantBuffers(0, {simple.get(), nullptr, tricky.get()});
  ctx().CSSetUnorderedAccessViews(0, {out.uav.get()});
  ctx().Dispatch(1, 1, 1);
  std::vector<float> got = ReadBufferAs<float>(device(), ctx(), out.buffer.get());
  std::vector<uint32_t> offsets = D3DOffsets();
  for (uint32_t i = 0; i < kCount; ++i) EXPECT_EQ(got[i], offsets[i] < 128 ? data.expected[i] : 0.0f) << "value " << i;
}

SP_INSTANTIATE_BACKEND_TESTS(CBufferPackingTest);

}  // namespace
}  // namespace sp::test
