// TYPELESS depth textures with a depth-stencil view for rendering and shader-resource views for
// reading, as shadow maps use them:
//   R32_TYPELESS: D32_FLOAT DSV, R32_FLOAT SRV
//   R24G8_TYPELESS: D24_UNORM_S8_UINT DSV, R24_UNORM_X8_TYPELESS SRV (depth), X24_TYPELESS_G8_UINT
//     SRV (stencil in .g)
//   R16_TYPELESS: D16_UNORM DSV, R16_UNORM SRV
// Three regions are written: a ClearDepthStencilView value (depth 0.25, stencil 0x3c), a sloped
// plane (stencil ref 0x5a) and a constant depth 0.6 (stencil ref 0xa7). Checks:
// - staging copy (D3D11's mapped layout): UNORM codes within 0.6 LSB of z * (2^n - 1) (FLOAT ->
//   UNORM, D3D11 3.2.3.6), plus, on the plane, 2 float32 ulp of z for the rasterizer's
//   interpolation converted to LSB; D32_FLOAT within 2 ulp on the plane, exact elsewhere;
// - depth SRV: Load and point Sample return (d, 0, 0, 1) with d the stored float bits or, for
//   UNORM, code / (2^n - 1) correctly rounded (D3D11 3.2.3.2 requires conversions between integer
//   and float representations to be exact): tolerance 0 ulp. A read further than 1 ulp off, or
//   not (d, 0, 0, 1), is reported as a wrong view; 1 ulp as an inexact UNORM -> FLOAT conversion;
// - stencil SRV: .g is the stencil value exactly.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "render-helpers.h"

namespace sp::conformance {
namespace {

const char* kGroup = "Resources";
constexpr uint32_t W = 16, H = 8;

const char* kReadCS = R"(
Texture2D<float4> depthView : register(t0);
#ifdef HAS_STENCIL
Texture2D<uint2> stencilView : register(t1);
#endif
SamplerState pt : register(s0);
RWStructuredBuffer<float4> output : register(u0);
[numthreads(16, 1, 1)] void main(uint3 i : SV_DispatchThreadID) {
  uint x = i.x % 16, y = i.x / 16;
  output[i.x * 2] = depthView.Load(int3(x, y, 0));
  float stencil = 0;
#ifdef HAS_STENCIL
  stencil = stencilView.Load(int3(x, y, 0)).g;
#endif
  output[i.x * 2 + 1] = float4(depthView.SampleLevel(pt, (float2(x, y) + 0.5) / float2(16, 8), 0).r, stencil, 0, 0);
}
)";

struct Family {
  FORMAT typeless, dsv, srv, stencilSrv;
  uint32_t bits;  // 0 for D32_FLOAT
};

double PlaneZ(double x, double y) { return 0.3 + x / 64 + y / 128; }
// What the region at pixel (x, y) holds: depth and stencil, and whether the depth is interpolated.
void Expected(uint32_t x, uint32_t y, double* z, uint8_t* stencil, bool* plane) {
  *plane = false;
  if (x < 5) *z = 0.25, *stencil = 0x3c;
  else if (x < 11) *z = PlaneZ(x + 0.5, y + 0.5), *stencil = 0x5a, *plane = true;
  else *z = 0.6f, *stencil = 0xa7;  // the float the vertices carry
}

Result CheckFamily(Device& device, const Family& fam) {
  DeviceContext& ctx = *device.GetImmediateContext();
  if (!(device.CheckFormatSupport(fam.dsv) & FORMAT_SUPPORT_DEPTH_STENCIL)) return Unsupported(std::string(FormatName(fam.dsv)) + " is not a depth format here");
  const bool hasStencil = fam.stencilSrv != FORMAT_UNKNOWN;
  Ref<Texture2D> tex = gpu::MakeTexture2D(device, W, H, fam.typeless, BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE);
  DEPTH_STENCIL_VIEW_DESC dd;
  dd.Format = fam.dsv;
  dd.ViewDimension = DSV_DIMENSION_TEXTURE2D;
  Ref<DepthStencilView> dsv = device.CreateDepthStencilView(tex.get(), &dd);
  DEPTH_STENCIL_DESC ds;
  ds.DepthFunc = COMPARISON_ALWAYS;
  ds.StencilEnable = hasStencil;
  ds.FrontFace.StencilPassOp = ds.BackFace.StencilPassOp = STENCIL_OP_REPLACE;
  Ref<DepthStencilState> state = device.CreateDepthStencilState(ds);
  RASTERIZER_DESC rd;
  rd.CullMode = CULL_NONE;
  Ref<RasterizerState> rs = device.CreateRasterizerState(rd);

  ctx.ClearDepthStencilView(dsv.get(), CLEAR_DEPTH | CLEAR_STENCIL, 0.25f, 0x3c);
  ctx.OMSetRenderTargets(0, nullptr, dsv.get());
  ctx.RSSetState(rs.get());
  VIEWPORT vp{0, 0, float(W), float(H), 0, 1};
  ctx.RSSetViewports(1, &vp);
  ctx.PSSetShader(nullptr);
  PixelDrawer drawer(device);
  // The plane over columns 5..10 (its vertices extend it exactly), then columns 11..15 at 0.6.
  auto v = [](double x, double y) { return PixelVertex{x, y, float(PlaneZ(x, y))}; };
  ctx.OMSetDepthStencilState(state.get(), 0x5a);
  drawer.Draw(ctx, {v(5, 0), v(11, 0), v(5, H), v(11, 0), v(11, H), v(5, H)}, W, H);
  ctx.OMSetDepthStencilState(state.get(), 0xa7);
  drawer.Draw(ctx, {{11, 0, 0.6f}, {16, 0, 0.6f}, {11, H, 0.6f}, {16, 0, 0.6f}, {16, H, 0.6f}, {11, H, 0.6f}}, W, H);
  ctx.OMSetRenderTargets(0, nullptr, nullptr);

  // Staging copy in D3D11's mapped layout.
  std::vector<uint8_t> raw = gpu::ReadTexture(device, ctx, tex.get());
  std::vector<double> stored(W * H);  // UNORM code or float value
  std::vector<uint8_t> storedStencil(W * H, 0);
  for (uint32_t i = 0; i < W * H; ++i) {
    if (fam.bits == 16) {
      uint16_t c;
      std::memcpy(&c, &raw[i * 2], 2);
      stored[i] = c;
    } else if (fam.bits == 24) {
      uint32_t c;
      std::memcpy(&c, &raw[i * 4], 4);
      stored[i] = c & 0xffffff;
      storedStencil[i] = uint8_t(c >> 24);
    } else {
      float f;
      std::memcpy(&f, &raw[i * 4], 4);
      stored[i] = f;
    }
  }

  Ref<ShaderResourceView> depthSrv = MakeSrv(device, tex.get(), fam.srv, SRV_DIMENSION_TEXTURE2D);
  Ref<ShaderResourceView> stencilSrv = hasStencil ? MakeSrv(device, tex.get(), fam.stencilSrv, SRV_DIMENSION_TEXTURE2D) : nullptr;
  Ref<SamplerState> pt = MakeSampler(device, FILTER_MIN_MAG_MIP_POINT);
  std::vector<ShaderResourceView*> srvs = {depthSrv.get()};
  if (hasStencil) srvs.push_back(stencilSrv.get());
  std::vector<std::array<float, 4>> r =
      RunCompute(device, hasStencil ? "#define HAS_STENCIL 1\n" + std::string(kReadCS) : std::string(kReadCS), "conformance/depth-views.hlsl", W * H * 2, srvs,
                 {pt.get()}, W * H / 16);

  double worstStore = 0, worstStoreTol = 0.6, worstUlp = 0;
  int wrongStencil = 0, wrongView = 0;
  std::string storeDetail, viewDetail, stencilDetail, ulpDetail;
  const double scale = fam.bits ? double((1u << fam.bits) - 1) : 0;
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      uint32_t i = y * W + x;
      double z;
      uint8_t stencil;
      bool plane;
      Expected(x, y, &z, &stencil, &plane);
      std::string at = "pixel (" + std::to_string(x) + "," + std::to_string(y) + ")";
      // Stored value against D3D11's conversion of z.
      double err, tol;
      if (fam.bits) {
        err = std::abs(stored[i] - z * scale);
        tol = 0.6 + (plane ? 2 * FloatUlp(z) * scale : 0.0);
      } else {
        err = std::abs(stored[i] - z) / FloatUlp(z);
        tol = plane ? 2.0 : 0.0;
      }
      if (err - tol > worstStore - worstStoreTol) {
        worstStore = err;
        worstStoreTol = tol;
        storeDetail = at + " stored " + std::to_string(stored[i]) + ", D3D11 " + std::to_string(fam.bits ? z * scale : z);
      }
      // Views against the stored value.
      float d = fam.bits ? UnormToFloat(uint32_t(stored[i]), fam.bits) : float(stored[i]);
      const std::array<float, 4>& load = r[i * 2];
      const std::array<float, 4>& sampled = r[i * 2 + 1];
      double ulps = std::max(std::abs(load[0] - d), std::abs(sampled[0] - d)) / FloatUlp(d);
      if (load[1] != 0 || load[2] != 0 || load[3] != 1 || ulps > 1) {
        if (++wrongView == 1)
          viewDetail = at + ": Load (" + std::to_string(load[0]) + ", " + std::to_string(load[1]) + ", " + std::to_string(load[2]) + ", " +
                       std::to_string(load[3]) + "), Sample " + std::to_string(sampled[0]) + ", stored " + std::to_string(d);
      } else if (ulps > worstUlp) {
        worstUlp = ulps;
        ulpDetail = at + ": stored code " + std::to_string(uint32_t(stored[i])) + " reads " + std::to_string(load[0]) + ", " + std::to_string(ulps) +
                    " ulp from code / (2^" + std::to_string(fam.bits) + " - 1)";
      }
      if (hasStencil && (storedStencil[i] != stencil || sampled[1] != float(stencil))) {
        if (++wrongStencil == 1)
          stencilDetail = at + ": staging stencil " + std::to_string(storedStencil[i]) + ", SRV .g " + std::to_string(sampled[1]) + ", D3D11 " +
                          std::to_string(stencil);
      }
    }
  if (wrongStencil) return Fail(std::to_string(wrongStencil) + " pixels with the wrong stencil; " + stencilDetail, wrongStencil, "pixels", 0);
  if (wrongView)
    return Fail(std::to_string(wrongView) + " pixels where the depth view does not read (d, 0, 0, 1) of the stored depth; " + viewDetail, wrongView, "pixels", 0);
  if (worstStore > worstStoreTol) return Within(worstStore, worstStoreTol, fam.bits ? "LSB" : "ulp", "stored depth: " + storeDetail);
  // The view reads the right texel and code; D3D11 3.2.3.2 also requires UNORM -> FLOAT to be
  // correctly rounded (0.5 ulp). Mesa's llvmpipe/lavapipe multiply by a float reciprocal for
  // 24-bit depth and are 1 ulp off for about a third of the codes: a driver deviation.
  if (worstUlp > 0)
    return WithinKnownDeviation(worstUlp, 0, 1, "ulp", ulpDetail, kUnormReadDeviation);
  return Pass(worstStore, fam.bits ? "LSB" : "ulp", worstStoreTol);
}

}  // namespace

SP_PROBE(kGroup, "R32_TYPELESS depth: D32_FLOAT DSV written, R32_FLOAT SRV read",
         "depth rendered or cleared through D32_FLOAT reads back through R32_FLOAT as (d, 0, 0, 1) with d the stored float") {
  return CheckFamily(device, {FORMAT_R32_TYPELESS, FORMAT_D32_FLOAT, FORMAT_R32_FLOAT, FORMAT_UNKNOWN, 0});
}

SP_PROBE(kGroup, "R24G8_TYPELESS depth-stencil: D24_UNORM_S8_UINT DSV, R24_UNORM_X8_TYPELESS and X24_TYPELESS_G8_UINT SRVs",
         "depth reads as (code / (2^24 - 1), 0, 0, 1), stencil in .g of the X24_TYPELESS_G8_UINT view") {
  return CheckFamily(device, {FORMAT_R24G8_TYPELESS, FORMAT_D24_UNORM_S8_UINT, FORMAT_R24_UNORM_X8_TYPELESS, FORMAT_X24_TYPELESS_G8_UINT, 24});
}

SP_PROBE(kGroup, "R16_TYPELESS depth: D16_UNORM DSV written, R16_UNORM SRV read",
         "depth rendered or cleared through D16_UNORM reads back through R16_UNORM as (code / 65535, 0, 0, 1)") {
  return CheckFamily(device, {FORMAT_R16_TYPELESS, FORMAT_D16_UNORM, FORMAT_R16_UNORM, FORMAT_UNKNOWN, 16});
}

}  // namespace sp::conformance
