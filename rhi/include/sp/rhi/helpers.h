// D3D11's helper classes (CD3D11_*) and default-value constants (D3D11_DEFAULT_*, ...), with
// D3D11's constructor signatures, default arguments and values, so description set-up ports line
// for line. Naming follows the rest of the port, dropping `D3D11_`:
//   CD3D11_TEXTURE2D_DESC -> sp::CTEXTURE2D_DESC      CD3D11_VIEWPORT -> sp::CVIEWPORT
//   CD3D11_DEFAULT        -> sp::CDEFAULT             D3D11_DEFAULT   -> sp::DEFAULT
//   D3D11_DEFAULT_SAMPLE_MASK -> sp::DEFAULT_SAMPLE_MASK, D3D11_FLOAT32_MAX -> sp::FLOAT32_MAX
// The constructors that read a resource take `sp::Texture2D*` etc. where D3D11 takes
// `ID3D11Texture2D*`; a `sp::Ref<sp::Texture2D>` is accepted as well.
#pragma once
#include <sp/rhi/context.h>
#include <sp/rhi/query.h>
#include <sp/rhi/resource.h>
#include <sp/rhi/state.h>
#include <sp/rhi/view.h>

namespace sp {

// ---- constants (d3d11.h's values) -------------------------------------------------------------

inline constexpr float FLOAT32_MAX = 3.402823466e+38f;
inline constexpr float MIN_DEPTH = 0.0f;
inline constexpr float MAX_DEPTH = 1.0f;

inline constexpr float DEFAULT_BLEND_FACTOR_RED = 1.0f;
inline constexpr float DEFAULT_BLEND_FACTOR_GREEN = 1.0f;
inline constexpr float DEFAULT_BLEND_FACTOR_BLUE = 1.0f;
inline constexpr float DEFAULT_BLEND_FACTOR_ALPHA = 1.0f;
inline constexpr float DEFAULT_BORDER_COLOR_COMPONENT = 0.0f;
inline constexpr int32_t DEFAULT_DEPTH_BIAS = 0;
inline constexpr float DEFAULT_DEPTH_BIAS_CLAMP = 0.0f;
inline constexpr float DEFAULT_SLOPE_SCALED_DEPTH_BIAS = 0.0f;
inline constexpr uint32_t DEFAULT_MAX_ANISOTROPY = 16;
inline constexpr float DEFAULT_MIP_LOD_BIAS = 0.0f;
inline constexpr uint32_t DEFAULT_RENDER_TARGET_ARRAY_INDEX = 0;
inline constexpr uint32_t DEFAULT_SAMPLE_MASK = 0xffffffffu;
inline constexpr uint32_t DEFAULT_SCISSOR_STARTX = 0;
inline constexpr uint32_t DEFAULT_SCISSOR_STARTY = 0;
inline constexpr uint32_t DEFAULT_SCISSOR_ENDX = 0;
inline constexpr uint32_t DEFAULT_SCISSOR_ENDY = 0;
inline constexpr uint32_t DEFAULT_STENCIL_READ_MASK = 0xff;
inline constexpr uint32_t DEFAULT_STENCIL_WRITE_MASK = 0xff;
inline constexpr uint32_t DEFAULT_STENCIL_REFERENCE = 0;
inline constexpr uint32_t DEFAULT_VIEWPORT_AND_SCISSORRECT_INDEX = 0;
inline constexpr uint32_t DEFAULT_VIEWPORT_TOPLEFTX = 0;
inline constexpr uint32_t DEFAULT_VIEWPORT_TOPLEFTY = 0;
inline constexpr uint32_t DEFAULT_VIEWPORT_WIDTH = 0;
inline constexpr uint32_t DEFAULT_VIEWPORT_HEIGHT = 0;
inline constexpr float DEFAULT_VIEWPORT_MIN_DEPTH = 0.0f;
inline constexpr float DEFAULT_VIEWPORT_MAX_DEPTH = 0.0f;

inline constexpr uint32_t MAX_MAXANISOTROPY = 16;
inline constexpr uint32_t MIN_MAXANISOTROPY = 0;
inline constexpr uint32_t REQ_MAXANISOTROPY = 16;
inline constexpr float MIP_LOD_BIAS_MAX = 15.99f;
inline constexpr float MIP_LOD_BIAS_MIN = -16.0f;
inline constexpr int32_t VIEWPORT_BOUNDS_MAX = 32767;
inline constexpr int32_t VIEWPORT_BOUNDS_MIN = -32768;
inline constexpr uint32_t CS_THREAD_GROUP_MAX_THREADS_PER_GROUP = 1024;
inline constexpr uint32_t CS_THREAD_GROUP_MAX_X = 1024;
inline constexpr uint32_t CS_THREAD_GROUP_MAX_Y = 1024;
inline constexpr uint32_t CS_THREAD_GROUP_MAX_Z = 64;
inline constexpr uint32_t CS_DISPATCH_MAX_THREAD_GROUPS_PER_DIMENSION = 65535;
inline constexpr uint32_t COMMONSHADER_CONSTANT_BUFFER_ELEMENT_COUNT = 4096;  // float4s per cbuffer
inline constexpr uint32_t REQ_CONSTANT_BUFFER_ELEMENT_COUNT = 4096;

// ---- the D3D11_DEFAULT tag --------------------------------------------------------------------

struct CDEFAULT {};
inline constexpr CDEFAULT DEFAULT{};

// ---- state descriptions ------------------------------------------------------------------------

struct CRECT : RECT {
  CRECT() = default;
  explicit CRECT(const RECT& o) : RECT(o) {}
  explicit CRECT(int32_t Left, int32_t Top, int32_t Right, int32_t Bottom) {
    left = Left;
    top = Top;
    right = Right;
    bottom = Bottom;
  }
};

// D3D11 takes LONG coordinates for the UINT fields; so does this.
struct CBOX : BOX {
  CBOX() = default;
  explicit CBOX(const BOX& o) : BOX(o) {}
  explicit CBOX(int32_t Left, int32_t Top, int32_t Front, int32_t Right, int32_t Bottom, int32_t Back) {
    left = uint32_t(Left);
    top = uint32_t(Top);
    front = uint32_t(Front);
    right = uint32_t(Right);
    bottom = uint32_t(Bottom);
    back = uint32_t(Back);
  }
};

struct CDEPTH_STENCIL_DESC : DEPTH_STENCIL_DESC {
  CDEPTH_STENCIL_DESC() = default;
  explicit CDEPTH_STENCIL_DESC(const DEPTH_STENCIL_DESC& o) : DEPTH_STENCIL_DESC(o) {}
  explicit CDEPTH_STENCIL_DESC(CDEFAULT) {
    DepthEnable = true;
    DepthWriteMask = DEPTH_WRITE_MASK_ALL;
    DepthFunc = COMPARISON_LESS;
    StencilEnable = false;
    StencilReadMask = DEFAULT_STENCIL_READ_MASK;
    StencilWriteMask = DEFAULT_STENCIL_WRITE_MASK;
    FrontFace = BackFace = {STENCIL_OP_KEEP, STENCIL_OP_KEEP, STENCIL_OP_KEEP, COMPARISON_ALWAYS};
  }
  explicit CDEPTH_STENCIL_DESC(bool depthEnable, DEPTH_WRITE_MASK depthWriteMask, COMPARISON_FUNC depthFunc, bool stencilEnable,
                               uint8_t stencilReadMask, uint8_t stencilWriteMask, STENCIL_OP frontStencilFailOp,
                               STENCIL_OP frontStencilDepthFailOp, STENCIL_OP frontStencilPassOp, COMPARISON_FUNC frontStencilFunc,
                               STENCIL_OP backStencilFailOp, STENCIL_OP backStencilDepthFailOp, STENCIL_OP backStencilPassOp,
                               COMPARISON_FUNC backStencilFunc) {
    DepthEnable = depthEnable;
    DepthWriteMask = depthWriteMask;
    DepthFunc = depthFunc;
    StencilEnable = stencilEnable;
    StencilReadMask = stencilReadMask;
    StencilWriteMask = stencilWriteMask;
    FrontFace = {frontStencilFailOp, frontStencilDepthFailOp, frontStencilPassOp, frontStencilFunc};
    BackFace = {backStencilFailOp, backStencilDepthFailOp, backStencilPassOp, backStencilFunc};
  }
};

struct CBLEND_DESC : BLEND_DESC {
  CBLEND_DESC() = default;
  explicit CBLEND_DESC(const BLEND_DESC& o) : BLEND_DESC(o) {}
  explicit CBLEND_DESC(CDEFAULT) {
    AlphaToCoverageEnable = false;
    IndependentBlendEnable = false;
    for (RENDER_TARGET_BLEND_DESC& rt : RenderTarget)
      rt = {false, BLEND_ONE, BLEND_ZERO, BLEND_OP_ADD, BLEND_ONE, BLEND_ZERO, BLEND_OP_ADD, COLOR_WRITE_ENABLE_ALL};
  }
};

struct CRASTERIZER_DESC : RASTERIZER_DESC {
  CRASTERIZER_DESC() = default;
  explicit CRASTERIZER_DESC(const RASTERIZER_DESC& o) : RASTERIZER_DESC(o) {}
  explicit CRASTERIZER_DESC(CDEFAULT)
      : CRASTERIZER_DESC(FILL_SOLID, CULL_BACK, false, DEFAULT_DEPTH_BIAS, DEFAULT_DEPTH_BIAS_CLAMP, DEFAULT_SLOPE_SCALED_DEPTH_BIAS,
                         true, false, false, false) {}
  explicit CRASTERIZER_DESC(FILL_MODE fillMode, CULL_MODE cullMode, bool frontCounterClockwise, int32_t depthBias, float depthBiasClamp,
                            float slopeScaledDepthBias, bool depthClipEnable, bool scissorEnable, bool multisampleEnable,
                            bool antialiasedLineEnable) {
    FillMode = fillMode;
    CullMode = cullMode;
    FrontCounterClockwise = frontCounterClockwise;
    DepthBias = depthBias;
    DepthBiasClamp = depthBiasClamp;
    SlopeScaledDepthBias = slopeScaledDepthBias;
    DepthClipEnable = depthClipEnable;
    ScissorEnable = scissorEnable;
    MultisampleEnable = multisampleEnable;
    AntialiasedLineEnable = antialiasedLineEnable;
  }
};

struct CSAMPLER_DESC : SAMPLER_DESC {
  CSAMPLER_DESC() = default;
  explicit CSAMPLER_DESC(const SAMPLER_DESC& o) : SAMPLER_DESC(o) {}
  explicit CSAMPLER_DESC(CDEFAULT)
      : CSAMPLER_DESC(FILTER_MIN_MAG_MIP_LINEAR, TEXTURE_ADDRESS_CLAMP, TEXTURE_ADDRESS_CLAMP, TEXTURE_ADDRESS_CLAMP, 0.0f, 1,
                      COMPARISON_NEVER, nullptr, -FLOAT32_MAX, FLOAT32_MAX) {}
  // borderColor: 4 floats (RGBA), or null for opaque white as D3D11.
  explicit CSAMPLER_DESC(FILTER filter, TEXTURE_ADDRESS_MODE addressU, TEXTURE_ADDRESS_MODE addressV, TEXTURE_ADDRESS_MODE addressW,
                         float mipLODBias, uint32_t maxAnisotropy, COMPARISON_FUNC comparisonFunc, const float* borderColor, float minLOD,
                         float maxLOD) {
    static constexpr float kWhite[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    if (!borderColor) borderColor = kWhite;
    Filter = filter;
    AddressU = addressU;
    AddressV = addressV;
    AddressW = addressW;
    MipLODBias = mipLODBias;
    MaxAnisotropy = maxAnisotropy;
    ComparisonFunc = comparisonFunc;
    for (int i = 0; i < 4; ++i) BorderColor[i] = borderColor[i];
    MinLOD = minLOD;
    MaxLOD = maxLOD;
  }
};

struct CQUERY_DESC : QUERY_DESC {
  CQUERY_DESC() = default;
  explicit CQUERY_DESC(const QUERY_DESC& o) : QUERY_DESC(o) {}
  explicit CQUERY_DESC(QUERY query, uint32_t miscFlags = 0) {
    Query = query;
    MiscFlags = miscFlags;
  }
};

// ---- resource descriptions ---------------------------------------------------------------------

struct CBUFFER_DESC : BUFFER_DESC {
  CBUFFER_DESC() = default;
  explicit CBUFFER_DESC(const BUFFER_DESC& o) : BUFFER_DESC(o) {}
  explicit CBUFFER_DESC(uint32_t byteWidth, uint32_t bindFlags, USAGE usage = USAGE_DEFAULT, uint32_t cpuaccessFlags = 0,
                        uint32_t miscFlags = 0, uint32_t structureByteStride = 0) {
    ByteWidth = byteWidth;
    Usage = usage;
    BindFlags = bindFlags;
    CPUAccessFlags = cpuaccessFlags;
    MiscFlags = miscFlags;
    StructureByteStride = structureByteStride;
  }
};

// mipLevels = 0: the full chain, as in D3D11.
struct CTEXTURE1D_DESC : TEXTURE1D_DESC {
  CTEXTURE1D_DESC() = default;
  explicit CTEXTURE1D_DESC(const TEXTURE1D_DESC& o) : TEXTURE1D_DESC(o) {}
  explicit CTEXTURE1D_DESC(FORMAT format, uint32_t width, uint32_t arraySize = 1, uint32_t mipLevels = 0,
                           uint32_t bindFlags = BIND_SHADER_RESOURCE, USAGE usage = USAGE_DEFAULT, uint32_t cpuaccessFlags = 0,
                           uint32_t miscFlags = 0) {
    Width = width;
    MipLevels = mipLevels;
    ArraySize = arraySize;
    Format = format;
    Usage = usage;
    BindFlags = bindFlags;
    CPUAccessFlags = cpuaccessFlags;
    MiscFlags = miscFlags;
  }
};

struct CTEXTURE2D_DESC : TEXTURE2D_DESC {
  CTEXTURE2D_DESC() = default;
  explicit CTEXTURE2D_DESC(const TEXTURE2D_DESC& o) : TEXTURE2D_DESC(o) {}
  explicit CTEXTURE2D_DESC(FORMAT format, uint32_t width, uint32_t height, uint32_t arraySize = 1, uint32_t mipLevels = 0,
                           uint32_t bindFlags = BIND_SHADER_RESOURCE, USAGE usage = USAGE_DEFAULT, uint32_t cpuaccessFlags = 0,
                           uint32_t sampleCount = 1, uint32_t sampleQuality = 0, uint32_t miscFlags = 0) {
    Width = width;
    Height = height;
    MipLevels = mipLevels;
    ArraySize = arraySize;
    Format = format;
    SampleDesc = {sampleCount, sampleQuality};
    Usage = usage;
    BindFlags = bindFlags;
    CPUAccessFlags = cpuaccessFlags;
    MiscFlags = miscFlags;
  }
};

struct CTEXTURE3D_DESC : TEXTURE3D_DESC {
  CTEXTURE3D_DESC() = default;
  explicit CTEXTURE3D_DESC(const TEXTURE3D_DESC& o) : TEXTURE3D_DESC(o) {}
  explicit CTEXTURE3D_DESC(FORMAT format, uint32_t width, uint32_t height, uint32_t depth, uint32_t mipLevels = 0,
                           uint32_t bindFlags = BIND_SHADER_RESOURCE, USAGE usage = USAGE_DEFAULT, uint32_t cpuaccessFlags = 0,
                           uint32_t miscFlags = 0) {
    Width = width;
    Height = height;
    Depth = depth;
    MipLevels = mipLevels;
    Format = format;
    Usage = usage;
    BindFlags = bindFlags;
    CPUAccessFlags = cpuaccessFlags;
    MiscFlags = miscFlags;
  }
};

// ---- view descriptions -------------------------------------------------------------------------
// The dimension-first constructors give the view-dependent arguments D3D11's double meanings
// (for buffers mostDetailedMip is FirstElement and mipLevels NumElements, ...). The resource
// constructors fill FORMAT_UNKNOWN and uint32_t(-1) ("the rest") from the resource's desc, reading
// it only when one of them is given, as D3D11's do.

inline constexpr uint32_t kRest_ = uint32_t(-1);

struct CSHADER_RESOURCE_VIEW_DESC : SHADER_RESOURCE_VIEW_DESC {
  CSHADER_RESOURCE_VIEW_DESC() = default;
  explicit CSHADER_RESOURCE_VIEW_DESC(const SHADER_RESOURCE_VIEW_DESC& o) : SHADER_RESOURCE_VIEW_DESC(o) {}
  // firstArraySlice: First2DArrayFace and arraySize: NumCubes for cube arrays; flags: BUFFEREX.
  explicit CSHADER_RESOURCE_VIEW_DESC(SRV_DIMENSION viewDimension, FORMAT format = FORMAT_UNKNOWN, uint32_t mostDetailedMip = 0,
                                      uint32_t mipLevels = kRest_, uint32_t firstArraySlice = 0, uint32_t arraySize = kRest_,
                                      uint32_t flags = 0) {
    Fill_(viewDimension, format, mostDetailedMip, mipLevels, firstArraySlice, arraySize, flags);
  }
  explicit CSHADER_RESOURCE_VIEW_DESC(sp::Buffer*, FORMAT format, uint32_t firstElement, uint32_t numElements, uint32_t flags = 0) {
    Fill_(SRV_DIMENSION_BUFFEREX, format, firstElement, numElements, 0, 0, flags);
  }
  explicit CSHADER_RESOURCE_VIEW_DESC(sp::Texture1D* tex, SRV_DIMENSION viewDimension, FORMAT format = FORMAT_UNKNOWN,
                                      uint32_t mostDetailedMip = 0, uint32_t mipLevels = kRest_, uint32_t firstArraySlice = 0,
                                      uint32_t arraySize = kRest_) {
    if (format == FORMAT_UNKNOWN || mipLevels == kRest_ || (arraySize == kRest_ && viewDimension == SRV_DIMENSION_TEXTURE1DARRAY)) {
      TEXTURE1D_DESC t = tex->GetDesc();
      if (format == FORMAT_UNKNOWN) format = t.Format;
      if (mipLevels == kRest_) mipLevels = t.MipLevels - mostDetailedMip;
      if (arraySize == kRest_) arraySize = t.ArraySize - firstArraySlice;
    }
    Fill_(viewDimension, format, mostDetailedMip, mipLevels, firstArraySlice, arraySize, 0);
  }
  explicit CSHADER_RESOURCE_VIEW_DESC(sp::Texture2D* tex, SRV_DIMENSION viewDimension, FORMAT format = FORMAT_UNKNOWN,
                                      uint32_t mostDetailedMip = 0, uint32_t mipLevels = kRest_, uint32_t firstArraySlice = 0,
                                      uint32_t arraySize = kRest_) {
    bool ms = viewDimension == SRV_DIMENSION_TEXTURE2DMS || viewDimension == SRV_DIMENSION_TEXTURE2DMSARRAY;
    bool arrayed = viewDimension == SRV_DIMENSION_TEXTURE2DARRAY || viewDimension == SRV_DIMENSION_TEXTURE2DMSARRAY ||
                   viewDimension == SRV_DIMENSION_TEXTURECUBEARRAY;
    if (format == FORMAT_UNKNOWN || (mipLevels == kRest_ && !ms) || (arraySize == kRest_ && arrayed)) {
      TEXTURE2D_DESC t = tex->GetDesc();
      if (format == FORMAT_UNKNOWN) format = t.Format;
      if (mipLevels == kRest_) mipLevels = t.MipLevels - mostDetailedMip;
      if (arraySize == kRest_) {
        arraySize = t.ArraySize - firstArraySlice;
        if (viewDimension == SRV_DIMENSION_TEXTURECUBEARRAY) arraySize /= 6;
      }
    }
    Fill_(viewDimension, format, mostDetailedMip, mipLevels, firstArraySlice, arraySize, 0);
  }
  explicit CSHADER_RESOURCE_VIEW_DESC(sp::Texture3D* tex, FORMAT format = FORMAT_UNKNOWN, uint32_t mostDetailedMip = 0,
                                      uint32_t mipLevels = kRest_) {
    if (format == FORMAT_UNKNOWN || mipLevels == kRest_) {
      TEXTURE3D_DESC t = tex->GetDesc();
      if (format == FORMAT_UNKNOWN) format = t.Format;
      if (mipLevels == kRest_) mipLevels = t.MipLevels - mostDetailedMip;
    }
    Fill_(SRV_DIMENSION_TEXTURE3D, format, mostDetailedMip, mipLevels, 0, 0, 0);
  }
  template <class T, class... A>
  explicit CSHADER_RESOURCE_VIEW_DESC(const Ref<T>& resource, A... args) : CSHADER_RESOURCE_VIEW_DESC(resource.get(), args...) {}

 private:
  void Fill_(SRV_DIMENSION dim, FORMAT format, uint32_t mip, uint32_t mips, uint32_t first, uint32_t count, uint32_t flags) {
    Format = format;
    ViewDimension = dim;
    switch (dim) {
      case SRV_DIMENSION_BUFFER: Buffer.FirstElement = mip; Buffer.NumElements = mips; break;
      case SRV_DIMENSION_TEXTURE1D: Texture1D = {mip, mips}; break;
      case SRV_DIMENSION_TEXTURE1DARRAY: Texture1DArray = {mip, mips, first, count}; break;
      case SRV_DIMENSION_TEXTURE2D: Texture2D = {mip, mips}; break;
      case SRV_DIMENSION_TEXTURE2DARRAY: Texture2DArray = {mip, mips, first, count}; break;
      case SRV_DIMENSION_TEXTURE2DMS: break;
      case SRV_DIMENSION_TEXTURE2DMSARRAY: Texture2DMSArray = {first, count}; break;
      case SRV_DIMENSION_TEXTURE3D: Texture3D = {mip, mips}; break;
      case SRV_DIMENSION_TEXTURECUBE: TextureCube = {mip, mips}; break;
      case SRV_DIMENSION_TEXTURECUBEARRAY: TextureCubeArray = {mip, mips, first, count}; break;
      case SRV_DIMENSION_BUFFEREX: BufferEx = {mip, mips, flags}; break;
      default: break;
    }
  }
};

struct CRENDER_TARGET_VIEW_DESC : RENDER_TARGET_VIEW_DESC {
  CRENDER_TARGET_VIEW_DESC() = default;
  explicit CRENDER_TARGET_VIEW_DESC(const RENDER_TARGET_VIEW_DESC& o) : RENDER_TARGET_VIEW_DESC(o) {}
  // mipSlice: FirstElement for buffers; firstArraySlice: NumElements for buffers, FirstWSlice for
  // 3D; arraySize: WSize for 3D.
  explicit CRENDER_TARGET_VIEW_DESC(RTV_DIMENSION viewDimension, FORMAT format = FORMAT_UNKNOWN, uint32_t mipSlice = 0,
                                    uint32_t firstArraySlice = 0, uint32_t arraySize = kRest_) {
    Fill_(viewDimension, format, mipSlice, firstArraySlice, arraySize);
  }
  explicit CRENDER_TARGET_VIEW_DESC(sp::Buffer*, FORMAT format, uint32_t firstElement, uint32_t numElements) {
    Fill_(RTV_DIMENSION_BUFFER, format, firstElement, numElements, 0);
  }
  explicit CRENDER_TARGET_VIEW_DESC(sp::Texture1D* tex, RTV_DIMENSION viewDimension, FORMAT format = FORMAT_UNKNOWN, uint32_t mipSlice = 0,
                                    uint32_t firstArraySlice = 0, uint32_t arraySize = kRest_) {
    if (format == FORMAT_UNKNOWN || (arraySize == kRest_ && viewDimension == RTV_DIMENSION_TEXTURE1DARRAY)) {
      TEXTURE1D_DESC t = tex->GetDesc();
      if (format == FORMAT_UNKNOWN) format = t.Format;
      if (arraySize == kRest_) arraySize = t.ArraySize - firstArraySlice;
    }
    Fill_(viewDimension, format, mipSlice, firstArraySlice, arraySize);
  }
  explicit CRENDER_TARGET_VIEW_DESC(sp::Texture2D* tex, RTV_DIMENSION viewDimension, FORMAT format = FORMAT_UNKNOWN, uint32_t mipSlice = 0,
                                    uint32_t firstArraySlice = 0, uint32_t arraySize = kRest_) {
    bool arrayed = viewDimension == RTV_DIMENSION_TEXTURE2DARRAY || viewDimension == RTV_DIMENSION_TEXTURE2DMSARRAY;
    if (format == FORMAT_UNKNOWN || (arraySize == kRest_ && arrayed)) {
      TEXTURE2D_DESC t = tex->GetDesc();
      if (format == FORMAT_UNKNOWN) format = t.Format;
      if (arraySize == kRest_) arraySize = t.ArraySize - firstArraySlice;
    }
    Fill_(viewDimension, format, mipSlice, firstArraySlice, arraySize);
  }
  explicit CRENDER_TARGET_VIEW_DESC(sp::Texture3D* tex, FORMAT format = FORMAT_UNKNOWN, uint32_t mipSlice = 0, uint32_t firstWSlice = 0,
                                    uint32_t wSize = kRest_) {
    if (format == FORMAT_UNKNOWN || wSize == kRest_) {
      TEXTURE3D_DESC t = tex->GetDesc();
      if (format == FORMAT_UNKNOWN) format = t.Format;
      if (wSize == kRest_) wSize = t.Depth - firstWSlice;
    }
    Fill_(RTV_DIMENSION_TEXTURE3D, format, mipSlice, firstWSlice, wSize);
  }
  template <class T, class... A>
  explicit CRENDER_TARGET_VIEW_DESC(const Ref<T>& resource, A... args) : CRENDER_TARGET_VIEW_DESC(resource.get(), args...) {}

 private:
  void Fill_(RTV_DIMENSION dim, FORMAT format, uint32_t mip, uint32_t first, uint32_t count) {
    Format = format;
    ViewDimension = dim;
    switch (dim) {
      case RTV_DIMENSION_BUFFER: Buffer.FirstElement = mip; Buffer.NumElements = first; break;
      case RTV_DIMENSION_TEXTURE1D: Texture1D = {mip}; break;
      case RTV_DIMENSION_TEXTURE1DARRAY: Texture1DArray = {mip, first, count}; break;
      case RTV_DIMENSION_TEXTURE2D: Texture2D = {mip}; break;
      case RTV_DIMENSION_TEXTURE2DARRAY: Texture2DArray = {mip, first, count}; break;
      case RTV_DIMENSION_TEXTURE2DMS: break;
      case RTV_DIMENSION_TEXTURE2DMSARRAY: Texture2DMSArray = {first, count}; break;
      case RTV_DIMENSION_TEXTURE3D: Texture3D = {mip, first, count}; break;
      default: break;
    }
  }
};

struct CDEPTH_STENCIL_VIEW_DESC : DEPTH_STENCIL_VIEW_DESC {
  CDEPTH_STENCIL_VIEW_DESC() = default;
  explicit CDEPTH_STENCIL_VIEW_DESC(const DEPTH_STENCIL_VIEW_DESC& o) : DEPTH_STENCIL_VIEW_DESC(o) {}
  explicit CDEPTH_STENCIL_VIEW_DESC(DSV_DIMENSION viewDimension, FORMAT format = FORMAT_UNKNOWN, uint32_t mipSlice = 0,
                                    uint32_t firstArraySlice = 0, uint32_t arraySize = kRest_, uint32_t flags = 0) {
    Fill_(viewDimension, format, mipSlice, firstArraySlice, arraySize, flags);
  }
  explicit CDEPTH_STENCIL_VIEW_DESC(sp::Texture1D* tex, DSV_DIMENSION viewDimension, FORMAT format = FORMAT_UNKNOWN, uint32_t mipSlice = 0,
                                    uint32_t firstArraySlice = 0, uint32_t arraySize = kRest_, uint32_t flags = 0) {
    if (format == FORMAT_UNKNOWN || (arraySize == kRest_ && viewDimension == DSV_DIMENSION_TEXTURE1DARRAY)) {
      TEXTURE1D_DESC t = tex->GetDesc();
      if (format == FORMAT_UNKNOWN) format = t.Format;
      if (arraySize == kRest_) arraySize = t.ArraySize - firstArraySlice;
    }
    Fill_(viewDimension, format, mipSlice, firstArraySlice, arraySize, flags);
  }
  explicit CDEPTH_STENCIL_VIEW_DESC(sp::Texture2D* tex, DSV_DIMENSION viewDimension, FORMAT format = FORMAT_UNKNOWN, uint32_t mipSlice = 0,
                                    uint32_t firstArraySlice = 0, uint32_t arraySize = kRest_, uint32_t flags = 0) {
    bool arrayed = viewDimension == DSV_DIMENSION_TEXTURE2DARRAY || viewDimension == DSV_DIMENSION_TEXTURE2DMSARRAY;
    if (format == FORMAT_UNKNOWN || (arraySize == kRest_ && arrayed)) {
      TEXTURE2D_DESC t = tex->GetDesc();
      if (format == FORMAT_UNKNOWN) format = t.Format;
      if (arraySize == kRest_) arraySize = t.ArraySize - firstArraySlice;
    }
    Fill_(viewDimension, format, mipSlice, firstArraySlice, arraySize, flags);
  }
  template <class T, class... A>
  explicit CDEPTH_STENCIL_VIEW_DESC(const Ref<T>& resource, A... args) : CDEPTH_STENCIL_VIEW_DESC(resource.get(), args...) {}

 private:
  void Fill_(DSV_DIMENSION dim, FORMAT format, uint32_t mip, uint32_t first, uint32_t count, uint32_t flags) {
    Format = format;
    ViewDimension = dim;
    Flags = flags;
    switch (dim) {
      case DSV_DIMENSION_TEXTURE1D: Texture1D = {mip}; break;
      case DSV_DIMENSION_TEXTURE1DARRAY: Texture1DArray = {mip, first, count}; break;
      case DSV_DIMENSION_TEXTURE2D: Texture2D = {mip}; break;
      case DSV_DIMENSION_TEXTURE2DARRAY: Texture2DArray = {mip, first, count}; break;
      case DSV_DIMENSION_TEXTURE2DMS: break;
      case DSV_DIMENSION_TEXTURE2DMSARRAY: Texture2DMSArray = {first, count}; break;
      default: break;
    }
  }
};

struct CUNORDERED_ACCESS_VIEW_DESC : UNORDERED_ACCESS_VIEW_DESC {
  CUNORDERED_ACCESS_VIEW_DESC() = default;
  explicit CUNORDERED_ACCESS_VIEW_DESC(const UNORDERED_ACCESS_VIEW_DESC& o) : UNORDERED_ACCESS_VIEW_DESC(o) {}
  // mipSlice: FirstElement for buffers; firstArraySlice: NumElements for buffers, FirstWSlice for
  // 3D; arraySize: WSize for 3D; flags: buffers only.
  explicit CUNORDERED_ACCESS_VIEW_DESC(UAV_DIMENSION viewDimension, FORMAT format = FORMAT_UNKNOWN, uint32_t mipSlice = 0,
                                       uint32_t firstArraySlice = 0, uint32_t arraySize = kRest_, uint32_t flags = 0) {
    Fill_(viewDimension, format, mipSlice, firstArraySlice, arraySize, flags);
  }
  explicit CUNORDERED_ACCESS_VIEW_DESC(sp::Buffer*, FORMAT format, uint32_t firstElement, uint32_t numElements, uint32_t flags = 0) {
    Fill_(UAV_DIMENSION_BUFFER, format, firstElement, numElements, 0, flags);
  }
  explicit CUNORDERED_ACCESS_VIEW_DESC(sp::Texture1D* tex, UAV_DIMENSION viewDimension, FORMAT format = FORMAT_UNKNOWN, uint32_t mipSlice = 0,
                                       uint32_t firstArraySlice = 0, uint32_t arraySize = kRest_) {
    if (format == FORMAT_UNKNOWN || (arraySize == kRest_ && viewDimension == UAV_DIMENSION_TEXTURE1DARRAY)) {
      TEXTURE1D_DESC t = tex->GetDesc();
      if (format == FORMAT_UNKNOWN) format = t.Format;
      if (arraySize == kRest_) arraySize = t.ArraySize - firstArraySlice;
    }
    Fill_(viewDimension, format, mipSlice, firstArraySlice, arraySize, 0);
  }
  explicit CUNORDERED_ACCESS_VIEW_DESC(sp::Texture2D* tex, UAV_DIMENSION viewDimension, FORMAT format = FORMAT_UNKNOWN, uint32_t mipSlice = 0,
                                       uint32_t firstArraySlice = 0, uint32_t arraySize = kRest_) {
    if (format == FORMAT_UNKNOWN || (arraySize == kRest_ && viewDimension == UAV_DIMENSION_TEXTURE2DARRAY)) {
      TEXTURE2D_DESC t = tex->GetDesc();
      if (format == FORMAT_UNKNOWN) format = t.Format;
      if (arraySize == kRest_) arraySize = t.ArraySize - firstArraySlice;
    }
    Fill_(viewDimension, format, mipSlice, firstArraySlice, arraySize, 0);
  }
  explicit CUNORDERED_ACCESS_VIEW_DESC(sp::Texture3D* tex, FORMAT format = FORMAT_UNKNOWN, uint32_t mipSlice = 0, uint32_t firstWSlice = 0,
                                       uint32_t wSize = kRest_) {
    if (format == FORMAT_UNKNOWN || wSize == kRest_) {
      TEXTURE3D_DESC t = tex->GetDesc();
      if (format == FORMAT_UNKNOWN) format = t.Format;
      if (wSize == kRest_) wSize = t.Depth - firstWSlice;
    }
    Fill_(UAV_DIMENSION_TEXTURE3D, format, mipSlice, firstWSlice, wSize, 0);
  }
  template <class T, class... A>
  explicit CUNORDERED_ACCESS_VIEW_DESC(const Ref<T>& resource, A... args) : CUNORDERED_ACCESS_VIEW_DESC(resource.get(), args...) {}

 private:
  void Fill_(UAV_DIMENSION dim, FORMAT format, uint32_t mip, uint32_t first, uint32_t count, uint32_t flags) {
    Format = format;
    ViewDimension = dim;
    switch (dim) {
      case UAV_DIMENSION_BUFFER: Buffer = {mip, first, flags}; break;
      case UAV_DIMENSION_TEXTURE1D: Texture1D = {mip}; break;
      case UAV_DIMENSION_TEXTURE1DARRAY: Texture1DArray = {mip, first, count}; break;
      case UAV_DIMENSION_TEXTURE2D: Texture2D = {mip}; break;
      case UAV_DIMENSION_TEXTURE2DARRAY: Texture2DArray = {mip, first, count}; break;
      case UAV_DIMENSION_TEXTURE3D: Texture3D = {mip, first, count}; break;
      default: break;
    }
  }
};

// ---- viewport ----------------------------------------------------------------------------------

// The resource constructors cover the mip level the render-target view selects, from the given
// top-left corner to the far edge.
struct CVIEWPORT : VIEWPORT {
  CVIEWPORT() = default;
  explicit CVIEWPORT(const VIEWPORT& o) : VIEWPORT(o) {}
  explicit CVIEWPORT(float topLeftX, float topLeftY, float width, float height, float minDepth = MIN_DEPTH, float maxDepth = MAX_DEPTH) {
    TopLeftX = topLeftX;
    TopLeftY = topLeftY;
    Width = width;
    Height = height;
    MinDepth = minDepth;
    MaxDepth = maxDepth;
  }
  explicit CVIEWPORT(Buffer*, RenderTargetView* rtv, float topLeftX = 0.0f, float minDepth = MIN_DEPTH, float maxDepth = MAX_DEPTH) {
    const RENDER_TARGET_VIEW_DESC& d = rtv->GetDesc();
    uint32_t elements = d.ViewDimension == RTV_DIMENSION_BUFFER ? d.Buffer.NumElements : 0;
    *this = CVIEWPORT(topLeftX, 0.0f, float(elements) - topLeftX, 1.0f, minDepth, maxDepth);
  }
  explicit CVIEWPORT(Texture1D* tex, RenderTargetView* rtv, float topLeftX = 0.0f, float minDepth = MIN_DEPTH, float maxDepth = MAX_DEPTH) {
    const RENDER_TARGET_VIEW_DESC& d = rtv->GetDesc();
    uint32_t mip = d.ViewDimension == RTV_DIMENSION_TEXTURE1D        ? d.Texture1D.MipSlice
                   : d.ViewDimension == RTV_DIMENSION_TEXTURE1DARRAY ? d.Texture1DArray.MipSlice
                                                                     : 0;
    *this = CVIEWPORT(topLeftX, 0.0f, float(MipExtent_(tex->GetDesc().Width, mip)) - topLeftX, 1.0f, minDepth, maxDepth);
  }
  explicit CVIEWPORT(Texture2D* tex, RenderTargetView* rtv, float topLeftX = 0.0f, float topLeftY = 0.0f, float minDepth = MIN_DEPTH,
                     float maxDepth = MAX_DEPTH) {
    const RENDER_TARGET_VIEW_DESC& d = rtv->GetDesc();
    uint32_t mip = d.ViewDimension == RTV_DIMENSION_TEXTURE2D        ? d.Texture2D.MipSlice
                   : d.ViewDimension == RTV_DIMENSION_TEXTURE2DARRAY ? d.Texture2DArray.MipSlice
                                                                     : 0;  // MS: one level
    TEXTURE2D_DESC t = tex->GetDesc();
    *this = CVIEWPORT(topLeftX, topLeftY, float(MipExtent_(t.Width, mip)) - topLeftX, float(MipExtent_(t.Height, mip)) - topLeftY,
                      minDepth, maxDepth);
  }
  explicit CVIEWPORT(Texture3D* tex, RenderTargetView* rtv, float topLeftX = 0.0f, float topLeftY = 0.0f, float minDepth = MIN_DEPTH,
                     float maxDepth = MAX_DEPTH) {
    const RENDER_TARGET_VIEW_DESC& d = rtv->GetDesc();
    uint32_t mip = d.ViewDimension == RTV_DIMENSION_TEXTURE3D ? d.Texture3D.MipSlice : 0;
    TEXTURE3D_DESC t = tex->GetDesc();
    *this = CVIEWPORT(topLeftX, topLeftY, float(MipExtent_(t.Width, mip)) - topLeftX, float(MipExtent_(t.Height, mip)) - topLeftY,
                      minDepth, maxDepth);
  }
  template <class T, class... A>
  explicit CVIEWPORT(const Ref<T>& resource, const Ref<RenderTargetView>& rtv, A... args) : CVIEWPORT(resource.get(), rtv.get(), args...) {}

 private:
  static uint32_t MipExtent_(uint32_t size, uint32_t mip) { return size >> mip ? size >> mip : 1; }
};

}  // namespace sp
