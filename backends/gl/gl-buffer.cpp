// Buffers of every D3D11 kind. DEFAULT and IMMUTABLE buffers use immutable storage; DYNAMIC
// buffers mutable storage so that WRITE_DISCARD can orphan it; STAGING buffers persistently
// mapped, coherent storage. Constant buffers also keep their D3D-packed bytes on the CPU, from
// which the context builds std140 copies for blocks GL cannot read in D3D's packing.
#include <cstring>

#include "gl-context.h"

namespace sp::gl {

void GLStagingMemory::Create(GLsizeiptr size, const void* init) {
  glCreateBuffers(1, &buffer);
  const GLbitfield access = GL_MAP_READ_BIT | GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
  glNamedBufferStorage(buffer, size, init, access | GL_DYNAMIC_STORAGE_BIT);
  ptr = static_cast<uint8_t*>(glMapNamedBufferRange(buffer, 0, size, access));
}

void GLStagingMemory::Destroy(GLDevice& dev) {
  if (fence) glDeleteSync(fence);
  fence = nullptr;
  if (buffer) dev.DeleteBuffer(buffer);  // deleting unmaps
  buffer = 0;
  ptr = nullptr;
}

void GLStagingMemory::MarkGpuUse() {
  if (fence) glDeleteSync(fence);
  fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
}

bool GLStagingMemory::Wait(bool doNotWait) {
  if (!fence) return true;
  for (;;) {
    GLenum r = glClientWaitSync(fence, GL_SYNC_FLUSH_COMMANDS_BIT, doNotWait ? 0 : 1000000000ull);
    if (r == GL_ALREADY_SIGNALED || r == GL_CONDITION_SATISFIED || r == GL_WAIT_FAILED) break;
    if (doNotWait) return false;
  }
  glDeleteSync(fence);
  fence = nullptr;
  return true;
}

GLBuffer::~GLBuffer() {
  dev->MakeCurrent();
  if (usage == USAGE_STAGING) staging.Destroy(*dev);
  else dev->DeleteBuffer(name);
}

std::unique_ptr<detail::BackendObject> CreateGLBuffer(GLDevice& dev, Buffer& buffer, const SUBRESOURCE_DATA* init) {
  const BUFFER_DESC& d = buffer.GetDesc();
  auto b = std::make_unique<GLBuffer>();
  b->dev = &dev;
  b->size = d.ByteWidth;
  b->usage = d.Usage;
  b->constant = (d.BindFlags & BIND_CONSTANT_BUFFER) != 0;
  // Without initial data the contents are undefined in D3D11; zeros keep runs reproducible.
  std::vector<uint8_t> zeros;
  const void* data = init ? init->pSysMem : nullptr;
  if (!data) {
    zeros.assign(d.ByteWidth, 0);
    data = zeros.data();
  }
  if (b->constant) b->shadow.assign(static_cast<const uint8_t*>(data), static_cast<const uint8_t*>(data) + d.ByteWidth);
  switch (d.Usage) {
    case USAGE_STAGING:
      b->staging.Create(d.ByteWidth, data);
      b->name = b->staging.buffer;
      break;
    case USAGE_DYNAMIC:
      glCreateBuffers(1, &b->name);
      glNamedBufferData(b->name, d.ByteWidth, data, GL_DYNAMIC_DRAW);
      break;
    default:
      glCreateBuffers(1, &b->name);
      glNamedBufferStorage(b->name, d.ByteWidth, data, d.Usage == USAGE_IMMUTABLE ? 0 : GL_DYNAMIC_STORAGE_BIT);
      break;
  }
  return b;
}

}  // namespace sp::gl
