#include <sp/rhi/format.h>

#include <array>
#include <string>

namespace sp {
namespace {

using K = FormatKind;

struct Row {
  FORMAT f;
  const char* name;
  uint32_t bytes, comps;
  K kind;
  FORMAT family;
  uint32_t depthBits = 0, stencilBits = 0;
  bool dsv = false, readsDepth = false, readsStencil = false;
};

// clang-format off
constexpr Row kRows[] = {
  {FORMAT_R32G32B32A32_TYPELESS, "R32G32B32A32_TYPELESS", 16, 4, K::Typeless, FORMAT_R32G32B32A32_TYPELESS},
  {FORMAT_R32G32B32A32_FLOAT,    "R32G32B32A32_FLOAT",    16, 4, K::Float,    FORMAT_R32G32B32A32_TYPELESS},
  {FORMAT_R32G32B32A32_UINT,     "R32G32B32A32_UINT",     16, 4, K::UInt,     FORMAT_R32G32B32A32_TYPELESS},
  {FORMAT_R32G32B32A32_SINT,     "R32G32B32A32_SINT",     16, 4, K::SInt,     FORMAT_R32G32B32A32_TYPELESS},
  {FORMAT_R32G32B32_TYPELESS,    "R32G32B32_TYPELESS",    12, 3, K::Typeless, FORMAT_R32G32B32_TYPELESS},
  {FORMAT_R32G32B32_FLOAT,       "R32G32B32_FLOAT",       12, 3, K::Float,    FORMAT_R32G32B32_TYPELESS},
  {FORMAT_R32G32B32_UINT,        "R32G32B32_UINT",        12, 3, K::UInt,     FORMAT_R32G32B32_TYPELESS},
  {FORMAT_R32G32B32_SINT,        "R32G32B32_SINT",        12, 3, K::SInt,     FORMAT_R32G32B32_TYPELESS},
  {FORMAT_R16G16B16A16_TYPELESS, "R16G16B16A16_TYPELESS",  8, 4, K::Typeless, FORMAT_R16G16B16A16_TYPELESS},
  {FORMAT_R16G16B16A16_FLOAT,    "R16G16B16A16_FLOAT",     8, 4, K::Float,    FORMAT_R16G16B16A16_TYPELESS},
  {FORMAT_R16G16B16A16_UNORM,    "R16G16B16A16_UNORM",     8, 4, K::UNorm,    FORMAT_R16G16B16A16_TYPELESS},
  {FORMAT_R16G16B16A16_UINT,     "R16G16B16A16_UINT",      8, 4, K::UInt,     FORMAT_R16G16B16A16_TYPELESS},
  {FORMAT_R16G16B16A16_SNORM,    "R16G16B16A16_SNORM",     8, 4, K::SNorm,    FORMAT_R16G16B16A16_TYPELESS},
  {FORMAT_R16G16B16A16_SINT,     "R16G16B16A16_SINT",      8, 4, K::SInt,     FORMAT_R16G16B16A16_TYPELESS},
  {FORMAT_R32G32_TYPELESS,       "R32G32_TYPELESS",        8, 2, K::Typeless, FORMAT_R32G32_TYPELESS},
  {FORMAT_R32G32_FLOAT,          "R32G32_FLOAT",           8, 2, K::Float,    FORMAT_R32G32_TYPELESS},
  {FORMAT_R32G32_UINT,           "R32G32_UINT",            8, 2, K::UInt,     FORMAT_R32G32_TYPELESS},
  {FORMAT_R32G32_SINT,           "R32G32_SINT",            8, 2, K::SInt,     FORMAT_R32G32_TYPELESS},
  {FORMAT_R32G8X24_TYPELESS,     "R32G8X24_TYPELESS",      8, 2, K::Typeless, FORMAT_R32G8X24_TYPELESS, 32, 8},
  {FORMAT_D32_FLOAT_S8X24_UINT,  "D32_FLOAT_S8X24_UINT",   8, 2, K::DepthStencil, FORMAT_R32G8X24_TYPELESS, 32, 8, true},
  {FORMAT_R32_FLOAT_X8X24_TYPELESS, "R32_FLOAT_X8X24_TYPELESS", 8, 1, K::Float, FORMAT_R32G8X24_TYPELESS, 32, 8, false, true},
  {FORMAT_X32_TYPELESS_G8X24_UINT,  "X32_TYPELESS_G8X24_UINT",  8, 1, K::UInt,  FORMAT_R32G8X24_TYPELESS, 32, 8, false, false, true},
  {FORMAT_R10G10B10A2_TYPELESS,  "R10G10B10A2_TYPELESS",   4, 4, K::Typeless, FORMAT_R10G10B10A2_TYPELESS},
  {FORMAT_R10G10B10A2_UNORM,     "R10G10B10A2_UNORM",      4, 4, K::UNorm,    FORMAT_R10G10B10A2_TYPELESS},
  {FORMAT_R10G10B10A2_UINT,      "R10G10B10A2_UINT",       4, 4, K::UInt,     FORMAT_R10G10B10A2_TYPELESS},
  {FORMAT_R11G11B10_FLOAT,       "R11G11B10_FLOAT",        4, 3, K::Float,    FORMAT_R11G11B10_FLOAT},
  {FORMAT_R8G8B8A8_TYPELESS,     "R8G8B8A8_TYPELESS",      4, 4, K::Typeless, FORMAT_R8G8B8A8_TYPELESS},
  {FORMAT_R8G8B8A8_UNORM,        "R8G8B8A8_UNORM",         4, 4, K::UNorm,    FORMAT_R8G8B8A8_TYPELESS},
  {FORMAT_R8G8B8A8_UNORM_SRGB,   "R8G8B8A8_UNORM_SRGB",    4, 4, K::UNormSRGB, FORMAT_R8G8B8A8_TYPELESS},
  {FORMAT_R8G8B8A8_UINT,         "R8G8B8A8_UINT",          4, 4, K::UInt,     FORMAT_R8G8B8A8_TYPELESS},
  {FORMAT_R8G8B8A8_SNORM,        "R8G8B8A8_SNORM",         4, 4, K::SNorm,    FORMAT_R8G8B8A8_TYPELESS},
  {FORMAT_R8G8B8A8_SINT,         "R8G8B8A8_SINT",          4, 4, K::SInt,     FORMAT_R8G8B8A8_TYPELESS},
  {FORMAT_R16G16_TYPELESS,       "R16G16_TYPELESS",        4, 2, K::Typeless, FORMAT_R16G16_TYPELESS},
  {FORMAT_R16G16_FLOAT,          "R16G16_FLOAT",           4, 2, K::Float,    FORMAT_R16G16_TYPELESS},
  {FORMAT_R16G16_UNORM,          "R16G16_UNORM",           4, 2, K::UNorm,    FORMAT_R16G16_TYPELESS},
  {FORMAT_R16G16_UINT,           "R16G16_UINT",            4, 2, K::UInt,     FORMAT_R16G16_TYPELESS},
  {FORMAT_R16G16_SNORM,          "R16G16_SNORM",           4, 2, K::SNorm,    FORMAT_R16G16_TYPELESS},
  {FORMAT_R16G16_SINT,           "R16G16_SINT",            4, 2, K::SInt,     FORMAT_R16G16_TYPELESS},
  {FORMAT_R32_TYPELESS,          "R32_TYPELESS",           4, 1, K::Typeless, FORMAT_R32_TYPELESS, 32},
  {FORMAT_D32_FLOAT,             "D32_FLOAT",              4, 1, K::Depth,    FORMAT_R32_TYPELESS, 32, 0, true},
  {FORMAT_R32_FLOAT,             "R32_FLOAT",              4, 1, K::Float,    FORMAT_R32_TYPELESS, 32, 0, false, true},
  {FORMAT_R32_UINT,              "R32_UINT",               4, 1, K::UInt,     FORMAT_R32_TYPELESS},
  {FORMAT_R32_SINT,              "R32_SINT",               4, 1, K::SInt,     FORMAT_R32_TYPELESS},
  {FORMAT_R24G8_TYPELESS,        "R24G8_TYPELESS",         4, 2, K::Typeless, FORMAT_R24G8_TYPELESS, 24, 8},
  {FORMAT_D24_UNORM_S8_UINT,     "D24_UNORM_S8_UINT",      4, 2, K::DepthStencil, FORMAT_R24G8_TYPELESS, 24, 8, true},
  {FORMAT_R24_UNORM_X8_TYPELESS, "R24_UNORM_X8_TYPELESS",  4, 1, K::UNorm,    FORMAT_R24G8_TYPELESS, 24, 8, false, true},
  {FORMAT_X24_TYPELESS_G8_UINT,  "X24_TYPELESS_G8_UINT",   4, 1, K::UInt,     FORMAT_R24G8_TYPELESS, 24, 8, false, false, true},
  {FORMAT_R8G8_TYPELESS,         "R8G8_TYPELESS",          2, 2, K::Typeless, FORMAT_R8G8_TYPELESS},
  {FORMAT_R8G8_UNORM,            "R8G8_UNORM",             2, 2, K::UNorm,    FORMAT_R8G8_TYPELESS},
  {FORMAT_R8G8_UINT,             "R8G8_UINT",              2, 2, K::UInt,     FORMAT_R8G8_TYPELESS},
  {FORMAT_R8G8_SNORM,            "R8G8_SNORM",             2, 2, K::SNorm,    FORMAT_R8G8_TYPELESS},
  {FORMAT_R8G8_SINT,             "R8G8_SINT",              2, 2, K::SInt,     FORMAT_R8G8_TYPELESS},
  {FORMAT_R16_TYPELESS,          "R16_TYPELESS",           2, 1, K::Typeless, FORMAT_R16_TYPELESS, 16},
  {FORMAT_R16_FLOAT,             "R16_FLOAT",              2, 1, K::Float,    FORMAT_R16_TYPELESS},
  {FORMAT_D16_UNORM,             "D16_UNORM",              2, 1, K::Depth,    FORMAT_R16_TYPELESS, 16, 0, true},
  {FORMAT_R16_UNORM,             "R16_UNORM",              2, 1, K::UNorm,    FORMAT_R16_TYPELESS, 16, 0, false, true},
  {FORMAT_R16_UINT,              "R16_UINT",               2, 1, K::UInt,     FORMAT_R16_TYPELESS},
  {FORMAT_R16_SNORM,             "R16_SNORM",              2, 1, K::SNorm,    FORMAT_R16_TYPELESS},
  {FORMAT_R16_SINT,              "R16_SINT",               2, 1, K::SInt,     FORMAT_R16_TYPELESS},
  {FORMAT_R8_TYPELESS,           "R8_TYPELESS",            1, 1, K::Typeless, FORMAT_R8_TYPELESS},
  {FORMAT_R8_UNORM,              "R8_UNORM",               1, 1, K::UNorm,    FORMAT_R8_TYPELESS},
  {FORMAT_R8_UINT,               "R8_UINT",                1, 1, K::UInt,     FORMAT_R8_TYPELESS},
  {FORMAT_R8_SNORM,              "R8_SNORM",               1, 1, K::SNorm,    FORMAT_R8_TYPELESS},
  {FORMAT_R8_SINT,               "R8_SINT",                1, 1, K::SInt,     FORMAT_R8_TYPELESS},
  {FORMAT_B8G8R8A8_UNORM,        "B8G8R8A8_UNORM",         4, 4, K::UNorm,    FORMAT_B8G8R8A8_TYPELESS},
  {FORMAT_B8G8R8A8_TYPELESS,     "B8G8R8A8_TYPELESS",      4, 4, K::Typeless, FORMAT_B8G8R8A8_TYPELESS},
  {FORMAT_B8G8R8A8_UNORM_SRGB,   "B8G8R8A8_UNORM_SRGB",    4, 4, K::UNormSRGB, FORMAT_B8G8R8A8_TYPELESS},
};
// clang-format on

constexpr uint32_t kMaxFormat = 128;

const std::array<FormatInfo, kMaxFormat>& Table() {
  static const std::array<FormatInfo, kMaxFormat> table = [] {
    std::array<FormatInfo, kMaxFormat> t{};
    for (const Row& r : kRows) {
      FormatInfo& i = t[r.f];
      i.format = r.f;
      i.name = r.name;
      i.bytesPerElement = r.bytes;
      i.components = r.comps;
      i.kind = r.kind;
      i.typelessFamily = r.family;
      i.depthBits = r.depthBits;
      i.stencilBits = r.stencilBits;
      i.isDepthView = r.dsv;
      i.readsDepth = r.readsDepth;
      i.readsStencil = r.readsStencil;
    }
    return t;
  }();
  return table;
}

}  // namespace

const FormatInfo& GetFormatInfo(FORMAT format) {
  static const FormatInfo unknown{};
  if (format >= kMaxFormat) return unknown;
  return Table()[format];
}

std::string_view FormatName(FORMAT format) {
  const FormatInfo& i = GetFormatInfo(format);
  if (i.format != FORMAT_UNKNOWN) return i.name;
  if (format == FORMAT_UNKNOWN) return "UNKNOWN";
  static thread_local std::string buf;
  buf = "FORMAT(" + std::to_string(uint32_t(format)) + ")";
  return buf;
}

bool FormatsCompatibleForView(FORMAT resourceFormat, FORMAT viewFormat) {
  const FormatInfo& r = GetFormatInfo(resourceFormat);
  const FormatInfo& v = GetFormatInfo(viewFormat);
  if (r.format == FORMAT_UNKNOWN || v.format == FORMAT_UNKNOWN) return false;
  if (v.kind == FormatKind::Typeless) return false;  // views are always typed
  if (resourceFormat == viewFormat) return true;
  // A typed resource only allows its own format, except the depth formats whose SRVs read
  // through the family's read formats (D3D11 requires TYPELESS for that too).
  return r.kind == FormatKind::Typeless && r.typelessFamily == v.typelessFamily;
}

FORMAT DepthFormatOfFamily(FORMAT format) {
  switch (GetFormatInfo(format).typelessFamily) {
    case FORMAT_R16_TYPELESS: return FORMAT_D16_UNORM;
    case FORMAT_R24G8_TYPELESS: return FORMAT_D24_UNORM_S8_UINT;
    case FORMAT_R32_TYPELESS: return FORMAT_D32_FLOAT;
    case FORMAT_R32G8X24_TYPELESS: return FORMAT_D32_FLOAT_S8X24_UINT;
    default: return FORMAT_UNKNOWN;
  }
}

}  // namespace sp
