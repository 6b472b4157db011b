// Measures how the running driver scales the constant depth bias, per depth format, so that
// D3D11's DepthBias (in units of one depth LSB for UNORM formats, 2^(e-23) for D32_FLOAT) is
// reproduced exactly. Vulkan and GL leave the unit implementation-defined for UNORM formats
// (Mesa 22.3 uses 2 LSB, newer Mesa 1 LSB), so it is measured rather than assumed.
#include <sp/hlsl/compiler.h>
#include <sp/rhi/context.h>

#include <cmath>
#include <cstring>

namespace sp {
namespace {

const char* kCalibrationShader = R"(
// A full-viewport triangle at constant depth 0.5: no slope, so only the constant bias moves it.
float4 main(uint id : SV_VertexID) : SV_Position {
  float2 p = float2((id << 1) & 2, id & 2);
  return float4(p * 2.0 - 1.0, 0.25, 1.0);
}
)";

// Depth at the centre texel, in units of the format's LSB (UNORM) or as a float.
double RenderBiased(Device& dev, VertexShader* vs, FORMAT fmt, int32_t bias) {
  DeviceContext& ctx = *dev.GetImmediateContext();
  TEXTURE2D_DESC td;
  td.Width = td.Height = 4;
  td.Format = fmt;
  td.BindFlags = BIND_DEPTH_STENCIL;
  Ref<Texture2D> depth = dev.CreateTexture2D(td);
  depth->SetDebugName("depth-bias calibration target");
  Ref<DepthStencilView> dsv = dev.CreateDepthStencilView(depth.get());
  RASTERIZER_DESC rd;
  rd.CullMode = CULL_NONE;
  rd.DepthBias = bias;
  Ref<RasterizerState> rs = dev.CreateRasterizerState(rd);
  DEPTH_STENCIL_DESC dd;
  dd.DepthFunc = COMPARISON_ALWAYS;
  Ref<DepthStencilState> ds = dev.CreateDepthStencilState(dd);

  ctx.ClearState();
  ctx.ClearDepthStencilView(dsv.get(), CLEAR_DEPTH | CLEAR_STENCIL, 1.0f, 0);
  ctx.OMSetRenderTargets(0, nullptr, dsv.get());
  ctx.OMSetDepthStencilState(ds.get(), 0);
  ctx.RSSetState(rs.get());
  VIEWPORT vp{0, 0, 4, 4, 0, 1};
  ctx.RSSetViewports(1, &vp);
  ctx.IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  ctx.VSSetShader(vs);
  ctx.PSSetShader(nullptr);
  ctx.Draw(3, 0);

  td.BindFlags = 0;
  td.Usage = USAGE_STAGING;
  td.CPUAccessFlags = CPU_ACCESS_READ;
  Ref<Texture2D> staging = dev.CreateTexture2D(td);
  ctx.CopyResource(staging.get(), depth.get());
  MAPPED_SUBRESOURCE m;
  ctx.Map(staging.get(), 0, MAP_READ, 0, &m);
  const uint8_t* row = static_cast<const uint8_t*>(m.pData) + 2 * m.RowPitch;
  double value = 0;
  if (fmt == FORMAT_D16_UNORM) {
    uint16_t v;
    std::memcpy(&v, row + 2 * 2, 2);
    value = v;
  } else if (fmt == FORMAT_D24_UNORM_S8_UINT) {
    uint32_t v;
    std::memcpy(&v, row + 2 * 4, 4);
    value = v & 0xffffff;
  } else {
    float v;
    std::memcpy(&v, row + 2 * 4, 4);
    value = v;
  }
  ctx.Unmap(staging.get(), 0);
  ctx.ClearState();
  return value;
}

}  // namespace

void Device::CalibrateDepthBias() {
  hlsl::CompileOptions opt;
  opt.target = "vs_5_0";
  opt.cacheDir = shaderCacheDir_;
  ShaderBytecode bc = hlsl::CompileSource(kCalibrationShader, "shadowport/depth-bias-calibration.hlsl", opt);
  Ref<VertexShader> vs = CreateVertexShader(bc);
  struct Item {
    FORMAT fmt;
    float* scale;
    double lsbPerD3DUnit;  // how far one D3D11 bias unit moves the stored value
    int32_t units;         // as large as the format's range allows from z = 0.25, for precision
  };
  const Item items[] = {{FORMAT_D16_UNORM, &info_.depthBiasScaleD16, 1.0, 10000},
                        {FORMAT_D24_UNORM_S8_UINT, &info_.depthBiasScaleD24, 1.0, 1000000},
                        {FORMAT_D32_FLOAT, &info_.depthBiasScaleD32, std::ldexp(1.0, -25), 100000}};  // z = 0.25: 2^(-2-23)
  for (const Item& it : items) {
    if (!(CheckFormatSupport(it.fmt) & FORMAT_SUPPORT_DEPTH_STENCIL)) continue;
    *it.scale = 1.0f;  // measure the raw driver behaviour
    double base = RenderBiased(*this, vs.get(), it.fmt, 0);
    double biased = RenderBiased(*this, vs.get(), it.fmt, it.units);
    double perUnit = (biased - base) / it.units / it.lsbPerD3DUnit;
    if (!(perUnit > 0.01 && perUnit < 100.0)) {
      Message(MessageSeverity::Warning, std::string("depth-bias calibration for ") + std::string(FormatName(it.fmt)) +
                                            " measured an implausible unit (" + std::to_string(perUnit) + "); using 1");
      continue;
    }
    // Drivers use a power of two of the format's LSB (Mesa 22.3: 2 for UNORM, 1 for float);
    // D3D11's UNORM unit 1/(2^n - 1) differs from 2^-n by less than the measurement can see.
    double snapped = std::exp2(std::round(std::log2(perUnit)));
    if (std::abs(perUnit - snapped) < 2e-3 * snapped) perUnit = snapped;
    *it.scale = float(1.0 / perUnit);
  }
}

}  // namespace sp
