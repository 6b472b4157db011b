// Map/Unmap. DYNAMIC buffers are renamed on WRITE_DISCARD (a fresh range while the GPU still reads
// the old one) and mapped in place for WRITE_NO_OVERWRITE; DYNAMIC textures hand out CPU memory
// uploaded on Unmap; STAGING resources wait only for the GPU work that conflicts with the map
// (reads wait for the last write, writes for the last use), or report "still drawing".
#include <cstring>

#include "vulkan-internal.h"

namespace sp::vk {

void MergePlanes(VkTextureObj& t) {
  const TextureShape& s = t.shape;
  bool d24 = GetFormatInfo(s.format).bytesPerElement == 4;
  for (uint32_t i = 0; i < s.subresourceCount(); ++i) {
    uint32_t mip = detail::SubresourceOf(s, i).mip;
    const VkTextureObj::Sub& sub = t.subs[i];
    uint64_t texels = uint64_t(s.mipWidth(mip)) * s.mipHeight(mip) * s.mipDepth(mip);
    uint8_t* main = t.main.mapped + sub.offset;
    const uint8_t* depth = t.depthPlane.mapped + sub.depthOffset;
    const uint8_t* stencil = t.stencilPlane.mapped + sub.stencilOffset;
    for (uint64_t k = 0; k < texels; ++k) {
      uint32_t dv;
      std::memcpy(&dv, depth + k * 4, 4);
      if (d24) {
        uint32_t v = (dv & 0xffffff) | (uint32_t(stencil[k]) << 24);
        std::memcpy(main + k * 4, &v, 4);
      } else {
        uint64_t v = uint64_t(dv) | (uint64_t(stencil[k]) << 32);
        std::memcpy(main + k * 8, &v, 8);
      }
    }
  }
  t.planesNewer = false;
}

void SplitPlanes(VkTextureObj& t) {
  const TextureShape& s = t.shape;
  bool d24 = GetFormatInfo(s.format).bytesPerElement == 4;
  for (uint32_t i = 0; i < s.subresourceCount(); ++i) {
    uint32_t mip = detail::SubresourceOf(s, i).mip;
    const VkTextureObj::Sub& sub = t.subs[i];
    uint64_t texels = uint64_t(s.mipWidth(mip)) * s.mipHeight(mip) * s.mipDepth(mip);
    const uint8_t* main = t.main.mapped + sub.offset;
    uint8_t* depth = t.depthPlane.mapped + sub.depthOffset;
    uint8_t* stencil = t.stencilPlane.mapped + sub.stencilOffset;
    for (uint64_t k = 0; k < texels; ++k) {
      if (d24) {
        uint32_t v;
        std::memcpy(&v, main + k * 4, 4);
        uint32_t dv = v & 0xffffff;
        std::memcpy(depth + k * 4, &dv, 4);
        stencil[k] = uint8_t(v >> 24);
      } else {
        std::memcpy(depth + k * 4, main + k * 8, 4);
        stencil[k] = main[k * 8 + 4];
      }
    }
  }
}

bool VulkanContext::WaitForMap(TrackedObject& o, MAP type, uint32_t flags) {
  uint64_t need = type == MAP_READ ? o.lastWrite : o.lastUse;
  if (!IsBusy(need)) return true;
  if (flags & MAP_FLAG_DO_NOT_WAIT) {
    if (need >= dev_->recordingSerial) Submit();
    return !IsBusy(need);
  }
  WaitForSerial(need);
  return true;
}

void VulkanContext::Rename(VkBufferObj& b) {
  if (!IsBusy(b.lastUse)) return;
  BufferRange fresh;
  // Versions retire in submission order, so the oldest is the first to become idle.
  if (!b.retired.empty() && b.retired.front().busyUntil <= dev_->completedSerial) {
    fresh = b.retired.front().range;
    b.retired.pop_front();
  }
  // The object's name is built only when a new block may fail: per rename it was a string of ~600
  // instructions (bench-rhi's shadow case renames a cbuffer every draw).
  if (!fresh && (b.ownVkBuffer || !dev_->alloc.SuballocateBuffer(b.range.size, b.kind, &fresh)))
    fresh = dev_->alloc.AllocateBuffer(b.range.size, b.kind, "Map", DescribeObject(b.owner), b.ownVkBuffer);
  b.retired.push_back({b.range, b.lastUse});
  b.range = fresh;
  // What the move invalidates for draws that keep their bindings (KeepDescriptors, BindVertexBuffers).
  // D3D11 never combines BIND_CONSTANT_BUFFER with other flags; dynamic cbuffers move by offset.
  if (b.desc.BindFlags & (BIND_SHADER_RESOURCE | BIND_UNORDERED_ACCESS)) ++viewRenames_;
  if (b.desc.BindFlags & (BIND_VERTEX_BUFFER | BIND_INDEX_BUFFER)) ++vertexRenames_;
  b.state = {};
  b.lastUse = b.lastWrite = 0;
}

bool VulkanContext::MapStaging(VkTextureObj& t, uint32_t sub, MAP type, uint32_t flags, MAPPED_SUBRESOURCE* out) {
  if (!WaitForMap(t, type, flags)) return false;
  if (t.usesPlanes && t.planesNewer) {
    // The planes were written by the GPU; make sure it finished before reading them.
    if (IsBusy(t.lastWrite)) {
      if (flags & MAP_FLAG_DO_NOT_WAIT) return false;
      WaitForSerial(t.lastWrite);
    }
    MergePlanes(t);
  }
  if (t.usesPlanes && type != MAP_READ) {
    if (IsBusy(t.lastUse)) {
      if (flags & MAP_FLAG_DO_NOT_WAIT) return false;
      WaitForSerial(t.lastUse);
    }
    t.pendingSplit = true;
  }
  const VkTextureObj::Sub& s = t.subs[sub];
  out->pData = t.main.mapped + s.offset;
  out->RowPitch = s.rowPitch;
  out->DepthPitch = s.depthPitch;
  return true;
}

bool VulkanContext::Map(Resource* resource, const detail::Subresource& sub, MAP type, uint32_t flags, MAPPED_SUBRESOURCE* out) {
  if (resource->GetType() == RESOURCE_DIMENSION_BUFFER) {
    VkBufferObj& b = BufferOf(resource);
    if (type != MAP_READ) b.contentVersion++;
    if (b.desc.Usage == USAGE_DYNAMIC) {
      if (type == MAP_WRITE_DISCARD) Rename(b);
    } else if (!WaitForMap(b, type, flags)) {
      return false;
    }
    out->pData = b.range.mapped;
    out->RowPitch = out->DepthPitch = b.desc.ByteWidth;
    return true;
  }
  VkTextureObj& t = TextureOf(resource);
  if (t.staging) return MapStaging(t, sub.index, type, flags, out);
  // USAGE_DYNAMIC textures (WRITE_DISCARD only): CPU memory, uploaded in order on Unmap.
  uint32_t row = sub.width * GetFormatInfo(t.shape.format).bytesPerElement;
  std::vector<uint8_t>& scratch = t.mapScratch[sub.index];
  scratch.assign(size_t(row) * sub.height * sub.depth, 0);
  out->pData = scratch.data();
  out->RowPitch = row;
  out->DepthPitch = row * sub.height;
  return true;
}

void VulkanContext::Unmap(Resource* resource, const detail::Subresource& sub) {
  if (resource->GetType() == RESOURCE_DIMENSION_BUFFER) {
    BufferOf(resource).contentVersion++;
    return;
  }
  VkTextureObj& t = TextureOf(resource);
  if (t.staging) {
    if (t.pendingSplit) {
      SplitPlanes(t);
      t.pendingSplit = false;
    }
    return;
  }
  auto it = t.mapScratch.find(sub.index);
  if (it == t.mapScratch.end()) return;
  uint32_t row = sub.width * GetFormatInfo(t.shape.format).bytesPerElement;
  UploadToImage(t, sub, sub.box(), it->second.data(), row, row * sub.height);
  t.mapScratch.erase(it);
}

}  // namespace sp::vk
