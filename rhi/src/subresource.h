// D3D11's subresource numbering, taken apart in one place for the core and the backends:
// index = mip + arraySlice * mipLevels (D3D11CalcSubresource); a Texture3D has one slice whose W
// extent is the mip's depth. The core validates the index and hands backends the decomposed form.
#pragma once
#include <cstdint>

#include <sp/rhi/context.h>

namespace sp::detail {

struct Subresource {
  uint32_t index = 0;  // D3D's number, for tables kept in D3D order
  uint32_t mip = 0, slice = 0;
  uint32_t width = 1, height = 1, depth = 1;  // the mip's extent (a buffer: its bytes, 1, 1)
  BOX box() const { return BOX{0, 0, 0, width, height, depth}; }
};

inline Subresource SubresourceOf(const TextureShape& s, uint32_t index) {
  const uint32_t mip = index % s.mipLevels;
  return {index, mip, index / s.mipLevels, s.mipWidth(mip), s.mipHeight(mip), s.mipDepth(mip)};
}

// A buffer's only subresource.
inline Subresource BufferSubresource(uint32_t byteWidth) { return {0, 0, 0, byteWidth, 1, 1}; }

}  // namespace sp::detail
