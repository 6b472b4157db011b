// The OpenGL 4.5 device: a headless EGL (surfaceless) context, debug output, the fixed state
// that makes GL behave like D3D11, device information and format support.
#include <cstring>
#include <map>
#include <mutex>
#include <string_view>

#include "gl-context.h"

namespace sp::gl {
namespace {

// eglTerminate is not reference counted: a display stays initialised while any device uses it.
// Keyed by the native display (null: the surfaceless one).
struct DisplayEntry {
  EGLDisplay display = EGL_NO_DISPLAY;
  int users = 0;
};
std::mutex gDisplayMutex;
std::map<void*, DisplayEntry> gDisplays;

std::string EglErrorText() {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "EGL error 0x%04x", unsigned(eglGetError()));
  return buf;
}

[[noreturn]] void CreationFailed(const std::string& why) { throw Error(ErrorId::DEVICE_CREATION_FAILED, "CreateDevice", "OpenGL", why); }

bool HasEglExtension(EGLDisplay d, const char* name) {
  const char* exts = eglQueryString(d, EGL_EXTENSIONS);
  if (!exts) return false;
  std::string_view all(exts), n(name);
  for (size_t pos = all.find(n); pos != std::string_view::npos; pos = all.find(n, pos + 1)) {
    size_t end = pos + n.size();
    if ((pos == 0 || all[pos - 1] == ' ') && (end == all.size() || all[end] == ' ')) return true;
  }
  return false;
}

// x11Display null: the headless surfaceless display. Otherwise an X11 platform display of that
// Display*, on which window surfaces can be made; the context still runs surfaceless between
// presentations, so it needs EGL_KHR_surfaceless_context and EGL_KHR_no_config_context there too.
EGLDisplay AcquireDisplay(void* x11Display) {
  std::lock_guard lock(gDisplayMutex);
  DisplayEntry& e = gDisplays[x11Display];
  if (e.users == 0) {
    const char* platform = x11Display ? "EGL_KHR_platform_x11" : "EGL_MESA_platform_surfaceless";
    if (!HasEglExtension(EGL_NO_DISPLAY, platform) && !(x11Display && HasEglExtension(EGL_NO_DISPLAY, "EGL_EXT_platform_x11")))
      CreationFailed(std::string("EGL has no ") + platform + " (install libegl-mesa0); " +
                     (x11Display ? "presenting to an X11 window needs it" : "headless rendering needs it"));
    auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!getPlatformDisplay) CreationFailed("eglGetPlatformDisplayEXT is not available");
    EGLDisplay d = x11Display ? getPlatformDisplay(EGL_PLATFORM_X11_KHR, x11Display, nullptr)
                              : getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (d == EGL_NO_DISPLAY) CreationFailed(std::string("eglGetPlatformDisplayEXT(") + (x11Display ? "EGL_PLATFORM_X11_KHR" : "EGL_PLATFORM_SURFACELESS_MESA") + ") failed: " + EglErrorText());
    EGLint major = 0, minor = 0;
    if (!eglInitialize(d, &major, &minor)) CreationFailed("eglInitialize failed: " + EglErrorText());
    if (x11Display) {
      for (const char* ext : {"EGL_KHR_surfaceless_context", "EGL_KHR_no_config_context"})
        if (!HasEglExtension(d, ext)) {
          eglTerminate(d);
          CreationFailed(std::string("the X11 EGL display lacks ") + ext);
        }
    }
    e.display = d;
  }
  ++e.users;
  return e.display;
}

void ReleaseDisplay(void* x11Display) {
  std::lock_guard lock(gDisplayMutex);
  DisplayEntry& e = gDisplays[x11Display];
  if (--e.users == 0) {
    eglTerminate(e.display);
    gDisplays.erase(x11Display);
  }
}

void APIENTRY DebugCallback(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei, const GLchar* message, const void* user) {
  static_cast<GLDevice*>(const_cast<void*>(user))->OnDebugMessage(source, type, id, severity, message);
}

const char* DebugTypeName(GLenum type) {
  switch (type) {
    case GL_DEBUG_TYPE_ERROR: return "error";
    case GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR: return "undefined behaviour";
    case GL_DEBUG_TYPE_DEPRECATED_BEHAVIOR: return "deprecated";
    case GL_DEBUG_TYPE_PORTABILITY: return "portability";
    case GL_DEBUG_TYPE_PERFORMANCE: return "performance";
    default: return "other";
  }
}

bool HasExtension(const char* name) {
  GLint n = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &n);
  for (GLint i = 0; i < n; ++i)
    if (std::strcmp(reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i))), name) == 0) return true;
  return false;
}

std::string GLString(GLenum e) {
  const GLubyte* s = glGetString(e);
  return s ? reinterpret_cast<const char*>(s) : "";
}

}  // namespace

void ThrowError(ErrorId id, const std::string& call, const std::string& object, const std::string& detail) {
  throw Error(id, call, object, detail);
}

GLDevice::GLDevice(Device& core, const DeviceDesc& desc) : DeviceBackend(core) {
  x11Display_ = desc.x11Display;
  display_ = AcquireDisplay(x11Display_);
  try {
    if (!eglBindAPI(EGL_OPENGL_API)) CreationFailed("eglBindAPI(EGL_OPENGL_API) failed: " + EglErrorText());
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5, EGL_CONTEXT_OPENGL_PROFILE_MASK,
                              EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_CONTEXT_OPENGL_DEBUG, desc.debug ? EGL_TRUE : EGL_FALSE, EGL_NONE};
    egl_ = eglCreateContext(display_, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
    if (egl_ == EGL_NO_CONTEXT) CreationFailed("eglCreateContext for an OpenGL 4.5 core context failed: " + EglErrorText());
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, egl_)) CreationFailed("eglMakeCurrent failed: " + EglErrorText());
  } catch (...) {
    if (egl_ != EGL_NO_CONTEXT) eglDestroyContext(display_, egl_);
    ReleaseDisplay(x11Display_);
    throw;
  }

  try {
    Init(desc);
  } catch (...) {
    // The destructor does not run for a half-built device: release what exists here.
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, egl_);
    ReleaseDisplay(x11Display_);
    throw;
  }
}

void GLDevice::Init(const DeviceDesc& desc) {
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major * 10 + minor < 45) CreationFailed("the driver offers OpenGL " + std::to_string(major) + "." + std::to_string(minor) + ", 4.5 is needed");

  if (desc.debug) {
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(DebugCallback, this);
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DEBUG_SEVERITY_NOTIFICATION, 0, nullptr, GL_FALSE);
  }
  info_.validationEnabled = desc.debug;

  // D3D11 conventions (see DEVELOPERS.md): z in [0, 1] with the VS flipping y, first-vertex
  // flat shading, seamless cubes, sRGB encoding on write. Strips cut at 0xffff(ffff): restart
  // follows the topology at each indexed draw (GLContext::SetPrimitiveRestart).
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glProvokingVertex(GL_FIRST_VERTEX_CONVENTION);
  glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
  glEnable(GL_FRAMEBUFFER_SRGB);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);

  polygonOffsetClamp = reinterpret_cast<PFNGLPOLYGONOFFSETCLAMPEXTPROC>(eglGetProcAddress("glPolygonOffsetClampEXT"));
  if (!polygonOffsetClamp) polygonOffsetClamp = reinterpret_cast<PFNGLPOLYGONOFFSETCLAMPEXTPROC>(eglGetProcAddress("glPolygonOffsetClamp"));
  if (desc.disableDepthBiasClamp) polygonOffsetClamp = nullptr;
  info_.depthBiasClamp = polygonOffsetClamp != nullptr;
  hasFilterMinmax = HasExtension("GL_ARB_texture_filter_minmax") || HasExtension("GL_EXT_texture_filter_minmax");
  // The GLSL of such a vertex shader requires this extension by name (hlsl/target-glsl.cpp).
  info_.vsRenderTargetArrayIndex = !desc.disableVsRenderTargetArrayIndex && HasExtension("GL_ARB_shader_viewport_layer_array");
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &ssboAlignment);
  glGetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &uboAlignment);
  glGetIntegerv(GL_TEXTURE_BUFFER_OFFSET_ALIGNMENT, &tboAlignment);

  std::string version = GLString(GL_VERSION);
  info_.backend = Backend::OpenGL;
  info_.apiVersion = "OpenGL " + version;
  info_.deviceName = GLString(GL_RENDERER);
  size_t mesa = version.find("Mesa");
  info_.driverName = mesa != std::string::npos ? version.substr(mesa) : GLString(GL_VENDOR) + " " + version;
  info_.timestampFrequency = 1000000000ull;  // GL_TIMESTAMP counts nanoseconds

  InitFormatSupport();
  info_.maxMsaaSamples = std::min(MaxSampleCountBackend(FORMAT_R8G8B8A8_UNORM), MaxSampleCountBackend(FORMAT_D32_FLOAT));
}

std::unique_ptr<detail::ContextBackend> GLDevice::CreateContextBackend() {
  MakeCurrent();
  auto ctx = CreateGLContext(*this);
  context_ = static_cast<GLContext*>(ctx.get());
  return ctx;
}

// The core has destroyed the context and released every object's GL names before this runs.
GLDevice::~GLDevice() {
  MakeCurrent();
  if (info_.validationEnabled) glDebugMessageCallback(nullptr, nullptr);
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display_, egl_);
  ReleaseDisplay(x11Display_);
}

void GLDevice::MakeCurrent() const {
  // Several devices may live on one thread; each call re-selects its own context when needed.
  if (eglGetCurrentContext() != egl_) eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, egl_);
}

void GLDevice::OnDebugMessage(GLenum source, GLenum type, GLuint id, GLenum severity, const char* message) {
  if (suppressDebugMessages || severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
  // In a debug context Mesa checks the programs of a pipeline against OpenGL ES 3.1's exact
  // interface matching (every output read, same types) and reports each pipeline that is not an
  // exact match, on every run: D3D11 and desktop GL let a pixel shader read a subset of what the
  // vertex shader writes, and the core validates the interface by D3D11's rules. That one message
  // is dropped, by source, type and id (Mesa assigns the id on first use, so the first one is
  // recognised by its text); every other message is reported.
  if (source == GL_DEBUG_SOURCE_API && type == GL_DEBUG_TYPE_PORTABILITY) {
    if (!esPipelineMessageId_ && std::strncmp(message, "glValidateProgramPipeline: pipeline ", 36) == 0 &&
        std::strstr(message, "does not meet strict OpenGL ES 3.1 requirements"))
      esPipelineMessageId_ = id;
    if (esPipelineMessageId_ && id == esPipelineMessageId_) return;
  }
  std::string text = std::string("GL ") + DebugTypeName(type) + " (id " + std::to_string(id) + "): " + message;
  if (type == GL_DEBUG_TYPE_ERROR || type == GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR) Message(MessageSeverity::Error, text);
  else if (severity == GL_DEBUG_SEVERITY_HIGH || severity == GL_DEBUG_SEVERITY_MEDIUM) Message(MessageSeverity::Warning, text);
  else Message(MessageSeverity::Info, text);
}

void GLDevice::DeleteTexture(GLuint name) {
  if (!name) return;
  if (context_) context_->ForgetTexture(name);
  glDeleteTextures(1, &name);
}

void GLDevice::DeleteBuffer(GLuint name) {
  if (!name) return;
  if (context_) context_->ForgetBuffer(name);
  glDeleteBuffers(1, &name);
}

void GLDevice::DeleteSampler(GLuint name) {
  if (!name) return;
  if (context_) context_->ForgetSampler(name);
  glDeleteSamplers(1, &name);
}

void GLDevice::DeleteProgram(GLuint name) {
  if (!name) return;
  if (context_) context_->ForgetProgram(name);
  glDeleteProgram(name);
}

void GLDevice::DeleteProgramPipeline(GLuint name) {
  if (!name) return;
  if (context_) context_->ForgetPipeline(name);
  glDeleteProgramPipelines(1, &name);
}

std::unique_ptr<detail::BackendObject> GLDevice::CreateBufferBackend(Buffer& b, const SUBRESOURCE_DATA* init) {
  MakeCurrent();
  return CreateGLBuffer(*this, b, init);
}
std::unique_ptr<detail::BackendObject> GLDevice::CreateTextureBackend(Texture& t, const SUBRESOURCE_DATA* init) {
  MakeCurrent();
  return CreateGLTexture(*this, t, init);
}
std::unique_ptr<detail::BackendObject> GLDevice::CreateViewBackend(View& v) {
  MakeCurrent();
  return CreateGLView(*this, v);
}
std::unique_ptr<detail::BackendObject> GLDevice::CreateSamplerBackend(SamplerState& s) {
  MakeCurrent();
  return CreateGLSampler(*this, s);
}
std::unique_ptr<detail::BackendObject> GLDevice::CreateShaderBackend(Shader& s) {
  MakeCurrent();
  return CreateGLShader(*this, s);
}
std::unique_ptr<detail::BackendObject> GLDevice::CreateQueryBackend(Query& q) {
  MakeCurrent();
  return CreateGLQuery(*this, q);
}

// ---------------------------------------------------------------------------------------------
// Format support, answered once from the driver (glGetInternalformativ) and GL's format tables.

std::vector<GLint> GLDevice::SampleCounts(GLenum internal) const {
  GLint n = 0;
  glGetInternalformativ(GL_TEXTURE_2D_MULTISAMPLE, internal, GL_NUM_SAMPLE_COUNTS, 1, &n);
  std::vector<GLint> counts(size_t(std::max(n, 0)));
  if (n > 0) glGetInternalformativ(GL_TEXTURE_2D_MULTISAMPLE, internal, GL_SAMPLES, n, counts.data());
  return counts;
}

void GLDevice::InitFormatSupport() {
  auto query = [](GLenum target, GLenum internal, GLenum pname) {
    GLint v = 0;
    glGetInternalformativ(target, internal, pname, 1, &v);
    return v;
  };
  for (uint32_t f = 1; f < support_.size(); ++f) {
    const FormatInfo& fi = GetFormatInfo(FORMAT(f));
    const GLFormat& g = FormatOf(FORMAT(f));
    if (fi.format == FORMAT_UNKNOWN || !g.internal) continue;
    if (!query(GL_TEXTURE_2D, g.internal, GL_INTERNALFORMAT_SUPPORTED)) continue;
    const bool typeless = fi.kind == FormatKind::Typeless;
    const bool depthFormat = fi.kind == FormatKind::Depth || fi.kind == FormatKind::DepthStencil;
    const bool depthRead = g.depth && !depthFormat && !typeless;  // R24_UNORM_X8, X24_G8, ...
    uint32_t s = 0;
    if (g.textureBuffer && !typeless) s |= FORMAT_SUPPORT_BUFFER;
    if (g.attribSize) s |= FORMAT_SUPPORT_IA_VERTEX_BUFFER;
    if (f == FORMAT_R16_UINT || f == FORMAT_R32_UINT) s |= FORMAT_SUPPORT_IA_INDEX_BUFFER;
    if (fi.bytesPerElement == 12) {
      // Texture support of 3-component 32-bit formats is optional in D3D11; buffers only here.
      if (!typeless) s |= FORMAT_SUPPORT_SHADER_LOAD;
      support_[f] = s;
      continue;
    }
    if (depthFormat || (typeless && g.depth)) {
      s |= FORMAT_SUPPORT_TEXTURE2D | FORMAT_SUPPORT_TEXTURECUBE | FORMAT_SUPPORT_MIP;
      if (query(GL_TEXTURE_2D, g.internal, GL_DEPTH_RENDERABLE)) s |= FORMAT_SUPPORT_DEPTH_STENCIL;
    } else if (!depthRead) {
      s |= FORMAT_SUPPORT_TEXTURE1D | FORMAT_SUPPORT_TEXTURE2D | FORMAT_SUPPORT_TEXTURE3D | FORMAT_SUPPORT_TEXTURECUBE | FORMAT_SUPPORT_MIP;
    }
    if (!typeless && !depthFormat) {
      const bool stencilRead = fi.readsStencil;
      s |= FORMAT_SUPPORT_SHADER_LOAD;
      if (!g.integer && !stencilRead && query(GL_TEXTURE_2D, g.internal, GL_FILTER))
        s |= FORMAT_SUPPORT_SHADER_SAMPLE | FORMAT_SUPPORT_SHADER_GATHER;
      if (fi.readsDepth) s |= FORMAT_SUPPORT_SHADER_SAMPLE_COMPARISON | FORMAT_SUPPORT_SHADER_GATHER_COMPARISON;
      if (!depthRead && query(GL_TEXTURE_2D, g.internal, GL_COLOR_RENDERABLE)) {
        s |= FORMAT_SUPPORT_RENDER_TARGET;
        if (!g.integer) s |= FORMAT_SUPPORT_BLENDABLE;
      }
      if (g.image && query(GL_TEXTURE_2D, g.internal, GL_SHADER_IMAGE_LOAD)) s |= FORMAT_SUPPORT_TYPED_UNORDERED_ACCESS_VIEW;
    }
    samples_[f] = SampleCounts(g.internal);
    bool ms = false;
    for (GLint c : samples_[f]) ms |= c > 1;
    if (ms && (s & (FORMAT_SUPPORT_RENDER_TARGET | FORMAT_SUPPORT_DEPTH_STENCIL))) s |= FORMAT_SUPPORT_MULTISAMPLE_RENDERTARGET;
    if (ms && (s & FORMAT_SUPPORT_SHADER_LOAD)) s |= FORMAT_SUPPORT_MULTISAMPLE_LOAD;
    if (ms && (s & FORMAT_SUPPORT_RENDER_TARGET) && !g.integer) s |= FORMAT_SUPPORT_MULTISAMPLE_RESOLVE;
    support_[f] = s;
  }
  // The core asks R32_FLOAT's sampling support before creating min/max reduction samplers.
  if (!hasFilterMinmax) support_[FORMAT_R32_FLOAT] &= ~uint32_t(FORMAT_SUPPORT_SHADER_SAMPLE);
}

uint32_t GLDevice::FormatSupportBackend(FORMAT format) const { return format < support_.size() ? support_[format] : 0; }

uint32_t GLDevice::MaxSampleCountBackend(FORMAT format) const {
  if (format >= samples_.size()) return 1;
  uint32_t best = 1;
  for (GLint c : samples_[format])
    if (c > 0 && uint32_t(c) <= 32 && (c & (c - 1)) == 0) best = std::max(best, uint32_t(c));
  return best;
}

bool GLDevice::SampleCountSupportedBackend(FORMAT format, uint32_t count) const {
  if (count == 1) return true;
  if (format >= samples_.size()) return false;
  for (GLint c : samples_[format])
    if (uint32_t(c) == count) return true;
  return false;
}

}  // namespace sp::gl

namespace sp::detail {
std::unique_ptr<DeviceBackend> CreateGLBackend(Device& core, const DeviceDesc& desc) { return std::make_unique<gl::GLDevice>(core, desc); }
}  // namespace sp::detail
