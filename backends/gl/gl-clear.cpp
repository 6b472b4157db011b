// Clears. D3D11 clears exactly the view's subresources and ignores the scissor rectangle and
// write masks, so the clears switch those off (through the state cache) before clearing.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "gl-context.h"

namespace sp::gl {
namespace {

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

namespace {

// The unsigned-integer format of a texel size: GL hands integer data over without conversion,
// while its float paths canonicalise NaNs and flush denormals of packed floats.
struct UintLayout {
  GLenum internal, format;
};
UintLayout UintOfSize(uint32_t bytes) {
  switch (bytes) {
    case 1: return {GL_R8UI, GL_RED_INTEGER};
    case 2: return {GL_R16UI, GL_RED_INTEGER};
    case 8: return {GL_RG32UI, GL_RG_INTEGER};
    case 12: return {GL_RGB32UI, GL_RGB_INTEGER};
    case 16: return {GL_RGBA32UI, GL_RGBA_INTEGER};
    default: return {GL_R32UI, GL_RED_INTEGER};
  }
}
GLenum UintType(uint32_t bytes) { return bytes == 1 ? GL_UNSIGNED_BYTE : bytes == 2 ? GL_UNSIGNED_SHORT : GL_UNSIGNED_INT; }

}  // namespace

static void ClearImage(GLView& v, const UnorderedAccessView* uav, const detail::UavClearValue& value) {
  const Texture* tex = static_cast<const Texture*>(uav->GetResource());
  const ViewRange& r = uav->Range();
  const TextureShape& s = tex->Shape();
  const uint32_t w = s.mipWidth(r.firstMip), h = s.mipHeight(r.firstMip);
  uint32_t layer = uint32_t(std::max(v.layer, 0)), layers = 1;
  if (v.layered) layers = s.dimension == RESOURCE_DIMENSION_TEXTURE3D ? s.mipDepth(r.firstMip) : r.sliceCount;
  const GLRegion g = RegionOf(v.target, 0, 0, layer, w, h, layers);
  // Integer formats take their own client layout unconverted.
  if (v.format->integer) return glClearTexSubImage(v.texture, v.level, g.x, g.y, g.z, g.w, g.h, g.d, v.format->extFormat, v.format->extType, value.texel);
  const UintLayout u = UintOfSize(value.texelBytes);
  if (!v.clearView) {
    // A view of all of `texture` (itself maybe a view), so that level and layers stay as above.
    GLint levels = 1, allLayers = 1;
    glGetTextureParameteriv(v.texture, GL_TEXTURE_IMMUTABLE_LEVELS, &levels);
    if (v.target == GL_TEXTURE_1D_ARRAY) glGetTextureLevelParameteriv(v.texture, 0, GL_TEXTURE_HEIGHT, &allLayers);
    else if (v.target == GL_TEXTURE_2D_ARRAY || v.target == GL_TEXTURE_CUBE_MAP_ARRAY) glGetTextureLevelParameteriv(v.texture, 0, GL_TEXTURE_DEPTH, &allLayers);
    else if (v.target == GL_TEXTURE_CUBE_MAP) allLayers = 6;
    glGenTextures(1, &v.clearView);
    glTextureView(v.clearView, v.target, v.texture, u.internal, 0, GLuint(levels), 0, GLuint(allLayers));
  }
  glClearTexSubImage(v.clearView, v.level, g.x, g.y, g.z, g.w, g.h, g.d, u.format, UintType(value.texelBytes), value.texel);
}

// The core packed the texel in memory order; it goes over as unsigned integers of the same size.
void GLContext::ClearUnorderedAccessView(UnorderedAccessView* uav, const detail::UavClearValue& value) {
  dev_.MakeCurrent();
  GLView& v = GL(uav);
  if (v.kind == GLView::Kind::Texture) return ClearImage(v, uav, value);
  const UintLayout u = UintOfSize(value.texelBytes);
  glClearNamedBufferSubData(v.buffer, u.internal, v.offset, v.size, u.format, UintType(value.texelBytes), value.texel);
}

}  // namespace sp::gl
