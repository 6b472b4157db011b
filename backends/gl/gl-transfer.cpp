// Copies, updates, mip generation, resolves and UAV counters.
//
// GPU textures copy with glCopyImageSubData; staging textures are buffers, filled with
// glGetTextureSubImage into a pixel-pack buffer and read with glTextureSubImage from a
// pixel-unpack buffer, in D3D's row layout. D24S8 is the one format whose GL packing differs
// from D3D's (depth high / stencil low): readbacks are marked and converted before the CPU or
// another copy sees them.
#include <cstring>

#include "gl-context.h"

namespace sp::gl {
namespace {

bool IsBuffer(const Resource* r) { return r->GetType() == RESOURCE_DIMENSION_BUFFER; }
uint32_t TexelBytes(const GLTexture& t) { return GetFormatInfo(t.shape.format).bytesPerElement; }
bool Is3D(const GLTexture& t) { return t.shape.dimension == RESOURCE_DIMENSION_TEXTURE3D; }

// Converts a staging subresource holding GL's D24S8 packing to D3D's (waits for the GPU).
void EnsureD3DLayout(GLTexture& t, uint32_t sub) {
  if (!t.glPacked[sub]) return;
  t.staging.Wait(false);
  const SubresourceLayout& l = t.subresources[sub];
  D24S8ToD3D(reinterpret_cast<uint32_t*>(t.staging.ptr + l.offset), size_t(l.depthPitch) * l.depth / 4);
  t.glPacked[sub] = 0;
}

void CopyBufferRegion(GLBuffer& dst, uint32_t dstOffset, GLBuffer& src, uint32_t srcOffset, uint32_t size) {
  RefreshStorage(src);
  RefreshStorage(dst);
  glCopyNamedBufferSubData(src.name, dst.name, srcOffset, dstOffset, size);
  if (src.usage == USAGE_STAGING) src.staging.MarkGpuUse();
  if (dst.usage == USAGE_STAGING) dst.staging.MarkGpuUse();
  if (dst.constant) {
    dst.shadowStale = true;
    ++dst.version;
  }
}


// A texture of a depth family stored as depth and its twin stored as colour (created without
// BIND_DEPTH_STENCIL) are copied bit for bit in D3D; glCopyImageSubData refuses depth-colour
// pairs, so the texels go through a buffer in the byte layout both share.
void CopyDepthColour(GLTexture& d, const detail::Subresource& dstSub, uint32_t x, uint32_t y, uint32_t z, GLTexture& s, const detail::Subresource& srcSub, const BOX& b) {
  const detail::Subresource& ss = srcSub;
  const uint32_t w = b.right - b.left, h = b.bottom - b.top, depth = b.back - b.front, bpe = TexelBytes(s);
  const GLsizei size = GLsizei(w * h * depth * bpe);
  const GLRegion r = RegionOf(s.target, b.left, b.top, Is3D(s) ? b.front : uint32_t(ss.slice), w, h, Is3D(s) ? depth : 1);
  GLuint temp = 0;
  glCreateBuffers(1, &temp);
  glNamedBufferStorage(temp, size, nullptr, 0);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, temp);
  glGetTextureSubImage(s.name, GLint(ss.mip), r.x, r.y, r.z, r.w, r.h, r.d, s.storage->extFormat, s.storage->extType, size, nullptr);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  UploadRegion(d, dstSub, x, y, z, w, h, depth, nullptr, w * bpe, w * bpe * h, temp);
  d.dev->DeleteBuffer(temp);
}

void CopyGpuTextures(GLTexture& d, const detail::Subresource& dstSub, uint32_t x, uint32_t y, uint32_t z, GLTexture& s, const detail::Subresource& srcSub, const BOX& b) {
  if (s.storage->depth != d.storage->depth) {
    CopyDepthColour(d, dstSub, x, y, z, s, srcSub, b);
    return;
  }
  const detail::Subresource &ss = srcSub, &ds = dstSub;
  const uint32_t w = b.right - b.left, h = b.bottom - b.top, depth = b.back - b.front;
  GLRegion sr = RegionOf(s.target, b.left, b.top, Is3D(s) ? b.front : uint32_t(ss.slice), w, h, Is3D(s) ? depth : 1);
  GLRegion dr = RegionOf(d.target, x, y, Is3D(d) ? z : uint32_t(ds.slice), w, h, Is3D(d) ? depth : 1);
  // Unlike the other image calls, glCopyImageSubData addresses 1D array layers with z.
  if (s.target == GL_TEXTURE_1D_ARRAY) sr = {sr.x, 0, sr.y, sr.w, 1, 1}, dr = {dr.x, 0, dr.y, dr.w, 1, 1};
  glCopyImageSubData(s.name, s.target, GLint(ss.mip), sr.x, sr.y, sr.z, d.name, d.target, GLint(ds.mip), dr.x, dr.y, dr.z, sr.w, sr.h, sr.d);
}

void ReadbackToStaging(GLTexture& d, const detail::Subresource& dstSub, uint32_t x, uint32_t y, uint32_t z, GLTexture& s, const detail::Subresource& srcSub, const BOX& b) {
  const SubresourceLayout& l = d.subresources[dstSub.index];
  const uint32_t bpe = TexelBytes(d);
  const uint64_t offset = l.offset + uint64_t(z) * l.depthPitch + uint64_t(y) * l.rowPitch + uint64_t(x) * bpe;
  const uint64_t total = d.subresources.back().offset + uint64_t(d.subresources.back().depthPitch) * d.subresources.back().depth;
  const detail::Subresource& ss = srcSub;
  const uint32_t w = b.right - b.left, h = b.bottom - b.top, depth = b.back - b.front;
  const GLRegion r = RegionOf(s.target, b.left, b.top, Is3D(s) ? b.front : uint32_t(ss.slice), w, h, Is3D(s) ? depth : 1);
  glPixelStorei(GL_PACK_ROW_LENGTH, GLint(l.rowPitch / bpe));
  glPixelStorei(GL_PACK_IMAGE_HEIGHT, GLint(l.height));
  glBindBuffer(GL_PIXEL_PACK_BUFFER, d.staging.buffer);
  glGetTextureSubImage(s.name, GLint(ss.mip), r.x, r.y, r.z, r.w, r.h, r.d, s.storage->extFormat, s.storage->extType, GLsizei(total - offset),
                       reinterpret_cast<void*>(uintptr_t(offset)));
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glPixelStorei(GL_PACK_ROW_LENGTH, 0);
  glPixelStorei(GL_PACK_IMAGE_HEIGHT, 0);
  if (s.storage->extType == GL_UNSIGNED_INT_24_8) d.glPacked[dstSub.index] = 1;
  d.staging.MarkGpuUse();
}

void UploadFromStaging(GLTexture& d, const detail::Subresource& dstSub, uint32_t x, uint32_t y, uint32_t z, GLTexture& s, const detail::Subresource& srcSub, const BOX& b) {
  const SubresourceLayout& l = s.subresources[srcSub.index];
  const uint64_t offset = l.offset + uint64_t(b.front) * l.depthPitch + uint64_t(b.top) * l.rowPitch + uint64_t(b.left) * TexelBytes(s);
  const uint32_t w = b.right - b.left, h = b.bottom - b.top, depth = b.back - b.front;
  if (d.storage->extType == GL_UNSIGNED_INT_24_8) {
    // Repacked for GL on the CPU: read the staging memory once the GPU is done with it.
    EnsureD3DLayout(s, srcSub.index);
    s.staging.Wait(false);
    UploadRegion(d, dstSub, x, y, z, w, h, depth, s.staging.ptr + offset, l.rowPitch, l.depthPitch);
    return;
  }
  UploadRegion(d, dstSub, x, y, z, w, h, depth, reinterpret_cast<const void*>(uintptr_t(offset)), l.rowPitch, l.depthPitch, s.staging.buffer);
  s.staging.MarkGpuUse();
}

void CopyStagingToStaging(GLTexture& d, const detail::Subresource& dstSub, uint32_t x, uint32_t y, uint32_t z, GLTexture& s, const detail::Subresource& srcSub, const BOX& b) {
  EnsureD3DLayout(s, srcSub.index);
  const SubresourceLayout &sl = s.subresources[srcSub.index], &dl = d.subresources[dstSub.index];
  const uint32_t bpe = TexelBytes(s);
  const uint32_t rowBytes = (b.right - b.left) * bpe;
  for (uint32_t k = 0; k < b.back - b.front; ++k)
    for (uint32_t j = 0; j < b.bottom - b.top; ++j) {
      uint64_t from = sl.offset + uint64_t(b.front + k) * sl.depthPitch + uint64_t(b.top + j) * sl.rowPitch + uint64_t(b.left) * bpe;
      uint64_t to = dl.offset + uint64_t(z + k) * dl.depthPitch + uint64_t(y + j) * dl.rowPitch + uint64_t(x) * bpe;
      glCopyNamedBufferSubData(s.staging.buffer, d.staging.buffer, GLintptr(from), GLintptr(to), rowBytes);
    }
  d.glPacked[dstSub.index] = 0;
  s.staging.MarkGpuUse();
  d.staging.MarkGpuUse();
}

void CopyTextureRegion(Texture* dst, const detail::Subresource& dstSub, uint32_t x, uint32_t y, uint32_t z, Texture* src, const detail::Subresource& srcSub, const BOX& b) {
  GLTexture &d = GL(dst), &s = GL(src);
  if (s.storage->depth != d.storage->depth && s.shape.sampleCount > 1)
    ThrowError(ErrorId::NOT_SUPPORTED, "CopyResource", src->Describe(),
               "OpenGL cannot copy multisampled textures between a depth-stencil texture and its colour twin");
  if (!s.isStaging() && !d.isStaging()) CopyGpuTextures(d, dstSub, x, y, z, s, srcSub, b);
  else if (!s.isStaging()) ReadbackToStaging(d, dstSub, x, y, z, s, srcSub, b);
  else if (!d.isStaging()) UploadFromStaging(d, dstSub, x, y, z, s, srcSub, b);
  else CopyStagingToStaging(d, dstSub, x, y, z, s, srcSub, b);
}

}  // namespace

void RefreshStorage(GLBuffer& b) {
  if (!b.storageStale) return;
  // Fresh storage first (Mesa turns a same-size glBufferData with data into an in-place write,
  // which waits for draws still reading the buffer), then the contents.
  glNamedBufferData(b.name, b.size, nullptr, GL_DYNAMIC_DRAW);
  glNamedBufferSubData(b.name, 0, b.size, b.shadow.data());
  b.storageStale = false;
}

void RefreshShadow(GLBuffer& b) {
  if (!b.shadowStale) return;
  // Waits for the copies that made it stale; only the repack path and partial updates get here.
  glGetNamedBufferSubData(b.name, 0, b.size, b.shadow.data());
  b.shadowStale = false;
}

void GLContext::CopyResource(Resource* dst, Resource* src) {
  dev_.MakeCurrent();
  if (IsBuffer(dst)) {
    GLBuffer &d = GL(static_cast<Buffer*>(dst)), &s = GL(static_cast<Buffer*>(src));
    CopyBufferRegion(d, 0, s, 0, d.size);
    return;
  }
  Texture *d = static_cast<Texture*>(dst), *s = static_cast<Texture*>(src);
  const TextureShape& shape = s->Shape();
  for (uint32_t sub = 0; sub < shape.subresourceCount(); ++sub) {
    const detail::Subresource at = detail::SubresourceOf(shape, sub);
    CopyTextureRegion(d, at, 0, 0, 0, s, at, at.box());
  }
}

void GLContext::CopySubresourceRegion(Resource* dst, const detail::Subresource& dstSub, uint32_t x, uint32_t y, uint32_t z, Resource* src, const detail::Subresource& srcSub,
                                      const BOX& b) {
  dev_.MakeCurrent();
  if (IsBuffer(dst)) {
    CopyBufferRegion(GL(static_cast<Buffer*>(dst)), x, GL(static_cast<Buffer*>(src)), b.left, b.right - b.left);
    return;
  }
  CopyTextureRegion(static_cast<Texture*>(dst), dstSub, x, y, z, static_cast<Texture*>(src), srcSub, b);
}

void GLContext::UpdateSubresource(Resource* dst, const detail::Subresource& sub, const BOX& b, const void* data, uint32_t rowPitch, uint32_t depthPitch) {
  dev_.MakeCurrent();
  if (IsBuffer(dst)) {
    GLBuffer& buf = GL(static_cast<Buffer*>(dst));
    const uint32_t size = b.right - b.left;
    if (buf.constant && size != buf.size) RefreshShadow(buf);  // the rest of the CPU copy must be current
    glNamedBufferSubData(buf.name, b.left, size, data);
    if (buf.constant) {
      std::memcpy(buf.shadow.data() + b.left, data, size);
      if (size == buf.size) buf.shadowStale = false;
      ++buf.version;
    }
    return;
  }
  GLTexture& t = GL(static_cast<Texture*>(dst));
  UploadRegion(t, sub, b.left, b.top, b.front, b.right - b.left, b.bottom - b.top, b.back - b.front, data, rowPitch, depthPitch);
}

void GLContext::GenerateMips(ShaderResourceView* srv) {
  dev_.MakeCurrent();
  if (GL(srv).format->integer || GL(srv).format->depth)
    ThrowError(ErrorId::FORMAT_UNSUPPORTED, "GenerateMips", srv->Describe(),
               std::string(FormatName(srv->ViewFormat())) + " has no automatic mip generation (integer and depth formats cannot be filtered)");
  // The SRV is the texture or a view of exactly its mip and slice range, in its format.
  glGenerateTextureMipmap(GL(srv).texture);
}

void GLContext::ResolveSubresource(Resource* dst, const detail::Subresource& dstSub, Resource* src, const detail::Subresource& srcSub, FORMAT format) {
  dev_.MakeCurrent();
  if (!(dev_.CheckFormatSupport(format) & FORMAT_SUPPORT_MULTISAMPLE_RESOLVE))
    ThrowError(ErrorId::FORMAT_UNSUPPORTED, "ResolveSubresource", src->Describe(),
               std::string(FormatName(format)) + " cannot be resolved (integer formats have no average; resolve in a shader)");
  GLTexture &d = GL(static_cast<Texture*>(dst)), &s = GL(static_cast<Texture*>(src));
  const GLenum internal = FormatOf(format).internal;
  // Both sides are attached in the resolve format, so the blit neither converts nor refuses.
  auto attachment = [&](GLTexture& t, const detail::Subresource& sr, GLuint& temp) {
    GLuint texture = t.name;
    if (t.storage->internal != internal) {
      glGenTextures(1, &temp);
      const bool ms = t.target == GL_TEXTURE_2D_MULTISAMPLE || t.target == GL_TEXTURE_2D_MULTISAMPLE_ARRAY;
      glTextureView(temp, t.target, t.name, internal, 0, ms ? 1 : t.shape.mipLevels, 0, t.arrayed() ? t.shape.arraySize : 1);
      texture = temp;
    }
    return Attachment{texture, GLint(sr.mip), t.arrayed() ? GLint(sr.slice) : -1};
  };
  GLuint tempSrc = 0, tempDst = 0;
  FramebufferKey readKey, drawKey;
  readKey.colors[0] = attachment(s, srcSub, tempSrc);
  drawKey.colors[0] = attachment(d, dstSub, tempDst);
  GLuint readFbo = Framebuffer(readKey, "ResolveSubresource");
  GLuint drawFbo = Framebuffer(drawKey, "ResolveSubresource");
  // Blits honour the scissor test and the colour mask of draw buffer 0.
  SetScissorTest(false);
  SetColorMask(0, 0xf);
  const GLint w = GLint(dstSub.width), h = GLint(dstSub.height);
  glBlitNamedFramebuffer(readFbo, drawFbo, 0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  if (tempSrc) dev_.DeleteTexture(tempSrc);
  if (tempDst) dev_.DeleteTexture(tempDst);
}

void GLContext::CopyStructureCount(Buffer* dst, uint32_t dstOffset, UnorderedAccessView* src) {
  dev_.MakeCurrent();
  GLBuffer& d = GL(dst);
  glCopyNamedBufferSubData(GL(src).counter, d.name, 0, dstOffset, 4);
  if (d.usage == USAGE_STAGING) d.staging.MarkGpuUse();
  if (d.constant) {
    d.shadowStale = true;
    ++d.version;
  }
}

void GLContext::SetUavCounter(UnorderedAccessView* uav, uint32_t value) {
  dev_.MakeCurrent();
  glNamedBufferSubData(GL(uav).counter, 0, 4, &value);
}

}  // namespace sp::gl
