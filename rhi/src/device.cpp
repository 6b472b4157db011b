// Device: object creation with D3D11's validation rules for buffers, textures, states and queries.
// Views are in device-views.cpp, shaders and input layouts in device-shaders.cpp.
#include <sp/rhi/context.h>

#include <cmath>
#include <cstdio>

#include "backend.h"
#include "null-resources.h"
#include "validate.h"

namespace sp {

const char* BackendName(Backend b) {
  switch (b) {
    case Backend::Vulkan: return "vulkan";
    case Backend::OpenGL: return "gl";
    case Backend::Null: return "null";
  }
  return "unknown";
}

bool ParseBackend(std::string_view s, Backend* out) {
  if (s == "vulkan" || s == "vk") {
    *out = Backend::Vulkan;
    return true;
  }
  if (s == "gl" || s == "opengl") {
    *out = Backend::OpenGL;
    return true;
  }
  if (s == "null") {
    *out = Backend::Null;
    return true;
  }
  return false;
}

std::string BindFlagsToString(uint32_t flags) {
  static const std::pair<uint32_t, const char*> names[] = {
      {BIND_VERTEX_BUFFER, "VERTEX_BUFFER"},     {BIND_INDEX_BUFFER, "INDEX_BUFFER"},
      {BIND_CONSTANT_BUFFER, "CONSTANT_BUFFER"}, {BIND_SHADER_RESOURCE, "SHADER_RESOURCE"},
      {BIND_STREAM_OUTPUT, "STREAM_OUTPUT"},     {BIND_RENDER_TARGET, "RENDER_TARGET"},
      {BIND_DEPTH_STENCIL, "DEPTH_STENCIL"},     {BIND_UNORDERED_ACCESS, "UNORDERED_ACCESS"}};
  std::string s;
  for (auto& [bit, name] : names) {
    if (flags & bit) s += (s.empty() ? "BIND_" : " | BIND_") + std::string(name);
  }
  return s.empty() ? "0" : s;
}

std::string UsageName(USAGE usage) {
  switch (usage) {
    case USAGE_DEFAULT: return "USAGE_DEFAULT";
    case USAGE_IMMUTABLE: return "USAGE_IMMUTABLE";
    case USAGE_DYNAMIC: return "USAGE_DYNAMIC";
    case USAGE_STAGING: return "USAGE_STAGING";
  }
  return "USAGE(" + std::to_string(uint32_t(usage)) + ")";
}

Device::Device(const DeviceDesc& desc)
    : strictUnboundResources_(desc.strictUnboundResources), x11Display_(desc.x11Display), shaderCacheDir_(desc.shaderCacheDir), callback_(desc.messageCallback) {
  info_.backend = desc.backend;
  info_.validationEnabled = desc.debug;
}

void Device::GetImmediateContext(DeviceContext** context) {
  if (!context) throw Error(ErrorId::INVALID_ARGUMENT, "GetImmediateContext", "Device", "ppImmediateContext is null");
  *context = context_.get();
  context_->AddRef();
}

Device::~Device() {
  ReleaseBackendData();
  backend_.reset();
}

void Device::ReleaseBackendData() {
  // The context first: it holds bindings and the backend's per-context caches.
  if (context_) {
    context_->ClearState();
    context_.reset();
  }
  nullResources_.reset();
  std::lock_guard lock(liveMutex_);
  if (!live_.empty() && backend_) {
    Message(MessageSeverity::Warning, std::to_string(live_.size()) +
                                          " object(s) outlived their device; their GPU memory is released now "
                                          "and using them is an error");
  }
  for (Object* o : live_) {
    o->backend_.reset();
    o->device_ = nullptr;
  }
  live_.clear();
}

void Device::Message(MessageSeverity severity, std::string_view text) {
  if (severity == MessageSeverity::Error) {
    ++validationErrors_;
    lastValidationError_ = std::string(text);
  }
  if (callback_) {
    callback_(severity, text);
  } else if (severity != MessageSeverity::Info) {
    std::fprintf(stderr, "shadowport %s %s: %.*s\n", BackendName(info_.backend),
                 severity == MessageSeverity::Error ? "error" : "warning", int(text.size()), text.data());
  }
}

std::string Device::LastValidationError() const { return lastValidationError_; }

// ---------------------------------------------------------------------------------------------
// Buffers

static void ValidateUsage(const char* call, const std::string& obj, USAGE usage, uint32_t bind, uint32_t cpu,
                          bool hasInit, bool isBuffer) {
  if (cpu & ~uint32_t(CPU_ACCESS_READ | CPU_ACCESS_WRITE))
    Fail(ErrorId::INVALID_DESC, call, obj, "CPUAccessFlags has unknown bits");
  switch (usage) {
    case USAGE_DEFAULT:
      if (cpu) Fail(ErrorId::USAGE_INVALID, call, obj, "USAGE_DEFAULT resources cannot have CPUAccessFlags; use USAGE_DYNAMIC (write) or USAGE_STAGING (read)");
      break;
    case USAGE_IMMUTABLE:
      if (cpu) Fail(ErrorId::USAGE_INVALID, call, obj, "USAGE_IMMUTABLE resources cannot have CPUAccessFlags");
      if (!hasInit) Fail(ErrorId::INITIAL_DATA_INVALID, call, obj, "USAGE_IMMUTABLE requires initial data");
      if (bind & (BIND_UNORDERED_ACCESS | BIND_RENDER_TARGET | BIND_DEPTH_STENCIL | BIND_STREAM_OUTPUT))
        Fail(ErrorId::USAGE_INVALID, call, obj, "USAGE_IMMUTABLE resources cannot be bound for output (" + BindFlagsToString(bind) + ")");
      break;
    case USAGE_DYNAMIC:
      if (cpu != CPU_ACCESS_WRITE) Fail(ErrorId::USAGE_INVALID, call, obj, "USAGE_DYNAMIC requires CPUAccessFlags = CPU_ACCESS_WRITE");
      if (bind & (BIND_UNORDERED_ACCESS | BIND_RENDER_TARGET | BIND_DEPTH_STENCIL | BIND_STREAM_OUTPUT))
        Fail(ErrorId::USAGE_INVALID, call, obj, "USAGE_DYNAMIC resources cannot be bound for output (" + BindFlagsToString(bind) + ")");
      if (!isBuffer && !(bind & BIND_SHADER_RESOURCE))
        Fail(ErrorId::USAGE_INVALID, call, obj, "a USAGE_DYNAMIC texture must be BIND_SHADER_RESOURCE");
      break;
    case USAGE_STAGING:
      if (bind) Fail(ErrorId::USAGE_INVALID, call, obj, "USAGE_STAGING resources cannot have BindFlags (got " + BindFlagsToString(bind) + ")");
      if (!cpu) Fail(ErrorId::USAGE_INVALID, call, obj, "USAGE_STAGING requires CPU_ACCESS_READ and/or CPU_ACCESS_WRITE");
      break;
    default:
      Fail(ErrorId::INVALID_DESC, call, obj, "unknown Usage " + std::to_string(uint32_t(usage)));
  }
}

Ref<Buffer> Device::CreateBuffer(const BUFFER_DESC& d, const SUBRESOURCE_DATA* init) {
  const char* call = "CreateBuffer";
  std::string obj = "Buffer, " + std::to_string(d.ByteWidth) + " bytes, " + BindFlagsToString(d.BindFlags);
  if (d.ByteWidth == 0) Fail(ErrorId::SIZE_OUT_OF_RANGE, call, obj, "ByteWidth must be greater than 0");
  if (d.ByteWidth > REQ_RESOURCE_SIZE_BYTES) Fail(ErrorId::SIZE_OUT_OF_RANGE, call, obj, "ByteWidth exceeds 2 GiB");
  if (d.BindFlags & ~0xffu) Fail(ErrorId::INVALID_DESC, call, obj, "BindFlags has unknown bits");
  if (d.BindFlags & (BIND_RENDER_TARGET | BIND_DEPTH_STENCIL))
    Fail(ErrorId::BIND_FLAGS_INVALID, call, obj, "buffers cannot be bound as render target or depth-stencil");
  if (d.BindFlags & BIND_STREAM_OUTPUT) Fail(ErrorId::NOT_SUPPORTED, call, obj, "stream output is not supported");
  if (d.MiscFlags & ~uint32_t(RESOURCE_MISC_DRAWINDIRECT_ARGS | RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS | RESOURCE_MISC_BUFFER_STRUCTURED))
    Fail(ErrorId::INVALID_DESC, call, obj, "MiscFlags has flags that do not apply to buffers");
  if (d.BindFlags & BIND_CONSTANT_BUFFER) {
    if (d.BindFlags != BIND_CONSTANT_BUFFER)
      Fail(ErrorId::BIND_FLAGS_INVALID, call, obj, "BIND_CONSTANT_BUFFER cannot be combined with other bind flags");
    if (d.ByteWidth % 16) Fail(ErrorId::SIZE_OUT_OF_RANGE, call, obj, "a constant buffer's ByteWidth must be a multiple of 16");
    if (d.ByteWidth > 65536) Fail(ErrorId::SIZE_OUT_OF_RANGE, call, obj, "a constant buffer holds at most 4096 float4 (65536 bytes)");
    if (d.MiscFlags) Fail(ErrorId::INVALID_DESC, call, obj, "constant buffers cannot have MiscFlags");
  }
  if (d.MiscFlags & RESOURCE_MISC_BUFFER_STRUCTURED) {
    if (d.StructureByteStride == 0 || d.StructureByteStride % 4 || d.StructureByteStride > 2048)
      Fail(ErrorId::INVALID_DESC, call, obj, "StructureByteStride must be a multiple of 4 in [4, 2048] for RESOURCE_MISC_BUFFER_STRUCTURED");
    if (d.ByteWidth % d.StructureByteStride)
      Fail(ErrorId::SIZE_OUT_OF_RANGE, call, obj, "ByteWidth must be a multiple of StructureByteStride");
    if (d.BindFlags & (BIND_VERTEX_BUFFER | BIND_INDEX_BUFFER))
      Fail(ErrorId::BIND_FLAGS_INVALID, call, obj, "structured buffers cannot be vertex or index buffers");
    if (d.MiscFlags & (RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS | RESOURCE_MISC_DRAWINDIRECT_ARGS))
      Fail(ErrorId::INVALID_DESC, call, obj, "structured buffers cannot allow raw views or hold indirect arguments");
  }
  if ((d.MiscFlags & RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS) && d.ByteWidth % 4)
    Fail(ErrorId::SIZE_OUT_OF_RANGE, call, obj, "raw buffers need ByteWidth a multiple of 4");
  ValidateUsage(call, obj, d.Usage, d.BindFlags, d.CPUAccessFlags, init != nullptr, true);
  if (init && !init->pSysMem) Fail(ErrorId::INITIAL_DATA_INVALID, call, obj, "pInitialData->pSysMem is null");

  Ref<Buffer> b = Make<Buffer>(d);
  b->backend_ = backend_->CreateBufferBackend(*b, init);
  return b;
}

// ---------------------------------------------------------------------------------------------
// Textures

Ref<Texture1D> Device::CreateTexture1D(const TEXTURE1D_DESC& desc, const SUBRESOURCE_DATA* init) {
  TextureShape s = ShapeFromDesc(desc);
  const char* call = "CreateTexture1D";
  std::string obj = "Texture1D " + std::to_string(desc.Width) + " " + std::string(FormatName(desc.Format));
  if (desc.Width == 0 || desc.Width > REQ_TEXTURE1D_U_DIMENSION)
    Fail(ErrorId::SIZE_OUT_OF_RANGE, call, obj, "Width must be in [1, 16384]");
  if (desc.ArraySize == 0 || desc.ArraySize > REQ_TEXTURE2D_ARRAY_AXIS_DIMENSION)
    Fail(ErrorId::SIZE_OUT_OF_RANGE, call, obj, "ArraySize must be in [1, 2048]");
  if (desc.BindFlags & BIND_DEPTH_STENCIL) Fail(ErrorId::NOT_SUPPORTED, call, obj, "1D depth-stencil textures are not supported");
  if (desc.MiscFlags & RESOURCE_MISC_TEXTURECUBE) Fail(ErrorId::INVALID_DESC, call, obj, "RESOURCE_MISC_TEXTURECUBE needs a Texture2D");
  ValidateTextureShape(s, call, obj, init);
  Ref<Texture1D> t = Make<Texture1D>(s);
  t->backend_ = backend_->CreateTextureBackend(*t, init);
  return t;
}

Ref<Texture2D> Device::CreateTexture2D(const TEXTURE2D_DESC& desc, const SUBRESOURCE_DATA* init) {
  TextureShape s = ShapeFromDesc(desc);
  const char* call = "CreateTexture2D";
  std::string obj = "Texture2D " + std::to_string(desc.Width) + "x" + std::to_string(desc.Height) + " " +
                    std::string(FormatName(desc.Format));
  if (desc.Width == 0 || desc.Height == 0 || desc.Width > REQ_TEXTURE2D_U_OR_V_DIMENSION ||
      desc.Height > REQ_TEXTURE2D_U_OR_V_DIMENSION)
    Fail(ErrorId::SIZE_OUT_OF_RANGE, call, obj, "Width and Height must be in [1, 16384]");
  if (desc.ArraySize == 0 || desc.ArraySize > REQ_TEXTURE2D_ARRAY_AXIS_DIMENSION)
    Fail(ErrorId::SIZE_OUT_OF_RANGE, call, obj, "ArraySize must be in [1, 2048]");
  if (desc.MiscFlags & RESOURCE_MISC_TEXTURECUBE) {
    if (desc.Width != desc.Height) Fail(ErrorId::INVALID_DESC, call, obj, "cube maps must be square");
    if (desc.ArraySize % 6) Fail(ErrorId::INVALID_DESC, call, obj, "a cube map's ArraySize must be a multiple of 6");
    if (desc.SampleDesc.Count > 1) Fail(ErrorId::INVALID_DESC, call, obj, "cube maps cannot be multisampled");
  }
  uint32_t samples = desc.SampleDesc.Count;
  if (samples == 0 || (samples & (samples - 1)) || samples > 32)
    Fail(ErrorId::INVALID_DESC, call, obj, "SampleDesc.Count must be 1, 2, 4, 8, 16 or 32");
  if (samples > 1) {
    if (desc.MipLevels != 1) Fail(ErrorId::INVALID_DESC, call, obj, "multisampled textures must have MipLevels = 1");
    if (desc.BindFlags & BIND_UNORDERED_ACCESS)
      Fail(ErrorId::BIND_FLAGS_INVALID, call, obj, "multisampled textures cannot be BIND_UNORDERED_ACCESS");
    if (desc.Usage != USAGE_DEFAULT) Fail(ErrorId::USAGE_INVALID, call, obj, "multisampled textures must be USAGE_DEFAULT");
    if (desc.SampleDesc.Quality != 0) Fail(ErrorId::INVALID_DESC, call, obj, "SampleDesc.Quality must be 0 (standard pattern)");
    if (init) Fail(ErrorId::INITIAL_DATA_INVALID, call, obj, "multisampled textures cannot have initial data");
    if (!backend_->SampleCountSupportedBackend(desc.Format, samples))
      Fail(ErrorId::FORMAT_UNSUPPORTED, call, obj,
           std::to_string(samples) + "x MSAA is not supported for this format on this device (max " +
               std::to_string(backend_->MaxSampleCountBackend(desc.Format)) + "x; check CheckMultisampleQualityLevels)");
  }
  ValidateTextureShape(s, call, obj, init);
  Ref<Texture2D> t = Make<Texture2D>(s);
  t->backend_ = backend_->CreateTextureBackend(*t, init);
  return t;
}

Ref<Texture3D> Device::CreateTexture3D(const TEXTURE3D_DESC& desc, const SUBRESOURCE_DATA* init) {
  TextureShape s = ShapeFromDesc(desc);
  const char* call = "CreateTexture3D";
  std::string obj = "Texture3D " + std::to_string(desc.Width) + "x" + std::to_string(desc.Height) + "x" +
                    std::to_string(desc.Depth) + " " + std::string(FormatName(desc.Format));
  if (desc.Width == 0 || desc.Height == 0 || desc.Depth == 0 || desc.Width > REQ_TEXTURE3D_U_V_OR_W_DIMENSION ||
      desc.Height > REQ_TEXTURE3D_U_V_OR_W_DIMENSION || desc.Depth > REQ_TEXTURE3D_U_V_OR_W_DIMENSION)
    Fail(ErrorId::SIZE_OUT_OF_RANGE, call, obj, "Width, Height and Depth must be in [1, 2048]");
  if (desc.BindFlags & BIND_DEPTH_STENCIL) Fail(ErrorId::BIND_FLAGS_INVALID, call, obj, "3D textures cannot be depth-stencil");
  if (desc.MiscFlags & RESOURCE_MISC_TEXTURECUBE) Fail(ErrorId::INVALID_DESC, call, obj, "RESOURCE_MISC_TEXTURECUBE needs a Texture2D");
  ValidateTextureShape(s, call, obj, init);
  Ref<Texture3D> t = Make<Texture3D>(s);
  t->backend_ = backend_->CreateTextureBackend(*t, init);
  return t;
}

void Device::ValidateTextureShape(TextureShape& s, const char* call, const std::string& obj, const SUBRESOURCE_DATA* init) const {
  const FormatInfo& fi = GetFormatInfo(s.format);
  if (fi.format == FORMAT_UNKNOWN) Fail(ErrorId::FORMAT_UNSUPPORTED, call, obj, "unknown or unsupported Format");
  if (fi.bytesPerElement == 12) Fail(ErrorId::FORMAT_UNSUPPORTED, call, obj, "R32G32B32 formats are only supported for buffers");
  // R24_UNORM_X8_TYPELESS & co. exist only as views of a depth-stencil family; R32_FLOAT and
  // R16_UNORM also read depth but are ordinary colour formats.
  if ((fi.readsDepth || fi.readsStencil) && fi.stencilBits)
    Fail(ErrorId::FORMAT_UNSUPPORTED, call, obj, std::string(fi.name) + " is a view format; create the texture as " +
                                                    std::string(FormatName(fi.typelessFamily)));
  if (s.bindFlags & ~0xffu) Fail(ErrorId::INVALID_DESC, call, obj, "BindFlags has unknown bits");
  if (s.bindFlags & (BIND_VERTEX_BUFFER | BIND_INDEX_BUFFER | BIND_CONSTANT_BUFFER | BIND_STREAM_OUTPUT))
    Fail(ErrorId::BIND_FLAGS_INVALID, call, obj, "textures cannot be bound as vertex, index, constant or stream-output buffers");
  if (s.miscFlags & ~uint32_t(RESOURCE_MISC_GENERATE_MIPS | RESOURCE_MISC_TEXTURECUBE))
    Fail(ErrorId::INVALID_DESC, call, obj, "MiscFlags has flags that do not apply to textures");

  uint32_t fullMips = FullMipCount(s.width, s.height, s.depth);
  if (s.mipLevels == 0) s.mipLevels = fullMips;
  if (s.mipLevels > fullMips)
    Fail(ErrorId::SIZE_OUT_OF_RANGE, call, obj, "MipLevels " + std::to_string(s.mipLevels) + " exceeds the full chain of " + std::to_string(fullMips));

  bool depthFmt = IsDepthFormat(s.format);
  if (s.bindFlags & BIND_DEPTH_STENCIL) {
    if (DepthFormatOfFamily(s.format) == FORMAT_UNKNOWN)
      Fail(ErrorId::BIND_FLAGS_INVALID, call, obj, "BIND_DEPTH_STENCIL needs a depth format (D16/D24S8/D32F/D32S8 or their TYPELESS family)");
    if (s.bindFlags & (BIND_RENDER_TARGET | BIND_UNORDERED_ACCESS))
      Fail(ErrorId::BIND_FLAGS_INVALID, call, obj, "BIND_DEPTH_STENCIL cannot be combined with BIND_RENDER_TARGET or BIND_UNORDERED_ACCESS");
  } else if (depthFmt && s.usage != USAGE_STAGING) {
    Fail(ErrorId::BIND_FLAGS_INVALID, call, obj, "a depth format needs BIND_DEPTH_STENCIL");
  }
  if (depthFmt && (s.bindFlags & BIND_SHADER_RESOURCE))
    Fail(ErrorId::BIND_FLAGS_INVALID, call, obj,
         "a depth texture read by shaders must be created TYPELESS (e.g. R32_TYPELESS, with a D32_FLOAT DSV and an R32_FLOAT SRV)");
  if (s.miscFlags & RESOURCE_MISC_GENERATE_MIPS) {
    if ((s.bindFlags & (BIND_RENDER_TARGET | BIND_SHADER_RESOURCE)) != (BIND_RENDER_TARGET | BIND_SHADER_RESOURCE))
      Fail(ErrorId::BIND_FLAGS_INVALID, call, obj, "RESOURCE_MISC_GENERATE_MIPS needs BIND_RENDER_TARGET | BIND_SHADER_RESOURCE");
  }
  uint32_t support = backend_->FormatSupportBackend(fi.kind == FormatKind::Typeless && (s.bindFlags & BIND_DEPTH_STENCIL)
                                              ? DepthFormatOfFamily(s.format) : s.format);
  uint32_t dimBit = s.dimension == RESOURCE_DIMENSION_TEXTURE1D   ? FORMAT_SUPPORT_TEXTURE1D
                    : s.dimension == RESOURCE_DIMENSION_TEXTURE3D ? FORMAT_SUPPORT_TEXTURE3D
                                                                   : FORMAT_SUPPORT_TEXTURE2D;
  if (fi.kind != FormatKind::Typeless && !(support & dimBit))
    Fail(ErrorId::FORMAT_UNSUPPORTED, call, obj, "this format cannot be used for this texture dimension on this device");
  if ((s.bindFlags & BIND_RENDER_TARGET) && fi.kind != FormatKind::Typeless && !(support & FORMAT_SUPPORT_RENDER_TARGET))
    Fail(ErrorId::FORMAT_UNSUPPORTED, call, obj, "format cannot be a render target on this device");
  if ((s.bindFlags & BIND_DEPTH_STENCIL) && !(support & FORMAT_SUPPORT_DEPTH_STENCIL))
    Fail(ErrorId::FORMAT_UNSUPPORTED, call, obj, "format cannot be a depth-stencil target on this device");

  ValidateUsage(call, obj, s.usage, s.bindFlags, s.cpuAccessFlags, init != nullptr, false);
  if (init) {
    for (uint32_t slice = 0; slice < s.arraySize; ++slice) {
      for (uint32_t mip = 0; mip < s.mipLevels; ++mip) {
        const SUBRESOURCE_DATA& sd = init[CalcSubresource(mip, slice, s.mipLevels)];
        uint32_t rowBytes = s.mipWidth(mip) * fi.bytesPerElement;
        std::string where = "pInitialData[" + std::to_string(CalcSubresource(mip, slice, s.mipLevels)) + "] (mip " +
                            std::to_string(mip) + ", slice " + std::to_string(slice) + ")";
        if (!sd.pSysMem) Fail(ErrorId::INITIAL_DATA_INVALID, call, obj, where + ": pSysMem is null");
        if (s.dimension != RESOURCE_DIMENSION_TEXTURE1D && sd.SysMemPitch < rowBytes)
          Fail(ErrorId::INITIAL_DATA_INVALID, call, obj, where + ": SysMemPitch " + std::to_string(sd.SysMemPitch) +
                                                              " is less than a row (" + std::to_string(rowBytes) + " bytes)");
        if (s.dimension == RESOURCE_DIMENSION_TEXTURE3D && sd.SysMemSlicePitch < sd.SysMemPitch * s.mipHeight(mip))
          Fail(ErrorId::INITIAL_DATA_INVALID, call, obj, where + ": SysMemSlicePitch is less than a slice");
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// State objects and queries

static bool ValidComparison(COMPARISON_FUNC f) { return f >= COMPARISON_NEVER && f <= COMPARISON_ALWAYS; }

Ref<SamplerState> Device::CreateSamplerState(const SAMPLER_DESC& d) {
  const char* call = "CreateSamplerState";
  const std::string obj = "SamplerState";
  static const uint32_t kValidLow[] = {0x0, 0x1, 0x4, 0x5, 0x10, 0x11, 0x14, 0x15, 0x55};
  uint32_t low = d.Filter & 0x7f;
  bool lowOk = false;
  for (uint32_t v : kValidLow) lowOk |= (low == v);
  if (!lowOk || (d.Filter & ~0x1ffu)) Fail(ErrorId::INVALID_DESC, call, obj, "unknown Filter " + std::to_string(uint32_t(d.Filter)));
  for (TEXTURE_ADDRESS_MODE m : {d.AddressU, d.AddressV, d.AddressW})
    if (m < TEXTURE_ADDRESS_WRAP || m > TEXTURE_ADDRESS_MIRROR_ONCE)
      Fail(ErrorId::INVALID_DESC, call, obj, "address mode " + std::to_string(uint32_t(m)) + " is not a TEXTURE_ADDRESS_MODE");
  if (FilterIsAnisotropic(d.Filter) && (d.MaxAnisotropy < 1 || d.MaxAnisotropy > 16))
    Fail(ErrorId::INVALID_DESC, call, obj, "MaxAnisotropy must be in [1, 16] for anisotropic filters");
  if (FilterIsComparison(d.Filter) && !ValidComparison(d.ComparisonFunc))
    Fail(ErrorId::INVALID_DESC, call, obj, "a comparison filter needs a valid ComparisonFunc");
  if (std::isnan(d.MinLOD) || std::isnan(d.MaxLOD) || d.MinLOD > d.MaxLOD)
    Fail(ErrorId::INVALID_DESC, call, obj, "MinLOD must not exceed MaxLOD");
  if (d.MipLODBias < -16.0f || d.MipLODBias > 15.99f)
    Fail(ErrorId::INVALID_DESC, call, obj, "MipLODBias must be in [-16, 15.99]");
  if (FilterReduction(d.Filter) >= 2 && !(backend_->FormatSupportBackend(FORMAT_R32_FLOAT) & FORMAT_SUPPORT_SHADER_SAMPLE))
    Fail(ErrorId::NOT_SUPPORTED, call, obj, "min/max reduction filters are not supported");
  Ref<SamplerState> s = Make<SamplerState>(d);
  s->backend_ = backend_->CreateSamplerBackend(*s);
  return s;
}

Ref<RasterizerState> Device::CreateRasterizerState(const RASTERIZER_DESC& d) {
  const char* call = "CreateRasterizerState";
  if (d.FillMode != FILL_SOLID && d.FillMode != FILL_WIREFRAME) Fail(ErrorId::INVALID_DESC, call, "RasterizerState", "FillMode must be FILL_SOLID or FILL_WIREFRAME");
  if (d.CullMode < CULL_NONE || d.CullMode > CULL_BACK) Fail(ErrorId::INVALID_DESC, call, "RasterizerState", "CullMode must be CULL_NONE, CULL_FRONT or CULL_BACK");
  if (std::isnan(d.DepthBiasClamp) || std::isnan(d.SlopeScaledDepthBias)) Fail(ErrorId::INVALID_DESC, call, "RasterizerState", "depth bias values must not be NaN");
  // One policy for both backends: a clamp the device cannot apply is refused here, where the
  // state is made, not dropped (a silently unclamped bias) or refused only at draw time.
  if (d.DepthBiasClamp != 0.0f && !info_.depthBiasClamp)
    Fail(ErrorId::NOT_SUPPORTED, call, "RasterizerState",
         "DepthBiasClamp=" + std::to_string(d.DepthBiasClamp) + " needs depth-bias clamping, which this device lacks (Vulkan depthBiasClamp, GL_EXT_polygon_offset_clamp)");
  return Make<RasterizerState>(d);
}

Ref<DepthStencilState> Device::CreateDepthStencilState(const DEPTH_STENCIL_DESC& d) {
  const char* call = "CreateDepthStencilState";
  if (d.DepthWriteMask > DEPTH_WRITE_MASK_ALL) Fail(ErrorId::INVALID_DESC, call, "DepthStencilState", "DepthWriteMask must be ZERO or ALL");
  if (!ValidComparison(d.DepthFunc)) Fail(ErrorId::INVALID_DESC, call, "DepthStencilState", "DepthFunc is not a COMPARISON_FUNC");
  for (const DEPTH_STENCILOP_DESC* f : {&d.FrontFace, &d.BackFace}) {
    if (!ValidComparison(f->StencilFunc)) Fail(ErrorId::INVALID_DESC, call, "DepthStencilState", "StencilFunc is not a COMPARISON_FUNC");
    for (STENCIL_OP op : {f->StencilFailOp, f->StencilDepthFailOp, f->StencilPassOp})
      if (op < STENCIL_OP_KEEP || op > STENCIL_OP_DECR) Fail(ErrorId::INVALID_DESC, call, "DepthStencilState", "stencil op is not a STENCIL_OP");
  }
  return Make<DepthStencilState>(d);
}

Ref<BlendState> Device::CreateBlendState(const BLEND_DESC& d) {
  const char* call = "CreateBlendState";
  auto validBlend = [](BLEND b) { return (b >= BLEND_ZERO && b <= BLEND_SRC_ALPHA_SAT) || (b >= BLEND_BLEND_FACTOR && b <= BLEND_INV_SRC1_ALPHA); };
  uint32_t n = d.IndependentBlendEnable ? SIMULTANEOUS_RENDER_TARGET_COUNT : 1;
  for (uint32_t i = 0; i < n; ++i) {
    const RENDER_TARGET_BLEND_DESC& rt = d.RenderTarget[i];
    std::string obj = "BlendState, RenderTarget[" + std::to_string(i) + "]";
    if (rt.RenderTargetWriteMask & ~0xfu) Fail(ErrorId::INVALID_DESC, call, obj, "RenderTargetWriteMask has bits above COLOR_WRITE_ENABLE_ALL");
    if (!rt.BlendEnable) continue;
    for (BLEND b : {rt.SrcBlend, rt.DestBlend, rt.SrcBlendAlpha, rt.DestBlendAlpha})
      if (!validBlend(b)) Fail(ErrorId::INVALID_DESC, call, obj, "blend factor " + std::to_string(uint32_t(b)) + " is not a BLEND value");
    for (BLEND b : {rt.SrcBlendAlpha, rt.DestBlendAlpha})
      if (b == BLEND_SRC_COLOR || b == BLEND_INV_SRC_COLOR || b == BLEND_DEST_COLOR || b == BLEND_INV_DEST_COLOR ||
          b == BLEND_SRC1_COLOR || b == BLEND_INV_SRC1_COLOR)
        Fail(ErrorId::INVALID_DESC, call, obj, "alpha blend factors cannot be *_COLOR factors");
    for (BLEND_OP op : {rt.BlendOp, rt.BlendOpAlpha})
      if (op < BLEND_OP_ADD || op > BLEND_OP_MAX) Fail(ErrorId::INVALID_DESC, call, obj, "BlendOp is not a BLEND_OP");
  }
  return Make<BlendState>(d);
}

Ref<Query> Device::CreateQuery(const QUERY_DESC& d) {
  if (d.Query > QUERY_TIMESTAMP_DISJOINT)
    Fail(ErrorId::NOT_SUPPORTED, "CreateQuery", "Query", "query type " + std::to_string(uint32_t(d.Query)) +
                                                             " is not supported (EVENT, OCCLUSION, TIMESTAMP, TIMESTAMP_DISJOINT are)");
  if (d.MiscFlags) Fail(ErrorId::INVALID_DESC, "CreateQuery", "Query", "MiscFlags must be 0 (predicates are not supported)");
  Ref<Query> q = Make<Query>(d);
  q->backend_ = backend_->CreateQueryBackend(*q);
  return q;
}

uint32_t Device::CheckFormatSupport(FORMAT format) const { return backend_->FormatSupportBackend(format); }

uint32_t Device::CheckMultisampleQualityLevels(FORMAT format, uint32_t sampleCount) const {
  if (sampleCount == 0 || (sampleCount & (sampleCount - 1))) return 0;
  return sampleCount == 1 || backend_->SampleCountSupportedBackend(format, sampleCount) ? 1 : 0;
}

}  // namespace sp
