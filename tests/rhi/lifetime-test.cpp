// Object lifetimes as D3D11 programs rely on them: releasing a resource right after the draw that
// uses it (the GPU may not have run it yet), recycling memory through many create/release
// cycles, resources larger than any pooled block, and a device destroyed while the application
// still holds objects.
#include <numeric>

#include "rhi-test-util.h"

namespace sp::test {
namespace {

class LifetimeTest : public BackendTest {};

const char* kCopyPS = R"(
Texture2D<float4> src : register(t0);
cbuffer C : register(b0) { float4 add; };
float4 main(float4 p : SV_Position) : SV_Target { return src.Load(int3(p.xy, 0)) + add; }
)";

// Every draw samples a texture and reads a constant buffer that are released immediately after;
// the results must still be those of the released objects.
TEST_P(LifetimeTest, ResourcesReleasedRightAfterUse) {
  const uint32_t W = 4, H = 4;
  RectDrawer rect(device());
  Ref<PixelShader> ps = device().CreatePixelShader(CompileHlsl(kCopyPS, "ps_5_0", "main"));
  Target t = MakeTarget(device(), W, H, FORMAT_R32G32B32A32_FLOAT);
  RenderTargetView* rtvs[] = {t.rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, nullptr);
  SetViewport(ctx(), W, H);
  ctx().PSSetShader(ps.get());
  std::vector<float> expect(W * H * 4, 0.0f);
  for (uint32_t col = 0; col < W; ++col) {
    std::vector<float> texels(W * H * 4);
    for (uint32_t i = 0; i < W * H * 4; ++i) texels[i] = float(col * 1000 + i);
    float add[4] = {0.5f * float(col + 1), 0, 0, 0};
    {
      Ref<Texture2D> tex = MakeTexture2D(device(), W, H, FORMAT_R32G32B32A32_FLOAT, BIND_SHADER_RESOURCE, texels.data());
      Ref<ShaderResourceView> srv = device().CreateShaderResourceView(tex.get());
      Ref<Buffer> cb = MakeBuffer(device(), BIND_CONSTANT_BUFFER, add, 16);
      ctx().PSSetShaderResources(0, {srv.get()});
      ctx().PSSetConstantBuffers(0, {cb.get()});
      rect.Draw(ctx(), float(col), 0, float(col + 1), float(H), float(W), float(H));
      // Unbind and drop every reference: only the GPU still needs them.
      ctx().PSSetShaderResources(0, {nullptr});
      ctx().PSSetConstantBuffers(0, {nullptr});
    }
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t c = 0; c < 4; ++c) expect[(y * W + col) * 4 + c] = texels[(y * W + col) * 4 + c] + add[c];
  }
  EXPECT_EQ(ReadTextureAs<float>(device(), ctx(), t.texture.get()), expect);
}

// Many buffers and textures created, used once and released, in a loop long enough to reuse
// memory many times over; every round's result must be its own.
TEST_P(LifetimeTest, CreateUseReleaseLoopsRecycleMemory) {
  const char* cs = R"(
StructuredBuffer<uint> input : register(t0);
RWStructuredBuffer<uint> output : register(u0);
[numthreads(64, 1, 1)] void main(uint i : SV_DispatchThreadID) { output[i] = input[i] * 2 + 1; }
)";
  Ref<ComputeShader> shader = device().CreateComputeShader(CompileHlsl(cs, "cs_5_0", "main"));
  ctx().CSSetShader(shader.get());
  for (uint32_t round = 0; round < 40; ++round) {
    uint32_t n = 64 * (1 + round % 5);
    std::vector<uint32_t> data(n);
    std::iota(data.begin(), data.end(), round * 7919u);
    Ref<Buffer> in = MakeBuffer(device(), BIND_SHADER_RESOURCE, data.data(), n * 4, RESOURCE_MISC_BUFFER_STRUCTURED, 4);
    Ref<ShaderResourceView> srv = device().CreateShaderResourceView(in.get());
    UavBuffer out = MakeUavBuffer(device(), n, 4);
    ctx().CSSetShaderResources(0, {srv.get()});
    ctx().CSSetUnorderedAccessViews(0, {out.uav.get()});
    ctx().Dispatch(n / 64, 1, 1);
    ctx().CSSetUnorderedAccessViews(0, {nullptr});
    ctx().CSSetShaderResources(0, {nullptr});
    // Read back only every few rounds, so most releases happen while work is in flight.
    if (round % 8 == 7) {
      std::vector<uint32_t> got = ReadBufferAs<uint32_t>(device(), ctx(), out.buffer.get());
      for (uint32_t i = 0; i < n; ++i) ASSERT_EQ(got[i], data[i] * 2 + 1) << "round " << round << " element " << i;
    }
    Ref<Texture2D> tex = MakeTexture2D(device(), 16 + round, 8, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE | BIND_RENDER_TARGET);
    Ref<RenderTargetView> rtv = device().CreateRenderTargetView(tex.get());
    const float c[4] = {float(round % 4) / 3.0f, 0, 0, 1};
    ctx().ClearRenderTargetView(rtv.get(), c);
  }
}

// Buffers and textures bigger than the backends' pooled blocks, with initial data, read back.
TEST_P(LifetimeTest, LargeResourcesWithInitialData) {
  const uint32_t words = (20u << 20) / 4;  // 20 MiB
  std::vector<uint32_t> data(words);
  for (uint32_t i = 0; i < words; ++i) data[i] = i * 2654435761u;
  Ref<Buffer> big = MakeBuffer(device(), BIND_SHADER_RESOURCE, data.data(), words * 4, RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS);
  EXPECT_TRUE(ReadBufferAs<uint32_t>(device(), ctx(), big.get()) == data);
  const uint32_t W = 2048, H = 1024;  // 8 MiB of RGBA8
  std::vector<uint32_t> texels(W * H);
  for (uint32_t i = 0; i < W * H; ++i) texels[i] = i ^ 0x5a5a5a5au;
  Ref<Texture2D> tex = MakeTexture2D(device(), W, H, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE, texels.data());
  EXPECT_TRUE(ReadTextureAs<uint32_t>(device(), ctx(), tex.get()) == texels);
}

SP_INSTANTIATE_BACKEND_TESTS(LifetimeTest);

// Misuse the core reports, without drawing: these run on the null backend too.
class LifetimeValidationTest : public BackendTest {};

// A device destroyed while the application still holds objects: they stay safe to release.
TEST_P(LifetimeValidationTest, ObjectsOutlivingTheirDevice) {
  std::vector<std::string> warnings;
  DeviceDesc desc;
  desc.backend = backend();
  desc.messageCallback = [&](MessageSeverity s, std::string_view text) {
    if (s == MessageSeverity::Error) validationMessages.emplace_back(text);
    else warnings.emplace_back(text);
  };
  Ref<Device> dev = CreateDevice(desc);
  Ref<Texture2D> tex = MakeTexture2D(*dev, 8, 8, FORMAT_R8G8B8A8_UNORM, BIND_RENDER_TARGET | BIND_SHADER_RESOURCE);
  Ref<RenderTargetView> rtv = dev->CreateRenderTargetView(tex.get());
  Ref<ShaderResourceView> srv = dev->CreateShaderResourceView(tex.get());
  Ref<Buffer> buf = MakeBuffer(*dev, BIND_CONSTANT_BUFFER, nullptr, 64);
  SAMPLER_DESC sd;
  Ref<SamplerState> smp = dev->CreateSamplerState(sd);
  QUERY_DESC qd;
  qd.Query = QUERY_OCCLUSION;
  Ref<Query> query = dev->CreateQuery(qd);
  const float c[4] = {1, 0, 0, 1};
  dev->GetImmediateContext()->ClearRenderTargetView(rtv.get(), c);
  dev->GetImmediateContext()->Begin(query.get());  // still active when the device goes
  dev.reset();
  EXPECT_FALSE(warnings.empty()) << "outliving objects are reported";
  query.reset();
  smp.reset();
  srv.reset();
  rtv.reset();
  tex.reset();
  buf.reset();
}

SP_INSTANTIATE_VALIDATION_TESTS(LifetimeValidationTest);

}  // namespace
}  // namespace sp::test
