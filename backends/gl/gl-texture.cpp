// Textures: immutable storage for GPU textures (2D arrays hold cube maps too, and views give
// them every D3D dimension), D3D-laid-out buffers for staging textures, and the upload path
// shared by initial data, UpdateSubresource, Unmap and staging copies.
#include <cstring>

#include "gl-context.h"

namespace sp::gl {
namespace {

GLenum TargetOf(const TextureShape& s) {
  switch (s.dimension) {
    case RESOURCE_DIMENSION_TEXTURE1D: return s.arraySize > 1 ? GL_TEXTURE_1D_ARRAY : GL_TEXTURE_1D;
    case RESOURCE_DIMENSION_TEXTURE3D: return GL_TEXTURE_3D;
    default:
      if (s.sampleCount > 1) return s.arraySize > 1 ? GL_TEXTURE_2D_MULTISAMPLE_ARRAY : GL_TEXTURE_2D_MULTISAMPLE;
      return s.arraySize > 1 || s.isCube() ? GL_TEXTURE_2D_ARRAY : GL_TEXTURE_2D;
  }
}

uint32_t BytesPerTexel(const TextureShape& s) { return GetFormatInfo(s.format).bytesPerElement; }

}  // namespace

GLRegion RegionOf(GLenum target, uint32_t x, uint32_t y, uint32_t z, uint32_t w, uint32_t h, uint32_t d) {
  GLRegion r;
  switch (target) {
    case GL_TEXTURE_1D: r = {GLint(x), 0, 0, GLsizei(w), 1, 1}; break;
    case GL_TEXTURE_1D_ARRAY: r = {GLint(x), GLint(z), 0, GLsizei(w), GLsizei(d), 1}; break;
    case GL_TEXTURE_2D:
    case GL_TEXTURE_2D_MULTISAMPLE: r = {GLint(x), GLint(y), 0, GLsizei(w), GLsizei(h), 1}; break;
    default: r = {GLint(x), GLint(y), GLint(z), GLsizei(w), GLsizei(h), GLsizei(d)}; break;
  }
  return r;
}

bool GLTexture::arrayed() const {
  return target == GL_TEXTURE_1D_ARRAY || target == GL_TEXTURE_2D_ARRAY || target == GL_TEXTURE_2D_MULTISAMPLE_ARRAY;
}

void D24S8ToD3D(uint32_t* t, size_t n) {
  for (size_t i = 0; i < n; ++i) t[i] = (t[i] >> 8) | (t[i] << 24);
}

void D24S8ToGL(uint32_t* t, size_t n) {
  for (size_t i = 0; i < n; ++i) t[i] = (t[i] << 8) | (t[i] >> 24);
}

void UploadRegion(GLTexture& t, const detail::Subresource& sub, uint32_t x, uint32_t y, uint32_t z, uint32_t w, uint32_t h, uint32_t d, const void* data,
                  uint32_t rowPitch, uint32_t depthPitch, GLuint pbo) {
  const uint32_t bpe = BytesPerTexel(t.shape);
  const uint32_t tightRow = w * bpe;
  if (rowPitch == 0) rowPitch = tightRow;
  if (depthPitch == 0) depthPitch = rowPitch * h;
  const GLFormat& f = *t.storage;
  std::vector<uint8_t> packed;
  // GL's row length is counted in texels; D24S8 needs GL's packing. Both cases go through a
  // tightly packed copy (client memory only: staging sources have texel-multiple pitches).
  const bool d24s8 = f.extType == GL_UNSIGNED_INT_24_8;
  if (!pbo && (d24s8 || rowPitch % bpe || depthPitch % rowPitch)) {
    packed.resize(size_t(tightRow) * h * d);
    for (uint32_t k = 0; k < d; ++k)
      for (uint32_t j = 0; j < h; ++j)
        std::memcpy(packed.data() + (size_t(k) * h + j) * tightRow, static_cast<const uint8_t*>(data) + size_t(k) * depthPitch + size_t(j) * rowPitch,
                    tightRow);
    if (d24s8) D24S8ToGL(reinterpret_cast<uint32_t*>(packed.data()), packed.size() / 4);
    data = packed.data();
    rowPitch = tightRow;
    depthPitch = tightRow * h;
  }
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, pbo);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, GLint(rowPitch / bpe));
  glPixelStorei(GL_UNPACK_IMAGE_HEIGHT, GLint(depthPitch / rowPitch));
  const GLRegion r = RegionOf(t.target, x, y, t.shape.dimension == RESOURCE_DIMENSION_TEXTURE3D ? z : sub.slice, w, h,
                              t.shape.dimension == RESOURCE_DIMENSION_TEXTURE3D ? d : 1);
  switch (t.target) {
    case GL_TEXTURE_1D: glTextureSubImage1D(t.name, GLint(sub.mip), r.x, r.w, f.extFormat, f.extType, data); break;
    case GL_TEXTURE_1D_ARRAY:
    case GL_TEXTURE_2D: glTextureSubImage2D(t.name, GLint(sub.mip), r.x, r.y, r.w, r.h, f.extFormat, f.extType, data); break;
    default: glTextureSubImage3D(t.name, GLint(sub.mip), r.x, r.y, r.z, r.w, r.h, r.d, f.extFormat, f.extType, data); break;
  }
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  glPixelStorei(GL_UNPACK_IMAGE_HEIGHT, 0);
  if (pbo) glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
}

GLTexture::~GLTexture() {
  dev->MakeCurrent();
  if (isStaging()) staging.Destroy(*dev);
  else dev->DeleteTexture(name);
}

static void CreateStaging(GLTexture& t, const SUBRESOURCE_DATA* init) {
  const TextureShape& s = t.shape;
  const uint32_t bpe = BytesPerTexel(s);
  uint64_t size = 0;
  t.subresources.resize(s.subresourceCount());
  for (uint32_t slice = 0; slice < s.arraySize; ++slice)
    for (uint32_t mip = 0; mip < s.mipLevels; ++mip) {
      SubresourceLayout& l = t.subresources[CalcSubresource(mip, slice, s.mipLevels)];
      l.width = s.mipWidth(mip);
      l.height = s.dimension == RESOURCE_DIMENSION_TEXTURE1D ? 1 : s.mipHeight(mip);
      l.depth = s.mipDepth(mip);
      l.rowPitch = l.width * bpe;
      l.depthPitch = l.rowPitch * l.height;
      l.offset = size;
      size += uint64_t(l.depthPitch) * l.depth;
    }
  // The buffer is never smaller than 4 bytes (a 1x1 R8 or R16 staging texture is 1-2); the
  // initial image glNamedBufferStorage copies from must be as large as the buffer.
  const uint64_t storage = std::max<uint64_t>(size, 4);
  std::vector<uint8_t> image(storage, 0);
  if (init) {
    for (uint32_t i = 0; i < t.subresources.size(); ++i) {
      const SubresourceLayout& l = t.subresources[i];
      const uint32_t rowPitch = init[i].SysMemPitch ? init[i].SysMemPitch : l.rowPitch;
      const uint32_t depthPitch = init[i].SysMemSlicePitch ? init[i].SysMemSlicePitch : rowPitch * l.height;
      for (uint32_t k = 0; k < l.depth; ++k)
        for (uint32_t j = 0; j < l.height; ++j)
          std::memcpy(image.data() + l.offset + size_t(k) * l.depthPitch + size_t(j) * l.rowPitch,
                      static_cast<const uint8_t*>(init[i].pSysMem) + size_t(k) * depthPitch + size_t(j) * rowPitch, l.rowPitch);
    }
  }
  t.staging.Create(GLsizeiptr(storage), image.data());
  t.glPacked.assign(t.subresources.size(), 0);
}

std::unique_ptr<detail::BackendObject> CreateGLTexture(GLDevice& dev, Texture& texture, const SUBRESOURCE_DATA* init) {
  auto t = std::make_unique<GLTexture>();
  t->dev = &dev;
  t->shape = texture.Shape();
  const TextureShape& s = t->shape;
  t->storage = &StorageFormatOf(s);
  if (s.usage == USAGE_STAGING) {
    CreateStaging(*t, init);
    return t;
  }
  if (!t->storage->internal)
    ThrowError(ErrorId::FORMAT_UNSUPPORTED, "CreateTexture", texture.Describe(), "the OpenGL backend has no storage format for this format");
  t->target = TargetOf(s);
  const GLenum internal = t->storage->internal;
  const GLsizei mips = GLsizei(s.mipLevels), w = GLsizei(s.width), h = GLsizei(s.height);
  glCreateTextures(t->target, 1, &t->name);
  switch (t->target) {
    case GL_TEXTURE_1D: glTextureStorage1D(t->name, mips, internal, w); break;
    case GL_TEXTURE_1D_ARRAY: glTextureStorage2D(t->name, mips, internal, w, GLsizei(s.arraySize)); break;
    case GL_TEXTURE_2D: glTextureStorage2D(t->name, mips, internal, w, h); break;
    case GL_TEXTURE_2D_ARRAY: glTextureStorage3D(t->name, mips, internal, w, h, GLsizei(s.arraySize)); break;
    case GL_TEXTURE_3D: glTextureStorage3D(t->name, mips, internal, w, h, GLsizei(s.depth)); break;
    // D3D's standard sample pattern is fixed: fixedsamplelocations = TRUE.
    case GL_TEXTURE_2D_MULTISAMPLE: glTextureStorage2DMultisample(t->name, GLsizei(s.sampleCount), internal, w, h, GL_TRUE); break;
    case GL_TEXTURE_2D_MULTISAMPLE_ARRAY:
      glTextureStorage3DMultisample(t->name, GLsizei(s.sampleCount), internal, w, h, GLsizei(s.arraySize), GL_TRUE);
      break;
  }
  if (init) {
    for (uint32_t i = 0; i < s.subresourceCount(); ++i) {
      const detail::Subresource r = detail::SubresourceOf(s, i);
      UploadRegion(*t, r, 0, 0, 0, r.width, r.height, r.depth, init[i].pSysMem, init[i].SysMemPitch,
                   init[i].SysMemSlicePitch);
    }
  } else {
    // D3D11 leaves the contents undefined; zeros keep runs reproducible.
    for (GLint level = 0; level < mips; ++level) glClearTexImage(t->name, level, t->storage->extFormat, t->storage->extType, nullptr);
  }
  if (s.usage == USAGE_DYNAMIC) t->dynamicData.resize(s.subresourceCount());
  return t;
}

}  // namespace sp::gl
