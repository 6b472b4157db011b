// D3D11's UAV clear encodings (docs: ClearUnorderedAccessViewUint/Float and "Data conversion
// rules"), computed on the CPU so that every backend writes the same bits whatever its driver's
// own conversions do.
#include "clear-values.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <sp/rhi/resource.h>
#include <sp/rhi/view.h>

namespace sp::detail {
namespace {

uint32_t FloatBits(float f) {
  uint32_t x;
  std::memcpy(&x, &f, 4);
  return x;
}

// FLOAT -> a float with a 5-bit exponent (bias 15) and `mantBits` of mantissa: float16 (signed)
// and the unsigned float11/float10 of R11G11B10. D3D11 rounds toward zero here, so an overflow
// gives the largest finite value while INF and NaN stay what they are.
uint32_t ToSmallFloat(float f, uint32_t mantBits, bool hasSign) {
  const uint32_t x = FloatBits(f);
  const bool negative = x >> 31;
  const uint32_t e = (x >> 23) & 0xff, m = x & 0x7fffff;
  const uint32_t sign = hasSign && negative ? 1u << (5 + mantBits) : 0u;
  const uint32_t expMask = 0x1fu << mantBits, mantMask = (1u << mantBits) - 1;
  if (e == 0xff && m) return sign | expMask | (1u << (mantBits - 1));  // NaN (quiet)
  if (negative && !hasSign) return 0;                                  // unsigned: negatives and -INF are 0
  if (e == 0xff) return sign | expMask;                                // INF
  const int32_t exp = int32_t(e) - 127 + 15;
  if (exp >= 31) return sign | (0x1eu << mantBits) | mantMask;
  if (exp <= 0) {
    // Denormal in the small format: the implicit one shifts into the mantissa.
    const uint32_t shift = uint32_t(24 - int32_t(mantBits) - exp);
    return e == 0 || shift >= 32 ? sign : sign | ((m | 0x800000u) >> shift);
  }
  return sign | (uint32_t(exp) << mantBits) | (m >> (23 - mantBits));
}

// FLOAT -> UNORM/SNORM: NaN is 0, clamp, scale, round to nearest.
uint32_t ToUnorm(float v, uint32_t bits) {
  if (std::isnan(v)) return 0;
  const double maxv = double((1ull << bits) - 1);
  return uint32_t(std::floor(double(std::clamp(v, 0.0f, 1.0f)) * maxv + 0.5));
}

uint32_t ToSnorm(float v, uint32_t bits) {
  if (std::isnan(v)) return 0;
  const double maxv = double((1ull << (bits - 1)) - 1);
  const int32_t i = int32_t(std::lround(double(std::clamp(v, -1.0f, 1.0f)) * maxv));
  return uint32_t(i) & uint32_t((1ull << bits) - 1);
}

float LinearToSrgb(float x) {
  const float c = std::isnan(x) ? 0.0f : std::clamp(x, 0.0f, 1.0f);
  return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

void Put(uint8_t* out, uint32_t bytes, uint64_t v) { std::memcpy(out, &v, bytes); }  // little endian

// The formats whose channels are not whole bytes of equal size.
bool Packed1010102(FORMAT f) { return f == FORMAT_R10G10B10A2_UNORM || f == FORMAT_R10G10B10A2_UINT || f == FORMAT_R10G10B10A2_TYPELESS; }

uint32_t ChannelBits(const FormatInfo& fi) { return fi.components ? fi.bytesPerElement * 8 / fi.components : 0; }

// D3D's BGRA formats store blue first; clear values are given as RGBA.
bool StoredBgra(FORMAT f) { return f == FORMAT_B8G8R8A8_UNORM || f == FORMAT_B8G8R8A8_UNORM_SRGB; }

}  // namespace

void PackClearUint(FORMAT f, const uint32_t v[4], uint8_t* out) {
  const FormatInfo& fi = GetFormatInfo(f);
  std::memset(out, 0, 16);
  if (Packed1010102(f)) return Put(out, 4, (v[0] & 0x3ff) | (v[1] & 0x3ff) << 10 | (v[2] & 0x3ff) << 20 | (v[3] & 3) << 30);
  if (f == FORMAT_R11G11B10_FLOAT) return Put(out, 4, (v[0] & 0x7ff) | (v[1] & 0x7ff) << 11 | (v[2] & 0x3ff) << 22);
  // Channel i of the format in memory order gets values[i]: the low bits, cut by Put's width.
  const uint32_t bytes = ChannelBits(fi) / 8;
  for (uint32_t c = 0; c < fi.components && bytes; ++c) Put(out + c * bytes, bytes, v[c]);
}

void PackClearFloat(FORMAT f, const float v[4], uint8_t* out) {
  const FormatInfo& fi = GetFormatInfo(f);
  std::memset(out, 0, 16);
  if (f == FORMAT_R10G10B10A2_UNORM)
    return Put(out, 4, ToUnorm(v[0], 10) | ToUnorm(v[1], 10) << 10 | ToUnorm(v[2], 10) << 20 | ToUnorm(v[3], 2) << 30);
  if (f == FORMAT_R11G11B10_FLOAT)
    return Put(out, 4, ToSmallFloat(v[0], 6, false) | ToSmallFloat(v[1], 6, false) << 11 | ToSmallFloat(v[2], 5, false) << 22);
  const uint32_t bits = ChannelBits(fi), bytes = bits / 8;
  for (uint32_t c = 0; c < fi.components; ++c) {
    const float x = v[StoredBgra(f) && c < 3 ? 2 - c : c];
    uint64_t enc = 0;
    switch (fi.kind) {
      case FormatKind::Float: enc = bits == 32 ? FloatBits(x) : ToSmallFloat(x, 10, true); break;
      case FormatKind::UNorm: enc = ToUnorm(x, bits); break;
      case FormatKind::UNormSRGB: enc = ToUnorm(LinearToSrgb(x), bits); break;
      case FormatKind::SNorm: enc = ToSnorm(x, bits); break;
      default: break;  // the core refuses float clears of integer views
    }
    Put(out + c * bytes, bytes, enc);
  }
}

UavClearValue ResolveUavClearUint(const UnorderedAccessView& uav, const uint32_t values[4]) {
  UavClearValue out;
  // Raw and structured buffer views: D3D11 treats them as R32_UINT.
  if (uav.Shape() == ViewShape::RawBuffer || uav.Shape() == ViewShape::StructuredBuffer) {
    out.perWord = true;
    out.texelBytes = 4;
    std::memcpy(out.texel, &values[0], 4);
    return out;
  }
  out.texelBytes = GetFormatInfo(uav.ViewFormat()).bytesPerElement;
  PackClearUint(uav.ViewFormat(), values, out.texel);
  return out;
}

UavClearValue ResolveUavClearFloat(const UnorderedAccessView& uav, const float values[4]) {
  UavClearValue out;
  out.texelBytes = GetFormatInfo(uav.ViewFormat()).bytesPerElement;
  PackClearFloat(uav.ViewFormat(), values, out.texel);
  return out;
}

}  // namespace sp::detail
