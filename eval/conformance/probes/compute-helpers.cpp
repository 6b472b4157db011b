#include "compute-helpers.h"

#include <chrono>
#include <sstream>

namespace sp::conformance {

BufferViews MakeStructured(Device& dev, uint32_t count, uint32_t stride, const void* init, uint32_t uavFlags, bool withSrv) {
  BufferViews v;
  v.buffer = gpu::MakeBuffer(dev, BIND_UNORDERED_ACCESS | (withSrv ? BIND_SHADER_RESOURCE : 0u), init, count * stride,
                             RESOURCE_MISC_BUFFER_STRUCTURED, stride);
  UNORDERED_ACCESS_VIEW_DESC d;
  d.Format = FORMAT_UNKNOWN;
  d.ViewDimension = UAV_DIMENSION_BUFFER;
  d.Buffer = {0, count, uavFlags};
  v.uav = dev.CreateUnorderedAccessView(v.buffer.get(), &d);
  if (withSrv) v.srv = dev.CreateShaderResourceView(v.buffer.get());
  return v;
}

BufferViews MakeRaw(Device& dev, uint32_t bytes, const void* init, uint32_t extraBind, uint32_t extraMisc) {
  BufferViews v;
  v.buffer = gpu::MakeBuffer(dev, BIND_UNORDERED_ACCESS | extraBind, init, bytes, RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS | extraMisc);
  UNORDERED_ACCESS_VIEW_DESC d;
  d.Format = FORMAT_R32_TYPELESS;
  d.ViewDimension = UAV_DIMENSION_BUFFER;
  d.Buffer = {0, bytes / 4, BUFFER_UAV_FLAG_RAW};
  v.uav = dev.CreateUnorderedAccessView(v.buffer.get(), &d);
  if (extraBind & BIND_SHADER_RESOURCE) {
    SHADER_RESOURCE_VIEW_DESC s;
    s.Format = FORMAT_R32_TYPELESS;
    s.ViewDimension = SRV_DIMENSION_BUFFEREX;
    s.BufferEx = {0, bytes / 4, BUFFEREX_SRV_FLAG_RAW};
    v.srv = dev.CreateShaderResourceView(v.buffer.get(), &s);
  }
  return v;
}

BufferViews MakeTyped(Device& dev, FORMAT format, uint32_t count, const void* init, uint32_t first, uint32_t num, uint32_t extraBind,
                      uint32_t extraMisc) {
  BufferViews v;
  v.buffer = gpu::MakeBuffer(dev, BIND_UNORDERED_ACCESS | extraBind, init, count * GetFormatInfo(format).bytesPerElement, extraMisc);
  UNORDERED_ACCESS_VIEW_DESC d;
  d.Format = format;
  d.ViewDimension = UAV_DIMENSION_BUFFER;
  d.Buffer = {first, num, 0};
  v.uav = dev.CreateUnorderedAccessView(v.buffer.get(), &d);
  if (extraBind & BIND_SHADER_RESOURCE) {
    SHADER_RESOURCE_VIEW_DESC s;
    s.Format = format;
    s.ViewDimension = SRV_DIMENSION_BUFFER;
    s.Buffer = {first, num};
    v.srv = dev.CreateShaderResourceView(v.buffer.get(), &s);
  }
  return v;
}

TextureViews MakeUavTexture(Device& dev, uint32_t w, uint32_t h, FORMAT format, uint32_t slices, const void* init, bool withSrv) {
  TextureViews t;
  TEXTURE2D_DESC d;
  d.Width = w;
  d.Height = h;
  d.ArraySize = slices;
  d.Format = format;
  d.BindFlags = BIND_UNORDERED_ACCESS | (withSrv ? BIND_SHADER_RESOURCE : 0u);
  uint32_t pitch = w * GetFormatInfo(format).bytesPerElement;
  std::vector<SUBRESOURCE_DATA> data(slices);
  for (uint32_t s = 0; s < slices; ++s) data[s] = {static_cast<const uint8_t*>(init) + size_t(s) * pitch * h, pitch, 0};
  t.texture = dev.CreateTexture2D(d, init ? data.data() : nullptr);
  t.uav = dev.CreateUnorderedAccessView(t.texture.get());
  if (withSrv) t.srv = dev.CreateShaderResourceView(t.texture.get());
  return t;
}

Ref<ComputeShader> MakeCS(Device& dev, const std::string& source, const std::string& name, const std::string& entry,
                          const std::vector<hlsl::Define>& defines) {
  return dev.CreateComputeShader(gpu::CompileInline(source, "conformance/" + name + ".hlsl", "cs_5_0", entry, defines));
}
Ref<VertexShader> MakeVS(Device& dev, const std::string& source, const std::string& name, const std::string& entry,
                         const std::vector<hlsl::Define>& defines) {
  return dev.CreateVertexShader(gpu::CompileInline(source, "conformance/" + name + ".hlsl", "vs_5_0", entry, defines));
}
Ref<PixelShader> MakePS(Device& dev, const std::string& source, const std::string& name, const std::string& entry,
                        const std::vector<hlsl::Define>& defines) {
  return dev.CreatePixelShader(gpu::CompileInline(source, "conformance/" + name + ".hlsl", "ps_5_0", entry, defines));
}

void DrawTarget::Clear(DeviceContext& ctx, float value) const {
  const float c[4] = {value, value, value, value};
  ctx.ClearRenderTargetView(rtv.get(), c);
}

void DrawTarget::Bind(DeviceContext& ctx) const {
  RenderTargetView* rtvs[] = {rtv.get()};
  ctx.OMSetRenderTargets(1, rtvs, nullptr);
  VIEWPORT vp{0, 0, float(width), float(height), 0, 1};
  ctx.RSSetViewports(1, &vp);
}

DrawTarget MakeDrawTarget(Device& dev, uint32_t w, uint32_t h, FORMAT format) {
  DrawTarget t;
  t.texture = gpu::MakeTexture2D(dev, w, h, format, BIND_RENDER_TARGET);
  t.rtv = dev.CreateRenderTargetView(t.texture.get());
  t.width = w;
  t.height = h;
  return t;
}

Result Mismatches::Finish(const std::string& unit) const {
  if (count_ == 0) return Pass(0, unit, 0);
  std::ostringstream s;
  s << what_ << ": " << count_ << " wrong; first: " << first_;
  return Fail(s.str(), double(count_), unit, 0);
}

bool WaitForQuery(DeviceContext& ctx, Query* q, void* data, uint32_t size) {
  auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!ctx.GetData(q, data, size, 0))
    if (std::chrono::steady_clock::now() > deadline) return false;
  return true;
}

std::string ExpectError(ErrorId id, const std::string& call, const std::string& object, const std::vector<std::string>& mentions,
                        const std::function<void()>& f, std::string* message) {
  std::string expected = "SP_" + std::string(ErrorIdName(id)) + " from " + call;
  try {
    f();
  } catch (const Error& e) {
    if (message) *message = e.what();
    if (e.id() != id) return "expected " + expected + ", got: " + e.what();
    if (e.call() != call) return "expected the call " + call + " to be named, got: " + e.what();
    if (e.object().find(object) == std::string::npos) return "expected the object '" + object + "' to be named, got: " + e.what();
    for (const std::string& m : mentions)
      if (std::string(e.what()).find(m) == std::string::npos) return "expected '" + m + "' in the message: " + e.what();
    return "";
  } catch (const std::exception& e) {
    return "expected " + expected + ", got another exception: " + e.what();
  }
  return "expected " + expected + ", but the call succeeded";
}

Result ExpectErrors(ErrorId id, const std::vector<MisuseCase>& cases) {
  std::string first;
  size_t wrong = 0;
  std::string detail;
  for (const MisuseCase& c : cases) {
    std::string message;
    std::string why = ExpectError(id, c.call, c.object, c.mentions, c.f, &message);
    if (!why.empty() && wrong++ == 0) detail = why;
    if (first.empty() && why.empty()) first = message;
  }
  if (wrong) return Fail(std::to_string(wrong) + " of " + std::to_string(cases.size()) + " cases wrong; first: " + detail, double(wrong), "cases", 0);
  return Pass(0, "cases", 0, first);
}

}  // namespace sp::conformance
