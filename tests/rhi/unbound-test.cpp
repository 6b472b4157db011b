// Registers read with nothing bound: D3D11 reads (0, 0, 0, 0) from every kind of shader resource
// and constant buffer, uses its default sampler state for samplers, and drops UAV writes; the
// debug layer warns. ShadowPort does the same by default (one warning per shader and register)
// and throws SP_UNBOUND_RESOURCE on a device created with strictUnboundResources.
#include <algorithm>

#include "rhi-test-util.h"

namespace sp::test {
namespace {

// One compute shader reading every kind of t register (and a b register) with nothing bound,
// each result as raw bits in outBuf[i].
const char* kReadEverything = R"(
Texture1D<float4> t1 : register(t0);
Texture1DArray<float4> t1a : register(t1);
Texture2D<float4> t2 : register(t2);
Texture2DArray<float4> t2a : register(t3);
Texture3D<float4> t3 : register(t4);
TextureCube<float4> tc : register(t5);
TextureCubeArray<float4> tca : register(t6);
Texture2DMS<float4> tms : register(t7);
Texture2D<uint4> t2u : register(t8);
Texture2D<int4> t2i : register(t9);
Buffer<float4> bf : register(t10);
Buffer<uint4> bu : register(t11);
Buffer<int4> bi : register(t12);
struct Pair { float4 a; uint4 b; };
StructuredBuffer<Pair> sb : register(t13);
ByteAddressBuffer rb : register(t14);
Texture2DMSArray<uint4> tmsa : register(t15);
Texture2D<float> shadow : register(t16);
SamplerState smp : register(s0);
SamplerComparisonState cmp : register(s1);
cbuffer Constants : register(b3) { float4 c0; uint4 c1; };
RWStructuredBuffer<uint4> outBuf : register(u0);
[numthreads(1, 1, 1)] void main() {
  outBuf[0] = asuint(t1.SampleLevel(smp, 0.3, 0));
  outBuf[1] = asuint(t1a.SampleLevel(smp, float2(0.3, 0), 0));
  outBuf[2] = asuint(t2.SampleLevel(smp, float2(0.3, 0.6), 0));
  outBuf[3] = asuint(t2a.SampleLevel(smp, float3(0.3, 0.6, 0), 0));
  outBuf[4] = asuint(t3.SampleLevel(smp, float3(0.3, 0.6, 0.5), 0));
  outBuf[5] = asuint(tc.SampleLevel(smp, float3(1, 0.2, -0.3), 0));
  outBuf[6] = asuint(tca.SampleLevel(smp, float4(-0.2, 1, 0.3, 0), 0));
  outBuf[7] = asuint(tms.Load(int2(0, 0), 0));
  outBuf[8] = t2u.Load(int3(0, 0, 0));
  outBuf[9] = asuint(t2i.Load(int3(0, 0, 0)));
  outBuf[10] = asuint(bf.Load(3));
  outBuf[11] = bu.Load(3);
  outBuf[12] = asuint(bi.Load(3));
  outBuf[13] = asuint(sb[2].a) | sb[2].b;
  outBuf[14] = rb.Load4(16);
  outBuf[15] = tmsa.Load(int3(0, 0, 0), 0);
  outBuf[16] = uint4(asuint(shadow.SampleCmpLevelZero(cmp, float2(0.5, 0.5), 0.5)), 0, 0, 0);
  outBuf[17] = asuint(c0) | c1;
}
)";
constexpr uint32_t kReadCount = 18;
constexpr uint32_t kSentinel = 0xdeadbeefu;
// t0-t16 and b3; s0 is unbound too (s1 is bound: the compared texture needs a real comparison).
constexpr size_t kUnboundInReadEverything = 19;

// UAVs: the first dispatch writes to unbound registers, the second reads them back.
const char* kUavs = R"(
cbuffer Phase : register(b0) { uint phase; };
RWStructuredBuffer<uint4> outBuf : register(u0);
RWStructuredBuffer<uint> counted : register(u1);
RWTexture2D<float> image : register(u2);
RWBuffer<uint> typed : register(u3);
RWByteAddressBuffer raw : register(u4);
AppendStructuredBuffer<uint> list : register(u5);
[numthreads(1, 1, 1)] void main() {
  if (phase == 0) {
    counted[1] = 7;
    image[uint2(0, 0)] = 7.0;
    typed[1] = 7;
    raw.Store(4, 7);
    list.Append(7);
  } else {
    outBuf[0] = uint4(counted[1], asuint(image[uint2(0, 0)]), typed[1], raw.Load(4));
    outBuf[1] = uint4(counted.IncrementCounter(), 0, 0, 0);
  }
}
)";

// The pixel stage: an unbound texture, cbuffer and sampler on top of known constants.
const char* kPixel = R"(
struct VOut { float4 pos : SV_Position; float2 uv : TEXCOORD0; };
VOut VSMain(uint id : SV_VertexID) {
  VOut o;
  o.uv = float2((id << 1) & 2, id & 2);
  o.pos = float4(o.uv.x * 2 - 1, 1 - o.uv.y * 2, 0.5, 1);  // clockwise: front-facing
  return o;
}
Texture2D<float4> g_txShadow : register(t3);
SamplerState g_samLinear : register(s0);
cbuffer Material : register(b2) { float4 tint; };
float4 PSMain(VOut v) : SV_Target {
  return g_txShadow.Sample(g_samLinear, v.uv) + tint + float4(0.2, 0.4, 0.6, 1.0);
}
)";

// D3D11's default sampler state, seen through a bound 2x1 texture (texel values 0 and 1): linear
// filtering and CLAMP addressing.
const char* kDefaultSampler = R"(
Texture2D<float> ramp : register(t0);
SamplerState unbound : register(s5);
RWStructuredBuffer<float4> outBuf : register(u0);
[numthreads(1, 1, 1)] void main() {
  outBuf[0] = float4(ramp.SampleLevel(unbound, float2(0.5, 0.5), 0), ramp.SampleLevel(unbound, float2(-0.25, 0.5), 0),
                     ramp.SampleLevel(unbound, float2(1.25, 0.5), 0), ramp.SampleLevel(unbound, float2(0.375, 0.5), 0));
}
)";

class UnboundTest : public BackendTest {
 protected:
  void CaptureWarnings() {
    device().SetMessageCallback([this](MessageSeverity s, std::string_view t) {
      if (s == MessageSeverity::Warning) warnings.emplace_back(t);
      if (s == MessageSeverity::Error) validationMessages.emplace_back(t);
    });
  }
  UavBuffer Output(uint32_t count) {
    std::vector<uint32_t> sentinel(count * 4, kSentinel);
    UavBuffer out = MakeUavBuffer(device(), count, 16);
    ctx().UpdateSubresource(out.buffer.get(), 0, nullptr, sentinel.data(), 0, 0);
    return out;
  }
  Ref<SamplerState> LessSampler() {
    SAMPLER_DESC d;
    d.Filter = FILTER_COMPARISON_MIN_MAG_MIP_POINT;
    d.ComparisonFunc = COMPARISON_LESS;
    return device().CreateSamplerState(d);
  }
  std::vector<std::string> warnings;
};

TEST_P(UnboundTest, EveryShaderResourceKindReadsZero) {
  CaptureWarnings();
  Ref<ComputeShader> cs = device().CreateComputeShader(CompileHlsl(kReadEverything, "cs_5_0", "main"));
  UavBuffer out = Output(kReadCount);
  Ref<SamplerState> less = LessSampler();
  ctx().CSSetShader(cs.get());
  ctx().CSSetUnorderedAccessViews(0, {out.uav.get()});
  ctx().CSSetSamplers(1, {less.get()});
  ctx().Dispatch(1, 1, 1);
  std::vector<uint32_t> got = ReadBufferAs<uint32_t>(device(), ctx(), out.buffer.get());
  // D3D11: every component of every read is 0 (float 0.0 is the bit pattern 0). The compared
  // texture: a comparison against an unbound texture gives 0 as well.
  for (uint32_t i = 0; i < kReadCount; ++i)
    for (uint32_t c = 0; c < 4; ++c) EXPECT_EQ(got[i * 4 + c], 0u) << "read " << i << " component " << c;
  EXPECT_EQ(warnings.size(), kUnboundInReadEverything);
  for (const std::string& w : warnings) EXPECT_NE(w.find("nothing is bound"), std::string::npos) << w;

  // Once per shader and register: the same dispatch again adds nothing.
  ctx().Dispatch(1, 1, 1);
  EXPECT_EQ(warnings.size(), kUnboundInReadEverything);
  // The application's state is unchanged: the stand-ins never show through the getters.
  Ref<ShaderResourceView> bound;
  ctx().CSGetShaderResources(2, 1, &bound);
  EXPECT_EQ(bound, nullptr);
  Ref<SamplerState> boundSampler;
  ctx().CSGetSamplers(0, 1, &boundSampler);
  EXPECT_EQ(boundSampler, nullptr);
  Ref<Buffer> boundCb;
  ctx().CSGetConstantBuffers(3, 1, &boundCb);
  EXPECT_EQ(boundCb, nullptr);
}

TEST_P(UnboundTest, WarningNamesStageRegisterDeclarationAndShaderOncePerShader) {
  CaptureWarnings();
  ShaderBytecode psCode = CompileHlsl(kPixel, "ps_5_0", "PSMain");
  Ref<VertexShader> vs = device().CreateVertexShader(CompileHlsl(kPixel, "vs_5_0", "VSMain"));
  Ref<PixelShader> ps = device().CreatePixelShader(psCode);
  Target t = MakeTarget(device(), 4, 4, FORMAT_R8G8B8A8_UNORM);
  RenderTargetView* rtvs[] = {t.rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, nullptr);
  SetViewport(ctx(), 4, 4);
  ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  ctx().VSSetShader(vs.get());
  ctx().PSSetShader(ps.get());
  ctx().Draw(3, 0);
  // D3D11: texture and tint read 0, so the target holds the constant, UNORM-encoded.
  std::vector<uint32_t> pixels = ReadTextureAs<uint32_t>(device(), ctx(), t.texture.get());
  const uint32_t expected = 51u | (102u << 8) | (153u << 16) | (255u << 24);  // round(0.2/0.4/0.6/1 * 255)
  for (uint32_t p : pixels) EXPECT_EQ(p, expected);

  const std::string texture = "PSSetShaderResources: PS slot t3 (Texture2D 'g_txShadow' in " + psCode.sourceName +
                              ") is read but nothing is bound; it reads zeros as in D3D11";
  const std::string cbuffer = "PSSetConstantBuffers: PS slot b2 (cbuffer 'Material' in " + psCode.sourceName +
                              ") is read but nothing is bound; it reads zeros as in D3D11";
  const std::string sampler = "PSSetSamplers: PS slot s0 (SamplerState 'g_samLinear' in " + psCode.sourceName +
                              ") is used but nothing is bound; D3D11's default sampler state applies";
  ASSERT_EQ(warnings.size(), 3u);
  for (const std::string& want : {texture, cbuffer, sampler})
    EXPECT_NE(std::find(warnings.begin(), warnings.end(), want), warnings.end()) << "missing: " << want;

  ctx().Draw(3, 0);
  EXPECT_EQ(warnings.size(), 3u);
  // Another shader object reading the same registers is reported for itself.
  Ref<PixelShader> again = device().CreatePixelShader(psCode);
  ctx().PSSetShader(again.get());
  ctx().Draw(3, 0);
  EXPECT_EQ(warnings.size(), 6u);
  // Binding the registers ends the stand-ins and the warnings.
  Ref<Texture2D> white = MakeTexture2D(device(), 1, 1, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE);
  const uint32_t ones = 0xffffffffu;
  ctx().UpdateSubresource(white.get(), 0, nullptr, &ones, 4, 4);
  Ref<ShaderResourceView> srv = device().CreateShaderResourceView(white.get());
  ctx().PSSetShaderResources(3, {srv.get()});
  ctx().Draw(3, 0);
  pixels = ReadTextureAs<uint32_t>(device(), ctx(), t.texture.get());
  for (uint32_t p : pixels) EXPECT_EQ(p, 0xffffffffu);  // 1 + 0 + constant saturates
  EXPECT_EQ(warnings.size(), 6u);
}

TEST_P(UnboundTest, DefaultSamplerStateIsD3D11s) {
  CaptureWarnings();
  Ref<ComputeShader> cs = device().CreateComputeShader(CompileHlsl(kDefaultSampler, "cs_5_0", "main"));
  const float ramp[2] = {0.0f, 1.0f};
  Ref<Texture2D> tex = MakeTexture2D(device(), 2, 1, FORMAT_R32_FLOAT, BIND_SHADER_RESOURCE, ramp);
  Ref<ShaderResourceView> srv = device().CreateShaderResourceView(tex.get());
  UavBuffer out = Output(1);
  ctx().CSSetShader(cs.get());
  ctx().CSSetShaderResources(0, {srv.get()});
  ctx().CSSetUnorderedAccessViews(0, {out.uav.get()});
  ctx().Dispatch(1, 1, 1);
  std::vector<float> got = ReadBufferAs<float>(device(), ctx(), out.buffer.get());
  // MIN_MAG_MIP_LINEAR, CLAMP: texel centres at u = 0.25 and 0.75.
  auto sample = [&](float u) {
    float x = std::clamp(u * 2 - 0.5f, 0.0f, 1.0f);
    return ramp[0] * (1 - x) + ramp[1] * x;
  };
  EXPECT_FLOAT_EQ(got[0], sample(0.5f));    // 0.5: linear
  EXPECT_FLOAT_EQ(got[1], sample(-0.25f));  // 0: clamped (WRAP would give 1)
  EXPECT_FLOAT_EQ(got[2], sample(1.25f));   // 1: clamped (WRAP would give 0)
  EXPECT_NEAR(got[3], sample(0.375f), 1.0f / 256);  // 0.25, within the filter's fixed-point weights
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("CS slot s5 (SamplerState 'unbound'"), std::string::npos) << warnings[0];
}

TEST_P(UnboundTest, UnboundComparisonSamplerComparesWithNever) {
  CaptureWarnings();
  const char* src = R"(
Texture2D<float> depth : register(t0);
SamplerComparisonState cmp : register(s2);
RWStructuredBuffer<float4> outBuf : register(u0);
[numthreads(1, 1, 1)] void main() { outBuf[0] = float4(depth.SampleCmpLevelZero(cmp, float2(0.5, 0.5), 0.25), 0, 0, 0); }
)";
  Ref<ComputeShader> cs = device().CreateComputeShader(CompileHlsl(src, "cs_5_0", "main"));
  Ref<Texture2D> depth = MakeTexture2D(device(), 4, 4, FORMAT_R32_TYPELESS, BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE);
  DEPTH_STENCIL_VIEW_DESC dd;
  dd.Format = FORMAT_D32_FLOAT;
  dd.ViewDimension = DSV_DIMENSION_TEXTURE2D;
  ctx().ClearDepthStencilView(device().CreateDepthStencilView(depth.get(), &dd).get(), CLEAR_DEPTH, 1.0f, 0);
  SHADER_RESOURCE_VIEW_DESC sd;
  sd.Format = FORMAT_R32_FLOAT;
  sd.ViewDimension = SRV_DIMENSION_TEXTURE2D;
  sd.Texture2D = {0, 1};
  Ref<ShaderResourceView> srv = device().CreateShaderResourceView(depth.get(), &sd);
  UavBuffer out = Output(1);
  ctx().CSSetShader(cs.get());
  ctx().CSSetShaderResources(0, {srv.get()});
  ctx().CSSetUnorderedAccessViews(0, {out.uav.get()});
  ctx().Dispatch(1, 1, 1);
  // D3D11's default sampler has ComparisonFunc NEVER: 0, where LESS (0.25 < 1) would give 1.
  EXPECT_EQ(ReadBufferAs<float>(device(), ctx(), out.buffer.get())[0], 0.0f);
  Ref<SamplerState> less = LessSampler();
  ctx().CSSetSamplers(2, {less.get()});
  ctx().Dispatch(1, 1, 1);
  EXPECT_EQ(ReadBufferAs<float>(device(), ctx(), out.buffer.get())[0], 1.0f);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("SamplerComparisonState 'cmp'"), std::string::npos) << warnings[0];
}

TEST_P(UnboundTest, UnboundUavsReadZeroAndDropWrites) {
  CaptureWarnings();
  Ref<ComputeShader> cs = device().CreateComputeShader(CompileHlsl(kUavs, "cs_5_0", "main"));
  UavBuffer out = Output(2);
  BUFFER_DESC bd;
  bd.ByteWidth = 16;
  bd.Usage = USAGE_DYNAMIC;
  bd.BindFlags = BIND_CONSTANT_BUFFER;
  bd.CPUAccessFlags = CPU_ACCESS_WRITE;
  Ref<Buffer> phase = device().CreateBuffer(bd);
  ctx().CSSetShader(cs.get());
  ctx().CSSetUnorderedAccessViews(0, {out.uav.get()});
  ctx().CSSetConstantBuffers(0, {phase.get()});
  for (uint32_t p = 0; p < 2; ++p) {
    MAPPED_SUBRESOURCE m;
    ASSERT_TRUE(ctx().Map(phase.get(), 0, MAP_WRITE_DISCARD, 0, &m));
    std::memcpy(m.pData, &p, 4);
    ctx().Unmap(phase.get(), 0);
    ctx().Dispatch(1, 1, 1);
  }
  std::vector<uint32_t> got = ReadBufferAs<uint32_t>(device(), ctx(), out.buffer.get());
  // What the first dispatch wrote is gone; reads and the counter give 0.
  for (uint32_t c = 0; c < 4; ++c) EXPECT_EQ(got[c], 0u) << "component " << c;
  EXPECT_EQ(got[4], 0u);
  // u1 (RWStructuredBuffer with its counter), u2, u3, u4, u5: one warning each.
  EXPECT_EQ(warnings.size(), 5u);
  for (const std::string& w : warnings) EXPECT_NE(w.find("CSSetUnorderedAccessViews: CS slot u"), std::string::npos) << w;
}

SP_INSTANTIATE_BACKEND_TESTS(UnboundTest);

// What the core refuses, without drawing: these run on the null backend too.
class UnboundValidationTest : public BackendTest {};

TEST_P(UnboundValidationTest, StrictDeviceThrows) {
  DeviceDesc dd;
  dd.backend = backend();
  dd.strictUnboundResources = true;
  dd.shaderCacheDir = TestShaderCacheDir();
  dd.messageCallback = [this](MessageSeverity s, std::string_view t) {
    if (s == MessageSeverity::Error) validationMessages.emplace_back(t);
  };
  Ref<Device> strict = CreateDevice(dd);
  DeviceContext& c = *strict->GetImmediateContext();
  Ref<ComputeShader> cs = strict->CreateComputeShader(CompileHlsl(kReadEverything, "cs_5_0", "main"));
  UavBuffer out = MakeUavBuffer(*strict, kReadCount, 16);
  c.CSSetShader(cs.get());
  c.CSSetUnorderedAccessViews(0, {out.uav.get()});
  try {
    c.Dispatch(1, 1, 1);
    FAIL() << "the dispatch went through";
  } catch (const Error& e) {
    EXPECT_EQ(e.id(), ErrorId::UNBOUND_RESOURCE);
    EXPECT_EQ(e.call(), "Dispatch");
    EXPECT_NE(std::string(e.what()).find("CS slot "), std::string::npos) << e.what();
  }
  Ref<ComputeShader> uavs = strict->CreateComputeShader(CompileHlsl(kUavs, "cs_5_0", "main"));
  Ref<Buffer> phase = MakeBuffer(*strict, BIND_CONSTANT_BUFFER, nullptr, 16);
  c.CSSetShader(uavs.get());
  c.CSSetConstantBuffers(0, {phase.get()});
  try {
    c.Dispatch(1, 1, 1);
    FAIL() << "the dispatch went through";
  } catch (const Error& e) {
    EXPECT_EQ(e.id(), ErrorId::UNBOUND_RESOURCE);
    EXPECT_NE(std::string(e.what()).find("CS slot u"), std::string::npos) << e.what();
  }
  c.ClearState();
}

SP_INSTANTIATE_VALIDATION_TESTS(UnboundValidationTest);

}  // namespace
}  // namespace sp::test
