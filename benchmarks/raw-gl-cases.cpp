// The raw OpenGL side of every case, written as a careful GL 4.5 renderer would: program pipelines,
// one VAO, direct state access, constants in a persistently mapped ring bound with
// glBindBufferRange, state set only when the object changes.
#include <cstring>
#include <regex>
#include <stdexcept>

#include "bench-cases.h"
#include "raw-gl.h"

namespace spbench {
namespace {

// The binding the toolchain's GLSL declares for the declaration containing `what`
// ("uniform PerDraw", "sampler2D", "buffer outBuf").
GLuint GlslBinding(const std::string& glsl, const std::string& what) {
  std::regex re("layout\\(binding = ([0-9]+)[^)]*\\) [^;{]*" + what);
  std::smatch m;
  if (!std::regex_search(glsl, m, re)) throw std::runtime_error("raw GL: no binding for " + what);
  return GLuint(std::stoul(m[1]));
}

GLuint PositionLocation(const sp::ShaderBytecode& vs) {
  const sp::SignatureElement* e = vs.reflection.FindInput("POSITION", 0);
  if (!e) throw std::runtime_error("raw GL: VSMain has no POSITION");
  return e->location;
}

GLintptr AlignUp(GLintptr v, GLintptr a) { return (v + a - 1) / a * a; }

// Constants written per draw into a persistently mapped, coherent buffer; every iteration waits
// for the GPU before the next one, so the ring restarts at 0 each iteration.
class Ring {
 public:
  Ring(GLintptr elementSize, uint32_t count, GLint align) : size_(elementSize), stride_(AlignUp(elementSize, align)) {
    glCreateBuffers(1, &buffer_);
    GLbitfield flags = GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
    glNamedBufferStorage(buffer_, stride_ * count, nullptr, flags);
    data_ = static_cast<uint8_t*>(glMapNamedBufferRange(buffer_, 0, stride_ * count, flags));
  }
  // Writes `value` and binds it at `binding` (and `binding2` unless it is the same).
  void Push(const void* value, GLuint binding, GLuint binding2) {
    std::memcpy(data_ + offset_, value, size_);
    glBindBufferRange(GL_UNIFORM_BUFFER, binding, buffer_, offset_, size_);
    if (binding2 != binding) glBindBufferRange(GL_UNIFORM_BUFFER, binding2, buffer_, offset_, size_);
    offset_ += stride_;
  }
  void Reset() { offset_ = 0; }

 private:
  GLuint buffer_ = 0;
  uint8_t* data_ = nullptr;
  GLintptr size_, stride_, offset_ = 0;
};

class GlGraphics : public Case {
 public:
  GlGraphics(RawGL& gl, const sp::ShaderBytecode* ps, uint32_t draws)
      : gl_(gl), ring_((gl.MakeCurrent(), GLintptr(sizeof(DrawConstants))), draws, gl.uniformAlignment()) {
    const Shaders& s = GetShaders();
    program_ = gl.LinkGraphics(s.vs.glsl, ps ? ps->glsl : "");
    vsCb_ = GlslBinding(s.vs.glsl, "uniform PerDraw");
    psCb_ = ps ? GlslBinding(ps->glsl, "uniform PerDraw") : vsCb_;
    glCreateTextures(GL_TEXTURE_2D, 1, &color_);
    glTextureStorage2D(color_, 1, GL_RGBA8, kTargetSize, kTargetSize);
    glCreateTextures(GL_TEXTURE_2D, 1, &depth_);
    glTextureStorage2D(depth_, 1, GL_DEPTH_COMPONENT32F, kTargetSize, kTargetSize);
    glCreateFramebuffers(1, &fbo_);
    if (ps) glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, color_, 0);
    else glNamedFramebufferDrawBuffer(fbo_, GL_NONE);
    glNamedFramebufferTexture(fbo_, GL_DEPTH_ATTACHMENT, depth_, 0);
    glCreateVertexArrays(1, &vao_);
    GLuint loc = PositionLocation(s.vs);
    glEnableVertexArrayAttrib(vao_, loc);
    glVertexArrayAttribFormat(vao_, loc, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao_, loc, 0);
    for (uint32_t m = 0; m < 2; ++m) {
      const Mesh& mesh = GetMesh(m);
      glCreateBuffers(1, &vb_[m]);
      glNamedBufferStorage(vb_[m], mesh.positions.size() * 4, mesh.positions.data(), 0);
      glCreateBuffers(1, &ib_[m]);
      glNamedBufferStorage(ib_[m], mesh.indices.size() * 2, mesh.indices.data(), 0);
    }
    DrawConstants c = MakeConstants(0);
    glCreateBuffers(1, &staticCb_);
    glNamedBufferStorage(staticCb_, sizeof(c), &c, 0);
    hasColor_ = ps != nullptr;
  }

  void Wait() override {
    gl_.MakeCurrent();
    glFinish();
    ring_.Reset();
  }

 protected:
  void BeginPass(bool staticConstants) {
    gl_.MakeCurrent();
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo_);
    glDepthMask(GL_TRUE);
    const float black[4] = {0, 0, 0, 1}, one = 1.0f;
    if (hasColor_) glClearNamedFramebufferfv(fbo_, GL_COLOR, 0, black);
    glClearNamedFramebufferfv(fbo_, GL_DEPTH, 0, &one);
    glViewport(0, 0, kTargetSize, kTargetSize);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glUseProgram(0);  // a program made current by glUseProgram (the compute case) overrides pipelines
    glBindProgramPipeline(program_);
    glBindVertexArray(vao_);
    SetMesh(0);
    if (staticConstants) {
      glBindBufferBase(GL_UNIFORM_BUFFER, vsCb_, staticCb_);
      glBindBufferBase(GL_UNIFORM_BUFFER, psCb_, staticCb_);
    }
  }
  void SetMesh(uint32_t m) {
    glVertexArrayVertexBuffer(vao_, 0, vb_[m], 0, 12);
    glVertexArrayElementBuffer(vao_, ib_[m]);
  }
  void DrawMesh() { glDrawElements(GL_TRIANGLES, kMeshIndices, GL_UNSIGNED_SHORT, nullptr); }

  RawGL& gl_;
  Ring ring_;
  GLuint program_ = 0, vsCb_ = 0, psCb_ = 0;
  GLuint color_ = 0, depth_ = 0, fbo_ = 0, vao_ = 0, vb_[2]{}, ib_[2]{}, staticCb_ = 0;
  bool hasColor_ = true;
};

class GlCBuffer : public GlGraphics {
 public:
  explicit GlCBuffer(RawGL& gl) : GlGraphics(gl, &GetShaders().psColor, kDraws) {
    for (uint32_t i = 0; i < kDraws; ++i) constants_.push_back(MakeConstants(i));
  }
  void Record() override {
    BeginPass(false);
    for (uint32_t i = 0; i < kDraws; ++i) {
      ring_.Push(&constants_[i], vsCb_, psCb_);
      DrawMesh();
    }
    glFlush();
  }

 private:
  std::vector<DrawConstants> constants_;
};

class GlTexture : public GlGraphics {
 public:
  explicit GlTexture(RawGL& gl) : GlGraphics(gl, &GetShaders().psTex, 1) {
    unit_ = GlslBinding(GetShaders().psTex.glsl, "sampler2D");
    for (uint32_t i = 0; i < kTextures; ++i) {
      std::vector<uint32_t> texels = TextureTexels(i);
      glCreateTextures(GL_TEXTURE_2D, 1, &textures_[i]);
      glTextureStorage2D(textures_[i], 1, GL_RGBA8, 4, 4);
      glTextureSubImage2D(textures_[i], 0, 0, 0, 4, 4, GL_RGBA, GL_UNSIGNED_BYTE, texels.data());
    }
    glCreateSamplers(kSamplers, samplers_);
    for (uint32_t i = 0; i < kSamplers; ++i) {
      glSamplerParameteri(samplers_[i], GL_TEXTURE_MIN_FILTER, i ? GL_NEAREST_MIPMAP_NEAREST : GL_LINEAR_MIPMAP_LINEAR);
      glSamplerParameteri(samplers_[i], GL_TEXTURE_MAG_FILTER, i ? GL_NEAREST : GL_LINEAR);
      GLint wrap = i ? GL_REPEAT : GL_CLAMP_TO_EDGE;
      glSamplerParameteri(samplers_[i], GL_TEXTURE_WRAP_S, wrap);
      glSamplerParameteri(samplers_[i], GL_TEXTURE_WRAP_T, wrap);
    }
  }
  void Record() override {
    BeginPass(true);
    GLuint lastSampler = 0;
    for (uint32_t i = 0; i < kDraws; ++i) {
      glBindTextureUnit(unit_, textures_[i % kTextures]);
      GLuint smp = samplers_[(i / kTextures) % kSamplers];
      if (smp != lastSampler) glBindSampler(unit_, lastSampler = smp);
      DrawMesh();
    }
    glFlush();
  }

 private:
  GLuint unit_ = 0, textures_[kTextures]{}, samplers_[kSamplers]{};
};

class GlState : public GlGraphics {
 public:
  explicit GlState(RawGL& gl) : GlGraphics(gl, &GetShaders().psColor, 1) {}
  void Record() override {
    BeginPass(true);
    for (uint32_t i = 0; i < kDraws; ++i) {
      // The three objects change on every draw (periods 4, 3, 3), so each is applied whole.
      uint32_t r = i % kRasterStates, d = i % kDepthStates, b = i % kBlendStates;
      if (r == 2) glDisable(GL_CULL_FACE);
      else glEnable(GL_CULL_FACE), glCullFace(r == 1 ? GL_FRONT : GL_BACK);
      if (r == 3) glEnable(GL_POLYGON_OFFSET_FILL), glPolygonOffset(kShadowSlopeBias, float(kShadowDepthBias));
      else glDisable(GL_POLYGON_OFFSET_FILL);
      if (d == 2) glDisable(GL_DEPTH_TEST);
      else glEnable(GL_DEPTH_TEST), glDepthFunc(d ? GL_LEQUAL : GL_LESS), glDepthMask(d ? GL_FALSE : GL_TRUE);
      if (b == 0) glDisablei(GL_BLEND, 0);
      else glEnablei(GL_BLEND, 0), glBlendFuncSeparatei(0, b == 1 ? GL_SRC_ALPHA : GL_ONE, b == 1 ? GL_ONE_MINUS_SRC_ALPHA : GL_ONE, GL_ONE, GL_ZERO);
      DrawMesh();
    }
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDisablei(GL_BLEND, 0);
    glFlush();
  }
};

class GlShadow : public GlGraphics {
 public:
  explicit GlShadow(RawGL& gl) : GlGraphics(gl, nullptr, kShadowDraws) {
    for (uint32_t i = 0; i < kShadowDraws; ++i) constants_.push_back(MakeConstants(i));
  }
  void Record() override {
    BeginPass(false);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(kShadowSlopeBias, float(kShadowDepthBias));
    for (uint32_t i = 0; i < kShadowDraws; ++i) {
      if (i % kShadowMeshRun == 0) SetMesh((i / kShadowMeshRun) & 1);
      ring_.Push(&constants_[i], vsCb_, vsCb_);
      if (i % kShadowInstanceEvery == 0)
        glDrawElementsInstanced(GL_TRIANGLES, kMeshIndices, GL_UNSIGNED_SHORT, nullptr, kShadowInstances);
      else
        DrawMesh();
    }
    glDisable(GL_POLYGON_OFFSET_FILL);
    glFlush();
  }

 private:
  std::vector<DrawConstants> constants_;
};

class GlCompute : public Case {
 public:
  explicit GlCompute(RawGL& gl) : gl_(gl), ring_((gl.MakeCurrent(), GLintptr(sizeof(DispatchConstants))), kDispatches, gl.uniformAlignment()) {
    const std::string& glsl = GetShaders().cs.glsl;
    program_ = gl.LinkCompute(glsl);
    cb_ = GlslBinding(glsl, "uniform Dispatch");
    ssbo_ = GlslBinding(glsl, "buffer outBuf");
    glCreateBuffers(kUavs, buffers_);
    for (GLuint b : buffers_) glNamedBufferStorage(b, kUavElements * 4, nullptr, 0);
  }
  void Record() override {
    gl_.MakeCurrent();
    glUseProgram(program_);
    for (uint32_t i = 0; i < kDispatches; ++i) {
      DispatchConstants c{i, {}};
      ring_.Push(&c, cb_, cb_);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, ssbo_, buffers_[i % kUavs]);
      // D3D11 orders dispatches that write one UAV: the buffer written now was last written
      // kUavs dispatches ago, so one barrier per round of kUavs buffers is enough.
      if (i && i % kUavs == 0) glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
      glDispatchCompute(1, 1, 1);
    }
    glFlush();
  }
  void Wait() override {
    gl_.MakeCurrent();
    glFinish();
    ring_.Reset();
  }

 private:
  RawGL& gl_;
  Ring ring_;
  GLuint program_ = 0, cb_ = 0, ssbo_ = 0, buffers_[kUavs]{};
};

}  // namespace

std::unique_ptr<Case> MakeRawGLCase(CaseId id, RawGL& gl) {
  switch (id) {
    case CaseId::CBuffer: return std::make_unique<GlCBuffer>(gl);
    case CaseId::Texture: return std::make_unique<GlTexture>(gl);
    case CaseId::State: return std::make_unique<GlState>(gl);
    case CaseId::Compute: return std::make_unique<GlCompute>(gl);
    default: return std::make_unique<GlShadow>(gl);
  }
}

}  // namespace spbench
