// Map and Unmap with D3D11's semantics per usage:
//  - STAGING: persistently mapped memory; Map waits (fence) for the GPU commands that use it.
//  - DYNAMIC buffers: WRITE_DISCARD orphans the storage (draws in flight keep the old one),
//    NO_OVERWRITE maps unsynchronised, in place. Constant buffers are written through their CPU
//    copy; draws read it from the upload ring (see GLBuffer::storageStale).
//  - DYNAMIC textures: CPU memory laid out as D3D maps it, uploaded on Unmap.
#include <cstring>

#include "gl-context.h"

namespace sp::gl {

bool GLContext::Map(Resource* r, const detail::Subresource& sub, MAP type, uint32_t flags, MAPPED_SUBRESOURCE* out) {
  dev_.MakeCurrent();
  const bool doNotWait = (flags & MAP_FLAG_DO_NOT_WAIT) != 0;
  if (r->GetType() == RESOURCE_DIMENSION_BUFFER) {
    GLBuffer& b = GL(static_cast<Buffer*>(r));
    out->RowPitch = out->DepthPitch = b.size;
    if (b.usage == USAGE_STAGING) {
      if (!b.staging.Wait(doNotWait)) return false;
      out->pData = b.staging.ptr;
      return true;
    }
    if (b.constant) {
      if (type != MAP_WRITE_DISCARD) RefreshShadow(b);
      out->pData = b.shadow.data();
      return true;
    }
    if (type == MAP_WRITE_DISCARD) {
      glNamedBufferData(b.name, b.size, nullptr, GL_DYNAMIC_DRAW);
      out->pData = glMapNamedBufferRange(b.name, 0, b.size, GL_MAP_WRITE_BIT | GL_MAP_INVALIDATE_BUFFER_BIT);
    } else {
      out->pData = glMapNamedBufferRange(b.name, 0, b.size, GL_MAP_WRITE_BIT | GL_MAP_UNSYNCHRONIZED_BIT);
    }
    if (!out->pData) ThrowError(ErrorId::DEVICE_API_ERROR, "Map", r->Describe(), "glMapNamedBufferRange failed");
    b.mappedGL = true;
    return true;
  }
  GLTexture& t = GL(static_cast<Texture*>(r));
  if (t.isStaging()) {
    if (!t.staging.Wait(doNotWait)) return false;
    const SubresourceLayout& l = t.subresources[sub.index];
    if (t.glPacked[sub.index]) {
      D24S8ToD3D(reinterpret_cast<uint32_t*>(t.staging.ptr + l.offset), size_t(l.depthPitch) * l.depth / 4);
      t.glPacked[sub.index] = 0;
    }
    out->pData = t.staging.ptr + l.offset;
    out->RowPitch = l.rowPitch;
    out->DepthPitch = l.depthPitch;
    return true;
  }
  // USAGE_DYNAMIC with WRITE_DISCARD (the only way the core lets a dynamic texture be mapped).
  const uint32_t rowPitch = sub.width * GetFormatInfo(t.shape.format).bytesPerElement;
  const uint32_t height = t.shape.dimension == RESOURCE_DIMENSION_TEXTURE1D ? 1 : sub.height;
  std::vector<uint8_t>& data = t.dynamicData[sub.index];
  data.resize(size_t(rowPitch) * height * sub.depth);
  out->pData = data.data();
  out->RowPitch = rowPitch;
  out->DepthPitch = rowPitch * height;
  return true;
}

void GLContext::Unmap(Resource* r, const detail::Subresource& sub) {
  dev_.MakeCurrent();
  if (r->GetType() == RESOURCE_DIMENSION_BUFFER) {
    GLBuffer& b = GL(static_cast<Buffer*>(r));
    if (b.usage != USAGE_DYNAMIC) return;
    if (b.constant) {
      b.shadowStale = false;
      ++b.version;
      b.storageStale = true;  // bound through the upload ring (GLContext::BindUniformBlock)
      return;
    }
    if (b.mappedGL) {
      glUnmapNamedBuffer(b.name);
      b.mappedGL = false;
    }
    return;
  }
  GLTexture& t = GL(static_cast<Texture*>(r));
  if (t.isStaging()) return;  // coherent: the GPU sees CPU writes
  const uint32_t rowPitch = sub.width * GetFormatInfo(t.shape.format).bytesPerElement;
  const uint32_t height = t.shape.dimension == RESOURCE_DIMENSION_TEXTURE1D ? 1 : sub.height;
  UploadRegion(t, sub, 0, 0, 0, sub.width, sub.height, sub.depth, t.dynamicData[sub.index].data(), rowPitch, rowPitch * height);
}

}  // namespace sp::gl
