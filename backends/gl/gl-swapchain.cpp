// Presentation on GL: an EGL window surface of the device's X11 display. The context renders
// surfaceless as always; Present makes it current on the window, blits the back buffer's texture
// to the window's framebuffer upside down (GL's row 0 is the bottom of a window, D3D's row 0 the
// top, and textures here hold D3D's row 0 in GL's row 0), swaps, and goes back to surfaceless.
#include "gl-context.h"

namespace sp::gl {
namespace {

std::string EglError() {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "EGL error 0x%04x", unsigned(eglGetError()));
  return buf;
}

class GLSwapChain final : public detail::SwapChainBackend {
 public:
  GLSwapChain(GLDevice& dev, const SwapChainDesc& desc, unsigned long visualId) : dev_(dev), window_(desc.window.x11Window) {
    const char* call = "CreateSwapChain";
    EGLDisplay d = dev_.eglDisplay();
    const EGLint want[] = {EGL_SURFACE_TYPE, EGL_WINDOW_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8,
                           EGL_BLUE_SIZE, 8, EGL_NONE};
    EGLint n = 0;
    eglChooseConfig(d, want, nullptr, 0, &n);
    std::vector<EGLConfig> configs(size_t(std::max(n, 0)));
    if (n > 0) eglChooseConfig(d, want, configs.data(), n, &n);
    // The config must describe the window's visual, or the surface cannot be made.
    std::string tried;
    for (EGLConfig c : configs) {
      EGLint visual = 0;
      eglGetConfigAttrib(d, c, EGL_NATIVE_VISUAL_ID, &visual);
      if (visualId && EGLint(visualId) != visual) continue;
      surface_ = eglCreatePlatformWindowSurface(d, c, &window_, nullptr);
      if (surface_ != EGL_NO_SURFACE) break;
      tried += " " + EglError();
    }
    if (surface_ == EGL_NO_SURFACE)
      ThrowError(ErrorId::NOT_SUPPORTED, call, "OpenGL",
                 "no EGL config makes a window surface for X visual " + std::to_string(visualId) + " (" + std::to_string(configs.size()) +
                     " window configs;" + (tried.empty() ? std::string(" none matches the visual") : tried) + ")");
    dev_.MakeCurrent();
    glCreateFramebuffers(1, &readFbo_);
  }

  ~GLSwapChain() override {
    dev_.MakeCurrent();
    glDeleteFramebuffers(1, &readFbo_);
    eglDestroySurface(dev_.eglDisplay(), surface_);
  }

  // The blit copies channels without conversion while GL_FRAMEBUFFER_SRGB is off, so every
  // 8-bit colour format shows exactly; wider formats would be quantised by an 8-bit window.
  std::vector<FORMAT> Formats() const override {
    return {FORMAT_R8G8B8A8_UNORM, FORMAT_R8G8B8A8_UNORM_SRGB, FORMAT_B8G8R8A8_UNORM, FORMAT_B8G8R8A8_UNORM_SRGB};
  }

  void Configure(const SwapChainDesc&) override {}

  void Present(Texture2D& backBuffer, uint32_t syncInterval) override {
    const char* call = "Present";
    EGLDisplay d = dev_.eglDisplay();
    GLContext& ctx = *dev_.context();
    if (!eglMakeCurrent(d, surface_, surface_, dev_.eglContext()))
      ThrowError(ErrorId::DEVICE_API_ERROR, call, "OpenGL", "eglMakeCurrent on the window surface failed: " + EglError());
    EGLint w = 0, h = 0;
    eglQuerySurface(d, surface_, EGL_WIDTH, &w);
    eglQuerySurface(d, surface_, EGL_HEIGHT, &h);
    const TextureShape& shape = backBuffer.Shape();
    glNamedFramebufferTexture(readFbo_, GL_COLOR_ATTACHMENT0, GL(&backBuffer).name, 0);
    glNamedFramebufferReadBuffer(readFbo_, GL_COLOR_ATTACHMENT0);
    // A blit is subject to the scissor test and, with GL_FRAMEBUFFER_SRGB on, to sRGB decoding
    // of the source and encoding of the destination: both off, the bytes are copied as they are.
    ctx.SetScissorTest(false);
    glDisable(GL_FRAMEBUFFER_SRGB);
    // Mesa allocates a window's buffers when its framebuffer is validated, which happens for the
    // bound draw framebuffer only: a blit to framebuffer 0 while another is bound writes nowhere.
    // The draw buffer is set because a context first made current surfaceless starts with GL_NONE.
    ctx.BindDrawFramebuffer(0);
    glNamedFramebufferDrawBuffer(0, GL_BACK);
    const bool scaled = GLint(shape.width) != w || GLint(shape.height) != h;
    glBlitNamedFramebuffer(readFbo_, 0, 0, 0, GLint(shape.width), GLint(shape.height), 0, h, w, 0, GL_COLOR_BUFFER_BIT,
                           scaled ? GL_LINEAR : GL_NEAREST);
    glEnable(GL_FRAMEBUFFER_SRGB);
    if (int(syncInterval) != interval_) {
      eglSwapInterval(d, EGLint(syncInterval));
      interval_ = int(syncInterval);
    }
    const bool swapped = eglSwapBuffers(d, surface_);
    std::string swapError = swapped ? std::string() : EglError();
    eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, dev_.eglContext());
    if (!swapped) ThrowError(ErrorId::DEVICE_API_ERROR, call, "OpenGL", "eglSwapBuffers failed: " + swapError);
  }

 private:
  GLDevice& dev_;
  unsigned long window_;  // eglCreatePlatformWindowSurface takes a pointer to it
  EGLSurface surface_ = EGL_NO_SURFACE;
  GLuint readFbo_ = 0;
  int interval_ = -1;
};

}  // namespace

std::unique_ptr<detail::SwapChainBackend> GLDevice::CreateSwapChainBackend(const SwapChainDesc& desc, unsigned long visualId) {
  if (!x11Display_) ThrowError(ErrorId::INVALID_ARGUMENT, "CreateSwapChain", "OpenGL", "the device was created without DeviceDesc::x11Display");
  MakeCurrent();
  return std::make_unique<GLSwapChain>(*this, desc, visualId);
}

}  // namespace sp::gl
