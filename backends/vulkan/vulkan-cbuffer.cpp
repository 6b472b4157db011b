// Constant buffers whose HLSL packing the SPIR-V block cannot express. fxc places the member after
// a matrix, an array or a struct in the unused tail of that member's last register (a float right
// after a float3x3 at +44); glslang's SPIR-V offsets start a new register, and Vulkan block rules
// forbid the overlap. For such blocks the bound buffer (laid out by D3D11's rules) is copied into
// the SPIR-V layout before the draw: on the CPU when its contents are in host memory, else with
// copy commands. The copy table comes with the bytecode (rhi/src/hlsl/target-cbuffer.cpp, the
// rule the GL target's std140 repacking uses too).
#include <algorithm>
#include <cstring>

#include "vulkan-internal.h"

namespace sp::vk {

VulkanContext::RepackedConstants VulkanContext::RepackConstants(VkBufferObj& b, const CBufferRepack& rp, uint64_t key, VkPipelineStageFlags2 stage) {
  uint64_t serial = dev_->recordingSerial;
  for (const VkBufferObj::RepackCache& c : b.repackCache)
    if (c.key == key && c.version == b.contentVersion && c.serial == serial) return {c.buffer, c.offset, rp.size};
  UploadSpan up = Upload(rp.size, dev_->alloc.BufferAlignment());
  std::memset(up.ptr, 0, rp.size);
  const uint32_t width = b.desc.ByteWidth;  // D3D11 reads 0 beyond the buffer's end
  if (b.range.mapped && b.lastWrite < serial && !IsBusy(b.lastWrite)) {
    // Every write to the buffer has landed in host memory: repack on the CPU.
    for (const CBufferCopyRange& r : rp.ranges)
      if (r.src < width) std::memcpy(up.ptr + r.dst, b.range.mapped + r.src, std::min(r.size, width - r.src));
  } else {
    VkCommandBuffer cmd = Cmd();
    UseBuffer(b, access::TransferRead());
    FlushBarriers();
    std::vector<VkBufferCopy> regions;
    for (const CBufferCopyRange& r : rp.ranges)
      if (r.src < width) regions.push_back({b.range.offset + r.src, up.offset + r.dst, std::min(r.size, width - r.src)});
    if (!regions.empty()) vkCmdCopyBuffer(cmd, b.range.buffer, up.buffer, uint32_t(regions.size()), regions.data());
    AccessState scratch;
    UseRange(scratch, access::TransferWrite());
    UseRange(scratch, access::ShaderRead(stage, VK_ACCESS_2_UNIFORM_READ_BIT));
  }
  b.lastUse = serial;
  auto it = std::find_if(b.repackCache.begin(), b.repackCache.end(), [&](const VkBufferObj::RepackCache& c) { return c.key == key; });
  VkBufferObj::RepackCache entry{key, b.contentVersion, serial, up.buffer, up.offset};
  if (it != b.repackCache.end()) *it = entry;
  else b.repackCache.push_back(entry);
  return {up.buffer, up.offset, rp.size};
}

}  // namespace sp::vk
