// Framebuffer objects, cached by their attachments. Render-target and depth-stencil views are
// attachments (a texture or texture view, a level, a layer or all layers), so a framebuffer is
// made once per combination of views and reused by draws, clears and resolves.
#include "gl-context.h"

namespace sp::gl {
namespace {

void Attach(GLuint fbo, GLenum point, const Attachment& a) {
  if (a.layer >= 0) glNamedFramebufferTextureLayer(fbo, point, a.texture, a.level, a.layer);
  else glNamedFramebufferTexture(fbo, point, a.texture, a.level);
}

const char* StatusName(GLenum status) {
  switch (status) {
    case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT: return "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT: return "GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT";
    case GL_FRAMEBUFFER_UNSUPPORTED: return "GL_FRAMEBUFFER_UNSUPPORTED";
    case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE: return "GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE";
    case GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS: return "GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS";
    default: return "incomplete";
  }
}

}  // namespace

Attachment GLContext::AttachmentOf(const View* view) {
  const GLView& v = GL(view);
  return {v.texture, v.level, v.layer};
}

GLenum GLContext::DepthAttachmentPoint(const View* dsv) {
  return GetFormatInfo(dsv->ViewFormat()).stencilBits ? GL_DEPTH_STENCIL_ATTACHMENT : GL_DEPTH_ATTACHMENT;
}

GLuint GLContext::Framebuffer(const FramebufferKey& key, const char* call) {
  auto it = framebuffers_.find(key);
  if (it != framebuffers_.end()) return it->second;
  GLuint fbo = 0;
  glCreateFramebuffers(1, &fbo);
  std::array<GLenum, SIMULTANEOUS_RENDER_TARGET_COUNT> draw{};
  GLsizei count = 0;
  for (uint32_t i = 0; i < SIMULTANEOUS_RENDER_TARGET_COUNT; ++i) {
    draw[i] = GL_NONE;
    if (!key.colors[i].texture) continue;
    Attach(fbo, GL_COLOR_ATTACHMENT0 + i, key.colors[i]);
    draw[i] = GL_COLOR_ATTACHMENT0 + i;  // SV_Target i goes to render target slot i
    count = GLsizei(i + 1);
  }
  glNamedFramebufferDrawBuffers(fbo, count ? count : 1, draw.data());
  glNamedFramebufferReadBuffer(fbo, key.colors[0].texture ? GL_COLOR_ATTACHMENT0 : GL_NONE);
  if (key.depth.texture) Attach(fbo, key.depthPoint, key.depth);
  if (key.emptyWidth) {
    glNamedFramebufferParameteri(fbo, GL_FRAMEBUFFER_DEFAULT_WIDTH, GLint(key.emptyWidth));
    glNamedFramebufferParameteri(fbo, GL_FRAMEBUFFER_DEFAULT_HEIGHT, GLint(key.emptyHeight));
    glNamedFramebufferParameteri(fbo, GL_FRAMEBUFFER_DEFAULT_LAYERS, GLint(key.emptyLayers > 1 ? key.emptyLayers : 0));
  }
  GLenum status = glCheckNamedFramebufferStatus(fbo, GL_DRAW_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    glDeleteFramebuffers(1, &fbo);
    ThrowError(ErrorId::DEVICE_API_ERROR, call, "framebuffer",
               std::string("the driver rejected this combination of render targets and depth-stencil view (") + StatusName(status) + ")");
  }
  framebuffers_.emplace(key, fbo);
  return fbo;
}

void GLContext::BindDrawFramebuffer(GLuint fbo) {
  SetCached(cache_.drawFramebuffer, fbo, [&] {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    disturbed_ |= DIRTY_RENDER_TARGETS;
  });
}

void GLContext::BindReadFramebuffer(GLuint fbo) {
  SetCached(cache_.readFramebuffer, fbo, [&] { glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo); });
}

}  // namespace sp::gl
