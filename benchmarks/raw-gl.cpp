#include "raw-gl.h"

#include <stdexcept>
#include <vector>

namespace spbench {
namespace {

[[noreturn]] void Fail(const std::string& what) { throw std::runtime_error("raw GL: " + what); }

GLuint CompileStage(GLenum type, const std::string& src) {
  GLuint s = glCreateShader(type);
  const char* p = src.c_str();
  glShaderSource(s, 1, &p, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetShaderInfoLog(s, sizeof(log), nullptr, log);
    Fail(std::string("shader compile: ") + log);
  }
  return s;
}

GLuint Link(const std::vector<GLuint>& shaders, bool separable = false) {
  GLuint p = glCreateProgram();
  if (separable) glProgramParameteri(p, GL_PROGRAM_SEPARABLE, GL_TRUE);
  for (GLuint s : shaders) glAttachShader(p, s);
  glLinkProgram(p);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetProgramInfoLog(p, sizeof(log), nullptr, log);
    Fail(std::string("link: ") + log);
  }
  for (GLuint s : shaders) glDeleteShader(s);
  return p;
}

}  // namespace

RawGL::RawGL() {
  auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!getPlatformDisplay) Fail("no eglGetPlatformDisplayEXT");
  display_ = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  EGLint major = 0, minor = 0;
  if (display_ == EGL_NO_DISPLAY || !eglInitialize(display_, &major, &minor)) Fail("no surfaceless EGL display");
  if (!eglBindAPI(EGL_OPENGL_API)) Fail("eglBindAPI");
  // No debug context: the sp:: device of the benchmark is created without debug output too.
  const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5, EGL_CONTEXT_OPENGL_PROFILE_MASK,
                            EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  context_ = eglCreateContext(display_, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
  if (context_ == EGL_NO_CONTEXT) Fail("eglCreateContext (4.5 core)");
  MakeCurrent();
  glGetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &uboAlign_);
}

RawGL::~RawGL() {
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display_, context_);
}

void RawGL::MakeCurrent() {
  if (eglGetCurrentContext() != context_ && !eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
    Fail("eglMakeCurrent");
}

GLuint RawGL::LinkGraphics(const std::string& vertex, const std::string& fragment) {
  GLuint pipeline = 0;
  glCreateProgramPipelines(1, &pipeline);
  glUseProgramStages(pipeline, GL_VERTEX_SHADER_BIT, Link({CompileStage(GL_VERTEX_SHADER, vertex)}, true));
  if (!fragment.empty())
    glUseProgramStages(pipeline, GL_FRAGMENT_SHADER_BIT, Link({CompileStage(GL_FRAGMENT_SHADER, fragment)}, true));
  return pipeline;
}

GLuint RawGL::LinkCompute(const std::string& compute) { return Link({CompileStage(GL_COMPUTE_SHADER, compute)}); }

}  // namespace spbench
