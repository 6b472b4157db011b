// Front faces and culling. D3D11 judges winding as the triangle appears on the render target
// (y down): clockwise is front unless FrontCounterClockwise; CULL_BACK / CULL_FRONT drop the
// other / the front faces, and SV_IsFrontFace tells the pixel shader which side it sees. In a
// triangle strip every odd triangle is taken as (v1, v0, v2) so all keep the first one's winding.
// Expected images come from the signed area of the triangles in pixel coordinates and the
// top-left rule; coverage and facing are exact, so the tolerance is 0 pixels.
#include "render-helpers.h"

namespace sp::conformance {
namespace {

const char* kGroup = "Rasterization";
constexpr uint32_t W = 32, H = 32;

const char* kFacePS = R"(
float4 main(float4 p : SV_Position, bool front : SV_IsFrontFace) : SV_Target { return float4(front ? 1.0 : 2.0, 0, 0, 0); }
)";

using Tri = std::array<PixelVertex, 3>;

// Clockwise on the render target: positive signed area with y pointing down.
bool Clockwise(const Tri& t) { return (t[1].x - t[0].x) * (t[2].y - t[0].y) - (t[1].y - t[0].y) * (t[2].x - t[0].x) > 0; }

// The triangles a strip of `v` makes, in D3D11's vertex order.
std::vector<Tri> StripTriangles(const std::vector<PixelVertex>& v) {
  std::vector<Tri> out;
  for (size_t i = 0; i + 2 < v.size(); ++i) out.push_back(i % 2 == 0 ? Tri{v[i], v[i + 1], v[i + 2]} : Tri{v[i + 1], v[i], v[i + 2]});
  return out;
}

Result CheckWinding(Device& device, bool frontCCW, CULL_MODE cull) {
  DeviceContext& ctx = *device.GetImmediateContext();
  // A clockwise and a counter-clockwise triangle, and a clockwise-starting and a
  // counter-clockwise-starting strip of four triangles each.
  std::vector<Tri> list = {{{{2.5, 2.5}, {14.5, 2.5}, {2.5, 14.5}}}, {{{17.5, 2.5}, {17.5, 14.5}, {29.5, 2.5}}}};
  std::vector<PixelVertex> stripCW = {{2, 18}, {14, 18}, {2, 23}, {14, 23}, {2, 29}, {14, 29}};
  std::vector<PixelVertex> stripCCW = {{18, 18}, {18, 23}, {30, 18}, {30, 23}, {18, 29}};
  std::vector<PixelVertex> flat;
  for (const Tri& t : list) flat.insert(flat.end(), t.begin(), t.end());

  Ref<Texture2D> target = gpu::MakeTexture2D(device, W, H, FORMAT_R32_FLOAT, BIND_RENDER_TARGET);
  Ref<RenderTargetView> rtv = device.CreateRenderTargetView(target.get());
  Ref<PixelShader> ps = device.CreatePixelShader(gpu::CompileInline(kFacePS, "conformance/is-front-face.hlsl", "ps_5_0", "main"));
  RASTERIZER_DESC rd;
  rd.CullMode = cull;
  rd.FrontCounterClockwise = frontCCW;
  Ref<RasterizerState> rs = device.CreateRasterizerState(rd);
  const float zero[4] = {0, 0, 0, 0};
  ctx.ClearRenderTargetView(rtv.get(), zero);
  RenderTargetView* rtvs[] = {rtv.get()};
  ctx.OMSetRenderTargets(1, rtvs, nullptr);
  ctx.RSSetState(rs.get());
  VIEWPORT vp{0, 0, float(W), float(H), 0, 1};
  ctx.RSSetViewports(1, &vp);
  ctx.PSSetShader(ps.get());
  PixelDrawer drawer(device);
  drawer.Draw(ctx, flat, W, H);
  drawer.Draw(ctx, stripCW, W, H, PRIMITIVE_TOPOLOGY_TRIANGLESTRIP);
  drawer.Draw(ctx, stripCCW, W, H, PRIMITIVE_TOPOLOGY_TRIANGLESTRIP);
  std::vector<float> got = gpu::ReadAs<float>(gpu::ReadTexture(device, ctx, target.get()));

  std::vector<Tri> all = list;
  for (auto* s : {&stripCW, &stripCCW}) {
    std::vector<Tri> st = StripTriangles(*s);
    all.insert(all.end(), st.begin(), st.end());
  }
  std::vector<float> expected(W * H, 0.0f);
  for (const Tri& t : all) {
    bool front = Clockwise(t) != frontCCW;
    if ((cull == CULL_BACK && !front) || (cull == CULL_FRONT && front)) continue;
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x)
        if (D3DCovers({t[0].x, t[0].y}, {t[1].x, t[1].y}, {t[2].x, t[2].y}, x + 0.5, y + 0.5)) expected[y * W + x] = front ? 1.0f : 2.0f;
  }
  std::string detail;
  int wrong = CountMismatches(got, expected, W, &detail, "(0 none, 1 front, 2 back)");
  if (wrong) return Fail(std::to_string(wrong) + " pixels with the wrong face or culling; " + detail, wrong, "pixels", 0);
  return Pass(0, "pixels", 0);
}

}  // namespace

SP_PROBE(kGroup, "winding: FrontCounterClockwise FALSE, CULL_NONE", "clockwise on the render target (y down) is front; SV_IsFrontFace says so") {
  return CheckWinding(device, false, CULL_NONE);
}
SP_PROBE(kGroup, "winding: FrontCounterClockwise FALSE, CULL_BACK", "counter-clockwise triangles on the render target are culled") {
  return CheckWinding(device, false, CULL_BACK);
}
SP_PROBE(kGroup, "winding: FrontCounterClockwise FALSE, CULL_FRONT", "clockwise triangles on the render target are culled") {
  return CheckWinding(device, false, CULL_FRONT);
}
SP_PROBE(kGroup, "winding: FrontCounterClockwise TRUE, CULL_NONE", "counter-clockwise on the render target is front; SV_IsFrontFace says so") {
  return CheckWinding(device, true, CULL_NONE);
}
SP_PROBE(kGroup, "winding: FrontCounterClockwise TRUE, CULL_BACK", "clockwise triangles on the render target are culled") {
  return CheckWinding(device, true, CULL_BACK);
}
SP_PROBE(kGroup, "winding: FrontCounterClockwise TRUE, CULL_FRONT", "counter-clockwise triangles on the render target are culled") {
  return CheckWinding(device, true, CULL_FRONT);
}

}  // namespace sp::conformance
