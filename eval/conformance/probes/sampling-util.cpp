#include "sampling-util.h"

#include <algorithm>
#include <charconv>

namespace sp::conformance::sampling {
namespace {

constexpr uint32_t kCaseSlot = 15;
constexpr uint32_t kComputeGroup = 64;
constexpr uint32_t kPixelColumns = 16;  // cases per row of quads in RunPixel

const char* kCasePrologue = R"(
struct Case { float4 a; float4 b; };
StructuredBuffer<Case> cases : register(t15);
)";

Ref<ShaderResourceView> StructuredView(Device& device, Buffer* buffer, uint32_t count) {
  SHADER_RESOURCE_VIEW_DESC d;
  d.Format = FORMAT_UNKNOWN;
  d.ViewDimension = SRV_DIMENSION_BUFFER;
  d.Buffer = {0, count};
  return device.CreateShaderResourceView(buffer, &d);
}

// The case table padded to a multiple of `multiple` (with copies of the first case) and its view.
struct CaseTable {
  Ref<Buffer> buffer;
  Ref<ShaderResourceView> srv;
  uint32_t count = 0;
};

CaseTable UploadCases(Device& device, std::vector<Case> cases, uint32_t multiple) {
  if (cases.empty()) cases.push_back({});
  while (cases.size() % multiple) cases.push_back(cases.front());
  CaseTable t;
  t.count = uint32_t(cases.size());
  t.buffer = gpu::MakeBuffer(device, BIND_SHADER_RESOURCE, cases.data(), uint32_t(cases.size() * sizeof(Case)), RESOURCE_MISC_BUFFER_STRUCTURED,
                             sizeof(Case));
  t.srv = StructuredView(device, t.buffer.get(), t.count);
  return t;
}



}  // namespace

std::vector<Float4> RunCompute(Device& device, const std::string& body, const std::string& name, const std::vector<Case>& cases,
                               const std::vector<ShaderResourceView*>& srvs, const std::vector<SamplerState*>& samplers) {
  DeviceContext& ctx = *device.GetImmediateContext();
  ctx.ClearState();
  std::string src = std::string(kCasePrologue) + "RWStructuredBuffer<float4> output : register(u0);\n" + body +
                    "\n[numthreads(64, 1, 1)] void main(uint3 id : SV_DispatchThreadID) { output[id.x] = Probe(cases[id.x], id.x); }\n";
  Ref<ComputeShader> cs = device.CreateComputeShader(gpu::CompileInline(src, "conformance/" + name + ".hlsl", "cs_5_0", "main"));
  CaseTable table = UploadCases(device, cases, kComputeGroup);
  Ref<Buffer> out = gpu::MakeBuffer(device, BIND_UNORDERED_ACCESS, nullptr, table.count * 16, RESOURCE_MISC_BUFFER_STRUCTURED, 16);
  UNORDERED_ACCESS_VIEW_DESC ud;
  ud.Format = FORMAT_UNKNOWN;
  ud.ViewDimension = UAV_DIMENSION_BUFFER;
  ud.Buffer = {0, table.count, 0};
  Ref<UnorderedAccessView> uav = device.CreateUnorderedAccessView(out.get(), &ud);
  ctx.CSSetShader(cs.get());
  if (!srvs.empty()) ctx.CSSetShaderResources(0, uint32_t(srvs.size()), srvs.data());
  if (!samplers.empty()) ctx.CSSetSamplers(0, uint32_t(samplers.size()), samplers.data());
  ShaderResourceView* caseView = table.srv.get();
  ctx.CSSetShaderResources(kCaseSlot, 1, &caseView);
  ctx.CSSetUnorderedAccessViews(0, {uav.get()});
  ctx.Dispatch(table.count / kComputeGroup, 1, 1);
  ctx.ClearState();
  std::vector<Float4> r = gpu::ReadAs<Float4>(gpu::ReadBuffer(device, ctx, out.get()));
  r.resize(cases.size());
  return r;
}

std::vector<Float4> RunPixel(Device& device, const std::string& body, const std::string& name, const std::vector<Case>& cases,
                             const std::vector<ShaderResourceView*>& srvs, const std::vector<SamplerState*>& samplers) {
  DeviceContext& ctx = *device.GetImmediateContext();
  ctx.ClearState();
  // Each case is drawn as its own 2x2-pixel rectangle and reaches the pixel shader as flat
  // attributes, so its data are constant across the quad by construction. (Loading them in the
  // pixel shader from `cases` by quad index gave wrong ddx/ddy of the loaded values in some quads
  // on llvmpipe, on both backends, which would have turned every implicit-LOD case into a test of
  // that instead of sampling.)
  const char* vsSource = R"(
struct Case { float4 a; float4 b; };
StructuredBuffer<Case> cases : register(t15);
struct Quad { float4 pos : SV_Position; nointerpolation float4 a : CASE_A; nointerpolation float4 b : CASE_B; };
Quad main(uint id : SV_VertexID) {
  static const float2 corners[6] = { float2(0, 0), float2(2, 0), float2(0, 2), float2(0, 2), float2(2, 0), float2(2, 2) };
  uint c = id / 6;
  float2 px = float2(c % COLUMNS, c / COLUMNS) * 2 + corners[id % 6];
  Quad q;
  q.pos = float4(px.x / WIDTH * 2 - 1, 1 - px.y / HEIGHT * 2, 0, 1);
  q.a = cases[c].a;
  q.b = cases[c].b;
  return q;
}
)";
  std::string src = R"(
struct Case { float4 a; float4 b; };
struct Quad { float4 pos : SV_Position; nointerpolation float4 a : CASE_A; nointerpolation float4 b : CASE_B; };
)" + body + R"(
float4 main(Quad q) : SV_Target {
  Case k;
  k.a = q.a;
  k.b = q.b;
  return Probe(k, float2(uint2(q.pos.xy) & 1));
}
)";
  CaseTable table = UploadCases(device, cases, kPixelColumns);
  const uint32_t w = 2 * kPixelColumns, h = 2 * (table.count / kPixelColumns);
  std::vector<hlsl::Define> defines = {{"COLUMNS", std::to_string(kPixelColumns)}, {"WIDTH", std::to_string(w) + ".0"}, {"HEIGHT", std::to_string(h) + ".0"}};
  Ref<VertexShader> vs = device.CreateVertexShader(gpu::CompileInline(vsSource, "conformance/sampling-quads.hlsl", "vs_5_0", "main", defines));
  Ref<PixelShader> ps = device.CreatePixelShader(gpu::CompileInline(src, "conformance/" + name + ".hlsl", "ps_5_0", "main"));
  Ref<Texture2D> target = gpu::MakeTexture2D(device, w, h, FORMAT_R32G32B32A32_FLOAT, BIND_RENDER_TARGET);
  Ref<RenderTargetView> rtv = device.CreateRenderTargetView(target.get());
  RenderTargetView* rtvs[] = {rtv.get()};
  ctx.OMSetRenderTargets(1, rtvs, nullptr);
  VIEWPORT vp{0, 0, float(w), float(h), 0, 1};
  ctx.RSSetViewports(1, &vp);
  ctx.IASetInputLayout(nullptr);
  ctx.IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  ctx.VSSetShader(vs.get());
  ctx.PSSetShader(ps.get());
  ShaderResourceView* caseView = table.srv.get();
  ctx.VSSetShaderResources(kCaseSlot, 1, &caseView);
  if (!srvs.empty()) ctx.PSSetShaderResources(0, uint32_t(srvs.size()), srvs.data());
  if (!samplers.empty()) ctx.PSSetSamplers(0, uint32_t(samplers.size()), samplers.data());
  ctx.Draw(6 * table.count, 0);
  ctx.ClearState();
  std::vector<Float4> px = gpu::ReadAs<Float4>(gpu::ReadTexture(device, ctx, target.get()));
  std::vector<Float4> r(cases.size());
  for (size_t i = 0; i < r.size(); ++i) r[i] = px[(i / kPixelColumns) * 2 * w + (i % kPixelColumns) * 2];
  return r;
}

Ref<SamplerState> MakeSampler(Device& device, const SAMPLER_DESC& desc) { return device.CreateSamplerState(desc); }

Ref<SamplerState> MakeSampler(Device& device, FILTER filter, TEXTURE_ADDRESS_MODE u, TEXTURE_ADDRESS_MODE v) {
  SAMPLER_DESC d;
  d.Filter = filter;
  d.AddressU = u;
  d.AddressV = v;
  return device.CreateSamplerState(d);
}

Ref<Texture2D> MakeFloatTexture(Device& device, uint32_t w, uint32_t h, uint32_t components, const std::vector<std::vector<float>>& levels) {
  TEXTURE2D_DESC d;
  d.Width = w;
  d.Height = h;
  d.MipLevels = uint32_t(levels.size());
  d.Format = components == 4 ? FORMAT_R32G32B32A32_FLOAT : FORMAT_R32_FLOAT;
  d.BindFlags = BIND_SHADER_RESOURCE;
  std::vector<SUBRESOURCE_DATA> init;
  for (uint32_t l = 0; l < levels.size(); ++l) init.push_back({levels[l].data(), std::max(1u, w >> l) * components * 4, 0});
  return device.CreateTexture2D(d, init.data());
}

DepthTexture MakeDepthTexture(Device& device, uint32_t w, uint32_t h, const std::vector<float>& depths, bool rendered) {
  DeviceContext& ctx = *device.GetImmediateContext();
  ctx.ClearState();
  DepthTexture t;
  t.texture = gpu::MakeTexture2D(device, w, h, FORMAT_R32_TYPELESS, BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE);
  if (rendered) {
    const char* src = R"(
StructuredBuffer<float> depths : register(t0);
float main(float4 pos : SV_Position) : SV_Depth { uint2 p = uint2(pos.xy); return depths[p.y * WIDTH + p.x]; }
)";
    Ref<VertexShader> vs = device.CreateVertexShader(gpu::CompileInline(gpu::kFullscreenVS, "conformance/fullscreen.hlsl", "vs_5_0", "FullscreenVS"));
    Ref<PixelShader> ps = device.CreatePixelShader(
        gpu::CompileInline(src, "conformance/sampling-depth-writer.hlsl", "ps_5_0", "main", {{"WIDTH", std::to_string(w)}}));
    Ref<Buffer> values = gpu::MakeBuffer(device, BIND_SHADER_RESOURCE, depths.data(), uint32_t(depths.size() * 4), RESOURCE_MISC_BUFFER_STRUCTURED, 4);
    Ref<ShaderResourceView> valuesView = StructuredView(device, values.get(), uint32_t(depths.size()));
    DEPTH_STENCIL_VIEW_DESC dd;
    dd.Format = FORMAT_D32_FLOAT;
    dd.ViewDimension = DSV_DIMENSION_TEXTURE2D;
    Ref<DepthStencilView> dsv = device.CreateDepthStencilView(t.texture.get(), &dd);
    DEPTH_STENCIL_DESC ds;
    ds.DepthFunc = COMPARISON_ALWAYS;
    Ref<DepthStencilState> always = device.CreateDepthStencilState(ds);
    ctx.ClearDepthStencilView(dsv.get(), CLEAR_DEPTH, 1.0f, 0);
    ctx.OMSetRenderTargets(0, nullptr, dsv.get());
    ctx.OMSetDepthStencilState(always.get(), 0);
    VIEWPORT vp{0, 0, float(w), float(h), 0, 1};
    ctx.RSSetViewports(1, &vp);
    ctx.IASetInputLayout(nullptr);
    ctx.IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    ctx.VSSetShader(vs.get());
    ctx.PSSetShader(ps.get());
    ctx.PSSetShaderResources(0, {valuesView.get()});
    ctx.Draw(3, 0);
    ctx.ClearState();
  } else {
    // Depth textures cannot take initial data or UpdateSubresource in D3D11: copy from staging.
    TEXTURE2D_DESC sd = t.texture->GetDesc();
    sd.BindFlags = 0;
    sd.Usage = USAGE_STAGING;
    sd.CPUAccessFlags = CPU_ACCESS_WRITE;
    SUBRESOURCE_DATA init{depths.data(), w * 4, 0};
    Ref<Texture2D> staging = device.CreateTexture2D(sd, &init);
    ctx.CopyResource(t.texture.get(), staging.get());
  }
  SHADER_RESOURCE_VIEW_DESC sd;
  sd.Format = FORMAT_R32_FLOAT;
  sd.ViewDimension = SRV_DIMENSION_TEXTURE2D;
  sd.Texture2D = {0, 1};
  t.srv = device.CreateShaderResourceView(t.texture.get(), &sd);
  return t;
}

int AddressTexel(TEXTURE_ADDRESS_MODE mode, int i, int n) {
  switch (mode) {
    case TEXTURE_ADDRESS_WRAP: return ((i % n) + n) % n;
    case TEXTURE_ADDRESS_MIRROR: {
      int p = ((i % (2 * n)) + 2 * n) % (2 * n);
      return p < n ? p : 2 * n - 1 - p;
    }
    case TEXTURE_ADDRESS_BORDER: return i < 0 || i >= n ? -1 : i;
    case TEXTURE_ADDRESS_MIRROR_ONCE: return std::min(i < 0 ? -i - 1 : i, n - 1);
    default: return std::clamp(i, 0, n - 1);
  }
}

Expected SampleLevelCpu(const MipChain& img, uint32_t level, double u, double v, const SamplerModel& s, int ox, int oy) {
  const int w = int(img.Width(level)), h = int(img.Height(level));
  auto fetch = [&](int i, int j) -> double {
    int x = AddressTexel(s.u, i, w), y = AddressTexel(s.v, j, h);
    return x < 0 || y < 0 ? s.border : double(img.At(level, uint32_t(x), uint32_t(y)));
  };
  if (!s.linear) return {fetch(int(std::floor(u * w)) + ox, int(std::floor(v * h)) + oy), 0.0};
  const double su = u * w - 0.5, sv = v * h - 0.5;
  const int i0 = int(std::floor(su)) + ox, j0 = int(std::floor(sv)) + oy;
  const double a = su - std::floor(su), b = sv - std::floor(sv);
  const double t00 = fetch(i0, j0), t10 = fetch(i0 + 1, j0), t01 = fetch(i0, j0 + 1), t11 = fetch(i0 + 1, j0 + 1);
  Expected e;
  e.value = (1 - b) * ((1 - a) * t00 + a * t10) + b * ((1 - a) * t01 + a * t11);
  const double du = std::max(std::abs(t10 - t00), std::abs(t11 - t01)), dv = std::max(std::abs(t01 - t00), std::abs(t11 - t10));
  const double magnitude = std::max({1.0, std::abs(t00), std::abs(t10), std::abs(t01), std::abs(t11)});
  e.tol = (a != 0 ? kWeightStep * du : 0) + (b != 0 ? kWeightStep * dv : 0) + kFloatSlack * magnitude;
  return e;
}

Expected SampleLodCpu(const MipChain& img, double lod, bool mipLinear, double u, double v, const SamplerModel& s, int ox, int oy) {
  const double last = double(img.Levels() - 1);
  lod = std::clamp(lod, 0.0, last);
  if (!mipLinear) return SampleLevelCpu(img, uint32_t(std::floor(lod + 0.5)), u, v, s, ox, oy);
  const uint32_t l0 = uint32_t(std::floor(lod));
  const double f = lod - l0;
  Expected e0 = SampleLevelCpu(img, l0, u, v, s, ox, oy);
  if (f == 0) return e0;
  Expected e1 = SampleLevelCpu(img, l0 + 1, u, v, s, ox, oy);
  Expected e;
  e.value = (1 - f) * e0.value + f * e1.value;
  e.tol = std::max(e0.tol, e1.tol) + kWeightStep * std::abs(e1.value - e0.value);
  return e;
}

void Worst::AddError(double err, double tol, const std::string& where) {
  if (std::isnan(err)) err = std::numeric_limits<double>::infinity();
  if (err > tol) {
    ++failures_;
    if (err - tol > margin_) {
      margin_ = err - tol;
      failErr_ = err;
      failTol_ = tol;
      failWhere_ = where;
    }
  }
  if (err > err_) {
    err_ = err;
    tol_ = tol;
    where_ = where;
  }
}

void Worst::Add(double got, const Expected& e, const std::string& where) {
  AddError(std::abs(got - e.value), e.tol, where + ": got " + Fmt(got) + ", D3D11 " + Fmt(e.value));
}

Result Worst::Finish(const std::string& unit) const {
  if (failures_ == 0) return Pass(std::max(err_, 0.0), unit, tol_, "largest error: " + where_);
  return Within(failErr_, failTol_, unit, std::to_string(failures_) + " case(s) off; worst " + failWhere_);
}

std::string Fmt(double v) {
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof(buf), v);
  return std::string(buf, r.ptr);
}

std::string AddressName(TEXTURE_ADDRESS_MODE m) {
  switch (m) {
    case TEXTURE_ADDRESS_WRAP: return "WRAP";
    case TEXTURE_ADDRESS_MIRROR: return "MIRROR";
    case TEXTURE_ADDRESS_CLAMP: return "CLAMP";
    case TEXTURE_ADDRESS_BORDER: return "BORDER";
    case TEXTURE_ADDRESS_MIRROR_ONCE: return "MIRROR_ONCE";
  }
  return "?";
}

}  // namespace sp::conformance::sampling
