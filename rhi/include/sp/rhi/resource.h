// Buffers and textures: D3D11_BUFFER_DESC, D3D11_TEXTURE{1,2,3}D_DESC and their interfaces.
#pragma once
#include <sp/rhi/common.h>
#include <sp/rhi/format.h>

namespace sp {

enum USAGE : uint32_t { USAGE_DEFAULT = 0, USAGE_IMMUTABLE = 1, USAGE_DYNAMIC = 2, USAGE_STAGING = 3 };

enum BIND_FLAG : uint32_t {
  BIND_VERTEX_BUFFER = 0x1,
  BIND_INDEX_BUFFER = 0x2,
  BIND_CONSTANT_BUFFER = 0x4,
  BIND_SHADER_RESOURCE = 0x8,
  BIND_STREAM_OUTPUT = 0x10,
  BIND_RENDER_TARGET = 0x20,
  BIND_DEPTH_STENCIL = 0x40,
  BIND_UNORDERED_ACCESS = 0x80,
};

enum CPU_ACCESS_FLAG : uint32_t { CPU_ACCESS_WRITE = 0x10000, CPU_ACCESS_READ = 0x20000 };

enum RESOURCE_MISC_FLAG : uint32_t {
  RESOURCE_MISC_GENERATE_MIPS = 0x1,
  RESOURCE_MISC_TEXTURECUBE = 0x4,
  RESOURCE_MISC_DRAWINDIRECT_ARGS = 0x10,
  RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS = 0x20,
  RESOURCE_MISC_BUFFER_STRUCTURED = 0x40,
};

enum RESOURCE_DIMENSION : uint32_t {
  RESOURCE_DIMENSION_UNKNOWN = 0,
  RESOURCE_DIMENSION_BUFFER = 1,
  RESOURCE_DIMENSION_TEXTURE1D = 2,
  RESOURCE_DIMENSION_TEXTURE2D = 3,
  RESOURCE_DIMENSION_TEXTURE3D = 4,
};

struct SUBRESOURCE_DATA {
  const void* pSysMem = nullptr;
  uint32_t SysMemPitch = 0;       // bytes between rows (textures)
  uint32_t SysMemSlicePitch = 0;  // bytes between depth slices (3D textures)
};

struct SAMPLE_DESC {
  uint32_t Count = 1;
  uint32_t Quality = 0;
};

struct BUFFER_DESC {
  uint32_t ByteWidth = 0;
  USAGE Usage = USAGE_DEFAULT;
  uint32_t BindFlags = 0;
  uint32_t CPUAccessFlags = 0;
  uint32_t MiscFlags = 0;
  uint32_t StructureByteStride = 0;
};

struct TEXTURE1D_DESC {
  uint32_t Width = 0;
  uint32_t MipLevels = 1;  // 0 = full chain, as in D3D11
  uint32_t ArraySize = 1;
  FORMAT Format = FORMAT_UNKNOWN;
  USAGE Usage = USAGE_DEFAULT;
  uint32_t BindFlags = 0;
  uint32_t CPUAccessFlags = 0;
  uint32_t MiscFlags = 0;
};

struct TEXTURE2D_DESC {
  uint32_t Width = 0;
  uint32_t Height = 0;
  uint32_t MipLevels = 1;  // 0 = full chain
  uint32_t ArraySize = 1;  // 6 * n for cube maps
  FORMAT Format = FORMAT_UNKNOWN;
  SAMPLE_DESC SampleDesc;
  USAGE Usage = USAGE_DEFAULT;
  uint32_t BindFlags = 0;
  uint32_t CPUAccessFlags = 0;
  uint32_t MiscFlags = 0;
};

struct TEXTURE3D_DESC {
  uint32_t Width = 0;
  uint32_t Height = 0;
  uint32_t Depth = 0;
  uint32_t MipLevels = 1;
  FORMAT Format = FORMAT_UNKNOWN;
  USAGE Usage = USAGE_DEFAULT;
  uint32_t BindFlags = 0;
  uint32_t CPUAccessFlags = 0;
  uint32_t MiscFlags = 0;
};

// D3D11 limits (D3D11_REQ_*), enforced identically on both backends.
inline constexpr uint32_t REQ_TEXTURE1D_U_DIMENSION = 16384;
inline constexpr uint32_t REQ_TEXTURE2D_U_OR_V_DIMENSION = 16384;
inline constexpr uint32_t REQ_TEXTURE3D_U_V_OR_W_DIMENSION = 2048;
inline constexpr uint32_t REQ_TEXTURE2D_ARRAY_AXIS_DIMENSION = 2048;
inline constexpr uint32_t REQ_TEXTURECUBE_DIMENSION = 16384;
inline constexpr uint32_t REQ_MIP_LEVELS = 15;
inline constexpr uint32_t REQ_RESOURCE_SIZE_BYTES = 1u << 31;  // generous; D3D11 uses a RAM fraction

// A texture's shape in one form for all dimensions (the backend-neutral core works on this).
struct TextureShape {
  RESOURCE_DIMENSION dimension = RESOURCE_DIMENSION_UNKNOWN;
  uint32_t width = 1, height = 1, depth = 1;
  uint32_t mipLevels = 1, arraySize = 1, sampleCount = 1;
  FORMAT format = FORMAT_UNKNOWN;
  USAGE usage = USAGE_DEFAULT;
  uint32_t bindFlags = 0, cpuAccessFlags = 0, miscFlags = 0;

  bool isCube() const { return (miscFlags & RESOURCE_MISC_TEXTURECUBE) != 0; }
  uint32_t subresourceCount() const { return mipLevels * arraySize; }
  uint32_t mipWidth(uint32_t mip) const { return width >> mip ? width >> mip : 1; }
  uint32_t mipHeight(uint32_t mip) const { return height >> mip ? height >> mip : 1; }
  uint32_t mipDepth(uint32_t mip) const { return depth >> mip ? depth >> mip : 1; }
};

// D3D11CalcSubresource.
inline uint32_t CalcSubresource(uint32_t mipSlice, uint32_t arraySlice, uint32_t mipLevels) {
  return mipSlice + arraySlice * mipLevels;
}

class Resource : public Object {
 public:
  virtual RESOURCE_DIMENSION GetType() const = 0;

 protected:
  friend class Device;
  using Object::Object;
};

class Buffer : public Resource {
 public:
  const BUFFER_DESC& GetDesc() const { return desc_; }
  void GetDesc(BUFFER_DESC* desc) const { *desc = desc_; }  // D3D11's shape
  RESOURCE_DIMENSION GetType() const override { return RESOURCE_DIMENSION_BUFFER; }
  const char* TypeName() const override { return "Buffer"; }

 protected:
  friend class Device;
  Buffer(Device* device, const BUFFER_DESC& desc) : Resource(device), desc_(desc) {}
  std::string DescribeShape() const override;

 private:
  BUFFER_DESC desc_;
};

// Common base of Texture1D/2D/3D so the core can treat textures uniformly.
class Texture : public Resource {
 public:
  const TextureShape& Shape() const { return shape_; }
  RESOURCE_DIMENSION GetType() const override { return shape_.dimension; }

 protected:
  friend class Device;
  Texture(Device* device, const TextureShape& shape) : Resource(device), shape_(shape) {}
  std::string DescribeShape() const override;

 private:
  TextureShape shape_;
};

class Texture1D : public Texture {
 public:
  TEXTURE1D_DESC GetDesc() const;
  void GetDesc(TEXTURE1D_DESC* desc) const { *desc = GetDesc(); }  // D3D11's shape
  const char* TypeName() const override { return "Texture1D"; }

 protected:
  friend class Device;
  using Texture::Texture;
};

class Texture2D : public Texture {
 public:
  TEXTURE2D_DESC GetDesc() const;
  void GetDesc(TEXTURE2D_DESC* desc) const { *desc = GetDesc(); }  // D3D11's shape
  const char* TypeName() const override { return "Texture2D"; }

 protected:
  friend class Device;
  using Texture::Texture;
};

class Texture3D : public Texture {
 public:
  TEXTURE3D_DESC GetDesc() const;
  void GetDesc(TEXTURE3D_DESC* desc) const { *desc = GetDesc(); }  // D3D11's shape
  const char* TypeName() const override { return "Texture3D"; }

 protected:
  friend class Device;
  using Texture::Texture;
};

TextureShape ShapeFromDesc(const TEXTURE1D_DESC& d);
TextureShape ShapeFromDesc(const TEXTURE2D_DESC& d);
TextureShape ShapeFromDesc(const TEXTURE3D_DESC& d);

}  // namespace sp
