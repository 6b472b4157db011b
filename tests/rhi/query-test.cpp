// Queries: occlusion counts samples (overlapping queries each count their own span), timestamps
// increase and come with their frequency, events complete; GetData returns false until then.
#include "rhi-test-util.h"

namespace sp::test {
namespace {

class QueryTest : public BackendTest {};

template <class T>
T Wait(DeviceContext& ctx, Query* q) {
  T value{};
  for (int i = 0; i < 1000000 && !ctx.GetData(q, &value, sizeof(T), 0); ++i) {
  }
  return value;
}

TEST_P(QueryTest, OverlappingOcclusionQueries) {
  const uint32_t W = 16, H = 16;
  Target t = MakeTarget(device(), W, H, FORMAT_R8G8B8A8_UNORM);
  Ref<Texture2D> depth = MakeTexture2D(device(), W, H, FORMAT_D32_FLOAT, BIND_DEPTH_STENCIL);
  Ref<DepthStencilView> dsv = device().CreateDepthStencilView(depth.get());
  const char* ps = "float4 main(float4 p : SV_Position) : SV_Target { return 1; }";
  Ref<PixelShader> shader = device().CreatePixelShader(CompileHlsl(ps, "ps_5_0", "main"));
  RectDrawer rect(device());
  QUERY_DESC qd;
  qd.Query = QUERY_OCCLUSION;
  Ref<Query> outer = device().CreateQuery(qd), inner = device().CreateQuery(qd);
  ctx().ClearDepthStencilView(dsv.get(), CLEAR_DEPTH, 1.0f, 0);
  RenderTargetView* rtvs[] = {t.rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, dsv.get());
  SetViewport(ctx(), W, H);
  ctx().PSSetShader(shader.get());
  ctx().Begin(outer.get());
  rect.Draw(ctx(), 0, 0, 4, 4, W, H, 0.5f);  // 16 samples
  ctx().Begin(inner.get());
  rect.Draw(ctx(), 8, 8, 10, 10, W, H, 0.5f);  // 4 samples
  rect.Draw(ctx(), 0, 0, 4, 4, W, H, 0.75f);   // behind the first quad: 0 samples
  ctx().End(outer.get());
  rect.Draw(ctx(), 12, 12, 13, 13, W, H, 0.5f);  // 1 sample
  ctx().End(inner.get());
  EXPECT_EQ(Wait<uint64_t>(ctx(), outer.get()), 20u);
  EXPECT_EQ(Wait<uint64_t>(ctx(), inner.get()), 5u);
  // A query reused for a second span counts only that span.
  ctx().Begin(outer.get());
  rect.Draw(ctx(), 0, 8, 2, 9, W, H, 0.5f);  // 2 samples
  ctx().End(outer.get());
  EXPECT_EQ(Wait<uint64_t>(ctx(), outer.get()), 2u);
}

TEST_P(QueryTest, TimestampsAndDisjoint) {
  QUERY_DESC td;
  td.Query = QUERY_TIMESTAMP;
  QUERY_DESC dd;
  dd.Query = QUERY_TIMESTAMP_DISJOINT;
  Ref<Query> disjoint = device().CreateQuery(dd), t0 = device().CreateQuery(td), t1 = device().CreateQuery(td);
  Target t = MakeTarget(device(), 32, 32, FORMAT_R8G8B8A8_UNORM);
  ctx().Begin(disjoint.get());
  ctx().End(t0.get());
  const float c[4] = {1, 0, 0, 1};
  ctx().ClearRenderTargetView(t.rtv.get(), c);
  ctx().End(t1.get());
  ctx().End(disjoint.get());
  QUERY_DATA_TIMESTAMP_DISJOINT d = Wait<QUERY_DATA_TIMESTAMP_DISJOINT>(ctx(), disjoint.get());
  uint64_t a = Wait<uint64_t>(ctx(), t0.get()), b = Wait<uint64_t>(ctx(), t1.get());
  EXPECT_EQ(d.Frequency, device().Info().timestampFrequency);
  EXPECT_FALSE(d.Disjoint);
  EXPECT_GT(a, 0u);
  EXPECT_GE(b, a);
}

TEST_P(QueryTest, EventCompletes) {
  QUERY_DESC ed;
  ed.Query = QUERY_EVENT;
  Ref<Query> ev = device().CreateQuery(ed);
  Target t = MakeTarget(device(), 16, 16, FORMAT_R8G8B8A8_UNORM);
  const float c[4] = {0, 1, 0, 1};
  ctx().ClearRenderTargetView(t.rtv.get(), c);
  ctx().End(ev.get());
  ctx().Flush();
  EXPECT_EQ(Wait<uint32_t>(ctx(), ev.get()), 1u);
  EXPECT_TRUE(ctx().GetData(ev.get(), nullptr, 0, 0));
}

SP_INSTANTIATE_BACKEND_TESTS(QueryTest);

}  // namespace
}  // namespace sp::test
