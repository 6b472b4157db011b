// Queries: OCCLUSION counts the samples that pass the depth test between Begin and End (exactly,
// also with MSAA and for nested spans), TIMESTAMP values are ordered like the commands around
// them and come with a TIMESTAMP_DISJOINT frequency, and EVENT completes. Timing values are only
// checked for ordering and plausibility; expected sample counts come from D3D11's top-left rule
// and standard sample positions evaluated on the CPU.
#include <chrono>

#include "compute-helpers.h"

namespace sp::conformance {
namespace {

const char* kGroup = "Queries";

Ref<Query> MakeQuery(Device& dev, QUERY type) {
  QUERY_DESC d;
  d.Query = type;
  return dev.CreateQuery(d);
}

// A triangle in pixel coordinates (y down) of a w x h viewport, at depth z.
const char* kTriangleVS = R"(
cbuffer Tri : register(b0) { float4 v[3]; float2 size; float z; float pad; };
float4 main(uint id : SV_VertexID) : SV_Position {
  float2 p = v[id].xy;
  return float4(p.x / size.x * 2 - 1, 1 - p.y / size.y * 2, z, 1);
}
)";
const char* kWhitePS = "float4 main(float4 p : SV_Position) : SV_Target { return 1; }";

struct Triangle {
  std::array<double, 2> a, b, c;
};

// Samples of a w x h target covered by `t` by D3D11's rules; `offsets` are the sample positions
// relative to the pixel centre (one {0, 0} for single-sampled targets).
uint64_t CoveredSamples(const Triangle& t, uint32_t w, uint32_t h, const std::vector<std::array<double, 2>>& offsets) {
  uint64_t n = 0;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x)
      for (auto o : offsets) n += D3DCovers(t.a, t.b, t.c, x + 0.5 + o[0], y + 0.5 + o[1]);
  return n;
}

class TriangleDrawer {
 public:
  explicit TriangleDrawer(Device& dev) : vs_(MakeVS(dev, kTriangleVS, "query-triangle")), ps_(MakePS(dev, kWhitePS, "query-white")) {
    cb_ = gpu::MakeBuffer(dev, BIND_CONSTANT_BUFFER, nullptr, 64);
  }
  void Draw(DeviceContext& ctx, const Triangle& t, uint32_t w, uint32_t h, float z) {
    float c[16] = {float(t.a[0]), float(t.a[1]), 0, 0, float(t.b[0]), float(t.b[1]), 0, 0,
                   float(t.c[0]), float(t.c[1]), 0, 0, float(w),      float(h),      z, 0};
    ctx.UpdateSubresource(cb_.get(), 0, nullptr, c, 0, 0);
    ctx.VSSetShader(vs_.get());
    ctx.VSSetConstantBuffers(0, {cb_.get()});
    ctx.PSSetShader(ps_.get());
    ctx.IASetInputLayout(nullptr);
    ctx.IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    ctx.Draw(3, 0);
  }
  // Two triangles covering [x0, x1) x [y0, y1).
  void Rect(DeviceContext& ctx, double x0, double y0, double x1, double y1, uint32_t w, uint32_t h, float z) {
    Draw(ctx, {{x0, y0}, {x1, y0}, {x1, y1}}, w, h, z);
    Draw(ctx, {{x0, y0}, {x1, y1}, {x0, y1}}, w, h, z);
  }

 private:
  Ref<VertexShader> vs_;
  Ref<PixelShader> ps_;
  Ref<Buffer> cb_;
};

// Colour and depth targets of `samples` samples, depth cleared to 1, test LESS.
struct Targets {
  Ref<Texture2D> color, depth;
  Ref<RenderTargetView> rtv;
  Ref<DepthStencilView> dsv;
};
Targets MakeTargets(Device& dev, uint32_t w, uint32_t h, uint32_t samples) {
  Targets t;
  t.color = gpu::MakeTexture2D(dev, w, h, FORMAT_R8G8B8A8_UNORM, BIND_RENDER_TARGET, nullptr, 1, 1, samples);
  t.depth = gpu::MakeTexture2D(dev, w, h, FORMAT_D32_FLOAT, BIND_DEPTH_STENCIL, nullptr, 1, 1, samples);
  t.rtv = dev.CreateRenderTargetView(t.color.get());
  t.dsv = dev.CreateDepthStencilView(t.depth.get());
  DeviceContext& ctx = *dev.GetImmediateContext();
  ctx.ClearDepthStencilView(t.dsv.get(), CLEAR_DEPTH, 1.0f, 0);
  RenderTargetView* rtvs[] = {t.rtv.get()};
  ctx.OMSetRenderTargets(1, rtvs, t.dsv.get());
  VIEWPORT vp{0, 0, float(w), float(h), 0, 1};
  ctx.RSSetViewports(1, &vp);
  return t;
}

uint64_t Occlusion(DeviceContext& ctx, Query* q, Mismatches& m, const std::string& what) {
  uint64_t v = ~0ull;
  m.Expect(WaitForQuery(ctx, q, &v, sizeof(v)), what + ": the query never completed");
  return v;
}

}  // namespace

SP_PROBE(kGroup, "OCCLUSION counts the samples of known rectangles and a triangle exactly",
         "the count is the number of samples passing the depth test between Begin and End; nested queries count their own spans") {
  DeviceContext& ctx = *device.GetImmediateContext();
  constexpr uint32_t W = 16, H = 16;
  Targets t = MakeTargets(device, W, H, 1);
  TriangleDrawer draw(device);
  Ref<Query> outer = MakeQuery(device, QUERY_OCCLUSION), inner = MakeQuery(device, QUERY_OCCLUSION), tri = MakeQuery(device, QUERY_OCCLUSION);
  ctx.Begin(outer.get());
  draw.Rect(ctx, 0, 0, 4, 4, W, H, 0.5f);  // 16 samples
  ctx.Begin(inner.get());
  draw.Rect(ctx, 8, 8, 10, 10, W, H, 0.5f);  // 4
  draw.Rect(ctx, 0, 0, 4, 4, W, H, 0.75f);   // behind the first quad: 0
  ctx.End(outer.get());
  draw.Rect(ctx, 12, 12, 13, 13, W, H, 0.5f);  // 1
  ctx.End(inner.get());
  Triangle slanted{{4.25, 1.75}, {15.5, 6.25}, {6.75, 15.25}};
  uint64_t expectTri = CoveredSamples(slanted, W, H, {{0, 0}});
  ctx.Begin(tri.get());
  draw.Draw(ctx, slanted, W, H, 0.25f);  // in front of everything drawn so far
  ctx.End(tri.get());
  Mismatches m("samples");
  m.Check(Occlusion(ctx, outer.get(), m, "outer"), uint64_t(20), "outer query (16 + 4 + 0 behind)");
  m.Check(Occlusion(ctx, inner.get(), m, "inner"), uint64_t(5), "nested query (4 + 0 + 1)");
  m.Check(Occlusion(ctx, tri.get(), m, "triangle"), expectTri, "slanted triangle (top-left rule)");
  ctx.Begin(outer.get());
  draw.Rect(ctx, 0, 14, 3, 15, W, H, 0.1f);  // 3
  ctx.End(outer.get());
  m.Check(Occlusion(ctx, outer.get(), m, "reused"), uint64_t(3), "reused query counts only its new span");
  return m.Finish("samples");
}

SP_PROBE(kGroup, "OCCLUSION counts samples, not pixels, with 4x MSAA",
         "with 4 samples per pixel, a covered pixel counts 4 and an edge pixel its covered samples") {
  if (device.CheckMultisampleQualityLevels(FORMAT_R8G8B8A8_UNORM, 4) == 0 || device.CheckMultisampleQualityLevels(FORMAT_D32_FLOAT, 4) == 0)
    return Unsupported("4x MSAA is not supported for R8G8B8A8_UNORM with D32_FLOAT");
  DeviceContext& ctx = *device.GetImmediateContext();
  constexpr uint32_t W = 16, H = 16;
  Targets t = MakeTargets(device, W, H, 4);
  TriangleDrawer draw(device);
  Ref<Query> rect = MakeQuery(device, QUERY_OCCLUSION), tri = MakeQuery(device, QUERY_OCCLUSION);
  ctx.Begin(rect.get());
  draw.Rect(ctx, 1, 1, 5, 5, W, H, 0.5f);
  ctx.End(rect.get());
  // D3D11's standard 4x pattern, in 1/16 pixel from the pixel centre.
  std::vector<std::array<double, 2>> pattern = {{-2 / 16.0, -6 / 16.0}, {6 / 16.0, -2 / 16.0}, {-6 / 16.0, 2 / 16.0}, {2 / 16.0, 6 / 16.0}};
  Triangle slanted{{6.125, 0.875}, {15.75, 9.375}, {7.625, 15.5}};
  ctx.Begin(tri.get());
  draw.Draw(ctx, slanted, W, H, 0.5f);
  ctx.End(tri.get());
  Mismatches m("samples");
  m.Check(Occlusion(ctx, rect.get(), m, "rectangle"), uint64_t(4 * 4 * 4), "4 x 4 pixel rectangle");
  m.Check(Occlusion(ctx, tri.get(), m, "triangle"), CoveredSamples(slanted, W, H, pattern), "slanted triangle at the standard 4x positions");
  return m.Finish("samples");
}

SP_PROBE(kGroup, "TIMESTAMP ordering and TIMESTAMP_DISJOINT frequency",
         "timestamps between commands are non-decreasing in command order; the disjoint query gives a non-zero Frequency and Disjoint = FALSE") {
  DeviceContext& ctx = *device.GetImmediateContext();
  Ref<Query> disjoint = MakeQuery(device, QUERY_TIMESTAMP_DISJOINT);
  std::vector<Ref<Query>> ts;
  for (int i = 0; i < 4; ++i) ts.push_back(MakeQuery(device, QUERY_TIMESTAMP));
  DrawTarget target = MakeDrawTarget(device, 32, 32, FORMAT_R8G8B8A8_UNORM);
  TriangleDrawer draw(device);
  BufferViews buf = MakeStructured(device, 64, 4);
  const uint32_t zero[4] = {0, 0, 0, 0};
  ctx.Begin(disjoint.get());
  ctx.End(ts[0].get());
  target.Clear(ctx, 0.5f);
  ctx.End(ts[1].get());
  target.Bind(ctx);
  draw.Rect(ctx, 0, 0, 32, 32, 32, 32, 0.5f);
  ctx.End(ts[2].get());
  ctx.ClearUnorderedAccessViewUint(buf.uav.get(), zero);
  ctx.End(ts[3].get());
  ctx.End(disjoint.get());
  Mismatches m("checks");
  QUERY_DATA_TIMESTAMP_DISJOINT d;
  m.Expect(WaitForQuery(ctx, disjoint.get(), &d, sizeof(d)), "the TIMESTAMP_DISJOINT query never completed");
  m.Expect(d.Frequency > 0, "TIMESTAMP_DISJOINT Frequency is 0");
  m.Expect(!d.Disjoint, "TIMESTAMP_DISJOINT reports Disjoint = TRUE on a steady run");
  uint64_t prev = 0;
  for (int i = 0; i < 4; ++i) {
    uint64_t v = 0;
    m.Expect(WaitForQuery(ctx, ts[i].get(), &v, sizeof(v)), "TIMESTAMP " + std::to_string(i) + " never completed");
    m.Expect(v > 0, "TIMESTAMP " + std::to_string(i) + " is 0");
    m.Expect(v >= prev,
             "TIMESTAMP " + std::to_string(i) + " (" + std::to_string(v) + ") is earlier than the one before it (" + std::to_string(prev) + ")");
    prev = v;
  }
  Result r = m.Finish("checks");
  if (r.status == Status::Pass) r.detail = "Frequency " + std::to_string(d.Frequency) + " Hz";
  return r;
}

SP_PROBE(kGroup, "TIMESTAMP interval of a heavy draw is positive and plausible",
         "the interval between timestamps around an expensive draw is > 0 and no longer than the wall-clock time the work took") {
  const char* heavy = R"(
cbuffer K : register(b1) { uint iterations; uint3 pad; };
float4 main(float4 p : SV_Position) : SV_Target {
  float acc = p.x * 0.001;
  for (uint i = 0; i < iterations; ++i) acc = frac(acc * 1.618 + p.y * 0.0001 + i * 1e-6);
  return acc;
}
)";
  DeviceContext& ctx = *device.GetImmediateContext();
  constexpr uint32_t W = 64, H = 64;
  DrawTarget target = MakeDrawTarget(device, W, H, FORMAT_R32_FLOAT);
  RectDrawer rect(device);
  Ref<PixelShader> ps = MakePS(device, heavy, "query-heavy");
  const uint32_t k[4] = {400, 0, 0, 0};
  Ref<Buffer> cb = gpu::MakeBuffer(device, BIND_CONSTANT_BUFFER, k, 16);
  target.Bind(ctx);
  ctx.PSSetShader(ps.get());
  ctx.PSSetConstantBuffers(1, {cb.get()});
  rect.Draw(ctx, 0, 0, W, H, W, H);  // warm-up: pipeline creation and JIT are not part of the interval
  ctx.WaitIdle();
  Ref<Query> disjoint = MakeQuery(device, QUERY_TIMESTAMP_DISJOINT), t0 = MakeQuery(device, QUERY_TIMESTAMP), t1 = MakeQuery(device, QUERY_TIMESTAMP);
  auto start = std::chrono::steady_clock::now();
  ctx.Begin(disjoint.get());
  ctx.End(t0.get());
  rect.Draw(ctx, 0, 0, W, H, W, H);
  ctx.End(t1.get());
  ctx.End(disjoint.get());
  QUERY_DATA_TIMESTAMP_DISJOINT d;
  uint64_t a = 0, b = 0;
  bool done =
      WaitForQuery(ctx, disjoint.get(), &d, sizeof(d)) && WaitForQuery(ctx, t0.get(), &a, sizeof(a)) && WaitForQuery(ctx, t1.get(), &b, sizeof(b));
  double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!done) return Fail("the timestamp queries never completed");
  if (d.Disjoint || d.Frequency == 0)
    return Fail("TIMESTAMP_DISJOINT: Disjoint = " + std::to_string(d.Disjoint) + ", Frequency " + std::to_string(d.Frequency));
  if (b <= a) return Fail("the heavy draw's interval is not positive: " + std::to_string(a) + " then " + std::to_string(b));
  double interval = double(b - a) / double(d.Frequency);
  std::string detail = "interval " + std::to_string(interval * 1e3) + " ms, wall clock " + std::to_string(wall * 1e3) + " ms";
  // The GPU cannot take longer than the CPU waited for it (1 ms slack for clock granularity).
  if (interval > wall + 1e-3) return Fail("implausible interval: " + detail);
  return Pass(0, "", 0, detail);
}

SP_PROBE(kGroup, "EVENT completes after Flush", "GetData of an EVENT query returns S_OK with TRUE once the GPU has reached it") {
  DeviceContext& ctx = *device.GetImmediateContext();
  Ref<Query> ev = MakeQuery(device, QUERY_EVENT);
  DrawTarget target = MakeDrawTarget(device, 16, 16, FORMAT_R8G8B8A8_UNORM);
  target.Clear(ctx, 1.0f);
  ctx.End(ev.get());
  ctx.Flush();
  uint32_t value = 0;
  if (!WaitForQuery(ctx, ev.get(), &value, sizeof(value))) return Fail("the EVENT query never completed");
  if (value != 1) return Fail("the EVENT query returned " + std::to_string(value) + " instead of TRUE");
  if (!ctx.GetData(ev.get(), nullptr, 0, 0)) return Fail("GetData(NULL, 0) of a completed EVENT returned S_FALSE");
  return Pass();
}

}  // namespace sp::conformance
