// The hand-written OpenGL 4.5 side: its own headless EGL context (surfaceless Mesa platform, as the
// GL backend creates its own), made current before each raw case; the GLSL the toolchain produced.
#pragma once
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>

#include <string>

namespace spbench {

class RawGL {
 public:
  RawGL();
  ~RawGL();
  RawGL(const RawGL&) = delete;
  RawGL& operator=(const RawGL&) = delete;

  void MakeCurrent();
  // A program pipeline of separable programs (the toolchain gives each stage its own binding
  // numbers for one cbuffer, which a single linked program refuses); fragment empty: vertex only.
  GLuint LinkGraphics(const std::string& vertex, const std::string& fragment);
  GLuint LinkCompute(const std::string& compute);
  GLint uniformAlignment() const { return uboAlign_; }

 private:
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  GLint uboAlign_ = 256;
};

}  // namespace spbench
