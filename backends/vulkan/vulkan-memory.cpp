// Device memory: images are placed in 64 MiB blocks (large ones get dedicated memory); buffers
// are sub-allocated from 32 MiB VkBuffers created with every usage flag, so creating a D3D buffer
// costs no Vulkan object at all. No VMA: Debian 12 does not package it.
#include <algorithm>

#include "vulkan-internal.h"

namespace sp::vk {
namespace {

constexpr VkDeviceSize kImageBlockSize = 64ull << 20;
constexpr VkDeviceSize kImageDedicatedThreshold = 16ull << 20;
constexpr VkDeviceSize kBufferBlockSize = 32ull << 20;
constexpr VkDeviceSize kBufferDedicatedThreshold = 8ull << 20;

constexpr VkBufferUsageFlags kAllBufferUsage =
    VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT |
    VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
    VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;

VkDeviceSize AlignUp(VkDeviceSize v, VkDeviceSize a) { return (v + a - 1) / a * a; }

}  // namespace

RangeAllocator::RangeAllocator(VkDeviceSize size) { Insert(0, size); }

void RangeAllocator::Insert(VkDeviceSize offset, VkDeviceSize size) {
  byOffset_[offset] = size;
  bySize_.emplace(size, offset);
}

void RangeAllocator::Erase(std::map<VkDeviceSize, VkDeviceSize>::iterator it) {
  bySize_.erase({it->second, it->first});
  byOffset_.erase(it);
}

bool RangeAllocator::Allocate(VkDeviceSize size, VkDeviceSize align, VkDeviceSize* offset) {
  // The smallest free range that holds the request at any alignment.
  auto s = bySize_.lower_bound({size + align - 1, 0});
  if (s == bySize_.end()) return false;
  VkDeviceSize start = s->second, len = s->first;
  Erase(byOffset_.find(start));
  VkDeviceSize aligned = AlignUp(start, align);
  if (aligned > start) Insert(start, aligned - start);
  if (aligned + size < start + len) Insert(aligned + size, start + len - aligned - size);
  *offset = aligned;
  used_ += size;
  return true;
}

void RangeAllocator::Free(VkDeviceSize offset, VkDeviceSize size) {
  used_ -= size;
  auto next = byOffset_.lower_bound(offset);
  if (next != byOffset_.end() && next->first == offset + size) {
    size += next->second;
    auto after = std::next(next);
    Erase(next);
    next = after;
  }
  if (next != byOffset_.begin()) {
    auto prev = std::prev(next);
    if (prev->first + prev->second == offset) {
      offset = prev->first;
      size += prev->second;
      Erase(prev);
    }
  }
  Insert(offset, size);
}

struct Allocator::MemBlock {
  VkDeviceMemory memory = VK_NULL_HANDLE;
  uint32_t type = 0;
  RangeAllocator ranges{kImageBlockSize};
};

struct Allocator::BufBlock {
  VkBuffer buffer = VK_NULL_HANDLE;
  Allocation memory;
  MemoryKind kind = MemoryKind::Device;
  RangeAllocator ranges{kBufferBlockSize};
};

Allocator::Allocator() = default;
Allocator::~Allocator() = default;

void Allocator::Init(VulkanDevice* dev) {
  dev_ = dev;
  const VkPhysicalDeviceLimits& l = dev->props.limits;
  bufferAlign_ = std::max<VkDeviceSize>({256, l.minUniformBufferOffsetAlignment, l.minStorageBufferOffsetAlignment,
                                         l.minTexelBufferOffsetAlignment, l.nonCoherentAtomSize});
}

void Allocator::Shutdown() {
  VkDevice d = dev_ ? dev_->device : VK_NULL_HANDLE;
  for (auto& b : bufBlocks_) {
    vkDestroyBuffer(d, b->buffer, nullptr);
    vkFreeMemory(d, b->memory.memory, nullptr);
  }
  bufBlocks_.clear();
  for (auto& b : memBlocks_) vkFreeMemory(d, b->memory, nullptr);
  memBlocks_.clear();
}

uint32_t Allocator::FindType(uint32_t typeBits, MemoryKind kind, const char* call, const std::string& object) const {
  const VkPhysicalDeviceMemoryProperties& mp = dev_->memProps;
  VkMemoryPropertyFlags required = 0, preferred = 0;
  switch (kind) {
    case MemoryKind::Device: preferred = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT; break;
    case MemoryKind::Upload: required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT; break;
    case MemoryKind::Readback:
      required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
      preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
      break;
  }
  int fallback = -1;
  for (uint32_t i = 0; i < mp.memoryTypeCount; ++i) {
    if (!(typeBits & (1u << i))) continue;
    VkMemoryPropertyFlags f = mp.memoryTypes[i].propertyFlags;
    if ((f & required) != required) continue;
    if ((f & preferred) == preferred) return i;
    if (fallback < 0) fallback = int(i);
  }
  if (fallback < 0) Throw(ErrorId::NOT_SUPPORTED, call, object, "the device has no memory type for this resource (host-visible coherent memory is required for mapping)");
  return uint32_t(fallback);
}

Allocation Allocator::AllocateDedicated(VkDeviceSize size, uint32_t type, const char* call, const std::string& object) {
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  ai.allocationSize = size;
  ai.memoryTypeIndex = type;
  Allocation a;
  Check(vkAllocateMemory(dev_->device, &ai, nullptr, &a.memory), call, object, "vkAllocateMemory");
  a.size = size;
  if (dev_->memProps.memoryTypes[type].propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) {
    void* p = nullptr;
    VkResult r = vkMapMemory(dev_->device, a.memory, 0, VK_WHOLE_SIZE, 0, &p);
    if (r != VK_SUCCESS) {
      vkFreeMemory(dev_->device, a.memory, nullptr);
      ThrowVk(r, call, object, "vkMapMemory");
    }
    a.mapped = static_cast<uint8_t*>(p);
  }
  return a;
}

Allocation Allocator::AllocateImage(const VkMemoryRequirements& req, const char* call, const std::string& object) {
  uint32_t type = FindType(req.memoryTypeBits, MemoryKind::Device, call, object);
  if (req.size > kImageDedicatedThreshold) return AllocateDedicated(req.size, type, call, object);
  for (auto& b : memBlocks_) {
    VkDeviceSize off;
    if (b->type == type && b->ranges.Allocate(req.size, req.alignment, &off)) {
      Allocation a;
      a.memory = b->memory;
      a.offset = off;
      a.size = req.size;
      a.block = b.get();
      return a;
    }
  }
  auto b = std::make_unique<MemBlock>();
  b->type = type;
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  ai.allocationSize = kImageBlockSize;
  ai.memoryTypeIndex = type;
  Check(vkAllocateMemory(dev_->device, &ai, nullptr, &b->memory), call, object, "vkAllocateMemory");
  VkDeviceSize off = 0;
  b->ranges.Allocate(req.size, req.alignment, &off);
  Allocation a;
  a.memory = b->memory;
  a.offset = off;
  a.size = req.size;
  a.block = b.get();
  memBlocks_.push_back(std::move(b));
  return a;
}

void Allocator::Free(Allocation& a) {
  if (!a.memory) return;
  if (a.block) {
    static_cast<MemBlock*>(a.block)->ranges.Free(a.offset, a.size);
  } else {
    vkFreeMemory(dev_->device, a.memory, nullptr);
  }
  a = Allocation{};
}

BufferRange Allocator::AllocateBuffer(VkDeviceSize size, MemoryKind kind, const char* call, const std::string& object, bool dedicated) {
  size = std::max<VkDeviceSize>(size, 4);
  auto createBuffer = [&](VkDeviceSize bytes, Allocation* mem) {
    VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bci.size = bytes;
    bci.usage = kAllBufferUsage;
    bci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VkBuffer buf;
    Check(vkCreateBuffer(dev_->device, &bci, nullptr, &buf), call, object, "vkCreateBuffer");
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(dev_->device, buf, &req);
    try {
      *mem = AllocateDedicated(req.size, FindType(req.memoryTypeBits, kind, call, object), call, object);
    } catch (...) {
      vkDestroyBuffer(dev_->device, buf, nullptr);
      throw;
    }
    VkResult r = vkBindBufferMemory(dev_->device, buf, mem->memory, 0);
    if (r != VK_SUCCESS) {
      vkDestroyBuffer(dev_->device, buf, nullptr);
      vkFreeMemory(dev_->device, mem->memory, nullptr);
      ThrowVk(r, call, object, "vkBindBufferMemory");
    }
    return buf;
  };

  BufferRange out;
  if (dedicated || size > kBufferDedicatedThreshold) {
    out.buffer = createBuffer(size, &out.memory);
    out.size = size;
    out.mapped = out.memory.mapped;
    return out;
  }
  if (SuballocateBuffer(size, kind, &out)) return out;
  auto b = std::make_unique<BufBlock>();
  b->kind = kind;
  b->buffer = createBuffer(kBufferBlockSize, &b->memory);
  bufBlocks_.push_back(std::move(b));
  TakeRange(*bufBlocks_.back(), size, &out);  // a fresh block holds any size under the threshold
  return out;
}

bool Allocator::TakeRange(BufBlock& b, VkDeviceSize size, BufferRange* out) {
  VkDeviceSize off = 0;
  if (!b.ranges.Allocate(size, bufferAlign_, &off)) return false;
  *out = BufferRange{};
  out->buffer = b.buffer;
  out->offset = off;
  out->size = size;
  out->mapped = b.memory.mapped ? b.memory.mapped + off : nullptr;
  out->block = &b;
  return true;
}

bool Allocator::SuballocateBuffer(VkDeviceSize size, MemoryKind kind, BufferRange* out) {
  size = std::max<VkDeviceSize>(size, 4);
  if (size > kBufferDedicatedThreshold) return false;
  for (auto& b : bufBlocks_)
    if (b->kind == kind && TakeRange(*b, size, out)) return true;
  return false;
}

void Allocator::Free(BufferRange& r) {
  if (!r.buffer) return;
  if (r.block) {
    static_cast<BufBlock*>(r.block)->ranges.Free(r.offset, r.size);
  } else {
    vkDestroyBuffer(dev_->device, r.buffer, nullptr);
    vkFreeMemory(dev_->device, r.memory.memory, nullptr);
  }
  r = BufferRange{};
}

void ReleaseBufferRange(VulkanDevice* dev, BufferRange& r, uint64_t serial) {
  if (!r) return;
  BufferRange copy = r;
  r = BufferRange{};
  dev->Defer(serial, [dev, copy]() mutable { dev->alloc.Free(copy); });
}

}  // namespace sp::vk
