// Work submission as D3D11 hides it: enough draws to force the backend to submit in the middle
// of a frame, queries and dynamic resources that span those submissions, Map with
// MAP_FLAG_DO_NOT_WAIT, and GetData with and without ASYNC_GETDATA_DONOTFLUSH.
#include <chrono>
#include <thread>

#include "rhi-test-util.h"

namespace sp::test {
namespace {

class SubmissionTest : public BackendTest {};

const char* kColorPS = R"(
cbuffer C : register(b0) { float4 color; };
float4 main(float4 p : SV_Position) : SV_Target { return color; }
)";

// Thousands of one-pixel draws, each with its own constant buffer contents (WRITE_DISCARD) and
// an occlusion query around all of them: the backend may submit and start new command buffers
// many times in between.
TEST_P(SubmissionTest, ManyDrawsWithDiscardedConstantsAndOneQuery) {
  const uint32_t W = 64, H = 72;
  RectDrawer rect(device());
  Ref<PixelShader> ps = device().CreatePixelShader(CompileHlsl(kColorPS, "ps_5_0", "main"));
  Target t = MakeTarget(device(), W, H, FORMAT_R32_FLOAT);
  BUFFER_DESC cd;
  cd.ByteWidth = 16;
  cd.Usage = USAGE_DYNAMIC;
  cd.BindFlags = BIND_CONSTANT_BUFFER;
  cd.CPUAccessFlags = CPU_ACCESS_WRITE;
  Ref<Buffer> cb = device().CreateBuffer(cd);
  QUERY_DESC qd;
  qd.Query = QUERY_OCCLUSION;
  Ref<Query> q = device().CreateQuery(qd);
  const float zero[4] = {0, 0, 0, 0};
  ctx().ClearRenderTargetView(t.rtv.get(), zero);
  RenderTargetView* rtvs[] = {t.rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, nullptr);
  SetViewport(ctx(), W, H);
  ctx().PSSetShader(ps.get());
  ctx().PSSetConstantBuffers(0, {cb.get()});
  ctx().Begin(q.get());
  std::vector<float> expect(W * H, 0.0f);
  for (uint32_t i = 0; i < W * H; ++i) {
    MAPPED_SUBRESOURCE m;
    ASSERT_TRUE(ctx().Map(cb.get(), 0, MAP_WRITE_DISCARD, 0, &m));
    float c[4] = {float(i) + 0.5f, 0, 0, 0};
    std::memcpy(m.pData, c, 16);
    ctx().Unmap(cb.get(), 0);
    uint32_t x = (i * 7) % W, y = (i * 7) / W % H;  // every pixel once, out of order
    rect.Draw(ctx(), float(x), float(y), float(x + 1), float(y + 1), float(W), float(H));
    expect[y * W + x] = float(i) + 0.5f;
    if (i == W * H / 2) ctx().Flush();
  }
  ctx().End(q.get());
  uint64_t samples = 0;
  while (!ctx().GetData(q.get(), &samples, 8, 0)) std::this_thread::yield();
  EXPECT_EQ(samples, uint64_t(W) * H);
  EXPECT_EQ(ReadTextureAs<float>(device(), ctx(), t.texture.get()), expect);
}

// A dynamic typed buffer (Buffer<float4>) rewritten with WRITE_DISCARD between draws: each draw
// reads its own contents through the same shader resource view.
TEST_P(SubmissionTest, DiscardedDynamicTypedBufferThroughOneView) {
  const uint32_t W = 8, H = 1;
  const char* ps = R"(
Buffer<float4> values : register(t0);
float4 main(float4 p : SV_Position) : SV_Target { return values[uint(p.x)]; }
)";
  RectDrawer rect(device());
  Ref<PixelShader> shader = device().CreatePixelShader(CompileHlsl(ps, "ps_5_0", "main"));
  BUFFER_DESC bd;
  bd.ByteWidth = W * 16;
  bd.Usage = USAGE_DYNAMIC;
  bd.BindFlags = BIND_SHADER_RESOURCE;
  bd.CPUAccessFlags = CPU_ACCESS_WRITE;
  Ref<Buffer> buf = device().CreateBuffer(bd);
  SHADER_RESOURCE_VIEW_DESC sd;
  sd.Format = FORMAT_R32G32B32A32_FLOAT;
  sd.ViewDimension = SRV_DIMENSION_BUFFER;
  sd.Buffer = {0, W};
  Ref<ShaderResourceView> srv = device().CreateShaderResourceView(buf.get(), &sd);
  Target t = MakeTarget(device(), W, H, FORMAT_R32G32B32A32_FLOAT);
  RenderTargetView* rtvs[] = {t.rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, nullptr);
  SetViewport(ctx(), W, H);
  ctx().PSSetShader(shader.get());
  ctx().PSSetShaderResources(0, {srv.get()});
  std::vector<float> expect(W * 4);
  for (uint32_t x = 0; x < W; ++x) {
    MAPPED_SUBRESOURCE m;
    ASSERT_TRUE(ctx().Map(buf.get(), 0, MAP_WRITE_DISCARD, 0, &m));
    float* f = static_cast<float*>(m.pData);
    for (uint32_t i = 0; i < W * 4; ++i) f[i] = float(x * 100 + i);
    ctx().Unmap(buf.get(), 0);
    rect.Draw(ctx(), float(x), 0, float(x + 1), 1, float(W), float(H));
    for (uint32_t c = 0; c < 4; ++c) expect[x * 4 + c] = float(x * 100 + x * 4 + c);
  }
  EXPECT_EQ(ReadTextureAs<float>(device(), ctx(), t.texture.get()), expect);
}

// Map(READ, DO_NOT_WAIT) on a staging buffer the GPU is still writing reports "still drawing"
// (false) until the copy is done, then succeeds without blocking; the data is the copied data.
TEST_P(SubmissionTest, MapDoNotWaitEventuallySucceeds) {
  std::vector<uint32_t> data(1024);
  for (uint32_t i = 0; i < data.size(); ++i) data[i] = i * 3 + 1;
  Ref<Buffer> src = MakeBuffer(device(), BIND_SHADER_RESOURCE, data.data(), 4096, RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS);
  BUFFER_DESC sd;
  sd.ByteWidth = 4096;
  sd.Usage = USAGE_STAGING;
  sd.CPUAccessFlags = CPU_ACCESS_READ;
  Ref<Buffer> staging = device().CreateBuffer(sd);
  ctx().CopyResource(staging.get(), src.get());
  MAPPED_SUBRESOURCE m;
  int attempts = 0;
  while (!ctx().Map(staging.get(), 0, MAP_READ, MAP_FLAG_DO_NOT_WAIT, &m)) {
    ASSERT_LT(++attempts, 100000) << "the copy never finished";
    std::this_thread::sleep_for(std::chrono::microseconds(50));
  }
  EXPECT_EQ(std::memcmp(m.pData, data.data(), 4096), 0);
  ctx().Unmap(staging.get(), 0);
}

// GetData with ASYNC_GETDATA_DONOTFLUSH never completes a query whose End was not submitted;
// an explicit Flush makes it complete.
TEST_P(SubmissionTest, EventQueryNeedsFlushWithDoNotFlush) {
  QUERY_DESC qd;
  qd.Query = QUERY_EVENT;
  Ref<Query> q = device().CreateQuery(qd);
  Target t = MakeTarget(device(), 4, 4, FORMAT_R8G8B8A8_UNORM);
  const float c[4] = {1, 1, 1, 1};
  ctx().ClearRenderTargetView(t.rtv.get(), c);
  ctx().End(q.get());
  uint32_t done = 0;
  ctx().Flush();
  int attempts = 0;
  while (!ctx().GetData(q.get(), &done, 4, ASYNC_GETDATA_DONOTFLUSH)) {
    ASSERT_LT(++attempts, 100000);
    std::this_thread::sleep_for(std::chrono::microseconds(50));
  }
  EXPECT_EQ(done, 1u);
}

// Timestamps written inside and around a render pass are ordered and use the disjoint
// query's frequency; an occlusion query left open across an explicit Flush counts both halves.
TEST_P(SubmissionTest, QueriesAcrossFlushes) {
  const uint32_t W = 16, H = 16;
  RectDrawer rect(device());
  Ref<PixelShader> ps = device().CreatePixelShader(CompileHlsl(kColorPS, "ps_5_0", "main"));
  Ref<Buffer> cb = MakeBuffer(device(), BIND_CONSTANT_BUFFER, nullptr, 16);
  Target t = MakeTarget(device(), W, H, FORMAT_R8G8B8A8_UNORM);
  QUERY_DESC qd;
  qd.Query = QUERY_OCCLUSION;
  Ref<Query> occ = device().CreateQuery(qd);
  qd.Query = QUERY_TIMESTAMP;
  Ref<Query> t0 = device().CreateQuery(qd), t1 = device().CreateQuery(qd), t2 = device().CreateQuery(qd);
  qd.Query = QUERY_TIMESTAMP_DISJOINT;
  Ref<Query> disjoint = device().CreateQuery(qd);
  RenderTargetView* rtvs[] = {t.rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, nullptr);
  SetViewport(ctx(), W, H);
  ctx().PSSetShader(ps.get());
  ctx().PSSetConstantBuffers(0, {cb.get()});
  ctx().Begin(disjoint.get());
  ctx().End(t0.get());
  ctx().Begin(occ.get());
  rect.Draw(ctx(), 0, 0, 4, 4, W, H);  // 16
  ctx().End(t1.get());
  ctx().Flush();
  rect.Draw(ctx(), 4, 4, 7, 7, W, H);  // 9
  ctx().Flush();
  rect.Draw(ctx(), 8, 8, 9, 10, W, H);  // 2
  ctx().End(occ.get());
  ctx().End(t2.get());
  ctx().End(disjoint.get());
  auto wait = [&](Query* q, void* data, uint32_t size) {
    while (!ctx().GetData(q, data, size, 0)) std::this_thread::yield();
  };
  uint64_t samples = 0, a = 0, b = 0, c = 0;
  QUERY_DATA_TIMESTAMP_DISJOINT dj;
  wait(occ.get(), &samples, 8);
  wait(t0.get(), &a, 8);
  wait(t1.get(), &b, 8);
  wait(t2.get(), &c, 8);
  wait(disjoint.get(), &dj, sizeof(dj));
  EXPECT_EQ(samples, 27u);
  EXPECT_LE(a, b);
  EXPECT_LE(b, c);
  EXPECT_FALSE(dj.Disjoint);
  EXPECT_EQ(dj.Frequency, device().Info().timestampFrequency);
  EXPECT_GT(dj.Frequency, 0u);
}

// More draws with distinct shader-resource bindings than one descriptor pool holds.
TEST_P(SubmissionTest, ManyDistinctBindingsInOneFrame) {
  const uint32_t W = 32, H = 32, N = 32;
  const char* ps = R"(
Texture2D<float> tex : register(t3);
SamplerState smp : register(s2);
cbuffer C : register(b1) { float scale; float3 pad; };
float4 main(float4 p : SV_Position) : SV_Target { return tex.Sample(smp, float2(0.5, 0.5)) * scale; }
)";
  RectDrawer rect(device());
  Ref<PixelShader> shader = device().CreatePixelShader(CompileHlsl(ps, "ps_5_0", "main"));
  std::vector<Ref<ShaderResourceView>> srvs;
  std::vector<Ref<Texture2D>> texs;
  for (uint32_t i = 0; i < N; ++i) {
    float v = float(i + 1);
    texs.push_back(MakeTexture2D(device(), 1, 1, FORMAT_R32_FLOAT, BIND_SHADER_RESOURCE, &v));
    srvs.push_back(device().CreateShaderResourceView(texs.back().get()));
  }
  std::vector<Ref<Buffer>> cbs;
  for (uint32_t i = 0; i < N; ++i) {
    float c[4] = {float(i % 3 + 1), 0, 0, 0};
    cbs.push_back(MakeBuffer(device(), BIND_CONSTANT_BUFFER, c, 16));
  }
  SAMPLER_DESC sd;
  sd.Filter = FILTER_MIN_MAG_MIP_POINT;
  Ref<SamplerState> smp = device().CreateSamplerState(sd);
  Target t = MakeTarget(device(), W, H, FORMAT_R32_FLOAT);
  RenderTargetView* rtvs[] = {t.rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, nullptr);
  SetViewport(ctx(), W, H);
  ctx().PSSetShader(shader.get());
  ctx().PSSetSamplers(2, {smp.get()});
  std::vector<float> expect(W * H);
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      uint32_t ti = (x * 5 + y) % N, ci = (x + y * 3) % N;
      ctx().PSSetShaderResources(3, {srvs[ti].get()});
      ctx().PSSetConstantBuffers(1, {cbs[ci].get()});
      rect.Draw(ctx(), float(x), float(y), float(x + 1), float(y + 1), float(W), float(H));
      expect[y * W + x] = float(ti + 1) * float(ci % 3 + 1);
    }
  EXPECT_EQ(ReadTextureAs<float>(device(), ctx(), t.texture.get()), expect);
}

SP_INSTANTIATE_BACKEND_TESTS(SubmissionTest);

}  // namespace
}  // namespace sp::test
