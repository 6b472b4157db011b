// Zero-filled stand-ins for unbound registers, and their binding around one draw or dispatch.
#include "null-resources.h"

#include <algorithm>

#include <vector>

#include "context-internal.h"
#include "shader-bindings.h"
#include "validate.h"

namespace sp::detail {
namespace {

constexpr uint32_t kBufferBytes = 65536;  // what shaders may index in a null buffer and read zeros

const char* ComponentName(ComponentType t) {
  switch (t) {
    case ComponentType::UInt: return "uint";
    case ComponentType::SInt: return "int";
    default: return "float";
  }
}

// The HLSL declaration of a register, as the warning names it.
std::string HlslType(const ShaderResourceBinding& b) {
  switch (b.type) {
    case ShaderResourceType::Texture: return SrvDimensionName(b.dimension);
    case ShaderResourceType::TypedBuffer: return "Buffer";
    case ShaderResourceType::StructuredBuffer: return "StructuredBuffer";
    case ShaderResourceType::ByteAddressBuffer: return "ByteAddressBuffer";
    case ShaderResourceType::Sampler: return "SamplerState";
    case ShaderResourceType::ComparisonSampler: return "SamplerComparisonState";
    case ShaderResourceType::RWTexture: return std::string("RW") + SrvDimensionName(b.dimension);
    case ShaderResourceType::RWTypedBuffer: return "RWBuffer";
    case ShaderResourceType::RWStructuredBuffer: return b.appendConsume ? "Append/ConsumeStructuredBuffer" : "RWStructuredBuffer";
    case ShaderResourceType::RWByteAddressBuffer: return "RWByteAddressBuffer";
    case ShaderResourceType::UavCounter: return "RWStructuredBuffer (counter)";
    default: return "resource";
  }
}

// Formats whose zero texel reads (0, 0, 0, 0) in the shader's return type.
FORMAT ColorFormat(ComponentType t) {
  switch (t) {
    case ComponentType::UInt: return FORMAT_R32G32B32A32_UINT;
    case ComponentType::SInt: return FORMAT_R32G32B32A32_SINT;
    default: return FORMAT_R8G8B8A8_UNORM;
  }
}
FORMAT ScalarFormat(ComponentType t) {
  switch (t) {
    case ComponentType::UInt: return FORMAT_R32_UINT;
    case ComponentType::SInt: return FORMAT_R32_SINT;
    default: return FORMAT_R32_FLOAT;
  }
}

bool IsCube(SRV_DIMENSION d) { return d == SRV_DIMENSION_TEXTURECUBE || d == SRV_DIMENSION_TEXTURECUBEARRAY; }

const std::vector<uint8_t>& Zeros() {
  static const std::vector<uint8_t> zeros(kBufferBytes, 0);
  return zeros;
}

}  // namespace

bool NullResources::FirstReport(const Shader* shader, RegisterClass cls, uint32_t reg) {
  return reported_.insert({shader->UniqueId(), cls, reg}).second;
}

Buffer* NullResources::ConstantBuffer() {
  if (!constants_) {
    BUFFER_DESC d;
    d.ByteWidth = kBufferBytes;
    d.Usage = USAGE_IMMUTABLE;
    d.BindFlags = BIND_CONSTANT_BUFFER;
    SUBRESOURCE_DATA init{Zeros().data(), 0, 0};
    constants_ = dev_.CreateBuffer(d, &init);
    constants_->SetDebugName("null constant buffer (unbound b registers)");
  }
  return constants_.get();
}

SamplerState* NullResources::Sampler(bool comparison) {
  Ref<SamplerState>& s = samplers_[comparison ? 1 : 0];
  if (!s) {
    SAMPLER_DESC d;  // D3D11's default sampler state
    if (comparison) d.Filter = FILTER_COMPARISON_MIN_MAG_MIP_LINEAR;
    s = dev_.CreateSamplerState(d);
    s->SetDebugName(comparison ? "D3D11 default comparison sampler (unbound s registers)" : "D3D11 default sampler (unbound s registers)");
  }
  return s.get();
}

ShaderResourceView* NullResources::ShaderResource(const ShaderResourceBinding& b, bool compared) {
  bool texture = b.type == ShaderResourceType::Texture;
  std::string key = HlslType(b) + "<" + ComponentName(b.returnType) + ">";
  if (b.type == ShaderResourceType::StructuredBuffer) key += " stride " + std::to_string(b.structureStride);
  if (texture && compared) key += " compared";
  Ref<ShaderResourceView>& v = views_[key];
  if (!v) {
    std::string name = "null " + key + " (unbound t registers)";
    v = texture ? MakeTextureView(b, compared, name) : MakeBufferView(b, name);
  }
  return v.get();
}

Ref<ShaderResourceView> NullResources::MakeTextureView(const ShaderResourceBinding& b, bool compared, const std::string& name) {
  DeviceContext& ctx = *dev_.GetImmediateContext();
  const SRV_DIMENSION dim = b.dimension;
  const bool ms = dim == SRV_DIMENSION_TEXTURE2DMS || dim == SRV_DIMENSION_TEXTURE2DMSARRAY;
  const bool is1D = dim == SRV_DIMENSION_TEXTURE1D || dim == SRV_DIMENSION_TEXTURE1DARRAY;
  // Depth textures cannot be 1D, 3D or multisampled; HLSL compares only 2D, 2D array and cube ones.
  compared = compared && !ms && !is1D && dim != SRV_DIMENSION_TEXTURE3D;
  SHADER_RESOURCE_VIEW_DESC sd;
  sd.ViewDimension = dim;
  sd.TextureCubeArray = {0, uint32_t(-1), 0, 1};  // also MostDetailedMip/MipLevels for the other dimensions
  if (dim == SRV_DIMENSION_TEXTURE1DARRAY || dim == SRV_DIMENSION_TEXTURE2DARRAY) sd.Texture2DArray = {0, uint32_t(-1), 0, 1};
  if (dim == SRV_DIMENSION_TEXTURE2DMSARRAY) sd.Texture2DMSArray = {0, 1};
  const std::vector<uint8_t>& zeros = Zeros();
  const uint32_t slices = IsCube(dim) ? 6 : 1;
  std::vector<SUBRESOURCE_DATA> init(slices, SUBRESOURCE_DATA{zeros.data(), 16, 16});

  Ref<Resource> resource;
  if (is1D) {
    TEXTURE1D_DESC d;
    d.Width = 1;
    d.Format = sd.Format = ColorFormat(b.returnType);
    d.Usage = USAGE_IMMUTABLE;
    d.BindFlags = BIND_SHADER_RESOURCE;
    resource = dev_.CreateTexture1D(d, init.data());
  } else if (dim == SRV_DIMENSION_TEXTURE3D) {
    TEXTURE3D_DESC d;
    d.Width = d.Height = d.Depth = 1;
    d.Format = sd.Format = ColorFormat(b.returnType);
    d.Usage = USAGE_IMMUTABLE;
    d.BindFlags = BIND_SHADER_RESOURCE;
    resource = dev_.CreateTexture3D(d, init.data());
  } else {
    TEXTURE2D_DESC d;
    d.Width = d.Height = 1;
    d.ArraySize = slices;
    d.MiscFlags = IsCube(dim) ? uint32_t(RESOURCE_MISC_TEXTURECUBE) : 0u;
    if (compared) {
      // Cleared to depth 0: LESS-style comparisons against it fail, giving D3D11's zero.
      d.Format = FORMAT_R32_TYPELESS;
      d.BindFlags = BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE;
      sd.Format = FORMAT_R32_FLOAT;
      Ref<Texture2D> t = dev_.CreateTexture2D(d);
      DEPTH_STENCIL_VIEW_DESC dd;
      dd.Format = FORMAT_D32_FLOAT;
      dd.ViewDimension = DSV_DIMENSION_TEXTURE2DARRAY;
      dd.Texture2DArray = {0, 0, slices};
      ctx.ClearDepthStencilView(dev_.CreateDepthStencilView(t.get(), &dd).get(), CLEAR_DEPTH, 0.0f, 0);
      resource = t;
    } else if (ms) {
      // Multisampled textures cannot have initial data: cleared as a render target instead.
      const FORMAT candidates[] = {ColorFormat(b.returnType), ScalarFormat(b.returnType)};
      for (FORMAT f : candidates) {
        if (!(dev_.CheckFormatSupport(f) & FORMAT_SUPPORT_MULTISAMPLE_LOAD)) continue;
        for (uint32_t n = 2; n <= 32; n *= 2)
          if (dev_.CheckMultisampleQualityLevels(f, n)) {
            d.Format = sd.Format = f;
            d.SampleDesc.Count = n;
            break;
          }
        if (d.SampleDesc.Count > 1) break;
      }
      if (d.SampleDesc.Count < 2)
        Fail(ErrorId::NOT_SUPPORTED, "Draw", name, "the device has no multisampled format to stand in for an unbound Texture2DMS");
      d.BindFlags = BIND_RENDER_TARGET | BIND_SHADER_RESOURCE;
      Ref<Texture2D> t = dev_.CreateTexture2D(d);
      const float black[4] = {0, 0, 0, 0};
      ctx.ClearRenderTargetView(dev_.CreateRenderTargetView(t.get()).get(), black);
      resource = t;
    } else {
      d.Format = sd.Format = ColorFormat(b.returnType);
      d.Usage = USAGE_IMMUTABLE;
      d.BindFlags = BIND_SHADER_RESOURCE;
      resource = dev_.CreateTexture2D(d, init.data());
    }
  }
  resource->SetDebugName(name);
  Ref<ShaderResourceView> v = dev_.CreateShaderResourceView(resource.get(), &sd);
  v->SetDebugName(name);
  return v;
}

Ref<ShaderResourceView> NullResources::MakeBufferView(const ShaderResourceBinding& b, const std::string& name) {
  BUFFER_DESC d;
  d.Usage = USAGE_IMMUTABLE;
  d.BindFlags = BIND_SHADER_RESOURCE;
  SHADER_RESOURCE_VIEW_DESC sd;
  sd.ViewDimension = SRV_DIMENSION_BUFFER;
  uint32_t stride = 16;
  if (b.type == ShaderResourceType::StructuredBuffer) {
    stride = b.structureStride ? b.structureStride : 4;
    d.MiscFlags = RESOURCE_MISC_BUFFER_STRUCTURED;
    d.StructureByteStride = stride;
  } else if (b.type == ShaderResourceType::ByteAddressBuffer) {
    stride = 4;
    d.MiscFlags = RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS;
    sd.Format = FORMAT_R32_TYPELESS;
    sd.ViewDimension = SRV_DIMENSION_BUFFEREX;
  } else {
    sd.Format = ColorFormat(b.returnType) == FORMAT_R8G8B8A8_UNORM ? FORMAT_R32G32B32A32_FLOAT : ColorFormat(b.returnType);
  }
  uint32_t elements = kBufferBytes / stride ? kBufferBytes / stride : 1;
  d.ByteWidth = elements * stride;
  std::vector<uint8_t> zeros(d.ByteWidth, 0);
  SUBRESOURCE_DATA init{zeros.data(), 0, 0};
  Ref<Buffer> buf = dev_.CreateBuffer(d, &init);
  buf->SetDebugName(name);
  if (sd.ViewDimension == SRV_DIMENSION_BUFFEREX) sd.BufferEx = {0, elements, BUFFEREX_SRV_FLAG_RAW};
  else sd.Buffer = {0, elements};
  Ref<ShaderResourceView> v = dev_.CreateShaderResourceView(buf.get(), &sd);
  v->SetDebugName(name);
  return v;
}

UnorderedAccessView* NullResources::UnorderedAccess(const ShaderResourceBinding& b, bool pixelStage, uint32_t slot, bool counter) {
  std::string key = std::string(pixelStage ? "PS" : "CS") + " u" + std::to_string(slot) + " " + HlslType(b) + "<" +
                    ComponentName(b.returnType) + ">";
  if (b.type == ShaderResourceType::RWStructuredBuffer) key += " stride " + std::to_string(b.structureStride);
  if (counter) key += " with counter";
  Ref<UnorderedAccessView>& v = uavs_[key];
  if (!v) v = MakeUav(b, counter, "null " + key + " (unbound u register)");
  return v.get();
}

Ref<UnorderedAccessView> NullResources::MakeUav(const ShaderResourceBinding& b, bool counter, const std::string& name) {
  UNORDERED_ACCESS_VIEW_DESC ud;
  Ref<Resource> resource;
  if (b.type == ShaderResourceType::RWTexture) {
    // Typed UAV loads of D3D11.0 read R32 formats only (the toolchain declares read images so).
    ud.Format = ScalarFormat(b.returnType);
    ud.ViewDimension = UAV_DIMENSION(b.dimension);
    ud.Texture2DArray = {0, 0, 1};  // also MipSlice (and WSize 1) for the other dimensions
    if (b.dimension == SRV_DIMENSION_TEXTURE1D || b.dimension == SRV_DIMENSION_TEXTURE1DARRAY) {
      TEXTURE1D_DESC d;
      d.Width = 1;
      d.Format = ud.Format;
      d.BindFlags = BIND_UNORDERED_ACCESS;
      resource = dev_.CreateTexture1D(d);
    } else if (b.dimension == SRV_DIMENSION_TEXTURE3D) {
      TEXTURE3D_DESC d;
      d.Width = d.Height = d.Depth = 1;
      d.Format = ud.Format;
      d.BindFlags = BIND_UNORDERED_ACCESS;
      resource = dev_.CreateTexture3D(d);
    } else {
      TEXTURE2D_DESC d;
      d.Width = d.Height = 1;
      d.Format = ud.Format;
      d.BindFlags = BIND_UNORDERED_ACCESS;
      resource = dev_.CreateTexture2D(d);
    }
  } else {
    BUFFER_DESC d;
    d.BindFlags = BIND_UNORDERED_ACCESS;
    ud.ViewDimension = UAV_DIMENSION_BUFFER;
    uint32_t stride = 4;
    if (b.type == ShaderResourceType::RWStructuredBuffer || b.type == ShaderResourceType::UavCounter) {
      stride = b.type == ShaderResourceType::RWStructuredBuffer && b.structureStride ? b.structureStride : 4;
      d.MiscFlags = RESOURCE_MISC_BUFFER_STRUCTURED;
      d.StructureByteStride = stride;
      if (counter) ud.Buffer.Flags = b.appendConsume ? BUFFER_UAV_FLAG_APPEND : BUFFER_UAV_FLAG_COUNTER;
    } else if (b.type == ShaderResourceType::RWByteAddressBuffer) {
      d.MiscFlags = RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS;
      ud.Format = FORMAT_R32_TYPELESS;
      ud.Buffer.Flags = BUFFER_UAV_FLAG_RAW;
    } else {
      ud.Format = ScalarFormat(b.returnType);
    }
    uint32_t elements = kBufferBytes / stride ? kBufferBytes / stride : 1;
    d.ByteWidth = elements * stride;
    ud.Buffer.FirstElement = 0;
    ud.Buffer.NumElements = elements;
    resource = dev_.CreateBuffer(d);
  }
  resource->SetDebugName(name);
  Ref<UnorderedAccessView> v = dev_.CreateUnorderedAccessView(resource.get(), &ud);
  v->SetDebugName(name);
  return v;
}

NullResources& DeviceAccess::Nulls(Device& d) {
  if (!d.nullResources_) d.nullResources_ = std::make_unique<NullResources>(d);
  return *d.nullResources_;
}

// ---------------------------------------------------------------------------------------------

namespace {

// The call that would have bound the register, for the warning: D3D11's debug layer names it.
std::string SetCall(ShaderStage stage, RegisterClass cls) {
  std::string p = ShaderStagePrefix(stage);
  switch (cls) {
    case RegisterClass::ConstantBuffer: return p + "SetConstantBuffers";
    case RegisterClass::ShaderResource: return p + "SetShaderResources";
    case RegisterClass::Sampler: return p + "SetSamplers";
    default: return stage == ShaderStage::Compute ? "CSSetUnorderedAccessViews" : "OMSetRenderTargetsAndUnorderedAccessViews";
  }
}

bool UsesCounter(const Shader& s, uint32_t reg) {
  for (const ShaderResourceBinding& r : s.Reflection().resources)
    if (r.registerClass == RegisterClass::UnorderedAccess && r.registerIndex == reg &&
        (r.type == ShaderResourceType::UavCounter || r.appendConsume))
      return true;
  return false;
}

}  // namespace

NullBindings::NullBindings(DeviceContext& ctx, const std::vector<UnboundRead>& unbound)
    : state_(*ctx.state_) {
  if (unbound.empty()) return;
  Device& dev = *ctx.GetDevice();
  NullResources& nulls = DeviceAccess::Nulls(dev);
  for (const UnboundRead& u : unbound) {
    StageBindings& sb = state_.stage(u.stage);
    const uint32_t reg = u.registerIndex;
    std::string declared, effect = "is read but nothing is bound; it reads zeros as in D3D11";
    switch (u.registerClass) {
      case RegisterClass::ConstantBuffer:
        sb.constantBuffers[reg] = RefOf(nulls.ConstantBuffer());
        buffers_.push_back(&sb.constantBuffers[reg]);
        declared = "cbuffer '" + u.cbuffer->name + "'";
        break;
      case RegisterClass::ShaderResource:
        sb.shaderResources[reg] = RefOf(nulls.ShaderResource(*u.binding, TextureIsCompared(u.shader->Bytecode(), reg)));
        sb.shaderResourceEnd = std::max(sb.shaderResourceEnd, reg + 1);
        views_.push_back(&sb.shaderResources[reg]);
        break;
      case RegisterClass::Sampler:
        sb.samplers[reg] = RefOf(nulls.Sampler(u.binding->type == ShaderResourceType::ComparisonSampler));
        samplers_.push_back(&sb.samplers[reg]);
        effect = "is used but nothing is bound; D3D11's default sampler state applies";
        break;
      case RegisterClass::UnorderedAccess: {
        bool counter = UsesCounter(*u.shader, reg);
        UnorderedAccessView* v = nulls.UnorderedAccess(*u.binding, u.stage == ShaderStage::Pixel, reg, counter);
        // Writes of earlier draws must not show through: D3D11 reads zeros every time.
        const uint32_t zeros[4] = {0, 0, 0, 0};
        ctx.ClearUnorderedAccessViewUint(v, zeros);
        if (counter) ctx.backend_->SetUavCounter(v, 0);
        Ref<UnorderedAccessView>& slot = state_.uavs(u.stage)[reg];
        slot = RefOf(v);
        uavs_.push_back(&slot);
        dirty_ |= u.stage == ShaderStage::Compute ? DIRTY_COMPUTE_UAVS : DIRTY_PIXEL_UAVS;
        effect = "is used but nothing is bound; it reads zeros and its writes are dropped as in D3D11";
        break;
      }
    }
    dirty_ |= DIRTY_BINDINGS_VS << uint32_t(u.stage);
    if (!nulls.FirstReport(u.shader, u.registerClass, reg)) continue;
    if (u.binding) declared = HlslType(*u.binding) + " '" + u.binding->name + "'";
    const std::string& source = u.shader->Bytecode().sourceName;
    dev.Message(MessageSeverity::Warning, SetCall(u.stage, u.registerClass) + ": " +
                                              SlotName(u.stage, RegisterClassLetter(u.registerClass), reg) + " (" + declared + " in " +
                                              (source.empty() ? Describe(u.shader) : source) + ") " + effect);
  }
}

NullBindings::~NullBindings() {
  for (Ref<Buffer>* p : buffers_) p->reset();
  for (Ref<ShaderResourceView>* p : views_) p->reset();
  for (Ref<SamplerState>* p : samplers_) p->reset();
  for (Ref<UnorderedAccessView>* p : uavs_) p->reset();
}

}  // namespace sp::detail
