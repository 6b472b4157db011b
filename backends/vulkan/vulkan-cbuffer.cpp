// Constant buffers whose HLSL packing the SPIR-V block cannot express. fxc places the member after
// a matrix, an array or a struct in the unused tail of that member's last register (a float right
// after a float3x3 at +44); glslang's SPIR-V offsets start a new register, and Vulkan block rules
// forbid the overlap. For such blocks the bound buffer (laid out by D3D11's rules) is copied into
// the SPIR-V layout before the draw: on the CPU when its contents are in host memory, else with
// copy commands. The walk mirrors the OpenGL backend's std140 repack table (rhi/src/hlsl/glsl.cpp),
// with the destination offsets read from the SPIR-V instead of assigned.
#include <spirv_cross/spirv_cross.hpp>

#include <algorithm>
#include <cstring>

#include "hlsl/toolchain.h"
#include "vulkan-internal.h"

namespace sp::vk {
namespace {

using spirv_cross::SPIRType;

uint32_t AlignUp(uint32_t v, uint32_t a) { return (v + a - 1) / a * a; }

class RepackWalker {
 public:
  explicit RepackWalker(const spirv_cross::Compiler& c) : c_(c) {}

  void Struct(uint32_t typeId, uint32_t src, uint32_t dst) {
    const SPIRType& t = c_.get_type(typeId);
    const std::vector<uint32_t> srcOffsets = hlsl::D3DMemberOffsets(c_, t);
    for (uint32_t i = 0; i < t.member_types.size(); ++i) {
      bool rowMajor = c_.has_member_decoration(t.self, i, spv::DecorationRowMajor);
      const SPIRType& mt = c_.get_type(t.member_types[i]);
      const SPIRType* base = &mt;
      while (!base->array.empty()) base = &c_.get_type(base->parent_type);
      uint32_t matrixStride = base->columns > 1 ? c_.type_struct_member_matrix_stride(t, i) : 16;
      Member(t.member_types[i], rowMajor, matrixStride, src + srcOffsets[i], dst + c_.type_struct_member_offset(t, i));
    }
  }

  std::vector<CopyRange> ranges;
  uint32_t end = 0;

 private:
  void Member(uint32_t typeId, bool rowMajor, uint32_t matrixStride, uint32_t src, uint32_t dst) {
    const SPIRType& t = c_.get_type(typeId);
    if (!t.array.empty()) {
      uint32_t elem = t.parent_type;
      uint32_t count = t.array.back();
      // In D3D every array element starts a register.
      uint32_t srcStride = AlignUp(hlsl::D3DTypeSize(c_, elem, rowMajor), 16);
      uint32_t dstStride = c_.get_decoration(typeId, spv::DecorationArrayStride);
      for (uint32_t i = 0; i < count; ++i) Member(elem, rowMajor, matrixStride, src + i * srcStride, dst + i * dstStride);
      return;
    }
    if (t.basetype == SPIRType::Struct) {
      Struct(typeId, src, dst);
      return;
    }
    if (t.columns > 1) {
      uint32_t vectors = rowMajor ? t.vecsize : t.columns;
      uint32_t comps = rowMajor ? t.columns : t.vecsize;
      for (uint32_t v = 0; v < vectors; ++v) Copy(src + v * 16, dst + v * matrixStride, comps * 4);
      return;
    }
    Copy(src, dst, t.vecsize * 4);
  }

  void Copy(uint32_t src, uint32_t dst, uint32_t size) {
    end = std::max(end, dst + size);
    if (!ranges.empty()) {
      CopyRange& last = ranges.back();
      if (last.src + last.size == src && last.dst + last.size == dst) {
        last.size += size;
        return;
      }
    }
    ranges.push_back({src, dst, size});
  }

  const spirv_cross::Compiler& c_;
};

}  // namespace

std::vector<CBufferRepack> ComputeCBufferRepacks(const std::vector<uint32_t>& spirv) {
  std::vector<CBufferRepack> out;
  spirv_cross::Compiler c(spirv);
  for (const auto& ub : c.get_shader_resources().uniform_buffers) {
    RepackWalker w(c);
    w.Struct(ub.base_type_id, 0, 0);
    bool identical = std::all_of(w.ranges.begin(), w.ranges.end(), [](const CopyRange& r) { return r.src == r.dst; });
    if (identical) continue;
    CBufferRepack r;
    r.reg = c.get_decoration(ub.id, spv::DecorationBinding) - vkbind::kConstantBuffer;
    r.size = AlignUp(std::max<uint32_t>(w.end, uint32_t(c.get_declared_struct_size(c.get_type(ub.base_type_id)))), 16);
    r.ranges = std::move(w.ranges);
    out.push_back(std::move(r));
  }
  return out;
}

VulkanContext::RepackedConstants VulkanContext::RepackConstants(VkBufferObj& b, const CBufferRepack& rp, uint64_t key, VkPipelineStageFlags2 stage) {
  uint64_t serial = dev_->recordingSerial;
  for (const VkBufferObj::RepackCache& c : b.repackCache)
    if (c.key == key && c.version == b.contentVersion && c.serial == serial) return {c.buffer, c.offset, rp.size};
  UploadSpan up = Upload(rp.size, dev_->alloc.BufferAlignment());
  std::memset(up.ptr, 0, rp.size);
  const uint32_t width = b.desc.ByteWidth;  // D3D11 reads 0 beyond the buffer's end
  if (b.range.mapped && b.lastWrite < serial && !IsBusy(b.lastWrite)) {
    // Every write to the buffer has landed in host memory: repack on the CPU.
    for (const CopyRange& r : rp.ranges)
      if (r.src < width) std::memcpy(up.ptr + r.dst, b.range.mapped + r.src, std::min(r.size, width - r.src));
  } else {
    VkCommandBuffer cmd = Cmd();
    UseBuffer(b, access::TransferRead());
    FlushBarriers();
    std::vector<VkBufferCopy> regions;
    for (const CopyRange& r : rp.ranges)
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
