// The cbuffer repacking rule, once for both targets. Applications fill constant buffers with
// D3D11's packing (16-byte registers, no member straddling a register, every array element
// starting a register, and fxc placing the member after a matrix, array or struct in the unused
// tail of its last register, see D3DMemberOffsets). Neither GL's std140 nor Vulkan's block rules
// can express all of it, so a target whose block layout differs gets a copy table from the
// D3D-packed buffer to its own layout. The walk is the same for both; only where the destination
// offsets come from differs: std140 assigns them (the GLSL target then declares them), Vulkan
// reads the Offset / ArrayStride / MatrixStride glslang decorated.
#include <algorithm>
#include <spirv_cross/spirv_cross.hpp>

#include "toolchain.h"

namespace sp::hlsl {
namespace {

using spirv_cross::SPIRType;

uint32_t AlignUp(uint32_t v, uint32_t a) { return (v + a - 1) / a * a; }

struct Layout {
  uint32_t size = 0, align = 0;
};

class CopyWalker {
 public:
  CopyWalker(spirv_cross::Compiler& c, BlockLayout layout, bool apply) : c_(c), layout_(layout), apply_(apply) {}

  // The layout of struct `typeId` in the destination; appends copies for data at src/dst.
  Layout Struct(uint32_t typeId, uint32_t src, uint32_t dst, bool record) {
    const SPIRType& t = c_.get_type(typeId);
    uint32_t offset = 0, align = 16;
    const std::vector<uint32_t> srcOffsets = D3DMemberOffsets(c_, t);
    for (uint32_t i = 0; i < t.member_types.size(); ++i) {
      bool rowMajor = c_.has_member_decoration(t.self, i, spv::DecorationRowMajor);
      uint32_t dstOffset, matrixStride = 16;
      if (layout_ == BlockLayout::Std140) {
        uint32_t memberAlign = Std140Align(t.member_types[i]);
        dstOffset = AlignUp(offset, memberAlign);
        align = std::max(align, memberAlign);
        if (apply_ && c_.get_member_decoration(t.self, i, spv::DecorationOffset) != dstOffset)
          c_.set_member_decoration(t.self, i, spv::DecorationOffset, dstOffset);
      } else {
        dstOffset = c_.type_struct_member_offset(t, i);
        const SPIRType* base = &c_.get_type(t.member_types[i]);
        while (!base->array.empty()) base = &c_.get_type(base->parent_type);
        if (base->columns > 1) matrixStride = c_.type_struct_member_matrix_stride(t, i);
      }
      Layout l = Member(t.member_types[i], rowMajor, matrixStride, src + srcOffsets[i], dst + dstOffset, record);
      offset = dstOffset + l.size;
    }
    return {AlignUp(offset, 16), align};
  }

  std::vector<CBufferCopyRange> ranges;
  uint32_t end = 0;  // one past the last destination byte written

 private:
  uint32_t Std140Align(uint32_t typeId) {
    const SPIRType& t = c_.get_type(typeId);
    if (!t.array.empty() || t.basetype == SPIRType::Struct || t.columns > 1) return 16;
    return t.vecsize == 1 ? 4 : t.vecsize == 2 ? 8 : 16;
  }

  Layout Member(uint32_t typeId, bool rowMajor, uint32_t matrixStride, uint32_t src, uint32_t dst, bool record) {
    const SPIRType& t = c_.get_type(typeId);
    if (!t.array.empty()) {
      uint32_t elem = t.parent_type;
      uint32_t count = t.array.back();
      if (!t.array_size_literal.back()) {
        const std::string msg = "specialization-constant array sizes are not supported in cbuffers";
        throw CompileError("Compile", "cbuffer", {{"cbuffer", 0, msg}}, msg);
      }
      // In D3D every array element starts a register.
      uint32_t srcStride = AlignUp(D3DTypeSize(c_, elem, rowMajor), 16);
      uint32_t stride;
      if (layout_ == BlockLayout::Std140) {
        // std140 rounds the element's own size up to 16.
        Layout el = Member(elem, rowMajor, matrixStride, src, dst, false);
        stride = AlignUp(std::max(el.size, 16u), 16);
        if (apply_ && c_.get_decoration(typeId, spv::DecorationArrayStride) != stride) c_.set_decoration(typeId, spv::DecorationArrayStride, stride);
      } else {
        stride = c_.get_decoration(typeId, spv::DecorationArrayStride);
      }
      for (uint32_t i = 0; i < count; ++i) Member(elem, rowMajor, matrixStride, src + i * srcStride, dst + i * stride, record);
      return {stride * count, 16};
    }
    if (t.basetype == SPIRType::Struct) return Struct(typeId, src, dst, record);
    if (t.columns > 1) {
      // D3D: one register per column (row with row_major); copy vector by vector.
      uint32_t vectors = rowMajor ? t.vecsize : t.columns;
      uint32_t comps = rowMajor ? t.columns : t.vecsize;
      for (uint32_t v = 0; v < vectors; ++v) Copy(src + v * 16, dst + v * matrixStride, comps * 4, record);
      return {vectors * 16, 16};
    }
    Copy(src, dst, t.vecsize * 4, record);
    return {t.vecsize * 4, t.vecsize == 1 ? 4u : t.vecsize == 2 ? 8u : 16u};
  }

  void Copy(uint32_t src, uint32_t dst, uint32_t size, bool record) {
    if (!record) return;
    end = std::max(end, dst + size);
    if (!ranges.empty()) {
      CBufferCopyRange& last = ranges.back();
      if (last.src + last.size == src && last.dst + last.size == dst) {
        last.size += size;
        return;
      }
    }
    ranges.push_back({src, dst, size});
  }

  spirv_cross::Compiler& c_;
  BlockLayout layout_;
  bool apply_;
};

}  // namespace

CBufferCopyTable D3DCBufferCopyTable(spirv_cross::Compiler& c, uint32_t blockType, BlockLayout layout) {
  CopyWalker probe(c, layout, false);
  Layout l = probe.Struct(blockType, 0, 0, true);
  CBufferCopyTable table;
  table.identity = std::all_of(probe.ranges.begin(), probe.ranges.end(), [](const CBufferCopyRange& r) { return r.src == r.dst; });
  if (table.identity) return table;
  if (layout == BlockLayout::Std140) {
    // The block is declared with the std140 offsets the copies were computed for.
    CopyWalker apply(c, layout, true);
    l = apply.Struct(blockType, 0, 0, true);
    table.ranges = std::move(apply.ranges);
    table.size = l.size;
  } else {
    table.ranges = std::move(probe.ranges);
    table.size = AlignUp(std::max<uint32_t>(probe.end, uint32_t(c.get_declared_struct_size(c.get_type(blockType)))), 16);
  }
  return table;
}

}  // namespace sp::hlsl
