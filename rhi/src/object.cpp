#include <sp/rhi/device.h>

#include <algorithm>
#include <cstring>
#include <string>

#include "backend.h"

namespace sp {

Object::Object(Device* device) : device_(device), uid_(0) {
  if (device_) {
    std::lock_guard lock(device_->liveMutex_);
    uid_ = device_->nextUid_++;
    device_->live_.insert(this);
  }
}

Object::~Object() {
  backend_.reset();
  if (device_) {
    std::lock_guard lock(device_->liveMutex_);
    device_->live_.erase(this);
  }
}

void Object::SetDebugName(std::string_view name) {
  name_ = std::string(name);
  OnDebugNameChanged();
}

uint32_t Object::AddRef() {
  if (comRefs_++ == 0) comSelf_ = shared_from_this();
  return comRefs_;
}

uint32_t Object::Release() {
  if (comRefs_ == 0)
    throw Error(ErrorId::INVALID_ARGUMENT, "Release", Describe(), "the object holds no COM reference (Release without AddRef, or once too often)");
  if (--comRefs_ > 0) return comRefs_;
  // The last COM reference: drop the self-reference last, since it may destroy this object.
  std::shared_ptr<Object> self = std::move(comSelf_);
  self.reset();
  return 0;
}

HRESULT Object::SetPrivateData(REFGUID guid, uint32_t dataSize, const void* data) {
  if (dataSize && !data) return E_INVALIDARG;
  if (guid == WKPDID_D3DDebugObjectName) {
    const char* text = static_cast<const char*>(data);
    SetDebugName(std::string_view(text ? text : "", text ? strnlen(text, dataSize) : 0));
    return S_OK;
  }
  auto it = std::find_if(privateData_.begin(), privateData_.end(), [&](const auto& e) { return e.first == guid; });
  if (!data) {
    if (it != privateData_.end()) privateData_.erase(it);
    return S_OK;
  }
  const uint8_t* bytes = static_cast<const uint8_t*>(data);
  std::vector<uint8_t> copy(bytes, bytes + dataSize);
  if (it != privateData_.end()) it->second = std::move(copy);
  else privateData_.emplace_back(guid, std::move(copy));
  return S_OK;
}

HRESULT Object::GetPrivateData(REFGUID guid, uint32_t* dataSize, void* data) const {
  if (!dataSize) return E_INVALIDARG;
  std::string_view bytes;
  if (guid == WKPDID_D3DDebugObjectName && !name_.empty()) {
    bytes = name_;
  } else {
    auto it = std::find_if(privateData_.begin(), privateData_.end(), [&](const auto& e) { return e.first == guid; });
    if (it == privateData_.end()) {
      *dataSize = 0;
      return DXGI_ERROR_NOT_FOUND;
    }
    bytes = std::string_view(reinterpret_cast<const char*>(it->second.data()), it->second.size());
  }
  if (!data) {
    *dataSize = uint32_t(bytes.size());
    return S_OK;
  }
  if (*dataSize < bytes.size()) {
    *dataSize = uint32_t(bytes.size());
    return DXGI_ERROR_MORE_DATA;
  }
  std::memcpy(data, bytes.data(), bytes.size());
  *dataSize = uint32_t(bytes.size());
  return S_OK;
}

std::string Object::Describe() const {
  std::string s = TypeName();
  if (!name_.empty()) {
    s += " '" + name_ + "'";
  } else {
    s += " #" + std::to_string(uid_);
  }
  std::string shape = DescribeShape();
  if (!shape.empty()) s += " (" + shape + ")";
  return s;
}

std::string Buffer::DescribeShape() const {
  std::string s = std::to_string(desc_.ByteWidth) + " bytes";
  if (desc_.StructureByteStride) s += ", stride " + std::to_string(desc_.StructureByteStride);
  return s;
}

std::string Texture::DescribeShape() const {
  const TextureShape& t = shape_;
  std::string s = std::to_string(t.width);
  if (t.dimension != RESOURCE_DIMENSION_TEXTURE1D) s += "x" + std::to_string(t.height);
  if (t.dimension == RESOURCE_DIMENSION_TEXTURE3D) s += "x" + std::to_string(t.depth);
  if (t.arraySize > 1) s += (t.isCube() ? ", " + std::to_string(t.arraySize / 6) + " cube" : ", array " + std::to_string(t.arraySize));
  if (t.mipLevels > 1) s += ", " + std::to_string(t.mipLevels) + " mips";
  if (t.sampleCount > 1) s += ", " + std::to_string(t.sampleCount) + "x MSAA";
  s += " ";
  s += FormatName(t.format);
  return s;
}

std::string View::DescribeShape() const {
  std::string s = std::string(FormatName(format_)) + " of " + (resource_ ? resource_->Describe() : "null");
  return s;
}

TEXTURE1D_DESC Texture1D::GetDesc() const {
  const TextureShape& s = Shape();
  TEXTURE1D_DESC d;
  d.Width = s.width;
  d.MipLevels = s.mipLevels;
  d.ArraySize = s.arraySize;
  d.Format = s.format;
  d.Usage = s.usage;
  d.BindFlags = s.bindFlags;
  d.CPUAccessFlags = s.cpuAccessFlags;
  d.MiscFlags = s.miscFlags;
  return d;
}

TEXTURE2D_DESC Texture2D::GetDesc() const {
  const TextureShape& s = Shape();
  TEXTURE2D_DESC d;
  d.Width = s.width;
  d.Height = s.height;
  d.MipLevels = s.mipLevels;
  d.ArraySize = s.arraySize;
  d.Format = s.format;
  d.SampleDesc.Count = s.sampleCount;
  d.Usage = s.usage;
  d.BindFlags = s.bindFlags;
  d.CPUAccessFlags = s.cpuAccessFlags;
  d.MiscFlags = s.miscFlags;
  return d;
}

TEXTURE3D_DESC Texture3D::GetDesc() const {
  const TextureShape& s = Shape();
  TEXTURE3D_DESC d;
  d.Width = s.width;
  d.Height = s.height;
  d.Depth = s.depth;
  d.MipLevels = s.mipLevels;
  d.Format = s.format;
  d.Usage = s.usage;
  d.BindFlags = s.bindFlags;
  d.CPUAccessFlags = s.cpuAccessFlags;
  d.MiscFlags = s.miscFlags;
  return d;
}

TextureShape ShapeFromDesc(const TEXTURE1D_DESC& d) {
  TextureShape s;
  s.dimension = RESOURCE_DIMENSION_TEXTURE1D;
  s.width = d.Width;
  s.mipLevels = d.MipLevels;
  s.arraySize = d.ArraySize;
  s.format = d.Format;
  s.usage = d.Usage;
  s.bindFlags = d.BindFlags;
  s.cpuAccessFlags = d.CPUAccessFlags;
  s.miscFlags = d.MiscFlags;
  return s;
}

TextureShape ShapeFromDesc(const TEXTURE2D_DESC& d) {
  TextureShape s;
  s.dimension = RESOURCE_DIMENSION_TEXTURE2D;
  s.width = d.Width;
  s.height = d.Height;
  s.mipLevels = d.MipLevels;
  s.arraySize = d.ArraySize;
  s.sampleCount = d.SampleDesc.Count;
  s.format = d.Format;
  s.usage = d.Usage;
  s.bindFlags = d.BindFlags;
  s.cpuAccessFlags = d.CPUAccessFlags;
  s.miscFlags = d.MiscFlags;
  return s;
}

TextureShape ShapeFromDesc(const TEXTURE3D_DESC& d) {
  TextureShape s;
  s.dimension = RESOURCE_DIMENSION_TEXTURE3D;
  s.width = d.Width;
  s.height = d.Height;
  s.depth = d.Depth;
  s.mipLevels = d.MipLevels;
  s.format = d.Format;
  s.usage = d.Usage;
  s.bindFlags = d.BindFlags;
  s.cpuAccessFlags = d.CPUAccessFlags;
  s.miscFlags = d.MiscFlags;
  return s;
}

bool ViewRange::overlaps(const ViewRange& o) const {
  if (byteCount || o.byteCount) {
    return firstByte < o.firstByte + o.byteCount && o.firstByte < firstByte + byteCount;
  }
  bool mips = firstMip < o.firstMip + o.mipCount && o.firstMip < firstMip + mipCount;
  bool slices = firstSlice < o.firstSlice + o.sliceCount && o.firstSlice < firstSlice + sliceCount;
  // Depth and stencil planes are separate subresources in D3D11 only for hazard purposes of
  // read-only DSVs; colour textures have neither flag set.
  bool aspects = (!depth && !stencil) || (!o.depth && !o.stencil) || (depth && o.depth) || (stencil && o.stencil);
  return mips && slices && aspects;
}

uint32_t Query::GetDataSize() const {
  switch (desc_.Query) {
    case QUERY_EVENT: return 4;
    case QUERY_OCCLUSION: return 8;
    case QUERY_TIMESTAMP: return 8;
    case QUERY_TIMESTAMP_DISJOINT: return sizeof(QUERY_DATA_TIMESTAMP_DISJOINT);
  }
  return 0;
}

}  // namespace sp
