#include "gpu-util.h"

#include <algorithm>
#include <cstdlib>

namespace sp::gpu {

const char* const kFullscreenVS = R"(
float4 FullscreenVS(uint id : SV_VertexID) : SV_Position {
  float2 p = float2((id << 1) & 2, id & 2);
  return float4(p * float2(2, -2) + float2(-1, 1), 0, 1);
}
)";

std::vector<uint8_t> ReadTexture(Device& dev, DeviceContext& ctx, Texture2D* tex, uint32_t sub) {
  TEXTURE2D_DESC d = tex->GetDesc();
  uint32_t mip = sub % d.MipLevels;
  TEXTURE2D_DESC s = d;
  s.Width = std::max(1u, d.Width >> mip);
  s.Height = std::max(1u, d.Height >> mip);
  s.MipLevels = 1;
  s.ArraySize = 1;
  s.SampleDesc = {1, 0};
  s.Usage = USAGE_STAGING;
  s.BindFlags = 0;
  s.CPUAccessFlags = CPU_ACCESS_READ;
  s.MiscFlags = 0;
  Ref<Texture2D> staging = dev.CreateTexture2D(s);
  ctx.CopySubresourceRegion(staging.get(), 0, 0, 0, 0, tex, sub, nullptr);
  MAPPED_SUBRESOURCE m;
  ctx.Map(staging.get(), 0, MAP_READ, 0, &m);
  uint32_t rowBytes = s.Width * GetFormatInfo(d.Format).bytesPerElement;
  std::vector<uint8_t> out(size_t(rowBytes) * s.Height);
  for (uint32_t y = 0; y < s.Height; ++y)
    std::memcpy(out.data() + size_t(y) * rowBytes, static_cast<uint8_t*>(m.pData) + size_t(y) * m.RowPitch, rowBytes);
  ctx.Unmap(staging.get(), 0);
  return out;
}

std::vector<uint8_t> ReadBuffer(Device& dev, DeviceContext& ctx, Buffer* buf) {
  BUFFER_DESC d;
  d.ByteWidth = buf->GetDesc().ByteWidth;
  d.Usage = USAGE_STAGING;
  d.CPUAccessFlags = CPU_ACCESS_READ;
  Ref<Buffer> staging = dev.CreateBuffer(d);
  ctx.CopyResource(staging.get(), buf);
  MAPPED_SUBRESOURCE m;
  ctx.Map(staging.get(), 0, MAP_READ, 0, &m);
  std::vector<uint8_t> out(d.ByteWidth);
  std::memcpy(out.data(), m.pData, d.ByteWidth);
  ctx.Unmap(staging.get(), 0);
  return out;
}

Ref<Buffer> MakeBuffer(Device& dev, uint32_t bind, const void* data, uint32_t size, uint32_t misc, uint32_t stride) {
  BUFFER_DESC d;
  d.ByteWidth = size;
  d.BindFlags = bind;
  d.MiscFlags = misc;
  d.StructureByteStride = stride;
  SUBRESOURCE_DATA init{data, 0, 0};
  return dev.CreateBuffer(d, data ? &init : nullptr);
}

Ref<Texture2D> MakeTexture2D(Device& dev, uint32_t w, uint32_t h, FORMAT fmt, uint32_t bind, const void* data, uint32_t mips, uint32_t arraySize,
                             uint32_t samples, uint32_t misc) {
  TEXTURE2D_DESC d;
  d.Width = w;
  d.Height = h;
  d.MipLevels = mips;
  d.ArraySize = arraySize;
  d.Format = fmt;
  d.SampleDesc.Count = samples;
  d.BindFlags = bind;
  d.MiscFlags = misc;
  SUBRESOURCE_DATA init{data, w * GetFormatInfo(fmt).bytesPerElement, 0};
  return dev.CreateTexture2D(d, data ? &init : nullptr);
}

ShaderBytecode CompileInline(const std::string& source, const std::string& name, const std::string& target, const std::string& entry,
                             const std::vector<hlsl::Define>& defines) {
  hlsl::CompileOptions o;
  o.target = target;
  o.entryPoint = entry;
  o.defines = defines;
  const char* dir = std::getenv("SHADOWPORT_SHADER_DIR");
  o.includeDirs = {dir && *dir ? std::string(dir) : std::string(SHADOWPORT_SHADER_DIR)};
  return hlsl::CompileSource(source, name, o);
}

RectDrawer::RectDrawer(Device& dev) {
  const char* vs = R"(
cbuffer Rect : register(b13) { float4 rect; float2 size; float depth; float pad; };
float4 main(uint id : SV_VertexID) : SV_Position {
  float2 corner = float2((id == 1 || id == 2 || id == 4) ? 1 : 0, (id == 2 || id == 4 || id == 5) ? 1 : 0);
  float2 p = lerp(rect.xy, rect.zw, corner);
  return float4(p.x / size.x * 2 - 1, 1 - p.y / size.y * 2, depth, 1);
}
)";
  vs_ = dev.CreateVertexShader(CompileInline(vs, "gpu-util/rect.hlsl", "vs_5_0", "main"));
  constants_ = MakeBuffer(dev, BIND_CONSTANT_BUFFER, nullptr, 32);
}

void RectDrawer::Draw(DeviceContext& ctx, float x0, float y0, float x1, float y1, float w, float h, float depth) {
  const float c[8] = {x0, y0, x1, y1, w, h, depth, 0};
  ctx.UpdateSubresource(constants_.get(), 0, nullptr, c, 0, 0);
  ctx.VSSetShader(vs_.get());
  ctx.VSSetConstantBuffers(13, {constants_.get()});
  ctx.IASetInputLayout(nullptr);
  ctx.IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  ctx.Draw(6, 0);
}

}  // namespace sp::gpu
