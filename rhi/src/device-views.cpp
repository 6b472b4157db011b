// View creation: D3D11's default views for a null desc, format-family and dimension rules, and the
// ViewRange every later stage (hazards, backends) works from.
#include <sp/rhi/context.h>

#include "validate.h"

namespace sp {
namespace {

constexpr uint32_t kAll = 0xffffffffu;

struct ViewCheck {
  const char* call;
  std::string obj;

  void mips(const TextureShape& s, uint32_t first, uint32_t& count) const {
    if (first >= s.mipLevels)
      Fail(ErrorId::SUBRESOURCE_OUT_OF_RANGE, call, obj, "mip " + std::to_string(first) + " does not exist (the texture has " + std::to_string(s.mipLevels) + ")");
    if (count == kAll) count = s.mipLevels - first;
    if (count == 0 || first + count > s.mipLevels)
      Fail(ErrorId::SUBRESOURCE_OUT_OF_RANGE, call, obj, "mips [" + std::to_string(first) + ", " + std::to_string(first + count) + ") exceed the texture's " + std::to_string(s.mipLevels));
  }
  void slices(uint32_t available, uint32_t first, uint32_t& count, const char* what = "array slices") const {
    if (count == kAll) count = available > first ? available - first : 0;
    if (count == 0 || first >= available || first + count > available)
      Fail(ErrorId::SUBRESOURCE_OUT_OF_RANGE, call, obj, std::string(what) + " [" + std::to_string(first) + ", " + std::to_string(first + count) + ") exceed the resource's " + std::to_string(available));
  }
  void dimension(bool ok, const std::string& why) const {
    if (!ok) Fail(ErrorId::VIEW_DIMENSION_INVALID, call, obj, why);
  }
};

bool Is1D(const TextureShape& s) { return s.dimension == RESOURCE_DIMENSION_TEXTURE1D; }
bool Is2D(const TextureShape& s) { return s.dimension == RESOURCE_DIMENSION_TEXTURE2D; }
bool Is3D(const TextureShape& s) { return s.dimension == RESOURCE_DIMENSION_TEXTURE3D; }

void CheckBufferElements(const ViewCheck& c, const BUFFER_DESC& bd, uint32_t stride, uint32_t first, uint32_t num, ViewRange& r) {
  if (stride == 0) Fail(ErrorId::VIEW_FORMAT_INCOMPATIBLE, c.call, c.obj, "buffer views need a typed Format, a structured buffer, or a raw view");
  uint64_t end = (uint64_t(first) + num) * stride;
  if (num == 0 || end > bd.ByteWidth)
    Fail(ErrorId::SUBRESOURCE_OUT_OF_RANGE, c.call, c.obj, "elements [" + std::to_string(first) + ", " + std::to_string(first + num) + ") of " +
                                                               std::to_string(stride) + " bytes exceed the buffer's " + std::to_string(bd.ByteWidth) + " bytes");
  r.firstByte = uint64_t(first) * stride;
  r.byteCount = uint64_t(num) * stride;
  r.elementStride = stride;
}

// Element size of a buffer view: structured stride, raw (4), or the typed format's size.
uint32_t BufferViewStride(const ViewCheck& c, const BUFFER_DESC& bd, FORMAT fmt, bool raw) {
  bool structured = bd.MiscFlags & RESOURCE_MISC_BUFFER_STRUCTURED;
  if (raw) {
    if (!(bd.MiscFlags & RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS))
      Fail(ErrorId::VIEW_FORMAT_INCOMPATIBLE, c.call, c.obj, "raw views need a buffer created with RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS");
    if (fmt != FORMAT_R32_TYPELESS) Fail(ErrorId::VIEW_FORMAT_INCOMPATIBLE, c.call, c.obj, "raw views must use FORMAT_R32_TYPELESS");
    return 4;
  }
  if (structured) {
    if (fmt != FORMAT_UNKNOWN) Fail(ErrorId::VIEW_FORMAT_INCOMPATIBLE, c.call, c.obj, "views of structured buffers must use FORMAT_UNKNOWN");
    return bd.StructureByteStride;
  }
  const FormatInfo& fi = GetFormatInfo(fmt);
  if (fi.format == FORMAT_UNKNOWN || fi.kind == FormatKind::Typeless || IsDepthFormat(fmt))
    Fail(ErrorId::VIEW_FORMAT_INCOMPATIBLE, c.call, c.obj, "typed buffer views need a typed colour Format (got " + std::string(FormatName(fmt)) + ")");
  return fi.bytesPerElement;
}

void CheckTextureFormat(const ViewCheck& c, const TextureShape& s, FORMAT viewFmt) {
  if (!FormatsCompatibleForView(s.format, viewFmt))
    Fail(ErrorId::VIEW_FORMAT_INCOMPATIBLE, c.call, c.obj,
         "view format " + std::string(FormatName(viewFmt)) + " is not compatible with the texture's " + std::string(FormatName(s.format)) +
             (GetFormatInfo(s.format).kind == FormatKind::Typeless ? " (it must be a typed member of that family)"
                                                                   : " (typed textures are viewed in their own format; create it TYPELESS to reinterpret)"));
}

// The subresources of a render-target, depth-stencil or unordered-access view: one mip, a range
// of slices (array slices, or W slices of a 3D texture). Checks the view's dimension against the
// texture and the ranges against its size.
enum class OutputKind { Tex1D, Tex1DArray, Tex2D, Tex2DArray, Tex2DMS, Tex2DMSArray, Tex3D };

ViewRange OutputRange(const ViewCheck& c, const TextureShape& s, OutputKind kind, const char* dimension, uint32_t mip,
                      uint32_t* firstSlice = nullptr, uint32_t* sliceCount = nullptr) {
  bool ms = s.sampleCount > 1;
  std::string need = std::string(dimension) + " needs a ";
  switch (kind) {
    case OutputKind::Tex1D:
    case OutputKind::Tex1DArray: c.dimension(Is1D(s), need + "Texture1D"); break;
    case OutputKind::Tex2D:
    case OutputKind::Tex2DArray: c.dimension(Is2D(s) && !ms, need + "single-sampled Texture2D"); break;
    case OutputKind::Tex2DMS:
    case OutputKind::Tex2DMSArray: c.dimension(Is2D(s) && ms, need + "multisampled Texture2D"); break;
    case OutputKind::Tex3D: c.dimension(Is3D(s), need + "Texture3D"); break;
  }
  ViewRange r;
  uint32_t one = 1;
  if (kind != OutputKind::Tex2DMS && kind != OutputKind::Tex2DMSArray) {
    c.mips(s, mip, one);
    r.firstMip = mip;
  }
  if (firstSlice) {
    if (kind == OutputKind::Tex3D) c.slices(s.mipDepth(mip), *firstSlice, *sliceCount, "depth slices");
    else c.slices(s.arraySize, *firstSlice, *sliceCount);
    r.firstSlice = *firstSlice;
    r.sliceCount = *sliceCount;
  }
  return r;
}

// The ViewShape of each desc, after the core has validated it. Buffer views are told apart by
// the buffer's structured flag and the view's raw flag.
ViewShape BufferShape(const Resource* r, bool raw) {
  if (static_cast<const Buffer*>(r)->GetDesc().MiscFlags & RESOURCE_MISC_BUFFER_STRUCTURED) return ViewShape::StructuredBuffer;
  return raw ? ViewShape::RawBuffer : ViewShape::TypedBuffer;
}

ViewShape ShapeOf(const Resource* r, const SHADER_RESOURCE_VIEW_DESC& d) {
  switch (d.ViewDimension) {
    case SRV_DIMENSION_BUFFER: return BufferShape(r, false);
    case SRV_DIMENSION_BUFFEREX: return BufferShape(r, d.BufferEx.Flags & BUFFEREX_SRV_FLAG_RAW);
    case SRV_DIMENSION_TEXTURE1D: return ViewShape::Texture1D;
    case SRV_DIMENSION_TEXTURE1DARRAY: return ViewShape::Texture1DArray;
    case SRV_DIMENSION_TEXTURE2DARRAY: return ViewShape::Texture2DArray;
    case SRV_DIMENSION_TEXTURE2DMS: return ViewShape::Texture2DMS;
    case SRV_DIMENSION_TEXTURE2DMSARRAY: return ViewShape::Texture2DMSArray;
    case SRV_DIMENSION_TEXTURE3D: return ViewShape::Texture3D;
    case SRV_DIMENSION_TEXTURECUBE: return ViewShape::TextureCube;
    case SRV_DIMENSION_TEXTURECUBEARRAY: return ViewShape::TextureCubeArray;
    default: return ViewShape::Texture2D;
  }
}

ViewShape ShapeOf(const RENDER_TARGET_VIEW_DESC& d) {
  switch (d.ViewDimension) {
    case RTV_DIMENSION_TEXTURE1D: return ViewShape::Texture1D;
    case RTV_DIMENSION_TEXTURE1DARRAY: return ViewShape::Texture1DArray;
    case RTV_DIMENSION_TEXTURE2DARRAY: return ViewShape::Texture2DArray;
    case RTV_DIMENSION_TEXTURE2DMS: return ViewShape::Texture2DMS;
    case RTV_DIMENSION_TEXTURE2DMSARRAY: return ViewShape::Texture2DMSArray;
    case RTV_DIMENSION_TEXTURE3D: return ViewShape::Texture3D;
    default: return ViewShape::Texture2D;
  }
}

ViewShape ShapeOf(const DEPTH_STENCIL_VIEW_DESC& d) {
  switch (d.ViewDimension) {
    case DSV_DIMENSION_TEXTURE1D: return ViewShape::Texture1D;
    case DSV_DIMENSION_TEXTURE1DARRAY: return ViewShape::Texture1DArray;
    case DSV_DIMENSION_TEXTURE2DARRAY: return ViewShape::Texture2DArray;
    case DSV_DIMENSION_TEXTURE2DMS: return ViewShape::Texture2DMS;
    case DSV_DIMENSION_TEXTURE2DMSARRAY: return ViewShape::Texture2DMSArray;
    default: return ViewShape::Texture2D;
  }
}

ViewShape ShapeOf(const Resource* r, const UNORDERED_ACCESS_VIEW_DESC& d) {
  switch (d.ViewDimension) {
    case UAV_DIMENSION_BUFFER: return BufferShape(r, d.Buffer.Flags & BUFFER_UAV_FLAG_RAW);
    case UAV_DIMENSION_TEXTURE1D: return ViewShape::Texture1D;
    case UAV_DIMENSION_TEXTURE1DARRAY: return ViewShape::Texture1DArray;
    case UAV_DIMENSION_TEXTURE2DARRAY: return ViewShape::Texture2DArray;
    case UAV_DIMENSION_TEXTURE3D: return ViewShape::Texture3D;
    default: return ViewShape::Texture2D;
  }
}

}  // namespace

Ref<ShaderResourceView> Device::CreateShaderResourceView(Resource* resource, const SHADER_RESOURCE_VIEW_DESC* pDesc) {
  ViewCheck c{"CreateShaderResourceView", Describe(resource)};
  if (!resource) Fail(ErrorId::INVALID_ARGUMENT, c.call, c.obj, "pResource is null");
  if (resource->GetDevice() != this) Fail(ErrorId::INVALID_ARGUMENT, c.call, c.obj, "the resource belongs to another device");
  ViewRange r;
  SHADER_RESOURCE_VIEW_DESC d;
  if (const Buffer* b = AsBuffer(resource)) {
    const BUFFER_DESC& bd = b->GetDesc();
    if (!(bd.BindFlags & BIND_SHADER_RESOURCE))
      Fail(ErrorId::BIND_FLAGS_INVALID, c.call, c.obj, "the buffer was not created with BIND_SHADER_RESOURCE (has " + BindFlagsToString(bd.BindFlags) + ")");
    if (pDesc) {
      d = *pDesc;
    } else {
      if (!(bd.MiscFlags & RESOURCE_MISC_BUFFER_STRUCTURED))
        Fail(ErrorId::INVALID_ARGUMENT, c.call, c.obj, "only structured buffers can have a view without a description");
      d.Format = FORMAT_UNKNOWN;
      d.ViewDimension = SRV_DIMENSION_BUFFER;
      d.Buffer.FirstElement = 0;
      d.Buffer.NumElements = bd.ByteWidth / bd.StructureByteStride;
    }
    if (d.ViewDimension == SRV_DIMENSION_BUFFER) {
      uint32_t stride = BufferViewStride(c, bd, d.Format, false);
      CheckBufferElements(c, bd, stride, d.Buffer.FirstElement, d.Buffer.NumElements, r);
    } else if (d.ViewDimension == SRV_DIMENSION_BUFFEREX) {
      bool raw = d.BufferEx.Flags & BUFFEREX_SRV_FLAG_RAW;
      uint32_t stride = BufferViewStride(c, bd, d.Format, raw);
      CheckBufferElements(c, bd, stride, d.BufferEx.FirstElement, d.BufferEx.NumElements, r);
    } else {
      c.dimension(false, "buffers need SRV_DIMENSION_BUFFER or SRV_DIMENSION_BUFFEREX");
    }
  } else {
    const TextureShape& s = AsTexture(resource)->Shape();
    if (!(s.bindFlags & BIND_SHADER_RESOURCE))
      Fail(ErrorId::BIND_FLAGS_INVALID, c.call, c.obj, "the texture was not created with BIND_SHADER_RESOURCE (has " + BindFlagsToString(s.bindFlags) + ")");
    if (pDesc) {
      d = *pDesc;
    } else {
      if (GetFormatInfo(s.format).kind == FormatKind::Typeless)
        Fail(ErrorId::VIEW_FORMAT_INCOMPATIBLE, c.call, c.obj, "a TYPELESS texture needs a view description with a typed Format");
      d.Format = s.format;
      if (Is1D(s)) {
        d.ViewDimension = s.arraySize > 1 ? SRV_DIMENSION_TEXTURE1DARRAY : SRV_DIMENSION_TEXTURE1D;
        d.Texture1DArray = {0, kAll, 0, s.arraySize};
      } else if (Is3D(s)) {
        d.ViewDimension = SRV_DIMENSION_TEXTURE3D;
        d.Texture3D = {0, kAll};
      } else if (s.sampleCount > 1) {
        d.ViewDimension = s.arraySize > 1 ? SRV_DIMENSION_TEXTURE2DMSARRAY : SRV_DIMENSION_TEXTURE2DMS;
        d.Texture2DMSArray = {0, s.arraySize};
      } else if (s.isCube()) {
        d.ViewDimension = s.arraySize > 6 ? SRV_DIMENSION_TEXTURECUBEARRAY : SRV_DIMENSION_TEXTURECUBE;
        d.TextureCubeArray = {0, kAll, 0, s.arraySize / 6};
      } else {
        d.ViewDimension = s.arraySize > 1 ? SRV_DIMENSION_TEXTURE2DARRAY : SRV_DIMENSION_TEXTURE2D;
        d.Texture2DArray = {0, kAll, 0, s.arraySize};
      }
    }
    CheckTextureFormat(c, s, d.Format);
    const FormatInfo& vf = GetFormatInfo(d.Format);
    if (s.bindFlags & BIND_DEPTH_STENCIL) {
      if (!vf.readsDepth && !vf.readsStencil)
        Fail(ErrorId::VIEW_FORMAT_INCOMPATIBLE, c.call, c.obj, "a depth texture is read through its depth or stencil read format (e.g. R32_FLOAT, R24_UNORM_X8_TYPELESS, X24_TYPELESS_G8_UINT, R16_UNORM), not " + std::string(FormatName(d.Format)));
      r.depth = vf.readsDepth;
      r.stencil = vf.readsStencil;
    }
    bool ms = s.sampleCount > 1;
    switch (d.ViewDimension) {
      case SRV_DIMENSION_TEXTURE1D:
        c.dimension(Is1D(s), "SRV_DIMENSION_TEXTURE1D needs a Texture1D");
        c.mips(s, d.Texture1D.MostDetailedMip, d.Texture1D.MipLevels);
        r.firstMip = d.Texture1D.MostDetailedMip, r.mipCount = d.Texture1D.MipLevels, r.firstSlice = 0, r.sliceCount = 1;
        break;
      case SRV_DIMENSION_TEXTURE1DARRAY:
        c.dimension(Is1D(s), "SRV_DIMENSION_TEXTURE1DARRAY needs a Texture1D");
        c.mips(s, d.Texture1DArray.MostDetailedMip, d.Texture1DArray.MipLevels);
        c.slices(s.arraySize, d.Texture1DArray.FirstArraySlice, d.Texture1DArray.ArraySize);
        r.firstMip = d.Texture1DArray.MostDetailedMip, r.mipCount = d.Texture1DArray.MipLevels;
        r.firstSlice = d.Texture1DArray.FirstArraySlice, r.sliceCount = d.Texture1DArray.ArraySize;
        break;
      case SRV_DIMENSION_TEXTURE2D:
        c.dimension(Is2D(s) && !ms, "SRV_DIMENSION_TEXTURE2D needs a single-sampled Texture2D");
        c.mips(s, d.Texture2D.MostDetailedMip, d.Texture2D.MipLevels);
        r.firstMip = d.Texture2D.MostDetailedMip, r.mipCount = d.Texture2D.MipLevels, r.firstSlice = 0, r.sliceCount = 1;
        break;
      case SRV_DIMENSION_TEXTURE2DARRAY:
        c.dimension(Is2D(s) && !ms, "SRV_DIMENSION_TEXTURE2DARRAY needs a single-sampled Texture2D");
        c.mips(s, d.Texture2DArray.MostDetailedMip, d.Texture2DArray.MipLevels);
        c.slices(s.arraySize, d.Texture2DArray.FirstArraySlice, d.Texture2DArray.ArraySize);
        r.firstMip = d.Texture2DArray.MostDetailedMip, r.mipCount = d.Texture2DArray.MipLevels;
        r.firstSlice = d.Texture2DArray.FirstArraySlice, r.sliceCount = d.Texture2DArray.ArraySize;
        break;
      case SRV_DIMENSION_TEXTURE2DMS:
        c.dimension(Is2D(s) && ms, "SRV_DIMENSION_TEXTURE2DMS needs a multisampled Texture2D");
        r.firstMip = 0, r.mipCount = 1, r.firstSlice = 0, r.sliceCount = 1;
        break;
      case SRV_DIMENSION_TEXTURE2DMSARRAY:
        c.dimension(Is2D(s) && ms, "SRV_DIMENSION_TEXTURE2DMSARRAY needs a multisampled Texture2D");
        c.slices(s.arraySize, d.Texture2DMSArray.FirstArraySlice, d.Texture2DMSArray.ArraySize);
        r.firstMip = 0, r.mipCount = 1, r.firstSlice = d.Texture2DMSArray.FirstArraySlice, r.sliceCount = d.Texture2DMSArray.ArraySize;
        break;
      case SRV_DIMENSION_TEXTURE3D:
        c.dimension(Is3D(s), "SRV_DIMENSION_TEXTURE3D needs a Texture3D");
        c.mips(s, d.Texture3D.MostDetailedMip, d.Texture3D.MipLevels);
        r.firstMip = d.Texture3D.MostDetailedMip, r.mipCount = d.Texture3D.MipLevels, r.firstSlice = 0, r.sliceCount = 1;
        break;
      case SRV_DIMENSION_TEXTURECUBE:
        c.dimension(Is2D(s) && s.isCube(), "SRV_DIMENSION_TEXTURECUBE needs a texture created with RESOURCE_MISC_TEXTURECUBE");
        c.mips(s, d.TextureCube.MostDetailedMip, d.TextureCube.MipLevels);
        r.firstMip = d.TextureCube.MostDetailedMip, r.mipCount = d.TextureCube.MipLevels, r.firstSlice = 0, r.sliceCount = 6;
        break;
      case SRV_DIMENSION_TEXTURECUBEARRAY: {
        c.dimension(Is2D(s) && s.isCube(), "SRV_DIMENSION_TEXTURECUBEARRAY needs a texture created with RESOURCE_MISC_TEXTURECUBE");
        c.mips(s, d.TextureCubeArray.MostDetailedMip, d.TextureCubeArray.MipLevels);
        uint32_t faces = d.TextureCubeArray.NumCubes == kAll ? kAll : d.TextureCubeArray.NumCubes * 6;
        c.slices(s.arraySize, d.TextureCubeArray.First2DArrayFace, faces, "cube faces");
        d.TextureCubeArray.NumCubes = faces / 6;
        r.firstMip = d.TextureCubeArray.MostDetailedMip, r.mipCount = d.TextureCubeArray.MipLevels;
        r.firstSlice = d.TextureCubeArray.First2DArrayFace, r.sliceCount = faces;
        break;
      }
      default:
        c.dimension(false, "ViewDimension " + std::to_string(uint32_t(d.ViewDimension)) + " does not fit a texture");
    }
    if (!(s.bindFlags & BIND_DEPTH_STENCIL) && !(backend_->FormatSupportBackend(d.Format) & FORMAT_SUPPORT_SHADER_LOAD))
      Fail(ErrorId::FORMAT_UNSUPPORTED, c.call, c.obj, std::string(FormatName(d.Format)) + " cannot be read by shaders on this device");
  }
  Ref<ShaderResourceView> v(new ShaderResourceView(this, std::static_pointer_cast<Resource>(resource->shared_from_this()), d, r, ShapeOf(resource, d)));
  v->backend_ = backend_->CreateViewBackend(*v);
  return v;
}

Ref<RenderTargetView> Device::CreateRenderTargetView(Resource* resource, const RENDER_TARGET_VIEW_DESC* pDesc) {
  ViewCheck c{"CreateRenderTargetView", Describe(resource)};
  if (!resource) Fail(ErrorId::INVALID_ARGUMENT, c.call, c.obj, "pResource is null");
  if (resource->GetDevice() != this) Fail(ErrorId::INVALID_ARGUMENT, c.call, c.obj, "the resource belongs to another device");
  const Texture* t = AsTexture(resource);
  if (!t) Fail(ErrorId::NOT_SUPPORTED, c.call, c.obj, "render target views of buffers are not supported");
  const TextureShape& s = t->Shape();
  if (!(s.bindFlags & BIND_RENDER_TARGET))
    Fail(ErrorId::BIND_FLAGS_INVALID, c.call, c.obj, "the texture was not created with BIND_RENDER_TARGET (has " + BindFlagsToString(s.bindFlags) + ")");
  RENDER_TARGET_VIEW_DESC d;
  if (pDesc) {
    d = *pDesc;
  } else {
    if (GetFormatInfo(s.format).kind == FormatKind::Typeless)
      Fail(ErrorId::VIEW_FORMAT_INCOMPATIBLE, c.call, c.obj, "a TYPELESS texture needs a view description with a typed Format");
    d.Format = s.format;
    if (Is1D(s)) {
      d.ViewDimension = s.arraySize > 1 ? RTV_DIMENSION_TEXTURE1DARRAY : RTV_DIMENSION_TEXTURE1D;
      d.Texture1DArray = {0, 0, s.arraySize};
    } else if (Is3D(s)) {
      d.ViewDimension = RTV_DIMENSION_TEXTURE3D;
      d.Texture3D = {0, 0, kAll};
    } else if (s.sampleCount > 1) {
      d.ViewDimension = s.arraySize > 1 ? RTV_DIMENSION_TEXTURE2DMSARRAY : RTV_DIMENSION_TEXTURE2DMS;
      d.Texture2DMSArray = {0, s.arraySize};
    } else {
      d.ViewDimension = s.arraySize > 1 ? RTV_DIMENSION_TEXTURE2DARRAY : RTV_DIMENSION_TEXTURE2D;
      d.Texture2DArray = {0, 0, s.arraySize};
    }
  }
  CheckTextureFormat(c, s, d.Format);
  if (!(backend_->FormatSupportBackend(d.Format) & FORMAT_SUPPORT_RENDER_TARGET))
    Fail(ErrorId::FORMAT_UNSUPPORTED, c.call, c.obj, std::string(FormatName(d.Format)) + " cannot be a render target on this device");
  ViewRange r;
  using K = OutputKind;
  switch (d.ViewDimension) {
    case RTV_DIMENSION_TEXTURE1D: r = OutputRange(c, s, K::Tex1D, "RTV_DIMENSION_TEXTURE1D", d.Texture1D.MipSlice); break;
    case RTV_DIMENSION_TEXTURE1DARRAY:
      r = OutputRange(c, s, K::Tex1DArray, "RTV_DIMENSION_TEXTURE1DARRAY", d.Texture1DArray.MipSlice, &d.Texture1DArray.FirstArraySlice, &d.Texture1DArray.ArraySize);
      break;
    case RTV_DIMENSION_TEXTURE2D: r = OutputRange(c, s, K::Tex2D, "RTV_DIMENSION_TEXTURE2D", d.Texture2D.MipSlice); break;
    case RTV_DIMENSION_TEXTURE2DARRAY:
      r = OutputRange(c, s, K::Tex2DArray, "RTV_DIMENSION_TEXTURE2DARRAY", d.Texture2DArray.MipSlice, &d.Texture2DArray.FirstArraySlice, &d.Texture2DArray.ArraySize);
      break;
    case RTV_DIMENSION_TEXTURE2DMS: r = OutputRange(c, s, K::Tex2DMS, "RTV_DIMENSION_TEXTURE2DMS", 0); break;
    case RTV_DIMENSION_TEXTURE2DMSARRAY:
      r = OutputRange(c, s, K::Tex2DMSArray, "RTV_DIMENSION_TEXTURE2DMSARRAY", 0, &d.Texture2DMSArray.FirstArraySlice, &d.Texture2DMSArray.ArraySize);
      break;
    case RTV_DIMENSION_TEXTURE3D:
      r = OutputRange(c, s, K::Tex3D, "RTV_DIMENSION_TEXTURE3D", d.Texture3D.MipSlice, &d.Texture3D.FirstWSlice, &d.Texture3D.WSize);
      break;
    default:
      c.dimension(false, "ViewDimension " + std::to_string(uint32_t(d.ViewDimension)) + " does not fit a texture");
  }
  Ref<RenderTargetView> v(new RenderTargetView(this, std::static_pointer_cast<Resource>(resource->shared_from_this()), d, r, ShapeOf(d)));
  v->backend_ = backend_->CreateViewBackend(*v);
  return v;
}

Ref<DepthStencilView> Device::CreateDepthStencilView(Resource* resource, const DEPTH_STENCIL_VIEW_DESC* pDesc) {
  ViewCheck c{"CreateDepthStencilView", Describe(resource)};
  if (!resource) Fail(ErrorId::INVALID_ARGUMENT, c.call, c.obj, "pResource is null");
  if (resource->GetDevice() != this) Fail(ErrorId::INVALID_ARGUMENT, c.call, c.obj, "the resource belongs to another device");
  const Texture* t = AsTexture(resource);
  if (!t) Fail(ErrorId::BIND_FLAGS_INVALID, c.call, c.obj, "buffers cannot be depth-stencil targets");
  const TextureShape& s = t->Shape();
  if (!(s.bindFlags & BIND_DEPTH_STENCIL))
    Fail(ErrorId::BIND_FLAGS_INVALID, c.call, c.obj, "the texture was not created with BIND_DEPTH_STENCIL (has " + BindFlagsToString(s.bindFlags) + ")");
  DEPTH_STENCIL_VIEW_DESC d;
  if (pDesc) {
    d = *pDesc;
  } else {
    if (GetFormatInfo(s.format).kind == FormatKind::Typeless)
      Fail(ErrorId::VIEW_FORMAT_INCOMPATIBLE, c.call, c.obj, "a TYPELESS texture needs a view description with a depth Format");
    d.Format = s.format;
    if (Is1D(s)) {
      d.ViewDimension = s.arraySize > 1 ? DSV_DIMENSION_TEXTURE1DARRAY : DSV_DIMENSION_TEXTURE1D;
      d.Texture1DArray = {0, 0, s.arraySize};
    } else if (s.sampleCount > 1) {
      d.ViewDimension = s.arraySize > 1 ? DSV_DIMENSION_TEXTURE2DMSARRAY : DSV_DIMENSION_TEXTURE2DMS;
      d.Texture2DMSArray = {0, s.arraySize};
    } else {
      d.ViewDimension = s.arraySize > 1 ? DSV_DIMENSION_TEXTURE2DARRAY : DSV_DIMENSION_TEXTURE2D;
      d.Texture2DArray = {0, 0, s.arraySize};
    }
  }
  if (d.Format != DepthFormatOfFamily(s.format) || !IsDepthFormat(d.Format))
    Fail(ErrorId::VIEW_FORMAT_INCOMPATIBLE, c.call, c.obj,
         "DSV format " + std::string(FormatName(d.Format)) + " does not fit the texture's " + std::string(FormatName(s.format)) +
             " (use " + std::string(FormatName(DepthFormatOfFamily(s.format))) + ")");
  const FormatInfo& fi = GetFormatInfo(d.Format);
  if (d.Flags & ~uint32_t(DSV_READ_ONLY_DEPTH | DSV_READ_ONLY_STENCIL)) Fail(ErrorId::INVALID_DESC, c.call, c.obj, "unknown DSV Flags");
  if ((d.Flags & DSV_READ_ONLY_STENCIL) && !fi.stencilBits)
    Fail(ErrorId::INVALID_DESC, c.call, c.obj, "DSV_READ_ONLY_STENCIL on a format without stencil");
  ViewRange r;
  using K = OutputKind;
  switch (d.ViewDimension) {
    case DSV_DIMENSION_TEXTURE1D: r = OutputRange(c, s, K::Tex1D, "DSV_DIMENSION_TEXTURE1D", d.Texture1D.MipSlice); break;
    case DSV_DIMENSION_TEXTURE1DARRAY:
      r = OutputRange(c, s, K::Tex1DArray, "DSV_DIMENSION_TEXTURE1DARRAY", d.Texture1DArray.MipSlice, &d.Texture1DArray.FirstArraySlice, &d.Texture1DArray.ArraySize);
      break;
    case DSV_DIMENSION_TEXTURE2D: r = OutputRange(c, s, K::Tex2D, "DSV_DIMENSION_TEXTURE2D", d.Texture2D.MipSlice); break;
    case DSV_DIMENSION_TEXTURE2DARRAY:
      r = OutputRange(c, s, K::Tex2DArray, "DSV_DIMENSION_TEXTURE2DARRAY", d.Texture2DArray.MipSlice, &d.Texture2DArray.FirstArraySlice, &d.Texture2DArray.ArraySize);
      break;
    case DSV_DIMENSION_TEXTURE2DMS: r = OutputRange(c, s, K::Tex2DMS, "DSV_DIMENSION_TEXTURE2DMS", 0); break;
    case DSV_DIMENSION_TEXTURE2DMSARRAY:
      r = OutputRange(c, s, K::Tex2DMSArray, "DSV_DIMENSION_TEXTURE2DMSARRAY", 0, &d.Texture2DMSArray.FirstArraySlice, &d.Texture2DMSArray.ArraySize);
      break;
    default:
      c.dimension(false, "ViewDimension " + std::to_string(uint32_t(d.ViewDimension)) + " does not fit a depth texture");
  }
  r.mipCount = 1;
  r.depth = true;
  r.stencil = fi.stencilBits > 0;
  Ref<DepthStencilView> v(new DepthStencilView(this, std::static_pointer_cast<Resource>(resource->shared_from_this()), d, r, ShapeOf(d)));
  v->backend_ = backend_->CreateViewBackend(*v);
  return v;
}

Ref<UnorderedAccessView> Device::CreateUnorderedAccessView(Resource* resource, const UNORDERED_ACCESS_VIEW_DESC* pDesc) {
  ViewCheck c{"CreateUnorderedAccessView", Describe(resource)};
  if (!resource) Fail(ErrorId::INVALID_ARGUMENT, c.call, c.obj, "pResource is null");
  if (resource->GetDevice() != this) Fail(ErrorId::INVALID_ARGUMENT, c.call, c.obj, "the resource belongs to another device");
  ViewRange r;
  UNORDERED_ACCESS_VIEW_DESC d;
  if (const Buffer* b = AsBuffer(resource)) {
    const BUFFER_DESC& bd = b->GetDesc();
    if (!(bd.BindFlags & BIND_UNORDERED_ACCESS))
      Fail(ErrorId::BIND_FLAGS_INVALID, c.call, c.obj, "the buffer was not created with BIND_UNORDERED_ACCESS (has " + BindFlagsToString(bd.BindFlags) + ")");
    if (pDesc) {
      d = *pDesc;
    } else {
      if (!(bd.MiscFlags & RESOURCE_MISC_BUFFER_STRUCTURED))
        Fail(ErrorId::INVALID_ARGUMENT, c.call, c.obj, "only structured buffers can have a view without a description");
      d.Format = FORMAT_UNKNOWN;
      d.ViewDimension = UAV_DIMENSION_BUFFER;
      d.Buffer = {0, bd.ByteWidth / bd.StructureByteStride, 0};
    }
    c.dimension(d.ViewDimension == UAV_DIMENSION_BUFFER, "buffers need UAV_DIMENSION_BUFFER");
    if (d.Buffer.Flags & ~uint32_t(BUFFER_UAV_FLAG_RAW | BUFFER_UAV_FLAG_APPEND | BUFFER_UAV_FLAG_COUNTER))
      Fail(ErrorId::INVALID_DESC, c.call, c.obj, "unknown Buffer.Flags");
    if ((d.Buffer.Flags & (BUFFER_UAV_FLAG_APPEND | BUFFER_UAV_FLAG_COUNTER)) && !(bd.MiscFlags & RESOURCE_MISC_BUFFER_STRUCTURED))
      Fail(ErrorId::INVALID_DESC, c.call, c.obj, "BUFFER_UAV_FLAG_APPEND/COUNTER need a structured buffer");
    uint32_t stride = BufferViewStride(c, bd, d.Format, d.Buffer.Flags & BUFFER_UAV_FLAG_RAW);
    CheckBufferElements(c, bd, stride, d.Buffer.FirstElement, d.Buffer.NumElements, r);
    if (d.Format != FORMAT_UNKNOWN && !(d.Buffer.Flags & BUFFER_UAV_FLAG_RAW) &&
        !(backend_->FormatSupportBackend(d.Format) & FORMAT_SUPPORT_TYPED_UNORDERED_ACCESS_VIEW))
      Fail(ErrorId::FORMAT_UNSUPPORTED, c.call, c.obj, std::string(FormatName(d.Format)) + " cannot be a typed UAV on this device");
  } else {
    const TextureShape& s = AsTexture(resource)->Shape();
    if (!(s.bindFlags & BIND_UNORDERED_ACCESS))
      Fail(ErrorId::BIND_FLAGS_INVALID, c.call, c.obj, "the texture was not created with BIND_UNORDERED_ACCESS (has " + BindFlagsToString(s.bindFlags) + ")");
    if (pDesc) {
      d = *pDesc;
    } else {
      if (GetFormatInfo(s.format).kind == FormatKind::Typeless)
        Fail(ErrorId::VIEW_FORMAT_INCOMPATIBLE, c.call, c.obj, "a TYPELESS texture needs a view description with a typed Format");
      d.Format = s.format;
      if (Is1D(s)) {
        d.ViewDimension = s.arraySize > 1 ? UAV_DIMENSION_TEXTURE1DARRAY : UAV_DIMENSION_TEXTURE1D;
        d.Texture1DArray = {0, 0, s.arraySize};
      } else if (Is3D(s)) {
        d.ViewDimension = UAV_DIMENSION_TEXTURE3D;
        d.Texture3D = {0, 0, kAll};
      } else {
        d.ViewDimension = s.arraySize > 1 ? UAV_DIMENSION_TEXTURE2DARRAY : UAV_DIMENSION_TEXTURE2D;
        d.Texture2DArray = {0, 0, s.arraySize};
      }
    }
    CheckTextureFormat(c, s, d.Format);
    if (!(backend_->FormatSupportBackend(d.Format) & FORMAT_SUPPORT_TYPED_UNORDERED_ACCESS_VIEW))
      Fail(ErrorId::FORMAT_UNSUPPORTED, c.call, c.obj, std::string(FormatName(d.Format)) + " cannot be a typed UAV on this device");
    using K = OutputKind;
    switch (d.ViewDimension) {
      case UAV_DIMENSION_TEXTURE1D: r = OutputRange(c, s, K::Tex1D, "UAV_DIMENSION_TEXTURE1D", d.Texture1D.MipSlice); break;
      case UAV_DIMENSION_TEXTURE1DARRAY:
        r = OutputRange(c, s, K::Tex1DArray, "UAV_DIMENSION_TEXTURE1DARRAY", d.Texture1DArray.MipSlice, &d.Texture1DArray.FirstArraySlice, &d.Texture1DArray.ArraySize);
        break;
      case UAV_DIMENSION_TEXTURE2D: r = OutputRange(c, s, K::Tex2D, "UAV_DIMENSION_TEXTURE2D", d.Texture2D.MipSlice); break;
      case UAV_DIMENSION_TEXTURE2DARRAY:
        r = OutputRange(c, s, K::Tex2DArray, "UAV_DIMENSION_TEXTURE2DARRAY", d.Texture2DArray.MipSlice, &d.Texture2DArray.FirstArraySlice, &d.Texture2DArray.ArraySize);
        break;
      case UAV_DIMENSION_TEXTURE3D:
        r = OutputRange(c, s, K::Tex3D, "UAV_DIMENSION_TEXTURE3D", d.Texture3D.MipSlice, &d.Texture3D.FirstWSlice, &d.Texture3D.WSize);
        break;
      default:
        c.dimension(false, "ViewDimension " + std::to_string(uint32_t(d.ViewDimension)) + " does not fit a texture");
    }
    r.mipCount = 1;
  }
  Ref<UnorderedAccessView> v(new UnorderedAccessView(this, std::static_pointer_cast<Resource>(resource->shared_from_this()), d, r, ShapeOf(resource, d)));
  v->backend_ = backend_->CreateViewBackend(*v);
  return v;
}

}  // namespace sp
