// DXGI_FORMAT mirror. Values are DXGI's, so a port is `DXGI_FORMAT_X` -> `sp::FORMAT_X` and
// serialized formats keep their meaning.
#pragma once
#include <cstdint>
#include <string_view>

namespace sp {

enum FORMAT : uint32_t {
  FORMAT_UNKNOWN = 0,
  FORMAT_R32G32B32A32_TYPELESS = 1,
  FORMAT_R32G32B32A32_FLOAT = 2,
  FORMAT_R32G32B32A32_UINT = 3,
  FORMAT_R32G32B32A32_SINT = 4,
  FORMAT_R32G32B32_TYPELESS = 5,
  FORMAT_R32G32B32_FLOAT = 6,
  FORMAT_R32G32B32_UINT = 7,
  FORMAT_R32G32B32_SINT = 8,
  FORMAT_R16G16B16A16_TYPELESS = 9,
  FORMAT_R16G16B16A16_FLOAT = 10,
  FORMAT_R16G16B16A16_UNORM = 11,
  FORMAT_R16G16B16A16_UINT = 12,
  FORMAT_R16G16B16A16_SNORM = 13,
  FORMAT_R16G16B16A16_SINT = 14,
  FORMAT_R32G32_TYPELESS = 15,
  FORMAT_R32G32_FLOAT = 16,
  FORMAT_R32G32_UINT = 17,
  FORMAT_R32G32_SINT = 18,
  FORMAT_R32G8X24_TYPELESS = 19,
  FORMAT_D32_FLOAT_S8X24_UINT = 20,
  FORMAT_R32_FLOAT_X8X24_TYPELESS = 21,
  FORMAT_X32_TYPELESS_G8X24_UINT = 22,
  FORMAT_R10G10B10A2_TYPELESS = 23,
  FORMAT_R10G10B10A2_UNORM = 24,
  FORMAT_R10G10B10A2_UINT = 25,
  FORMAT_R11G11B10_FLOAT = 26,
  FORMAT_R8G8B8A8_TYPELESS = 27,
  FORMAT_R8G8B8A8_UNORM = 28,
  FORMAT_R8G8B8A8_UNORM_SRGB = 29,
  FORMAT_R8G8B8A8_UINT = 30,
  FORMAT_R8G8B8A8_SNORM = 31,
  FORMAT_R8G8B8A8_SINT = 32,
  FORMAT_R16G16_TYPELESS = 33,
  FORMAT_R16G16_FLOAT = 34,
  FORMAT_R16G16_UNORM = 35,
  FORMAT_R16G16_UINT = 36,
  FORMAT_R16G16_SNORM = 37,
  FORMAT_R16G16_SINT = 38,
  FORMAT_R32_TYPELESS = 39,
  FORMAT_D32_FLOAT = 40,
  FORMAT_R32_FLOAT = 41,
  FORMAT_R32_UINT = 42,
  FORMAT_R32_SINT = 43,
  FORMAT_R24G8_TYPELESS = 44,
  FORMAT_D24_UNORM_S8_UINT = 45,
  FORMAT_R24_UNORM_X8_TYPELESS = 46,
  FORMAT_X24_TYPELESS_G8_UINT = 47,
  FORMAT_R8G8_TYPELESS = 48,
  FORMAT_R8G8_UNORM = 49,
  FORMAT_R8G8_UINT = 50,
  FORMAT_R8G8_SNORM = 51,
  FORMAT_R8G8_SINT = 52,
  FORMAT_R16_TYPELESS = 53,
  FORMAT_R16_FLOAT = 54,
  FORMAT_D16_UNORM = 55,
  FORMAT_R16_UNORM = 56,
  FORMAT_R16_UINT = 57,
  FORMAT_R16_SNORM = 58,
  FORMAT_R16_SINT = 59,
  FORMAT_R8_TYPELESS = 60,
  FORMAT_R8_UNORM = 61,
  FORMAT_R8_UINT = 62,
  FORMAT_R8_SNORM = 63,
  FORMAT_R8_SINT = 64,
  FORMAT_B8G8R8A8_UNORM = 87,
  FORMAT_B8G8R8A8_TYPELESS = 90,
  FORMAT_B8G8R8A8_UNORM_SRGB = 91,
};

// How a format's bits are interpreted; TYPELESS formats only fix the bit layout.
enum class FormatKind : uint8_t { Unknown, Typeless, UNorm, SNorm, UInt, SInt, Float, UNormSRGB, Depth, DepthStencil };

struct FormatInfo {
  FORMAT format = FORMAT_UNKNOWN;
  std::string_view name;         // "R32_TYPELESS", as DXGI spells it without the prefix
  uint32_t bytesPerElement = 0;  // texel or vertex element size
  uint32_t components = 0;
  FormatKind kind = FormatKind::Unknown;
  FORMAT typelessFamily = FORMAT_UNKNOWN;  // the TYPELESS format every view of this family shares
  uint32_t depthBits = 0;                  // 16, 24 or 32 for depth formats and their views
  uint32_t stencilBits = 0;
  bool isDepthView = false;    // D16/D24S8/D32F/D32S8: usable as DSV
  bool readsDepth = false;     // R16_UNORM, R24_UNORM_X8, R32_FLOAT, R32_FLOAT_X8X24 as SRV of a depth texture
  bool readsStencil = false;   // X24_TYPELESS_G8_UINT, X32_TYPELESS_G8X24_UINT
};

// Table lookup; returns an info with format == FORMAT_UNKNOWN for values ShadowPort does not know.
const FormatInfo& GetFormatInfo(FORMAT format);
std::string_view FormatName(FORMAT format);  // "R32_FLOAT" or "FORMAT(123)"

// D3D11 view-format compatibility: a view may use any format of the resource's typeless family
// (and a typed resource only its own format).
bool FormatsCompatibleForView(FORMAT resourceFormat, FORMAT viewFormat);

// The depth format a texture of this family is stored as (R32_TYPELESS -> D32_FLOAT, ...), or
// FORMAT_UNKNOWN when the family has no depth member.
FORMAT DepthFormatOfFamily(FORMAT format);

}  // namespace sp
