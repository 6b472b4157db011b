#include "render-helpers.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace sp::conformance {

static const char* kPixelVS = R"(
float4 main(float3 p : POSITION) : SV_Position { return float4(p, 1.0); }
)";

static const char* kCountPS = R"(
float4 main(float4 p : SV_Position) : SV_Target { return float4(1, 0, 0, 0); }
)";

PixelDrawer::PixelDrawer(Device& device) : device_(device) {
  ShaderBytecode vsb = gpu::CompileInline(kPixelVS, "conformance/pixel-position.hlsl", "vs_5_0", "main");
  vs_ = device.CreateVertexShader(vsb);
  INPUT_ELEMENT_DESC el{"POSITION", 0, FORMAT_R32G32B32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0};
  layout_ = device.CreateInputLayout(&el, 1, vsb);
}

void PixelDrawer::Draw(DeviceContext& ctx, const std::vector<PixelVertex>& vertices, double vpW, double vpH, PRIMITIVE_TOPOLOGY topology) {
  std::vector<float> ndc;
  for (const PixelVertex& v : vertices) {
    ndc.push_back(float(v.x / vpW * 2 - 1));
    ndc.push_back(float(1 - v.y / vpH * 2));
    ndc.push_back(v.z);
  }
  Ref<Buffer> vb = gpu::MakeBuffer(device_, BIND_VERTEX_BUFFER, ndc.data(), uint32_t(ndc.size() * sizeof(float)));
  Buffer* vbs[] = {vb.get()};
  uint32_t stride = 3 * sizeof(float), offset = 0;
  ctx.IASetVertexBuffers(0, 1, vbs, &stride, &offset);
  ctx.IASetInputLayout(layout_.get());
  ctx.IASetPrimitiveTopology(topology);
  ctx.VSSetShader(vs_.get());
  ctx.Draw(uint32_t(vertices.size()), 0);
}

std::vector<float> CountHits(Device& device, uint32_t w, uint32_t h, const std::vector<PixelVertex>& triangles) {
  DeviceContext& ctx = *device.GetImmediateContext();
  PixelDrawer drawer(device);
  Ref<PixelShader> ps = device.CreatePixelShader(gpu::CompileInline(kCountPS, "conformance/count-hits.hlsl", "ps_5_0", "main"));
  Ref<Texture2D> target = gpu::MakeTexture2D(device, w, h, FORMAT_R32_FLOAT, BIND_RENDER_TARGET);
  Ref<RenderTargetView> rtv = device.CreateRenderTargetView(target.get());
  BLEND_DESC bd;
  bd.RenderTarget[0].BlendEnable = true;
  bd.RenderTarget[0].SrcBlend = BLEND_ONE;
  bd.RenderTarget[0].DestBlend = BLEND_ONE;
  Ref<BlendState> blend = device.CreateBlendState(bd);
  RASTERIZER_DESC rd;
  rd.CullMode = CULL_NONE;
  Ref<RasterizerState> rs = device.CreateRasterizerState(rd);
  const float zero[4] = {0, 0, 0, 0};
  ctx.ClearRenderTargetView(rtv.get(), zero);
  RenderTargetView* rtvs[] = {rtv.get()};
  ctx.OMSetRenderTargets(1, rtvs, nullptr);
  ctx.OMSetBlendState(blend.get(), nullptr, 0xffffffffu);
  ctx.RSSetState(rs.get());
  VIEWPORT vp{0, 0, float(w), float(h), 0, 1};
  ctx.RSSetViewports(1, &vp);
  ctx.PSSetShader(ps.get());
  drawer.Draw(ctx, triangles, w, h);
  return gpu::ReadAs<float>(gpu::ReadTexture(device, ctx, target.get()));
}

int CountMismatches(const std::vector<float>& got, const std::vector<float>& expected, uint32_t w, std::string* detail, const char* what) {
  int wrong = 0;
  for (size_t i = 0; i < expected.size(); ++i) {
    if (got[i] == expected[i]) continue;
    if (++wrong <= 3) {
      if (!detail->empty()) *detail += "; ";
      *detail += "pixel (" + std::to_string(i % w) + "," + std::to_string(i / w) + ") " + what + " " + std::to_string(got[i]) +
                 ", D3D11 " + std::to_string(expected[i]);
    }
  }
  return wrong;
}

std::vector<std::array<float, 4>> RunCompute(Device& device, const std::string& source, const std::string& name, uint32_t count,
                                             const std::vector<ShaderResourceView*>& srvs, const std::vector<SamplerState*>& samplers,
                                             uint32_t groups) {
  DeviceContext& ctx = *device.GetImmediateContext();
  Ref<ComputeShader> cs = device.CreateComputeShader(gpu::CompileInline(source, name, "cs_5_0", "main"));
  Ref<Buffer> out = gpu::MakeBuffer(device, BIND_UNORDERED_ACCESS, nullptr, count * 16, RESOURCE_MISC_BUFFER_STRUCTURED, 16);
  UNORDERED_ACCESS_VIEW_DESC ud;
  ud.Format = FORMAT_UNKNOWN;
  ud.ViewDimension = UAV_DIMENSION_BUFFER;
  ud.Buffer = {0, count, 0};
  Ref<UnorderedAccessView> uav = device.CreateUnorderedAccessView(out.get(), &ud);
  ctx.CSSetShader(cs.get());
  if (!srvs.empty()) ctx.CSSetShaderResources(0, uint32_t(srvs.size()), srvs.data());
  if (!samplers.empty()) ctx.CSSetSamplers(0, uint32_t(samplers.size()), samplers.data());
  ctx.CSSetUnorderedAccessViews(0, {uav.get()});
  ctx.Dispatch(groups, 1, 1);
  ctx.CSSetUnorderedAccessViews(0, {nullptr});
  std::vector<float> f = gpu::ReadAs<float>(gpu::ReadBuffer(device, ctx, out.get()));
  std::vector<std::array<float, 4>> r(count);
  for (uint32_t i = 0; i < count; ++i) r[i] = {f[i * 4], f[i * 4 + 1], f[i * 4 + 2], f[i * 4 + 3]};
  return r;
}

void UploadThroughStaging(Device& device, Texture2D* texture, uint32_t sub, const void* texels) {
  TEXTURE2D_DESC d = texture->GetDesc();
  uint32_t mip = sub % d.MipLevels;
  TEXTURE2D_DESC s = d;
  s.Width = std::max(1u, d.Width >> mip);
  s.Height = std::max(1u, d.Height >> mip);
  s.MipLevels = 1;
  s.ArraySize = 1;
  s.Usage = USAGE_STAGING;
  s.BindFlags = 0;
  s.CPUAccessFlags = CPU_ACCESS_WRITE;
  s.MiscFlags = 0;
  SUBRESOURCE_DATA init{texels, s.Width * GetFormatInfo(d.Format).bytesPerElement, 0};
  Ref<Texture2D> staging = device.CreateTexture2D(s, &init);
  device.GetImmediateContext()->CopySubresourceRegion(texture, sub, 0, 0, 0, staging.get(), 0, nullptr);
}

Ref<SamplerState> MakeSampler(Device& device, FILTER filter, TEXTURE_ADDRESS_MODE address, COMPARISON_FUNC cmp) {
  SAMPLER_DESC d;
  d.Filter = filter;
  d.AddressU = d.AddressV = d.AddressW = address;
  d.ComparisonFunc = cmp;
  return device.CreateSamplerState(d);
}

Ref<ShaderResourceView> MakeSrv(Device& device, Resource* resource, FORMAT format, SRV_DIMENSION dim, uint32_t firstSlice, uint32_t slices) {
  SHADER_RESOURCE_VIEW_DESC d;
  d.Format = format;
  d.ViewDimension = dim;
  switch (dim) {
    case SRV_DIMENSION_TEXTURE2D: d.Texture2D = {0, 1}; break;
    case SRV_DIMENSION_TEXTURE2DARRAY: d.Texture2DArray = {0, 1, firstSlice, slices}; break;
    case SRV_DIMENSION_TEXTURECUBE: d.TextureCube = {0, 1}; break;
    case SRV_DIMENSION_TEXTURE2DMS: break;
    default: break;
  }
  return device.CreateShaderResourceView(resource, &d);
}

double UnormScaled(double c, uint32_t bits) {
  if (std::isnan(c)) return 0;
  return std::clamp(c, 0.0, 1.0) * double((1ull << bits) - 1);
}

float UnormToFloat(uint32_t code, uint32_t bits) { return float(code) / float((1ull << bits) - 1); }

double SrgbEncodeScaled(double c) {
  c = std::clamp(c, 0.0, 1.0);
  double s = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
  return s * 255.0;
}

double SrgbDecode(uint32_t code) {
  double c = code / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

uint16_t FloatToHalfRtz(float f) {
  uint32_t b;
  std::memcpy(&b, &f, 4);
  uint16_t sign = uint16_t((b >> 16) & 0x8000);
  uint32_t exp = (b >> 23) & 0xff, man = b & 0x7fffff;
  if (exp == 0xff) return uint16_t(sign | 0x7c00 | (man ? 0x200 : 0));  // INF stays INF, NaN stays NaN
  int e = int(exp) - 127 + 15;
  if (e >= 31) return uint16_t(sign | 0x7bff);  // beyond the range: the largest finite value
  if (e <= 0) {
    if (e < -10) return sign;
    // Denormal: shift the mantissa with its hidden bit, dropping the rest (toward zero).
    uint32_t m = (man | 0x800000) >> uint32_t(14 - e);
    return uint16_t(sign | m);
  }
  return uint16_t(sign | (uint32_t(e) << 10) | (man >> 13));
}

float HalfToFloat(uint16_t h) {
  uint32_t sign = uint32_t(h & 0x8000) << 16, exp = (h >> 10) & 0x1f, man = h & 0x3ff;
  float v;
  if (exp == 0) v = std::ldexp(float(man), -24);
  else if (exp == 31) v = man ? NAN : INFINITY;
  else v = std::ldexp(float(man | 0x400), int(exp) - 25);
  uint32_t b;
  std::memcpy(&b, &v, 4);
  b |= sign;
  std::memcpy(&v, &b, 4);
  return v;
}

}  // namespace sp::conformance
