// Resources every technique makes the same way (technique.h).
#include <sp/tech/technique.h>

namespace sp::tech {

DepthMap MakeDepthMap(Device& device, uint32_t width, uint32_t height, const char* name) {
  DepthMap m;
  TEXTURE2D_DESC td;
  td.Width = width;
  td.Height = height;
  td.Format = FORMAT_R32_TYPELESS;
  td.BindFlags = BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE;
  m.texture = device.CreateTexture2D(td);
  m.texture->SetDebugName(name);
  DEPTH_STENCIL_VIEW_DESC dd;
  dd.Format = FORMAT_D32_FLOAT;
  dd.ViewDimension = DSV_DIMENSION_TEXTURE2D;
  m.dsv = device.CreateDepthStencilView(m.texture.get(), &dd);
  SHADER_RESOURCE_VIEW_DESC sd;
  sd.Format = FORMAT_R32_FLOAT;
  sd.ViewDimension = SRV_DIMENSION_TEXTURE2D;
  sd.Texture2D = {0, 1};
  m.srv = device.CreateShaderResourceView(m.texture.get(), &sd);
  return m;
}

std::vector<Ref<DepthStencilView>> MakeSliceDepthViews(Device& device, Texture2D* texture) {
  const TEXTURE2D_DESC& td = texture->GetDesc();
  std::vector<Ref<DepthStencilView>> views;
  for (uint32_t s = 0; s < td.ArraySize; ++s) {
    DEPTH_STENCIL_VIEW_DESC dd;
    dd.Format = FORMAT_D32_FLOAT;
    if (td.SampleDesc.Count > 1) {
      dd.ViewDimension = DSV_DIMENSION_TEXTURE2DMSARRAY;
      dd.Texture2DMSArray = {s, 1};
    } else {
      dd.ViewDimension = DSV_DIMENSION_TEXTURE2DARRAY;
      dd.Texture2DArray = {0, s, 1};
    }
    views.push_back(device.CreateDepthStencilView(texture, &dd));
  }
  return views;
}

Ref<ShaderResourceView> MakeSliceArraySrv(Device& device, Texture2D* texture) {
  SHADER_RESOURCE_VIEW_DESC sd;
  sd.Format = FORMAT_R32_FLOAT;
  sd.ViewDimension = SRV_DIMENSION_TEXTURE2DARRAY;
  sd.Texture2DArray = {0, 1, 0, texture->GetDesc().ArraySize};
  return device.CreateShaderResourceView(texture, &sd);
}

Ref<SamplerState> MakeShadowComparisonSampler(Device& device) {
  SAMPLER_DESC smp;
  smp.Filter = FILTER_COMPARISON_MIN_MAG_LINEAR_MIP_POINT;
  smp.AddressU = smp.AddressV = smp.AddressW = TEXTURE_ADDRESS_BORDER;
  smp.ComparisonFunc = COMPARISON_LESS_EQUAL;
  for (float& c : smp.BorderColor) c = 1.0f;
  return device.CreateSamplerState(smp);
}

namespace {
Ref<Buffer> NamedBuffer(Device& device, uint32_t bytes, USAGE usage, uint32_t bindFlags, const char* name) {
  BUFFER_DESC d;
  d.ByteWidth = bytes;
  d.Usage = usage;
  d.BindFlags = bindFlags;
  d.CPUAccessFlags = usage == USAGE_DYNAMIC ? uint32_t(CPU_ACCESS_WRITE) : 0u;
  Ref<Buffer> b = device.CreateBuffer(d);
  b->SetDebugName(name);
  return b;
}
}  // namespace

Ref<Buffer> MakeConstantBuffer(Device& device, uint32_t bytes, const char* name) {
  return NamedBuffer(device, bytes, USAGE_DEFAULT, BIND_CONSTANT_BUFFER, name);
}

Ref<Buffer> MakeDynamicBuffer(Device& device, uint32_t bytes, uint32_t bindFlags, const char* name) {
  return NamedBuffer(device, bytes, USAGE_DYNAMIC, bindFlags, name);
}

Ref<Buffer> MakeRawBuffer(Device& device, uint32_t bytes, uint32_t bindFlags, const char* name, uint32_t extraMiscFlags) {
  BUFFER_DESC d;
  d.ByteWidth = bytes;
  d.BindFlags = bindFlags;
  d.MiscFlags = RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS | extraMiscFlags;
  Ref<Buffer> b = device.CreateBuffer(d);
  b->SetDebugName(name);
  return b;
}

Ref<UnorderedAccessView> MakeRawUav(Device& device, Buffer* buffer) {
  UNORDERED_ACCESS_VIEW_DESC d;
  d.Format = FORMAT_R32_TYPELESS;
  d.ViewDimension = UAV_DIMENSION_BUFFER;
  d.Buffer = {0, buffer->GetDesc().ByteWidth / 4, BUFFER_UAV_FLAG_RAW};
  return device.CreateUnorderedAccessView(buffer, &d);
}

Ref<ShaderResourceView> MakeRawSrv(Device& device, Buffer* buffer) {
  SHADER_RESOURCE_VIEW_DESC d;
  d.Format = FORMAT_R32_TYPELESS;
  d.ViewDimension = SRV_DIMENSION_BUFFEREX;
  d.BufferEx = {0, buffer->GetDesc().ByteWidth / 4, BUFFEREX_SRV_FLAG_RAW};
  return device.CreateShaderResourceView(buffer, &d);
}

}  // namespace sp::tech
