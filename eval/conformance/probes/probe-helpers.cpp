#include "probe-helpers.h"

#include <cstring>

namespace sp::conformance {

uint32_t UnormBits(FORMAT f) { return f == FORMAT_D16_UNORM ? 16 : f == FORMAT_D24_UNORM_S8_UINT ? 24 : 0; }

double QuantizeUnorm(double z, uint32_t bits) {
  double scale = double((1u << bits) - 1);
  return std::floor(std::min(1.0, std::max(0.0, z)) * scale + 0.5);
}

double FloatUlp(double z) {
  float f = float(z);
  return double(std::nextafter(f, 2.0f)) - double(f);
}

bool D3DCovers(std::array<double, 2> a, std::array<double, 2> b, std::array<double, 2> c, double px, double py) {
  double area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
  if (area == 0) return false;
  if (area < 0) std::swap(b, c);
  std::array<double, 2> v[3] = {a, b, c};
  for (int i = 0; i < 3; ++i) {
    auto p = v[i], q = v[(i + 1) % 3];
    double e = (q[0] - p[0]) * (py - p[1]) - (q[1] - p[1]) * (px - p[0]);
    bool top = q[1] == p[1] && q[0] > p[0];
    bool left = q[1] < p[1];
    if (e < 0 || (e == 0 && !top && !left)) return false;
  }
  return true;
}

static const char* kDepthVS = R"(
float4 main(float3 p : POSITION) : SV_Position { return float4(p, 1.0); }
)";

std::vector<double> DrawDepth(Device& device, FORMAT format, uint32_t w, uint32_t h, const std::vector<DepthVertex>& vertices,
                              PRIMITIVE_TOPOLOGY topology, const RASTERIZER_DESC& rasterizer, float clear, const VIEWPORT* viewport) {
  DeviceContext& ctx = *device.GetImmediateContext();
  ShaderBytecode vsb = gpu::CompileInline(kDepthVS, "conformance/depth-position.hlsl", "vs_5_0", "main");
  Ref<VertexShader> vs = device.CreateVertexShader(vsb);
  INPUT_ELEMENT_DESC el{"POSITION", 0, FORMAT_R32G32B32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0};
  Ref<InputLayout> layout = device.CreateInputLayout(&el, 1, vsb);
  Ref<Buffer> vb = gpu::MakeBuffer(device, BIND_VERTEX_BUFFER, vertices.data(), uint32_t(vertices.size() * sizeof(DepthVertex)));
  Ref<Texture2D> depth = gpu::MakeTexture2D(device, w, h, format, BIND_DEPTH_STENCIL);
  Ref<DepthStencilView> dsv = device.CreateDepthStencilView(depth.get());
  Ref<RasterizerState> rs = device.CreateRasterizerState(rasterizer);
  DEPTH_STENCIL_DESC dd;
  dd.DepthFunc = COMPARISON_ALWAYS;
  Ref<DepthStencilState> ds = device.CreateDepthStencilState(dd);

  ctx.ClearDepthStencilView(dsv.get(), CLEAR_DEPTH | CLEAR_STENCIL, clear, 0);
  ctx.OMSetRenderTargets(0, nullptr, dsv.get());
  ctx.OMSetDepthStencilState(ds.get(), 0);
  ctx.RSSetState(rs.get());
  VIEWPORT vp{0, 0, float(w), float(h), 0, 1};
  ctx.RSSetViewports(1, viewport ? viewport : &vp);
  ctx.IASetInputLayout(layout.get());
  ctx.IASetPrimitiveTopology(topology);
  Buffer* vbs[] = {vb.get()};
  uint32_t stride = sizeof(DepthVertex), offset = 0;
  ctx.IASetVertexBuffers(0, 1, vbs, &stride, &offset);
  ctx.VSSetShader(vs.get());
  ctx.PSSetShader(nullptr);
  ctx.Draw(uint32_t(vertices.size()), 0);

  std::vector<uint8_t> raw = gpu::ReadTexture(device, ctx, depth.get());
  std::vector<double> out(size_t(w) * h);
  for (size_t i = 0; i < out.size(); ++i) {
    if (format == FORMAT_D16_UNORM) {
      uint16_t v;
      std::memcpy(&v, raw.data() + i * 2, 2);
      out[i] = v;
    } else if (format == FORMAT_D24_UNORM_S8_UINT) {
      uint32_t v;
      std::memcpy(&v, raw.data() + i * 4, 4);
      out[i] = v & 0xffffff;
    } else {
      float v;
      std::memcpy(&v, raw.data() + i * 4, 4);
      out[i] = v;
    }
  }
  return out;
}

}  // namespace sp::conformance
