// Draw calls and input assembly: strips cut at the all-ones index (D3D11 always restarts strips),
// base vertex and start locations, 16- and 32-bit indices, line and point topologies, instance
// step rates, and wireframe. Expected coverage is computed on the CPU.
#include "rhi-test-util.h"

namespace sp::test {
namespace {

class DrawTest : public BackendTest {
 protected:
  // Vertex buffer of pixel-space positions (x, y) for a W x H target; the PS outputs the
  // primitive's instance-independent constant `value` from the constant buffer.
  void SetUpPipeline(uint32_t w, uint32_t h) {
    const char* src = R"(
cbuffer C : register(b0) { float value; float3 pad; };
float4 VSMain(float2 p : POSITION) : SV_Position { return float4(p, 0, 1); }
float4 PSMain(float4 p : SV_Position) : SV_Target { return value; }
)";
    ShaderBytecode vsb = CompileHlsl(src, "vs_5_0", "VSMain");
    vs_ = device().CreateVertexShader(vsb);
    ps_ = device().CreatePixelShader(CompileHlsl(src, "ps_5_0", "PSMain"));
    INPUT_ELEMENT_DESC el{"POSITION", 0, FORMAT_R32G32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0};
    layout_ = device().CreateInputLayout(&el, 1, vsb);
    target_ = MakeTarget(device(), w, h, FORMAT_R32_FLOAT);
    cb_ = MakeBuffer(device(), BIND_CONSTANT_BUFFER, nullptr, 16);
    const float zero[4] = {0, 0, 0, 0};
    ctx().ClearRenderTargetView(target_.rtv.get(), zero);
    RenderTargetView* rtvs[] = {target_.rtv.get()};
    ctx().OMSetRenderTargets(1, rtvs, nullptr);
    SetViewport(ctx(), float(w), float(h));
    RASTERIZER_DESC rd;
    rd.CullMode = CULL_NONE;
    rs_ = device().CreateRasterizerState(rd);
    ctx().RSSetState(rs_.get());
    ctx().IASetInputLayout(layout_.get());
    ctx().VSSetShader(vs_.get());
    ctx().PSSetShader(ps_.get());
    ctx().VSSetConstantBuffers(0, {cb_.get()});
    ctx().PSSetConstantBuffers(0, {cb_.get()});
    w_ = w;
    h_ = h;
  }
  // Positions in pixels (y down) -> NDC.
  Ref<Buffer> Vertices(const std::vector<std::pair<float, float>>& px) {
    std::vector<float> v;
    for (auto [x, y] : px) {
      v.push_back(x / float(w_) * 2 - 1);
      v.push_back(1 - y / float(h_) * 2);
    }
    Ref<Buffer> b = MakeBuffer(device(), BIND_VERTEX_BUFFER, v.data(), uint32_t(v.size() * 4));
    uint32_t stride = 8, offset = 0;
    Buffer* vbs[] = {b.get()};
    ctx().IASetVertexBuffers(0, 1, vbs, &stride, &offset);
    return b;
  }
  void SetValue(float v) {
    float c[4] = {v, 0, 0, 0};
    ctx().UpdateSubresource(cb_.get(), 0, nullptr, c, 0, 0);
  }
  std::vector<float> Read() { return ReadTextureAs<float>(device(), ctx(), target_.texture.get()); }

  uint32_t w_ = 0, h_ = 0;
  Ref<VertexShader> vs_;
  Ref<PixelShader> ps_;
  Ref<InputLayout> layout_;
  Ref<RasterizerState> rs_;
  Ref<Buffer> cb_;
  Target target_;
};

// Axis-aligned pixel rectangles as two-triangle strips, separated by the cut index.
TEST_P(DrawTest, StripsRestartAtAllOnesIndex) {
  const uint32_t W = 16, H = 8;
  SetUpPipeline(W, H);
  // Three rectangles' corners: (x0,y0) (x1,y0) (x0,y1) (x1,y1) each.
  std::vector<std::pair<float, float>> corners;
  const float rects[3][4] = {{0, 0, 4, 4}, {6, 2, 9, 8}, {11, 0, 16, 3}};
  for (auto& r : rects) corners.insert(corners.end(), {{r[0], r[1]}, {r[2], r[1]}, {r[0], r[3]}, {r[2], r[3]}});
  Ref<Buffer> vb = Vertices(corners);
  const uint16_t idx16[] = {0, 1, 2, 3, 0xffff, 4, 5, 6, 7, 0xffff, 8, 9, 10, 11};
  const uint32_t idx32[] = {0, 1, 2, 3, 0xffffffffu, 8, 9, 10, 11};
  Ref<Buffer> ib16 = MakeBuffer(device(), BIND_INDEX_BUFFER, idx16, sizeof(idx16));
  Ref<Buffer> ib32 = MakeBuffer(device(), BIND_INDEX_BUFFER, idx32, sizeof(idx32));
  ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLESTRIP);
  SetValue(1);
  ctx().IASetIndexBuffer(ib16.get(), FORMAT_R16_UINT, 0);
  ctx().DrawIndexed(14, 0, 0);
  SetValue(2);
  ctx().IASetIndexBuffer(ib32.get(), FORMAT_R32_UINT, 0);
  ctx().DrawIndexed(9, 0, 0);  // rectangles 0 and 2 again, not the middle one
  std::vector<float> expect(W * H, 0.0f);
  for (int r = 0; r < 3; ++r)
    for (uint32_t y = uint32_t(rects[r][1]); y < uint32_t(rects[r][3]); ++y)
      for (uint32_t x = uint32_t(rects[r][0]); x < uint32_t(rects[r][2]); ++x) expect[y * W + x] = r == 1 ? 1.0f : 2.0f;
  EXPECT_EQ(Read(), expect);
}

// D3D11 defines the all-ones cut for strips; in a list both backends read 0xffff as vertex
// 65535, while strips drawn between the lists still cut there. The topology switches list -> strip -> list in one context,
// so a backend that follows the topology with its restart state must switch it both ways.
TEST_P(DrawTest, ListsReadTheAllOnesIndexAsAVertexWhileStripsCutThere) {
  const uint32_t W = 16, H = 1;
  SetUpPipeline(W, H);
  std::vector<std::pair<float, float>> pts(65536, {-10.0f, -10.0f});  // off the target
  pts[0] = {0.5f, 0.5f};
  pts[1] = {1.5f, 0.5f};
  pts[2] = {10.5f, 0.5f};  // strip: 2-3 covers pixel 10, 4-5 pixel 13; across the cut 8..12
  pts[3] = {11.5f, 0.5f};
  pts[4] = {13.5f, 0.5f};
  pts[5] = {14.5f, 0.5f};
  pts[0xffff] = {8.5f, 0.5f};
  Ref<Buffer> vb = Vertices(pts);
  const uint16_t points[] = {0, 0xffff, 1};
  const uint16_t strip[] = {2, 3, 0xffff, 4, 5};
  Ref<Buffer> ibPoints = MakeBuffer(device(), BIND_INDEX_BUFFER, points, sizeof(points));
  Ref<Buffer> ibStrip = MakeBuffer(device(), BIND_INDEX_BUFFER, strip, sizeof(strip));
  SetValue(1);
  ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_POINTLIST);
  ctx().IASetIndexBuffer(ibPoints.get(), FORMAT_R16_UINT, 0);
  ctx().DrawIndexed(3, 0, 0);
  SetValue(2);
  ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_LINESTRIP);
  ctx().IASetIndexBuffer(ibStrip.get(), FORMAT_R16_UINT, 0);
  ctx().DrawIndexed(5, 0, 0);
  SetValue(3);
  ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_POINTLIST);
  ctx().IASetIndexBuffer(ibPoints.get(), FORMAT_R16_UINT, 2);
  ctx().DrawIndexed(1, 0, 0);  // the 0xffff alone
  std::vector<float> expect(W, 0.0f);
  expect[0] = expect[1] = 1;
  expect[10] = expect[13] = 2;
  expect[8] = 3;
  EXPECT_EQ(Read(), expect);
}

// StartIndexLocation, BaseVertexLocation (also negative) and StartVertexLocation pick the
// right vertices; an index buffer bound at an offset counts from there.
TEST_P(DrawTest, StartLocationsAndBaseVertex) {
  const uint32_t W = 16, H = 1;
  SetUpPipeline(W, H);
  std::vector<std::pair<float, float>> pts;
  for (uint32_t x = 0; x < W; ++x) pts.push_back({x + 0.5f, 0.5f});
  Ref<Buffer> vb = Vertices(pts);
  const uint16_t idx[] = {7, 7, 0, 1, 2, 3, 9, 10};
  Ref<Buffer> ib = MakeBuffer(device(), BIND_INDEX_BUFFER, idx, sizeof(idx));
  ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_POINTLIST);
  std::vector<float> expect(W, 0.0f);
  SetValue(1);
  ctx().IASetIndexBuffer(ib.get(), FORMAT_R16_UINT, 4);  // indices 0 1 2 3 9 10
  ctx().DrawIndexed(2, 1, 5);                              // 1+5, 2+5
  expect[6] = expect[7] = 1;
  SetValue(2);
  ctx().DrawIndexed(2, 4, -7);  // 9-7, 10-7
  expect[2] = expect[3] = 2;
  SetValue(3);
  ctx().Draw(3, 12);
  expect[12] = expect[13] = expect[14] = 3;
  EXPECT_EQ(Read(), expect);
}

// Line lists and strips: the pixels a horizontal and a vertical line cover under D3D11's
// diamond rule (a horizontal line from pixel-centre x0 to x1 covers x0 .. x1-1).
TEST_P(DrawTest, LinesAndLineStrips) {
  const uint32_t W = 16, H = 16;
  SetUpPipeline(W, H);
  Ref<Buffer> vb = Vertices({{2.5f, 3.5f}, {9.5f, 3.5f}, {12.5f, 1.5f}, {12.5f, 7.5f}, {1.5f, 10.5f}, {5.5f, 10.5f}, {5.5f, 14.5f}});
  SetValue(1);
  ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_LINELIST);
  ctx().Draw(4, 0);
  SetValue(2);
  ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_LINESTRIP);
  ctx().Draw(3, 4);
  std::vector<float> expect(W * H, 0.0f);
  for (uint32_t x = 2; x < 9; ++x) expect[3 * W + x] = 1;
  for (uint32_t y = 1; y < 7; ++y) expect[y * W + 12] = 1;
  for (uint32_t x = 1; x < 5; ++x) expect[10 * W + x] = 2;
  for (uint32_t y = 10; y < 14; ++y) expect[y * W + 5] = 2;
  std::vector<float> got = Read();
  // The endpoint pixel of each segment is implementation-dependent in D3D11 (the diamond
  // test at the exact last centre); compare everything else.
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      bool endpoint = (x == 9 && y == 3) || (x == 12 && y == 7) || (x == 5 && y == 10) || (x == 5 && y == 14);
      if (!endpoint) {
        EXPECT_EQ(got[y * W + x], expect[y * W + x]) << x << ", " << y;
      }
    }
}

// InstanceDataStepRate 0 keeps instance data at StartInstanceLocation's element for every
// instance (D3D11); 3 advances every third instance.
TEST_P(DrawTest, InstanceStepRates) {
  const char* src = R"(
struct V { float4 pos : SV_Position; nointerpolation float2 v : VALUES; };
V VSMain(float slow : SLOW, float fixed : FIXED, uint inst : SV_InstanceID) {
  V o;
  o.pos = float4((inst + 0.5) / 8 * 2 - 1, 0, 0, 1);
  o.v = float2(slow, fixed);
  return o;
}
float4 PSMain(V v) : SV_Target { return float4(v.v, 0, 1); }
)";
  ShaderBytecode vsb = CompileHlsl(src, "vs_5_0", "VSMain");
  Ref<VertexShader> vs = device().CreateVertexShader(vsb);
  Ref<PixelShader> ps = device().CreatePixelShader(CompileHlsl(src, "ps_5_0", "PSMain"));
  INPUT_ELEMENT_DESC el[] = {{"SLOW", 0, FORMAT_R32_FLOAT, 0, 0, INPUT_PER_INSTANCE_DATA, 3},
                             {"FIXED", 0, FORMAT_R32_FLOAT, 1, 0, INPUT_PER_INSTANCE_DATA, 0}};
  Ref<InputLayout> layout = device().CreateInputLayout(el, 2, vsb);
  const float slow[] = {10, 11, 12, 13, 14}, fixed[] = {20, 21, 22, 23};
  Ref<Buffer> b0 = MakeBuffer(device(), BIND_VERTEX_BUFFER, slow, sizeof(slow));
  Ref<Buffer> b1 = MakeBuffer(device(), BIND_VERTEX_BUFFER, fixed, sizeof(fixed));
  Target t = MakeTarget(device(), 8, 1, FORMAT_R32G32B32A32_FLOAT);
  RenderTargetView* rtvs[] = {t.rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, nullptr);
  SetViewport(ctx(), 8, 1);
  Buffer* vbs[] = {b0.get(), b1.get()};
  const uint32_t strides[] = {4, 4}, offsets[] = {0, 0};
  ctx().IASetVertexBuffers(0, 2, vbs, strides, offsets);
  ctx().IASetInputLayout(layout.get());
  ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_POINTLIST);
  ctx().VSSetShader(vs.get());
  ctx().PSSetShader(ps.get());
  ctx().DrawInstanced(1, 8, 0, 1);
  std::vector<float> px = ReadTextureAs<float>(device(), ctx(), t.texture.get());
  for (uint32_t i = 0; i < 8; ++i) {
    // D3D11: element = StartInstanceLocation + instance / rate; rate 0: StartInstanceLocation.
    EXPECT_EQ(px[i * 4 + 0], slow[1 + i / 3]) << i;
    EXPECT_EQ(px[i * 4 + 1], fixed[1]) << i;
  }
}

// FILL_WIREFRAME draws the edges of a triangle, not its interior.
TEST_P(DrawTest, WireframeDrawsEdgesOnly) {
  const uint32_t W = 16, H = 16;
  SetUpPipeline(W, H);
  Ref<Buffer> vb = Vertices({{2.5f, 2.5f}, {13.5f, 2.5f}, {2.5f, 13.5f}});
  RASTERIZER_DESC rd;
  rd.CullMode = CULL_NONE;
  rd.FillMode = FILL_WIREFRAME;
  Ref<RasterizerState> wire = device().CreateRasterizerState(rd);
  ctx().RSSetState(wire.get());
  ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  SetValue(1);
  ctx().Draw(3, 0);
  std::vector<float> got = Read();
  EXPECT_EQ(got[5 * W + 5], 0.0f) << "interior";
  EXPECT_EQ(got[2 * W + 8], 1.0f) << "top edge";
  EXPECT_EQ(got[8 * W + 2], 1.0f) << "left edge";
  EXPECT_EQ(got[12 * W + 12], 0.0f) << "outside";
}

SP_INSTANTIATE_BACKEND_TESTS(DrawTest);

}  // namespace
}  // namespace sp::test
