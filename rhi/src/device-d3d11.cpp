// The D3D11-shaped overloads of Device: descs by pointer, objects through out-pointers, failures
// as an HRESULT plus the debug layer's message. Each one is the throwing call plus this wrapper.
#include <new>

#include "validate.h"

namespace sp {
namespace {

// Runs `create` (the throwing API) and reports the outcome the way D3D11 does.
template <class T, class Fn>
HRESULT Report(Device& dev, const OutPtr<T>& out, Fn&& create) {
  out.Set(nullptr);
  try {
    Ref<T> object = create();
    if (out.IsNull()) return S_FALSE;
    out.Set(std::move(object));
    return S_OK;
  } catch (const Error& e) {
    dev.Message(MessageSeverity::Error, e.what());
    return HResultFromErrorId(e.id());
  } catch (const std::bad_alloc&) {
    dev.Message(MessageSeverity::Error, "out of host memory");
    return E_OUTOFMEMORY;
  }
}

template <class D>
const D& Deref(const D* desc, const char* call) {
  if (!desc) Fail(ErrorId::INVALID_ARGUMENT, call, "null", "pDesc is null");
  return *desc;
}

void CheckLinkage(const ClassLinkage* linkage, const char* call) {
  if (linkage)
    Fail(ErrorId::NOT_SUPPORTED, call, "ClassLinkage", "D3D11 class linkage (dynamic shader linkage) is not supported: pass pClassLinkage = NULL");
}

void CheckBlob(const void* bytecode, size_t length, const char* call) {
  if (!bytecode || !length) Fail(ErrorId::INVALID_ARGUMENT, call, "bytecode", "pShaderBytecode is null or BytecodeLength is 0");
}

}  // namespace

HRESULT Device::CreateBuffer(const BUFFER_DESC* desc, const SUBRESOURCE_DATA* init, OutPtr<Buffer> out) {
  return Report(*this, out, [&] { return CreateBuffer(Deref(desc, "CreateBuffer"), init); });
}
HRESULT Device::CreateTexture1D(const TEXTURE1D_DESC* desc, const SUBRESOURCE_DATA* init, OutPtr<Texture1D> out) {
  return Report(*this, out, [&] { return CreateTexture1D(Deref(desc, "CreateTexture1D"), init); });
}
HRESULT Device::CreateTexture2D(const TEXTURE2D_DESC* desc, const SUBRESOURCE_DATA* init, OutPtr<Texture2D> out) {
  return Report(*this, out, [&] { return CreateTexture2D(Deref(desc, "CreateTexture2D"), init); });
}
HRESULT Device::CreateTexture3D(const TEXTURE3D_DESC* desc, const SUBRESOURCE_DATA* init, OutPtr<Texture3D> out) {
  return Report(*this, out, [&] { return CreateTexture3D(Deref(desc, "CreateTexture3D"), init); });
}

HRESULT Device::CreateShaderResourceView(Resource* r, const SHADER_RESOURCE_VIEW_DESC* desc, OutPtr<ShaderResourceView> out) {
  return Report(*this, out, [&] { return CreateShaderResourceView(r, desc); });
}
HRESULT Device::CreateRenderTargetView(Resource* r, const RENDER_TARGET_VIEW_DESC* desc, OutPtr<RenderTargetView> out) {
  return Report(*this, out, [&] { return CreateRenderTargetView(r, desc); });
}
HRESULT Device::CreateDepthStencilView(Resource* r, const DEPTH_STENCIL_VIEW_DESC* desc, OutPtr<DepthStencilView> out) {
  return Report(*this, out, [&] { return CreateDepthStencilView(r, desc); });
}
HRESULT Device::CreateUnorderedAccessView(Resource* r, const UNORDERED_ACCESS_VIEW_DESC* desc, OutPtr<UnorderedAccessView> out) {
  return Report(*this, out, [&] { return CreateUnorderedAccessView(r, desc); });
}

HRESULT Device::CreateSamplerState(const SAMPLER_DESC* desc, OutPtr<SamplerState> out) {
  return Report(*this, out, [&] { return CreateSamplerState(Deref(desc, "CreateSamplerState")); });
}
HRESULT Device::CreateRasterizerState(const RASTERIZER_DESC* desc, OutPtr<RasterizerState> out) {
  return Report(*this, out, [&] { return CreateRasterizerState(Deref(desc, "CreateRasterizerState")); });
}
HRESULT Device::CreateDepthStencilState(const DEPTH_STENCIL_DESC* desc, OutPtr<DepthStencilState> out) {
  return Report(*this, out, [&] { return CreateDepthStencilState(Deref(desc, "CreateDepthStencilState")); });
}
HRESULT Device::CreateBlendState(const BLEND_DESC* desc, OutPtr<BlendState> out) {
  return Report(*this, out, [&] { return CreateBlendState(Deref(desc, "CreateBlendState")); });
}

HRESULT Device::CreateInputLayout(const INPUT_ELEMENT_DESC* elements, uint32_t num, const void* vsBytecode, size_t length,
                                  OutPtr<InputLayout> out) {
  return Report(*this, out, [&] {
    CheckBlob(vsBytecode, length, "CreateInputLayout");
    return CreateInputLayout(elements, num, ShaderBytecode::Deserialize(vsBytecode, length));
  });
}

HRESULT Device::CreateVertexShader(const void* bytecode, size_t length, ClassLinkage* linkage, OutPtr<VertexShader> out) {
  return Report(*this, out, [&] {
    CheckLinkage(linkage, "CreateVertexShader");
    CheckBlob(bytecode, length, "CreateVertexShader");
    return CreateVertexShader(bytecode, length);
  });
}
HRESULT Device::CreatePixelShader(const void* bytecode, size_t length, ClassLinkage* linkage, OutPtr<PixelShader> out) {
  return Report(*this, out, [&] {
    CheckLinkage(linkage, "CreatePixelShader");
    CheckBlob(bytecode, length, "CreatePixelShader");
    return CreatePixelShader(bytecode, length);
  });
}
HRESULT Device::CreateGeometryShader(const void* bytecode, size_t length, ClassLinkage* linkage, OutPtr<GeometryShader> out) {
  return Report(*this, out, [&] {
    CheckLinkage(linkage, "CreateGeometryShader");
    CheckBlob(bytecode, length, "CreateGeometryShader");
    return CreateGeometryShader(ShaderBytecode::Deserialize(bytecode, length));
  });
}
HRESULT Device::CreateComputeShader(const void* bytecode, size_t length, ClassLinkage* linkage, OutPtr<ComputeShader> out) {
  return Report(*this, out, [&] {
    CheckLinkage(linkage, "CreateComputeShader");
    CheckBlob(bytecode, length, "CreateComputeShader");
    return CreateComputeShader(bytecode, length);
  });
}

HRESULT Device::CreateQuery(const QUERY_DESC* desc, OutPtr<Query> out) {
  return Report(*this, out, [&] { return CreateQuery(Deref(desc, "CreateQuery")); });
}

HRESULT Device::CheckFormatSupport(FORMAT format, uint32_t* support) const {
  if (!support) return E_INVALIDARG;
  *support = CheckFormatSupport(format);
  return *support ? S_OK : E_FAIL;
}

HRESULT Device::CheckMultisampleQualityLevels(FORMAT format, uint32_t sampleCount, uint32_t* levels) const {
  if (!levels) return E_INVALIDARG;
  *levels = CheckMultisampleQualityLevels(format, sampleCount);
  return S_OK;
}

}  // namespace sp
