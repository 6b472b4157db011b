// Clears. D3D11 clears exactly the view's subresources and ignores the scissor rectangle and
// write masks, so the clears switch those off (through the state cache) before clearing.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "gl-context.h"

namespace sp::gl {
namespace {

// ClearUnorderedAccessViewUint writes the low bits of each value into each channel, unconverted.
std::array<uint8_t, 16> PackUintTexel(FORMAT format, const uint32_t v[4]) {
  std::array<uint8_t, 16> out{};
  const FormatInfo& fi = GetFormatInfo(format);
  if (format == FORMAT_R10G10B10A2_UNORM || format == FORMAT_R10G10B10A2_UINT) {
    uint32_t t = (v[0] & 0x3ff) | (v[1] & 0x3ff) << 10 | (v[2] & 0x3ff) << 20 | (v[3] & 3) << 30;
    std::memcpy(out.data(), &t, 4);
  } else if (format == FORMAT_R11G11B10_FLOAT) {
    uint32_t t = (v[0] & 0x7ff) | (v[1] & 0x7ff) << 11 | (v[2] & 0x3ff) << 22;
    std::memcpy(out.data(), &t, 4);
  } else {
    const uint32_t channelBytes = fi.bytesPerElement / std::max(fi.components, 1u);
    for (uint32_t c = 0; c < fi.components; ++c) std::memcpy(out.data() + c * channelBytes, &v[c], channelBytes);  // little endian
  }
  return out;
}

template <class T>
T ToInteger(float f, double lo, double hi) {
  if (std::isnan(f)) return 0;
  return T(std::clamp(double(f), lo, hi));
}

}  // namespace

void GLContext::ClearRenderTargetView(RenderTargetView* rtv, const float rgba[4]) {
  dev_.MakeCurrent();
  FramebufferKey key;
  key.colors[0] = AttachmentOf(rtv);
  GLuint fbo = Framebuffer(key, "ClearRenderTargetView");
  BindDrawFramebuffer(fbo);
  SetScissorTest(false);
  SetColorMask(0, 0xf);
  // With GL_FRAMEBUFFER_SRGB on, sRGB targets get the colour encoded as D3D does.
  switch (GetFormatInfo(rtv->ViewFormat()).kind) {
    case FormatKind::UInt: {
      GLuint v[4];
      for (int i = 0; i < 4; ++i) v[i] = ToInteger<GLuint>(rgba[i], 0.0, 4294967295.0);
      glClearNamedFramebufferuiv(fbo, GL_COLOR, 0, v);
      break;
    }
    case FormatKind::SInt: {
      GLint v[4];
      for (int i = 0; i < 4; ++i) v[i] = ToInteger<GLint>(rgba[i], -2147483648.0, 2147483647.0);
      glClearNamedFramebufferiv(fbo, GL_COLOR, 0, v);
      break;
    }
    default:
      glClearNamedFramebufferfv(fbo, GL_COLOR, 0, rgba);
  }
}

void GLContext::ClearDepthStencilView(DepthStencilView* dsv, uint32_t flags, float depth, uint8_t stencil) {
  dev_.MakeCurrent();
  FramebufferKey key;
  key.depth = AttachmentOf(dsv);
  key.depthPoint = DepthAttachmentPoint(dsv);
  GLuint fbo = Framebuffer(key, "ClearDepthStencilView");
  BindDrawFramebuffer(fbo);
  SetScissorTest(false);
  const bool clearDepth = flags & CLEAR_DEPTH, clearStencil = flags & CLEAR_STENCIL;
  if (clearDepth) SetDepthMask(true);
  if (clearStencil) SetStencilWriteMask(0xff);
  const GLint s = stencil;
  if (clearDepth && clearStencil) glClearNamedFramebufferfi(fbo, GL_DEPTH_STENCIL, 0, depth, s);
  else if (clearDepth) glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &depth);
  else glClearNamedFramebufferiv(fbo, GL_STENCIL, 0, &s);
}

static void ClearImage(const UnorderedAccessView* uav, GLenum format, GLenum type, const void* data) {
  const GLView& v = GL(uav);
  const Texture* tex = static_cast<const Texture*>(uav->GetResource());
  const ViewRange& r = uav->Range();
  const TextureShape& s = tex->Shape();
  const uint32_t w = s.mipWidth(r.firstMip), h = s.mipHeight(r.firstMip);
  uint32_t layer = uint32_t(std::max(v.layer, 0)), layers = 1;
  if (v.layered) layers = s.dimension == RESOURCE_DIMENSION_TEXTURE3D ? s.mipDepth(r.firstMip) : r.sliceCount;
  const GLRegion g = RegionOf(v.target, 0, 0, layer, w, h, layers);
  glClearTexSubImage(v.texture, v.level, g.x, g.y, g.z, g.w, g.h, g.d, format, type, data);
}

void GLContext::ClearUnorderedAccessViewUint(UnorderedAccessView* uav, const uint32_t values[4]) {
  dev_.MakeCurrent();
  const GLView& v = GL(uav);
  if (v.kind == GLView::Kind::StorageBuffer) {
    // Raw and structured views: every 32-bit word gets values[0].
    glClearNamedBufferSubData(v.buffer, GL_R32UI, v.offset, v.size, GL_RED_INTEGER, GL_UNSIGNED_INT, &values[0]);
    return;
  }
  // The texel is built in memory order and handed over in the format's exact client layout.
  const std::array<uint8_t, 16> texel = PackUintTexel(uav->ViewFormat(), values);
  if (v.kind == GLView::Kind::TypedBuffer)
    glClearNamedBufferSubData(v.buffer, v.format->internal, v.offset, v.size, v.format->extFormat, v.format->extType, texel.data());
  else
    ClearImage(uav, v.format->extFormat, v.format->extType, texel.data());
}

void GLContext::ClearUnorderedAccessViewFloat(UnorderedAccessView* uav, const float values[4]) {
  dev_.MakeCurrent();
  const GLView& v = GL(uav);
  if (v.kind == GLView::Kind::TypedBuffer) glClearNamedBufferSubData(v.buffer, v.format->internal, v.offset, v.size, GL_RGBA, GL_FLOAT, values);
  else ClearImage(uav, GL_RGBA, GL_FLOAT, values);
}

}  // namespace sp::gl
