// Buffers of every D3D11 kind. All are ranges of shared VkBuffers (see vulkan-memory.cpp); the
// usage decides the memory: DEFAULT/IMMUTABLE device-local, DYNAMIC upload memory renamed on
// every WRITE_DISCARD, STAGING host memory (cached when read back).
#include <algorithm>
#include <cstring>

#include "vulkan-internal.h"

namespace sp::vk {

std::unique_ptr<VkBufferObj> CreateBufferObj(VulkanDevice* dev, Buffer& buffer, const SUBRESOURCE_DATA* init) {
  const char* call = "CreateBuffer";
  auto b = std::make_unique<VkBufferObj>();
  b->dev = dev;
  b->owner = &buffer;
  b->desc = buffer.GetDesc();
  const BUFFER_DESC& d = b->desc;
  std::string object = DescribeObject(&buffer);
  switch (d.Usage) {
    case USAGE_DYNAMIC: b->kind = MemoryKind::Upload; break;
    case USAGE_STAGING: b->kind = (d.CPUAccessFlags & CPU_ACCESS_READ) ? MemoryKind::Readback : MemoryKind::Upload; break;
    default: b->kind = MemoryKind::Device; break;
  }
  const VkPhysicalDeviceLimits& lim = dev->props.limits;
  if ((d.BindFlags & BIND_CONSTANT_BUFFER) && d.ByteWidth > lim.maxUniformBufferRange)
    Throw(ErrorId::NOT_SUPPORTED, call, object, "the device binds at most " + std::to_string(lim.maxUniformBufferRange) + " bytes as a uniform buffer");
  if ((d.BindFlags & (BIND_SHADER_RESOURCE | BIND_UNORDERED_ACCESS)) && (d.MiscFlags & (RESOURCE_MISC_BUFFER_STRUCTURED | RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS)) &&
      d.ByteWidth > lim.maxStorageBufferRange)
    Throw(ErrorId::NOT_SUPPORTED, call, object, "the device binds at most " + std::to_string(lim.maxStorageBufferRange) + " bytes as a storage buffer");

  // Rounded to 4 bytes so fills and copies of whole 32-bit words never run past the end.
  VkDeviceSize size = (VkDeviceSize(d.ByteWidth) + 3) & ~VkDeviceSize(3);
  // lavapipe's indexed indirect draws ignore the index buffer's binding offset, which the draw
  // then works around with a copy; an index buffer of its own sits at offset 0 and needs none
  // (only an IASetIndexBuffer offset still does).
  b->ownVkBuffer = (d.BindFlags & BIND_INDEX_BUFFER) && dev->feat.indirectIgnoresIndexOffset;
  b->range = dev->alloc.AllocateBuffer(size, b->kind, call, object, b->ownVkBuffer);
  // Fresh ranges are idle (freed ranges are returned only after their last batch finished), so
  // host-visible memory can be written directly; D3D11 hands out zeroed memory.
  if (b->range.mapped) {
    if (init) {
      std::memcpy(b->range.mapped, init->pSysMem, d.ByteWidth);
      std::memset(b->range.mapped + d.ByteWidth, 0, size - d.ByteWidth);
    } else {
      std::memset(b->range.mapped, 0, size);
    }
  } else if (init) {
    dev->ctx->UploadToBuffer(*b, 0, init->pSysMem, d.ByteWidth);
  } else {
    dev->ctx->ZeroBuffer(*b);
  }
  return b;
}

VkBufferObj::~VkBufferObj() {
  ReleaseBufferRange(dev, range, lastUse);
  for (Retired& r : retired) ReleaseBufferRange(dev, r.range, r.busyUntil);
}

}  // namespace sp::vk
