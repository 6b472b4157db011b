// Draws and dispatches: program pipelines, vertex input, the shaders' binding tables, and the
// memory barriers that give UAV writes D3D11's visibility.
#include "gl-context.h"

#include <algorithm>
#include <cstring>

namespace sp::gl {
namespace {

// Everything that may read a buffer or texture a shader wrote through a UAV: D3D11 makes those
// writes visible to every later command, GL only to what the barrier names.
constexpr GLbitfield kBufferUavBarrier = GL_SHADER_STORAGE_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_ELEMENT_ARRAY_BARRIER_BIT |
                                         GL_UNIFORM_BARRIER_BIT | GL_COMMAND_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT |
                                         GL_PIXEL_BUFFER_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT;
constexpr GLbitfield kImageUavBarrier = GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                                        GL_FRAMEBUFFER_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT;

constexpr size_t kRingSize = 4u << 20;  // room for every cbuffer of a draw many times over

GLenum Topology(PRIMITIVE_TOPOLOGY t) {
  switch (t) {
    case PRIMITIVE_TOPOLOGY_POINTLIST: return GL_POINTS;
    case PRIMITIVE_TOPOLOGY_LINELIST: return GL_LINES;
    case PRIMITIVE_TOPOLOGY_LINESTRIP: return GL_LINE_STRIP;
    case PRIMITIVE_TOPOLOGY_TRIANGLESTRIP: return GL_TRIANGLE_STRIP;
    default: return GL_TRIANGLES;
  }
}

bool NeedsDualSource(const PipelineState& s) {
  const RENDER_TARGET_BLEND_DESC& rt = s.blend().RenderTarget[0];
  return rt.BlendEnable && BlendReadsSource1(rt);
}

template <class T, size_t N, class Pred>
void ForgetIf(std::array<std::optional<T>, N>& a, Pred pred) {
  for (auto& e : a)
    if (e && pred(*e)) e.reset();
}

}  // namespace

std::unique_ptr<detail::ContextBackend> CreateGLContext(GLDevice& dev) { return std::make_unique<GLContext>(dev); }

GLContext::GLContext(GLDevice& dev) : dev_(dev) {
  glCreateVertexArrays(1, &vao_);
  glBindVertexArray(vao_);
  // One vertex buffer binding per attribute: D3D offsets of any size fold into the binding
  // offset, and per-element instancing maps to per-binding divisors.
  for (GLuint i = 0; i < kMaxAttribs; ++i) glVertexArrayAttribBinding(vao_, i, i);
  glCreateSamplers(1, &loadSampler_);
  glSamplerParameteri(loadSampler_, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
  glSamplerParameteri(loadSampler_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glSamplerParameteri(loadSampler_, GL_TEXTURE_COMPARE_MODE, GL_NONE);
  NewRing(kRingSize);
}

GLContext::~GLContext() {
  dev_.MakeCurrent();
  if (currentSegment) glEndQuery(GL_SAMPLES_PASSED);
  currentSegment.reset();
  for (auto& [key, fbo] : framebuffers_) glDeleteFramebuffers(1, &fbo);
  for (auto& [key, pipeline] : pipelines_) glDeleteProgramPipelines(1, &pipeline);
  glDeleteVertexArrays(1, &vao_);
  glDeleteSamplers(1, &loadSampler_);
  glDeleteBuffers(1, &ring_);
  if (indexScratch_) glDeleteBuffers(1, &indexScratch_);
  dev_.DetachContext();
}

// ---------------------------------------------------------------------------------------------
// Draw

void GLContext::ApplyProgram(const PipelineState& s) {
  GLShader& vs = detail::BackendAs<GLShader>(s.stage(ShaderStage::Vertex).shader);
  GLuint ps = 0;
  if (const Shader* p = s.stage(ShaderStage::Pixel).shader.get()) {
    GLShader& g = detail::BackendAs<GLShader>(p);
    ps = g.writesTarget1 && NeedsDualSource(s) ? DualSourceProgram(dev_, g) : g.program;
  }
  GLuint& pipeline = pipelines_[{vs.program, ps}];
  if (!pipeline) {
    glCreateProgramPipelines(1, &pipeline);
    glUseProgramStages(pipeline, GL_VERTEX_SHADER_BIT, vs.program);
    if (ps) glUseProgramStages(pipeline, GL_FRAGMENT_SHADER_BIT, ps);
  }
  SetCached(cache_.pipeline, pipeline, [&] { glBindProgramPipeline(pipeline); });
}

void GLContext::ApplyFramebuffer(const PipelineState& s) {
  FramebufferKey key;
  bool any = false;
  for (uint32_t i = 0; i < SIMULTANEOUS_RENDER_TARGET_COUNT; ++i)
    if (const RenderTargetView* rtv = s.renderTargets[i].get()) {
      key.colors[i] = AttachmentOf(rtv);
      any = true;
    }
  if (const DepthStencilView* dsv = s.depthStencil.get()) {
    key.depth = AttachmentOf(dsv);
    key.depthPoint = DepthAttachmentPoint(dsv);
    any = true;
  }
  if (!any) {
    // UAV-only rendering: GL needs the framebuffer's size; a power of two covering every
    // viewport keeps the number of distinct framebuffers small.
    float w = 1, h = 1;
    for (uint32_t i = 0; i < s.numViewports; ++i) {
      w = std::max(w, s.viewports[i].TopLeftX + s.viewports[i].Width);
      h = std::max(h, s.viewports[i].TopLeftY + s.viewports[i].Height);
    }
    auto pow2 = [](float v) {
      uint32_t p = 1;
      while (p < v && p < 16384) p <<= 1;
      return p;
    };
    key.emptyWidth = pow2(w);
    key.emptyHeight = pow2(h);
    key.emptyLayers = 1;
  }
  BindDrawFramebuffer(Framebuffer(key, "Draw"));
}

void GLContext::ApplyInput(const PipelineState& s) {
  const ShaderReflection& vs = s.stage(ShaderStage::Vertex).shader->Reflection();
  std::array<bool, kMaxAttribs> wanted{};
  if (s.inputLayout) {
    for (const VertexAttribute& a : s.inputLayout->Attributes()) {
      if (a.location >= kMaxAttribs || !s.vertexBuffers[a.slot]) continue;
      bool read = std::any_of(vs.inputs.begin(), vs.inputs.end(),
                              [&](const SignatureElement& e) { return !e.systemValue && e.location == a.location; });
      if (!read) continue;  // an enabled array without a buffer is a GL error; unread ones stay off
      wanted[a.location] = true;
      const GLFormat& f = FormatOf(a.format);
      AttribFormat af{f.attribSize, f.attribType, f.attribNormalized, f.attribInteger};
      SetCached(cache_.attribFormats[a.location], af, [&] {
        if (af.integer) glVertexArrayAttribIFormat(vao_, a.location, af.size, af.type, 0);
        else glVertexArrayAttribFormat(vao_, a.location, af.size, af.type, af.normalized, 0);
      });
      // D3D's per-instance step rate 0 means the data never advances.
      GLuint divisor = !a.perInstance ? 0 : a.stepRate ? a.stepRate : 0xffffffffu;
      VertexBinding vb{GL(s.vertexBuffers[a.slot].get()).name, GLintptr(s.vertexOffsets[a.slot]) + a.offset, GLsizei(s.vertexStrides[a.slot]),
                       divisor};
      SetCached(cache_.vertexBindings[a.location], vb, [&] {
        glVertexArrayVertexBuffer(vao_, a.location, vb.buffer, vb.offset, vb.stride);
        glVertexArrayBindingDivisor(vao_, a.location, vb.divisor);
      });
    }
  }
  for (GLuint i = 0; i < kMaxAttribs; ++i)
    SetCached(cache_.attribEnabled[i], wanted[i], [&] { wanted[i] ? glEnableVertexArrayAttrib(vao_, i) : glDisableVertexArrayAttrib(vao_, i); });
}

// Indirect indexed draws have no byte offset for the index buffer: the indices from the
// IASetIndexBuffer offset on are copied (on the GPU) to a scratch buffer bound instead.
GLuint GLContext::IndexScratch(const PipelineState& s) {
  const GLBuffer& ib = GL(s.indexBuffer.get());
  size_t size = ib.size - std::min<size_t>(s.indexOffset, ib.size);
  if (size == 0) return ib.name;
  if (indexScratchSize_ < size) {
    if (indexScratch_) dev_.DeleteBuffer(indexScratch_);
    glCreateBuffers(1, &indexScratch_);
    indexScratchSize_ = std::max<size_t>(size, 4096);
    glNamedBufferStorage(indexScratch_, GLsizeiptr(indexScratchSize_), nullptr, 0);
  }
  glCopyNamedBufferSubData(ib.name, indexScratch_, s.indexOffset, 0, GLsizeiptr(size));
  return indexScratch_;
}

// Each group of fixed-function state is applied when the core marked what it reads as changed, or
// when the context itself changed that GL state since (a clear, a dispatch, a deleted object:
// `disturbed_`); within a group the cache still drops calls that would set what GL already has.
// The stage bindings are compared every draw: the upload ring can move under them.
void GLContext::Draw(const PipelineState& s, uint32_t dirty, const detail::DrawArgs& a) {
  dev_.MakeCurrent();
  const bool indexed = a.kind == detail::DrawArgs::DrawIndexed || a.kind == detail::DrawArgs::DrawIndexedInstancedIndirect;
  const uint32_t apply = dirty | disturbed_;
  auto changed = [&](uint32_t reads) { return (apply & reads) != 0; };
  if (changed(DIRTY_SHADERS | DIRTY_BLEND)) ApplyProgram(s);  // blend: dual-source variants
  if (changed(DIRTY_RENDER_TARGETS | DIRTY_VIEWPORTS)) ApplyFramebuffer(s);  // viewports: size without attachments
  if (changed(DIRTY_SHADERS | DIRTY_INPUT_LAYOUT | DIRTY_VERTEX_BUFFERS)) ApplyInput(s);
  if (indexed) {
    GLuint ib = GL(s.indexBuffer.get()).name;
    SetCached(cache_.elementBuffer, ib, [&] { glVertexArrayElementBuffer(vao_, ib); });
  }
  if (changed(DIRTY_RASTERIZER | DIRTY_RENDER_TARGETS)) ApplyRasterizer(s);  // targets: bias units
  if (changed(DIRTY_VIEWPORTS | DIRTY_RASTERIZER)) ApplyViewports(s);  // rasterizer: scissor enable
  if (changed(DIRTY_DEPTH_STENCIL | DIRTY_RENDER_TARGETS)) ApplyDepthStencil(s);  // targets: read-only DSV
  if (changed(DIRTY_BLEND | DIRTY_RENDER_TARGETS | DIRTY_SHADERS)) ApplyBlend(s, s.stage(ShaderStage::Pixel).shader != nullptr);
  disturbed_ = 0;

  GLbitfield barrier = 0;
  for (int pass = 0; pass < 2; ++pass) {
    uint64_t generation = ringGeneration_;
    barrier = BindStage(s, ShaderStage::Vertex) | BindStage(s, ShaderStage::Pixel);
    if (generation == ringGeneration_) break;  // the ring was recycled mid-way: bind everything again
  }

  const GLenum mode = Topology(s.topology);
  const GLenum indexType = s.indexFormat == FORMAT_R16_UINT ? GL_UNSIGNED_SHORT : GL_UNSIGNED_INT;
  const uint32_t indexSize = s.indexFormat == FORMAT_R16_UINT ? 2 : 4;
  switch (a.kind) {
    case detail::DrawArgs::Draw:
      glDrawArraysInstancedBaseInstance(mode, GLint(a.start), GLsizei(a.count), GLsizei(a.instanceCount), a.startInstance);
      break;
    case detail::DrawArgs::DrawIndexed: {
      SetPrimitiveRestart(s.cutsAtAllOnesIndex());
      uintptr_t offset = s.indexOffset + uintptr_t(a.start) * indexSize;
      glDrawElementsInstancedBaseVertexBaseInstance(mode, GLsizei(a.count), indexType, reinterpret_cast<const void*>(offset),
                                                    GLsizei(a.instanceCount), a.baseVertex, a.startInstance);
      break;
    }
    case detail::DrawArgs::DrawInstancedIndirect:
      glBindBuffer(GL_DRAW_INDIRECT_BUFFER, GL(a.argsBuffer).name);
      glDrawArraysIndirect(mode, reinterpret_cast<const void*>(uintptr_t(a.argsOffset)));
      break;
    case detail::DrawArgs::DrawIndexedInstancedIndirect: {
      // D3D11's argument layout is GL's DrawElementsIndirectCommand.
      SetPrimitiveRestart(s.cutsAtAllOnesIndex());
      if (s.indexOffset) {
        GLuint scratch = IndexScratch(s);
        SetCached(cache_.elementBuffer, scratch, [&] { glVertexArrayElementBuffer(vao_, scratch); });
      }
      glBindBuffer(GL_DRAW_INDIRECT_BUFFER, GL(a.argsBuffer).name);
      glDrawElementsIndirect(mode, indexType, reinterpret_cast<const void*>(uintptr_t(a.argsOffset)));
      break;
    }
  }
  if (barrier) glMemoryBarrier(barrier);
}

void GLContext::Dispatch(const PipelineState& s, uint32_t dirty, uint32_t x, uint32_t y, uint32_t z, Buffer* args, uint32_t argsOffset) {
  dev_.MakeCurrent();
  GLShader& cs = detail::BackendAs<GLShader>(s.stage(ShaderStage::Compute).shader);
  SetCached(cache_.pipeline, cs.computePipeline, [&] {
    glBindProgramPipeline(cs.computePipeline);
    disturbed_ |= DIRTY_SHADERS;
  });
  GLbitfield barrier = 0;
  for (int pass = 0; pass < 2; ++pass) {
    uint64_t generation = ringGeneration_;
    barrier = BindStage(s, ShaderStage::Compute);
    if (generation == ringGeneration_) break;
  }
  if (args) {
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, GL(args).name);
    glDispatchComputeIndirect(GLintptr(argsOffset));
  } else {
    glDispatchCompute(x, y, z);
  }
  if (barrier) glMemoryBarrier(barrier);
}

// ---------------------------------------------------------------------------------------------
// Bindings from the shader's GL binding table

void GLContext::BindTexture(GLuint unit, GLuint texture, GLuint sampler) {
  SetCached(cache_.textures[unit], texture, [&] { glBindTextureUnit(unit, texture); });
  SetCached(cache_.samplers[unit], sampler, [&] { glBindSampler(unit, sampler); });
}

void GLContext::BindRange(GLenum target, GLuint index, const RangeBinding& r) {
  auto& slot = target == GL_UNIFORM_BUFFER ? cache_.uniformBuffers[index] : cache_.storageBuffers[index];
  SetCached(slot, r, [&] { glBindBufferRange(target, index, r.buffer, r.offset, r.size); });
}

void GLContext::BindUniformBlock(const Shader& shader, size_t index, const Buffer* buffer) {
  const GlBinding& b = detail::GlBindingsOf(shader.Bytecode())[index];
  const CBufferInfo* info = shader.Reflection().FindCBuffer(b.registerIndex);
  const uint32_t declared = info ? info->size : 0;
  GLBuffer& gb = GL(buffer);  // not const: the repack may refresh its CPU copy
  // DYNAMIC constant buffers always go through the ring: their contents live in `shadow`.
  if (b.repack.empty() && gb.size >= declared && gb.usage != USAGE_DYNAMIC) {
    BindRange(GL_UNIFORM_BUFFER, b.glBinding, {gb.name, 0, GLsizeiptr(gb.size)});
    return;
  }
  // std140 copy (or a zero-padded copy of a buffer smaller than the cbuffer, which D3D reads as 0).
  RepackRecord& rec = repacked_[b.glBinding];
  if (rec.uid == buffer->UniqueId() && rec.version == gb.version && rec.generation == ringGeneration_ &&
      rec.shaderUid == shader.UniqueId() && rec.bindingIndex == index) {
    BindRange(GL_UNIFORM_BUFFER, b.glBinding, rec.range);
    return;
  }
  const uint32_t blockSize = b.repack.empty() ? declared : std::max(b.glBlockSize, 16u);
  static thread_local std::vector<uint8_t> block;
  block.assign(blockSize, 0);
  RefreshShadow(gb);
  auto copy = [&](uint32_t src, uint32_t dst, uint32_t n) {
    if (src >= gb.shadow.size() || dst >= blockSize) return;
    n = std::min({n, uint32_t(gb.shadow.size() - src), blockSize - dst});
    std::memcpy(block.data() + dst, gb.shadow.data() + src, n);
  };
  if (b.repack.empty()) copy(0, 0, declared);
  for (const GlCopyRange& r : b.repack) copy(r.src, r.dst, r.size);
  GLintptr offset = UploadToRing(block.data(), blockSize);
  rec = {buffer->UniqueId(), gb.version, ringGeneration_, shader.UniqueId(), index, {ring_, offset, GLsizeiptr(blockSize)}};
  BindRange(GL_UNIFORM_BUFFER, b.glBinding, rec.range);
}

GLbitfield GLContext::BindStage(const PipelineState& s, ShaderStage stage) {
  const StageBindings& sb = s.stage(stage);
  const Shader* sh = sb.shader.get();
  if (!sh) return 0;
  const auto& uavs = stage == ShaderStage::Compute ? s.computeUavs : s.pixelUavs;
  const std::vector<GlBinding>& bindings = detail::GlBindingsOf(sh->Bytecode());
  GLbitfield barrier = 0;
  for (size_t i = 0; i < bindings.size(); ++i) {
    const GlBinding& b = bindings[i];
    switch (b.kind) {
      case GlBindingKind::CombinedSampler: {
        const ShaderResourceView* v = sb.shaderResources[b.registerIndex].get();
        GLuint sampler = loadSampler_;
        if (b.samplerRegister >= 0 && sb.samplers[size_t(b.samplerRegister)])
          sampler = detail::BackendAs<GLSampler>(sb.samplers[size_t(b.samplerRegister)]).name;
        BindTexture(b.glBinding, v ? GL(v).texture : 0, sampler);
        break;
      }
      case GlBindingKind::UniformBlock:
        if (const Buffer* cb = sb.constantBuffers[b.registerIndex].get()) BindUniformBlock(*sh, i, cb);
        break;
      case GlBindingKind::StorageBlock: {
        if (b.registerClass == RegisterClass::ShaderResource) {
          if (const ShaderResourceView* v = sb.shaderResources[b.registerIndex].get()) {
            const GLView& gv = GL(v);
            BindRange(GL_SHADER_STORAGE_BUFFER, b.glBinding, {gv.buffer, gv.offset, gv.size});
          }
        } else if (const UnorderedAccessView* u = uavs[b.registerIndex].get()) {
          const GLView& gv = GL(u);
          if (b.uavCounter) BindRange(GL_SHADER_STORAGE_BUFFER, b.glBinding, {gv.counter, 0, 4});
          else BindRange(GL_SHADER_STORAGE_BUFFER, b.glBinding, {gv.buffer, gv.offset, gv.size});
          barrier |= kBufferUavBarrier;
        }
        break;
      }
      case GlBindingKind::Image: {
        const UnorderedAccessView* u = uavs[b.registerIndex].get();
        if (!u) break;
        const GLView& gv = GL(u);
        ImageBinding ib{gv.texture, gv.level, gv.layered, std::max(gv.layer, 0), gv.format->internal};
        SetCached(cache_.images[b.glBinding], ib,
                  [&] { glBindImageTexture(b.glBinding, ib.texture, ib.level, ib.layered, ib.layer, GL_READ_WRITE, ib.format); });
        barrier |= gv.kind == GLView::Kind::TypedBuffer ? kBufferUavBarrier : kImageUavBarrier;
        break;
      }
    }
  }
  return barrier;
}

// The ring is persistently mapped: a map and unmap per upload (one per Map WRITE_DISCARD of a
// constant buffer) cost Mesa more than the draw. A full ring is replaced, not orphaned: draws still
// reading the old buffer keep it alive after glDeleteBuffers, and new uploads go to fresh memory.
void GLContext::NewRing(size_t size) {
  if (ring_) {
    ForgetBuffer(ring_);
    glDeleteBuffers(1, &ring_);
  }
  const GLbitfield flags = GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
  glCreateBuffers(1, &ring_);
  glNamedBufferStorage(ring_, GLsizeiptr(size), nullptr, flags);
  ringData_ = static_cast<uint8_t*>(glMapNamedBufferRange(ring_, 0, GLsizeiptr(size), flags));
  ringSize_ = size;
  ringCursor_ = 0;
}

GLintptr GLContext::UploadToRing(const void* data, size_t size) {
  const size_t align = size_t(std::max<GLint>(dev_.uboAlignment, 16));
  size_t offset = (ringCursor_ + align - 1) / align * align;
  if (offset + size > ringSize_) {
    NewRing(std::max(ringSize_, size));
    ++ringGeneration_;
    offset = 0;
  }
  std::memcpy(ringData_ + offset, data, size);
  ringCursor_ = offset + size;
  return GLintptr(offset);
}

// ---------------------------------------------------------------------------------------------

void GLContext::ForgetTexture(GLuint name) {
  disturbed_ = DIRTY_ALL;
  ForgetIf(cache_.textures, [&](GLuint t) { return t == name; });
  ForgetIf(cache_.images, [&](const ImageBinding& b) { return b.texture == name; });
  for (auto it = framebuffers_.begin(); it != framebuffers_.end();) {
    const FramebufferKey& k = it->first;
    bool uses = k.depth.texture == name || std::any_of(k.colors.begin(), k.colors.end(), [&](const Attachment& a) { return a.texture == name; });
    if (!uses) {
      ++it;
      continue;
    }
    if (cache_.drawFramebuffer == it->second) cache_.drawFramebuffer.reset();
    if (cache_.readFramebuffer == it->second) cache_.readFramebuffer.reset();
    glDeleteFramebuffers(1, &it->second);
    it = framebuffers_.erase(it);
  }
}

void GLContext::ForgetBuffer(GLuint name) {
  disturbed_ = DIRTY_ALL;
  ForgetIf(cache_.uniformBuffers, [&](const RangeBinding& r) { return r.buffer == name; });
  ForgetIf(cache_.storageBuffers, [&](const RangeBinding& r) { return r.buffer == name; });
  ForgetIf(cache_.vertexBindings, [&](const VertexBinding& v) { return v.buffer == name; });
  if (cache_.elementBuffer == name) cache_.elementBuffer.reset();
}

void GLContext::ForgetSampler(GLuint name) {
  disturbed_ = DIRTY_ALL;
  ForgetIf(cache_.samplers, [&](GLuint s) { return s == name; });
}

void GLContext::ForgetProgram(GLuint name) {
  disturbed_ = DIRTY_ALL;
  for (auto it = pipelines_.begin(); it != pipelines_.end();) {
    if (it->first.first != name && it->first.second != name) {
      ++it;
      continue;
    }
    if (cache_.pipeline == it->second) cache_.pipeline.reset();
    glDeleteProgramPipelines(1, &it->second);
    it = pipelines_.erase(it);
  }
}

void GLContext::ForgetPipeline(GLuint name) {
  disturbed_ = DIRTY_ALL;
  if (cache_.pipeline == name) cache_.pipeline.reset();
}

void GLContext::Flush() {
  dev_.MakeCurrent();
  glFlush();
}

void GLContext::WaitIdle() {
  dev_.MakeCurrent();
  glFinish();
}

}  // namespace sp::gl
