// D3D11's UAV clear rules, resolved once in the core: the backends get the bits memory must hold
// and only choose the driver command that writes them.
#pragma once
#include <cstdint>

#include <sp/rhi/format.h>

namespace sp {
class UnorderedAccessView;
}

namespace sp::detail {

struct UavClearValue {
  // Raw and structured views have no format: D3D11 writes values[0] to every 32-bit word (the
  // R32_UINT rule), which is texel[0..3] with texelBytes 4.
  bool perWord = false;
  uint32_t texelBytes = 0;
  alignas(4) uint8_t texel[16] = {};  // one texel of the view's format, in memory order
};

// ClearUnorderedAccessViewUint: the low bits of each value, unconverted, in each channel.
void PackClearUint(FORMAT format, const uint32_t values[4], uint8_t* texel);
// ClearUnorderedAccessViewFloat: D3D11's conversions (FLOAT -> UNORM/SNORM round to nearest after
// clamping, NaN -> 0; FLOAT -> smaller floats round toward zero, keeping NaN and infinities).
void PackClearFloat(FORMAT format, const float values[4], uint8_t* texel);

UavClearValue ResolveUavClearUint(const UnorderedAccessView& uav, const uint32_t values[4]);
UavClearValue ResolveUavClearFloat(const UnorderedAccessView& uav, const float values[4]);

}  // namespace sp::detail
