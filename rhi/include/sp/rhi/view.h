// The four D3D11 view kinds with D3D11's view descriptions.
#pragma once
#include <sp/rhi/resource.h>

namespace sp {

enum SRV_DIMENSION : uint32_t {
  SRV_DIMENSION_UNKNOWN = 0,
  SRV_DIMENSION_BUFFER = 1,
  SRV_DIMENSION_TEXTURE1D = 2,
  SRV_DIMENSION_TEXTURE1DARRAY = 3,
  SRV_DIMENSION_TEXTURE2D = 4,
  SRV_DIMENSION_TEXTURE2DARRAY = 5,
  SRV_DIMENSION_TEXTURE2DMS = 6,
  SRV_DIMENSION_TEXTURE2DMSARRAY = 7,
  SRV_DIMENSION_TEXTURE3D = 8,
  SRV_DIMENSION_TEXTURECUBE = 9,
  SRV_DIMENSION_TEXTURECUBEARRAY = 10,
  SRV_DIMENSION_BUFFEREX = 11,
};

enum RTV_DIMENSION : uint32_t {
  RTV_DIMENSION_UNKNOWN = 0,
  RTV_DIMENSION_BUFFER = 1,
  RTV_DIMENSION_TEXTURE1D = 2,
  RTV_DIMENSION_TEXTURE1DARRAY = 3,
  RTV_DIMENSION_TEXTURE2D = 4,
  RTV_DIMENSION_TEXTURE2DARRAY = 5,
  RTV_DIMENSION_TEXTURE2DMS = 6,
  RTV_DIMENSION_TEXTURE2DMSARRAY = 7,
  RTV_DIMENSION_TEXTURE3D = 8,
};

enum DSV_DIMENSION : uint32_t {
  DSV_DIMENSION_UNKNOWN = 0,
  DSV_DIMENSION_TEXTURE1D = 1,
  DSV_DIMENSION_TEXTURE1DARRAY = 2,
  DSV_DIMENSION_TEXTURE2D = 3,
  DSV_DIMENSION_TEXTURE2DARRAY = 4,
  DSV_DIMENSION_TEXTURE2DMS = 5,
  DSV_DIMENSION_TEXTURE2DMSARRAY = 6,
};

enum UAV_DIMENSION : uint32_t {
  UAV_DIMENSION_UNKNOWN = 0,
  UAV_DIMENSION_BUFFER = 1,
  UAV_DIMENSION_TEXTURE1D = 2,
  UAV_DIMENSION_TEXTURE1DARRAY = 3,
  UAV_DIMENSION_TEXTURE2D = 4,
  UAV_DIMENSION_TEXTURE2DARRAY = 5,
  UAV_DIMENSION_TEXTURE3D = 8,
};

enum BUFFEREX_SRV_FLAG : uint32_t { BUFFEREX_SRV_FLAG_RAW = 0x1 };
enum DSV_FLAG : uint32_t { DSV_READ_ONLY_DEPTH = 0x1, DSV_READ_ONLY_STENCIL = 0x2 };
enum BUFFER_UAV_FLAG : uint32_t { BUFFER_UAV_FLAG_RAW = 0x1, BUFFER_UAV_FLAG_APPEND = 0x2, BUFFER_UAV_FLAG_COUNTER = 0x4 };

// The members of the view unions are trivial, as in D3D11 (a union of non-trivial members cannot
// be default-constructed): zero them through the desc, not on their own.
// D3D11 names the buffer fields twice (FirstElement/ElementOffset, NumElements/ElementWidth).
struct BUFFER_SRV {
  union { uint32_t FirstElement; uint32_t ElementOffset; };
  union { uint32_t NumElements; uint32_t ElementWidth; };
};
struct BUFFEREX_SRV { uint32_t FirstElement; uint32_t NumElements; uint32_t Flags; };
struct TEX1D_SRV { uint32_t MostDetailedMip; uint32_t MipLevels; };
struct TEX1D_ARRAY_SRV { uint32_t MostDetailedMip; uint32_t MipLevels; uint32_t FirstArraySlice; uint32_t ArraySize; };
struct TEX2D_SRV { uint32_t MostDetailedMip; uint32_t MipLevels; };
struct TEX2D_ARRAY_SRV { uint32_t MostDetailedMip; uint32_t MipLevels; uint32_t FirstArraySlice; uint32_t ArraySize; };
struct TEX2DMS_SRV { uint32_t UnusedField_NothingToDefine; };
struct TEX2DMS_ARRAY_SRV { uint32_t FirstArraySlice; uint32_t ArraySize; };
struct TEX3D_SRV { uint32_t MostDetailedMip; uint32_t MipLevels; };
struct TEXCUBE_SRV { uint32_t MostDetailedMip; uint32_t MipLevels; };
struct TEXCUBE_ARRAY_SRV { uint32_t MostDetailedMip; uint32_t MipLevels; uint32_t First2DArrayFace; uint32_t NumCubes; };

// The view descs are aggregates laid out as D3D11's, so D3D11's brace initialisation works:
//   SHADER_RESOURCE_VIEW_DESC d = { FORMAT_R32_FLOAT, SRV_DIMENSION_TEXTURE2D, 0, 1 };
// fills the union's first words (Buffer.FirstElement/NumElements in D3D11, the same bytes as
// Texture2D.MostDetailedMip/MipLevels). Each union starts with Words_, the whole union as words,
// so that brace initialisation and a default-constructed desc leave every field not given zero,
// whichever union member is read. Words_ is not part of D3D11's interface; don't use it.

// MipLevels = uint32_t(-1) means "all remaining mips", as in D3D11.
struct SHADER_RESOURCE_VIEW_DESC {
  FORMAT Format = FORMAT_UNKNOWN;
  SRV_DIMENSION ViewDimension = SRV_DIMENSION_UNKNOWN;
  union {
    uint32_t Words_[4] = {};
    BUFFER_SRV Buffer;
    TEX1D_SRV Texture1D;
    TEX1D_ARRAY_SRV Texture1DArray;
    TEX2D_SRV Texture2D;
    TEX2D_ARRAY_SRV Texture2DArray;
    TEX2DMS_SRV Texture2DMS;
    TEX2DMS_ARRAY_SRV Texture2DMSArray;
    TEX3D_SRV Texture3D;
    TEXCUBE_SRV TextureCube;
    TEXCUBE_ARRAY_SRV TextureCubeArray;
    BUFFEREX_SRV BufferEx;
  };
};

struct BUFFER_RTV {
  union { uint32_t FirstElement; uint32_t ElementOffset; };
  union { uint32_t NumElements; uint32_t ElementWidth; };
};
struct TEX1D_RTV { uint32_t MipSlice; };
struct TEX1D_ARRAY_RTV { uint32_t MipSlice; uint32_t FirstArraySlice; uint32_t ArraySize; };
struct TEX2D_RTV { uint32_t MipSlice; };
struct TEX2D_ARRAY_RTV { uint32_t MipSlice; uint32_t FirstArraySlice; uint32_t ArraySize; };
struct TEX2DMS_RTV { uint32_t UnusedField_NothingToDefine; };
struct TEX2DMS_ARRAY_RTV { uint32_t FirstArraySlice; uint32_t ArraySize; };
struct TEX3D_RTV { uint32_t MipSlice; uint32_t FirstWSlice; uint32_t WSize; };

struct RENDER_TARGET_VIEW_DESC {
  FORMAT Format = FORMAT_UNKNOWN;
  RTV_DIMENSION ViewDimension = RTV_DIMENSION_UNKNOWN;
  union {
    uint32_t Words_[3] = {};
    BUFFER_RTV Buffer;
    TEX1D_RTV Texture1D;
    TEX1D_ARRAY_RTV Texture1DArray;
    TEX2D_RTV Texture2D;
    TEX2D_ARRAY_RTV Texture2DArray;
    TEX2DMS_RTV Texture2DMS;
    TEX2DMS_ARRAY_RTV Texture2DMSArray;
    TEX3D_RTV Texture3D;
  };
};

struct TEX1D_DSV { uint32_t MipSlice; };
struct TEX1D_ARRAY_DSV { uint32_t MipSlice; uint32_t FirstArraySlice; uint32_t ArraySize; };
struct TEX2D_DSV { uint32_t MipSlice; };
struct TEX2D_ARRAY_DSV { uint32_t MipSlice; uint32_t FirstArraySlice; uint32_t ArraySize; };
struct TEX2DMS_DSV { uint32_t UnusedField_NothingToDefine; };
struct TEX2DMS_ARRAY_DSV { uint32_t FirstArraySlice; uint32_t ArraySize; };

struct DEPTH_STENCIL_VIEW_DESC {
  FORMAT Format = FORMAT_UNKNOWN;
  DSV_DIMENSION ViewDimension = DSV_DIMENSION_UNKNOWN;
  uint32_t Flags = 0;
  union {
    uint32_t Words_[3] = {};
    TEX1D_DSV Texture1D;
    TEX1D_ARRAY_DSV Texture1DArray;
    TEX2D_DSV Texture2D;
    TEX2D_ARRAY_DSV Texture2DArray;
    TEX2DMS_DSV Texture2DMS;
    TEX2DMS_ARRAY_DSV Texture2DMSArray;
  };
};

struct BUFFER_UAV { uint32_t FirstElement; uint32_t NumElements; uint32_t Flags; };
struct TEX1D_UAV { uint32_t MipSlice; };
struct TEX1D_ARRAY_UAV { uint32_t MipSlice; uint32_t FirstArraySlice; uint32_t ArraySize; };
struct TEX2D_UAV { uint32_t MipSlice; };
struct TEX2D_ARRAY_UAV { uint32_t MipSlice; uint32_t FirstArraySlice; uint32_t ArraySize; };
struct TEX3D_UAV { uint32_t MipSlice; uint32_t FirstWSlice; uint32_t WSize; };

struct UNORDERED_ACCESS_VIEW_DESC {
  FORMAT Format = FORMAT_UNKNOWN;
  UAV_DIMENSION ViewDimension = UAV_DIMENSION_UNKNOWN;
  union {
    uint32_t Words_[3] = {};
    BUFFER_UAV Buffer;
    TEX1D_UAV Texture1D;
    TEX1D_ARRAY_UAV Texture1DArray;
    TEX2D_UAV Texture2D;
    TEX2D_ARRAY_UAV Texture2DArray;
    TEX3D_UAV Texture3D;
  };
};

// What a view covers, in one form for all view kinds. Filled by the core when the view is
// created; backends and hazard tracking use it instead of the unions.
struct ViewRange {
  uint32_t firstMip = 0, mipCount = 1;
  uint32_t firstSlice = 0, sliceCount = 1;  // array slices (cube faces count as slices); W for 3D
  uint64_t firstByte = 0, byteCount = 0;    // buffers
  uint32_t elementStride = 0;               // buffers: bytes per element of the view
  bool depth = false, stencil = false;      // aspects (depth textures)

  bool overlaps(const ViewRange& o) const;
};

// What a view is and what it sees, set by the core when it creates the view, so that hazard
// tracking and backends switch on them instead of casting or reading the per-kind unions.
enum class ViewKind : uint8_t { ShaderResource, RenderTarget, DepthStencil, UnorderedAccess };
enum class ViewShape : uint8_t {
  TypedBuffer,
  RawBuffer,         // BUFFEREX_SRV_FLAG_RAW / BUFFER_UAV_FLAG_RAW
  StructuredBuffer,  // a view of a RESOURCE_MISC_BUFFER_STRUCTURED buffer
  Texture1D,
  Texture1DArray,
  Texture2D,
  Texture2DArray,
  Texture2DMS,
  Texture2DMSArray,
  Texture3D,
  TextureCube,
  TextureCubeArray,
};

class View : public Object {
 public:
  Resource* GetResource() const { return resource_.get(); }
  // D3D11's shape: the resource, AddRef'd (COM-style), for the caller to Release.
  void GetResource(Resource** resource) const {
    *resource = resource_.get();
    if (*resource) (*resource)->AddRef();
  }
  const Ref<Resource>& resource() const { return resource_; }
  const ViewRange& Range() const { return range_; }
  FORMAT ViewFormat() const { return format_; }
  ViewKind Kind() const { return kind_; }
  ViewShape Shape() const { return shape_; }
  bool IsBuffer() const { return shape_ <= ViewShape::StructuredBuffer; }

 protected:
  friend class Device;
  View(Device* device, Ref<Resource> resource, const ViewRange& range, FORMAT format, ViewKind kind, ViewShape shape)
      : Object(device), resource_(std::move(resource)), range_(range), format_(format), kind_(kind), shape_(shape) {}
  std::string DescribeShape() const override;

 private:
  Ref<Resource> resource_;
  ViewRange range_;
  FORMAT format_;
  ViewKind kind_;
  ViewShape shape_;
};

class ShaderResourceView : public View {
 public:
  const SHADER_RESOURCE_VIEW_DESC& GetDesc() const { return desc_; }
  void GetDesc(SHADER_RESOURCE_VIEW_DESC* desc) const { *desc = desc_; }  // D3D11's shape
  const char* TypeName() const override { return "ShaderResourceView"; }

 protected:
  friend class Device;
  ShaderResourceView(Device* device, Ref<Resource> resource, const SHADER_RESOURCE_VIEW_DESC& desc, const ViewRange& range, ViewShape shape)
      : View(device, std::move(resource), range, desc.Format, ViewKind::ShaderResource, shape), desc_(desc) {}

 private:
  SHADER_RESOURCE_VIEW_DESC desc_;
};

class RenderTargetView : public View {
 public:
  const RENDER_TARGET_VIEW_DESC& GetDesc() const { return desc_; }
  void GetDesc(RENDER_TARGET_VIEW_DESC* desc) const { *desc = desc_; }  // D3D11's shape
  const char* TypeName() const override { return "RenderTargetView"; }

 protected:
  friend class Device;
  RenderTargetView(Device* device, Ref<Resource> resource, const RENDER_TARGET_VIEW_DESC& desc, const ViewRange& range, ViewShape shape)
      : View(device, std::move(resource), range, desc.Format, ViewKind::RenderTarget, shape), desc_(desc) {}

 private:
  RENDER_TARGET_VIEW_DESC desc_;
};

class DepthStencilView : public View {
 public:
  const DEPTH_STENCIL_VIEW_DESC& GetDesc() const { return desc_; }
  void GetDesc(DEPTH_STENCIL_VIEW_DESC* desc) const { *desc = desc_; }  // D3D11's shape
  const char* TypeName() const override { return "DepthStencilView"; }

 protected:
  friend class Device;
  DepthStencilView(Device* device, Ref<Resource> resource, const DEPTH_STENCIL_VIEW_DESC& desc, const ViewRange& range, ViewShape shape)
      : View(device, std::move(resource), range, desc.Format, ViewKind::DepthStencil, shape), desc_(desc) {}

 private:
  DEPTH_STENCIL_VIEW_DESC desc_;
};

class UnorderedAccessView : public View {
 public:
  const UNORDERED_ACCESS_VIEW_DESC& GetDesc() const { return desc_; }
  void GetDesc(UNORDERED_ACCESS_VIEW_DESC* desc) const { *desc = desc_; }  // D3D11's shape
  const char* TypeName() const override { return "UnorderedAccessView"; }

 protected:
  friend class Device;
  UnorderedAccessView(Device* device, Ref<Resource> resource, const UNORDERED_ACCESS_VIEW_DESC& desc, const ViewRange& range, ViewShape shape)
      : View(device, std::move(resource), range, desc.Format, ViewKind::UnorderedAccess, shape), desc_(desc) {}

 private:
  UNORDERED_ACCESS_VIEW_DESC desc_;
};

}  // namespace sp
