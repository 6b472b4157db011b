// DXGI formats as GL sized internal formats, client formats that keep D3D's memory layout, and
// vertex attribute formats.
//
// TYPELESS colour textures are stored in the UINT member of their family where there is one:
// every view reinterprets the bits through glTextureView, and integer client formats make
// uploads and readbacks bit-exact (no float canonicalisation on the way).
#include "gl-internal.h"

namespace sp::gl {
namespace {

struct Entry {
  FORMAT format;
  GLFormat gl;
};

// Shorthands for the table.
constexpr GLFormat Color(GLenum internal, GLenum fmt, GLenum type, bool integer, GLint attribSize, GLenum attribType, bool norm,
                         bool tbo, bool image) {
  GLFormat f;
  f.internal = internal;
  f.extFormat = fmt;
  f.extType = type;
  f.integer = integer;
  f.attribSize = attribSize;
  f.attribType = attribType;
  f.attribNormalized = norm;
  f.attribInteger = integer && attribSize > 0;
  f.textureBuffer = tbo;
  f.image = image;
  return f;
}
constexpr GLFormat Depth(GLenum internal, GLenum fmt, GLenum type, bool stencil) {
  GLFormat f;
  f.internal = internal;
  f.extFormat = fmt;
  f.extType = type;
  f.depth = true;
  f.stencil = stencil;
  return f;
}

constexpr GLenum RGBA_I = GL_RGBA_INTEGER, RGB_I = GL_RGB_INTEGER, RG_I = GL_RG_INTEGER, R_I = GL_RED_INTEGER;
constexpr GLenum U8 = GL_UNSIGNED_BYTE, S8 = GL_BYTE, U16 = GL_UNSIGNED_SHORT, S16 = GL_SHORT, U32 = GL_UNSIGNED_INT, S32 = GL_INT,
                 F16 = GL_HALF_FLOAT, F32 = GL_FLOAT;

// clang-format off
const Entry kEntries[] = {
  {FORMAT_R32G32B32A32_TYPELESS, Color(GL_RGBA32UI, RGBA_I, U32, true, 0, 0, false, true, true)},
  {FORMAT_R32G32B32A32_FLOAT,    Color(GL_RGBA32F, GL_RGBA, F32, false, 4, F32, false, true, true)},
  {FORMAT_R32G32B32A32_UINT,     Color(GL_RGBA32UI, RGBA_I, U32, true, 4, U32, false, true, true)},
  {FORMAT_R32G32B32A32_SINT,     Color(GL_RGBA32I, RGBA_I, S32, true, 4, S32, false, true, true)},
  {FORMAT_R32G32B32_TYPELESS,    Color(GL_RGB32UI, RGB_I, U32, true, 0, 0, false, true, false)},
  {FORMAT_R32G32B32_FLOAT,       Color(GL_RGB32F, GL_RGB, F32, false, 3, F32, false, true, false)},
  {FORMAT_R32G32B32_UINT,        Color(GL_RGB32UI, RGB_I, U32, true, 3, U32, false, true, false)},
  {FORMAT_R32G32B32_SINT,        Color(GL_RGB32I, RGB_I, S32, true, 3, S32, false, true, false)},
  {FORMAT_R16G16B16A16_TYPELESS, Color(GL_RGBA16UI, RGBA_I, U16, true, 0, 0, false, true, true)},
  {FORMAT_R16G16B16A16_FLOAT,    Color(GL_RGBA16F, GL_RGBA, F16, false, 4, F16, false, true, true)},
  {FORMAT_R16G16B16A16_UNORM,    Color(GL_RGBA16, GL_RGBA, U16, false, 4, U16, true, true, true)},
  {FORMAT_R16G16B16A16_UINT,     Color(GL_RGBA16UI, RGBA_I, U16, true, 4, U16, false, true, true)},
  {FORMAT_R16G16B16A16_SNORM,    Color(GL_RGBA16_SNORM, GL_RGBA, S16, false, 4, S16, true, false, true)},
  {FORMAT_R16G16B16A16_SINT,     Color(GL_RGBA16I, RGBA_I, S16, true, 4, S16, false, true, true)},
  {FORMAT_R32G32_TYPELESS,       Color(GL_RG32UI, RG_I, U32, true, 0, 0, false, true, true)},
  {FORMAT_R32G32_FLOAT,          Color(GL_RG32F, GL_RG, F32, false, 2, F32, false, true, true)},
  {FORMAT_R32G32_UINT,           Color(GL_RG32UI, RG_I, U32, true, 2, U32, false, true, true)},
  {FORMAT_R32G32_SINT,           Color(GL_RG32I, RG_I, S32, true, 2, S32, false, true, true)},
  {FORMAT_R32G8X24_TYPELESS,     Depth(GL_DEPTH32F_STENCIL8, GL_DEPTH_STENCIL, GL_FLOAT_32_UNSIGNED_INT_24_8_REV, true)},
  {FORMAT_D32_FLOAT_S8X24_UINT,  Depth(GL_DEPTH32F_STENCIL8, GL_DEPTH_STENCIL, GL_FLOAT_32_UNSIGNED_INT_24_8_REV, true)},
  {FORMAT_R32_FLOAT_X8X24_TYPELESS, Depth(GL_DEPTH32F_STENCIL8, GL_DEPTH_STENCIL, GL_FLOAT_32_UNSIGNED_INT_24_8_REV, true)},
  {FORMAT_X32_TYPELESS_G8X24_UINT,  Depth(GL_DEPTH32F_STENCIL8, GL_DEPTH_STENCIL, GL_FLOAT_32_UNSIGNED_INT_24_8_REV, true)},
  {FORMAT_R10G10B10A2_TYPELESS,  Color(GL_RGB10_A2UI, RGBA_I, GL_UNSIGNED_INT_2_10_10_10_REV, true, 0, 0, false, false, true)},
  {FORMAT_R10G10B10A2_UNORM,     Color(GL_RGB10_A2, GL_RGBA, GL_UNSIGNED_INT_2_10_10_10_REV, false, 4, GL_UNSIGNED_INT_2_10_10_10_REV, true, false, true)},
  // GL has no integer vertex fetch of packed 10:10:10:2 data.
  {FORMAT_R10G10B10A2_UINT,      Color(GL_RGB10_A2UI, RGBA_I, GL_UNSIGNED_INT_2_10_10_10_REV, true, 0, 0, false, false, true)},
  {FORMAT_R11G11B10_FLOAT,       Color(GL_R11F_G11F_B10F, GL_RGB, GL_UNSIGNED_INT_10F_11F_11F_REV, false, 3, GL_UNSIGNED_INT_10F_11F_11F_REV, false, false, true)},
  {FORMAT_R8G8B8A8_TYPELESS,     Color(GL_RGBA8UI, RGBA_I, U8, true, 0, 0, false, true, true)},
  {FORMAT_R8G8B8A8_UNORM,        Color(GL_RGBA8, GL_RGBA, U8, false, 4, U8, true, true, true)},
  {FORMAT_R8G8B8A8_UNORM_SRGB,   Color(GL_SRGB8_ALPHA8, GL_RGBA, U8, false, 0, 0, false, false, false)},
  {FORMAT_R8G8B8A8_UINT,         Color(GL_RGBA8UI, RGBA_I, U8, true, 4, U8, false, true, true)},
  {FORMAT_R8G8B8A8_SNORM,        Color(GL_RGBA8_SNORM, GL_RGBA, S8, false, 4, S8, true, false, true)},
  {FORMAT_R8G8B8A8_SINT,         Color(GL_RGBA8I, RGBA_I, S8, true, 4, S8, false, true, true)},
  {FORMAT_R16G16_TYPELESS,       Color(GL_RG16UI, RG_I, U16, true, 0, 0, false, true, true)},
  {FORMAT_R16G16_FLOAT,          Color(GL_RG16F, GL_RG, F16, false, 2, F16, false, true, true)},
  {FORMAT_R16G16_UNORM,          Color(GL_RG16, GL_RG, U16, false, 2, U16, true, true, true)},
  {FORMAT_R16G16_UINT,           Color(GL_RG16UI, RG_I, U16, true, 2, U16, false, true, true)},
  {FORMAT_R16G16_SNORM,          Color(GL_RG16_SNORM, GL_RG, S16, false, 2, S16, true, false, true)},
  {FORMAT_R16G16_SINT,           Color(GL_RG16I, RG_I, S16, true, 2, S16, false, true, true)},
  {FORMAT_R32_TYPELESS,          Color(GL_R32UI, R_I, U32, true, 0, 0, false, true, true)},
  {FORMAT_D32_FLOAT,             Depth(GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, F32, false)},
  {FORMAT_R32_FLOAT,             Color(GL_R32F, GL_RED, F32, false, 1, F32, false, true, true)},
  {FORMAT_R32_UINT,              Color(GL_R32UI, R_I, U32, true, 1, U32, false, true, true)},
  {FORMAT_R32_SINT,              Color(GL_R32I, R_I, S32, true, 1, S32, false, true, true)},
  {FORMAT_R24G8_TYPELESS,        Depth(GL_DEPTH24_STENCIL8, GL_DEPTH_STENCIL, GL_UNSIGNED_INT_24_8, true)},
  {FORMAT_D24_UNORM_S8_UINT,     Depth(GL_DEPTH24_STENCIL8, GL_DEPTH_STENCIL, GL_UNSIGNED_INT_24_8, true)},
  {FORMAT_R24_UNORM_X8_TYPELESS, Depth(GL_DEPTH24_STENCIL8, GL_DEPTH_STENCIL, GL_UNSIGNED_INT_24_8, true)},
  {FORMAT_X24_TYPELESS_G8_UINT,  Depth(GL_DEPTH24_STENCIL8, GL_DEPTH_STENCIL, GL_UNSIGNED_INT_24_8, true)},
  {FORMAT_R8G8_TYPELESS,         Color(GL_RG8UI, RG_I, U8, true, 0, 0, false, true, true)},
  {FORMAT_R8G8_UNORM,            Color(GL_RG8, GL_RG, U8, false, 2, U8, true, true, true)},
  {FORMAT_R8G8_UINT,             Color(GL_RG8UI, RG_I, U8, true, 2, U8, false, true, true)},
  {FORMAT_R8G8_SNORM,            Color(GL_RG8_SNORM, GL_RG, S8, false, 2, S8, true, false, true)},
  {FORMAT_R8G8_SINT,             Color(GL_RG8I, RG_I, S8, true, 2, S8, false, true, true)},
  {FORMAT_R16_TYPELESS,          Color(GL_R16UI, R_I, U16, true, 0, 0, false, true, true)},
  {FORMAT_R16_FLOAT,             Color(GL_R16F, GL_RED, F16, false, 1, F16, false, true, true)},
  {FORMAT_D16_UNORM,             Depth(GL_DEPTH_COMPONENT16, GL_DEPTH_COMPONENT, U16, false)},
  {FORMAT_R16_UNORM,             Color(GL_R16, GL_RED, U16, false, 1, U16, true, true, true)},
  {FORMAT_R16_UINT,              Color(GL_R16UI, R_I, U16, true, 1, U16, false, true, true)},
  {FORMAT_R16_SNORM,             Color(GL_R16_SNORM, GL_RED, S16, false, 1, S16, true, false, true)},
  {FORMAT_R16_SINT,              Color(GL_R16I, R_I, S16, true, 1, S16, false, true, true)},
  {FORMAT_R8_TYPELESS,           Color(GL_R8UI, R_I, U8, true, 0, 0, false, true, true)},
  {FORMAT_R8_UNORM,              Color(GL_R8, GL_RED, U8, false, 1, U8, true, true, true)},
  {FORMAT_R8_UINT,               Color(GL_R8UI, R_I, U8, true, 1, U8, false, true, true)},
  {FORMAT_R8_SNORM,              Color(GL_R8_SNORM, GL_RED, S8, false, 1, S8, true, false, true)},
  {FORMAT_R8_SINT,               Color(GL_R8I, R_I, S8, true, 1, S8, false, true, true)},
  // BGRA is stored as RGBA; GL_BGRA client data keeps D3D's byte order in memory.
  {FORMAT_B8G8R8A8_UNORM,        Color(GL_RGBA8, GL_BGRA, U8, false, GL_BGRA, U8, true, false, false)},
  {FORMAT_B8G8R8A8_TYPELESS,     Color(GL_RGBA8, GL_BGRA, U8, false, 0, 0, false, false, false)},
  {FORMAT_B8G8R8A8_UNORM_SRGB,   Color(GL_SRGB8_ALPHA8, GL_BGRA, U8, false, 0, 0, false, false, false)},
};
// clang-format on

const std::array<GLFormat, 128>& Table() {
  static const std::array<GLFormat, 128> table = [] {
    std::array<GLFormat, 128> t{};
    for (const Entry& e : kEntries) t[e.format] = e.gl;
    return t;
  }();
  return table;
}

}  // namespace

const GLFormat& FormatOf(FORMAT format) {
  static const GLFormat none{};
  return format < 128 ? Table()[format] : none;
}

bool IsDepthStorage(const TextureShape& s) {
  if (s.usage == USAGE_STAGING) return false;
  if (s.bindFlags & BIND_DEPTH_STENCIL) return true;
  // The packed depth-stencil families have no colour member GL could store them as.
  const FORMAT family = GetFormatInfo(s.format).typelessFamily;
  return family == FORMAT_R24G8_TYPELESS || family == FORMAT_R32G8X24_TYPELESS || FormatOf(s.format).depth;
}

const GLFormat& StorageFormatOf(const TextureShape& s) {
  if (s.bindFlags & BIND_DEPTH_STENCIL) return FormatOf(DepthFormatOfFamily(s.format));
  return FormatOf(s.format);
}

}  // namespace sp::gl
