// Views. A texture view is the texture itself when it sees the texture whole, in its storage
// format and dimension; otherwise a GL texture view (glTextureView) of the range, format and
// target. Render-target and depth-stencil views become framebuffer attachments (a level and one
// layer or all of them). Buffer views are buffer textures (typed) or storage-buffer ranges.
#include "gl-context.h"

namespace sp::gl {
namespace {

GLenum SrvTarget(SRV_DIMENSION d) {
  switch (d) {
    case SRV_DIMENSION_TEXTURE1D: return GL_TEXTURE_1D;
    case SRV_DIMENSION_TEXTURE1DARRAY: return GL_TEXTURE_1D_ARRAY;
    case SRV_DIMENSION_TEXTURE2D: return GL_TEXTURE_2D;
    case SRV_DIMENSION_TEXTURE2DARRAY: return GL_TEXTURE_2D_ARRAY;
    case SRV_DIMENSION_TEXTURE2DMS: return GL_TEXTURE_2D_MULTISAMPLE;
    case SRV_DIMENSION_TEXTURE2DMSARRAY: return GL_TEXTURE_2D_MULTISAMPLE_ARRAY;
    case SRV_DIMENSION_TEXTURE3D: return GL_TEXTURE_3D;
    case SRV_DIMENSION_TEXTURECUBE: return GL_TEXTURE_CUBE_MAP;
    case SRV_DIMENSION_TEXTURECUBEARRAY: return GL_TEXTURE_CUBE_MAP_ARRAY;
    default: return 0;
  }
}

// The non-array target of an array target (a view of one layer).
GLenum SingleLayerTarget(GLenum arrayTarget) {
  switch (arrayTarget) {
    case GL_TEXTURE_1D_ARRAY: return GL_TEXTURE_1D;
    case GL_TEXTURE_2D_ARRAY: return GL_TEXTURE_2D;
    case GL_TEXTURE_2D_MULTISAMPLE_ARRAY: return GL_TEXTURE_2D_MULTISAMPLE;
    default: return arrayTarget;
  }
}

// The array target whose views include a non-array target (a 2D texture seen as a 2D array).
GLenum ArrayTarget(GLenum target) {
  switch (target) {
    case GL_TEXTURE_1D: return GL_TEXTURE_1D_ARRAY;
    case GL_TEXTURE_2D: return GL_TEXTURE_2D_ARRAY;
    case GL_TEXTURE_2D_MULTISAMPLE: return GL_TEXTURE_2D_MULTISAMPLE_ARRAY;
    default: return target;
  }
}

bool Multisampled(GLenum target) { return target == GL_TEXTURE_2D_MULTISAMPLE || target == GL_TEXTURE_2D_MULTISAMPLE_ARRAY; }

// Views need names from glGenTextures that were never bound (glCreateTextures fixes a target).
GLuint MakeView(const GLTexture& t, GLenum target, GLenum internal, uint32_t firstMip, uint32_t mips, uint32_t firstLayer, uint32_t layers) {
  GLuint v = 0;
  glGenTextures(1, &v);
  if (Multisampled(target)) firstMip = 0, mips = 1;
  if (target == GL_TEXTURE_3D || t.target == GL_TEXTURE_3D) firstLayer = 0, layers = 1;
  glTextureView(v, target, t.name, internal, firstMip, mips, firstLayer, layers);
  return v;
}

[[noreturn]] void NotSupported(const View& v, const char* call, const std::string& why) {
  ThrowError(ErrorId::NOT_SUPPORTED, call, v.Describe(), why);
}

void CreateBufferView(GLDevice& dev, GLView& v, View& view, bool uav) {
  const char* call = uav ? "CreateUnorderedAccessView" : "CreateShaderResourceView";
  const Buffer* buf = static_cast<const Buffer*>(view.GetResource());
  const GLBuffer& gb = GL(buf);
  const ViewRange& r = view.Range();
  v.buffer = gb.name;
  v.offset = GLintptr(r.firstByte);
  v.size = GLsizeiptr(r.byteCount);
  const uint32_t uavFlags = uav ? static_cast<const UnorderedAccessView&>(view).GetDesc().Buffer.Flags : 0;
  if (view.Shape() != ViewShape::TypedBuffer) {
    v.kind = GLView::Kind::StorageBuffer;
    if (r.firstByte % uint64_t(dev.ssboAlignment))
      NotSupported(view, call, "the view starts at byte " + std::to_string(r.firstByte) + ", but this driver's storage-buffer offset alignment is " +
                                   std::to_string(dev.ssboAlignment) + " bytes (GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT); choose FirstElement accordingly");
    if (uavFlags & (BUFFER_UAV_FLAG_APPEND | BUFFER_UAV_FLAG_COUNTER)) {
      const uint32_t zero = 0;
      glCreateBuffers(1, &v.counter);
      glNamedBufferStorage(v.counter, 4, &zero, GL_DYNAMIC_STORAGE_BIT);
    }
    return;
  }
  v.kind = GLView::Kind::TypedBuffer;
  v.format = &FormatOf(view.ViewFormat());
  if (!v.format->textureBuffer)
    ThrowError(ErrorId::FORMAT_UNSUPPORTED, call, view.Describe(),
               std::string(FormatName(view.ViewFormat())) + " is not a texture-buffer format in OpenGL (typed buffer views)");
  if (r.firstByte % uint64_t(dev.tboAlignment))
    NotSupported(view, call, "the view starts at byte " + std::to_string(r.firstByte) + ", but this driver's texture-buffer offset alignment is " +
                                 std::to_string(dev.tboAlignment) + " bytes (GL_TEXTURE_BUFFER_OFFSET_ALIGNMENT); choose FirstElement accordingly");
  glCreateTextures(GL_TEXTURE_BUFFER, 1, &v.texture);
  glTextureBufferRange(v.texture, v.format->internal, gb.name, v.offset, v.size);
  v.ownsTexture = true;
  v.target = GL_TEXTURE_BUFFER;
}

void CreateShaderResourceView(GLView& v, const ShaderResourceView& view, const GLTexture& t) {
  const ViewRange& r = view.Range();
  const TextureShape& s = t.shape;
  const bool stencil = t.storage->depth && GetFormatInfo(view.ViewFormat()).readsStencil;
  const GLenum target = SrvTarget(view.GetDesc().ViewDimension);
  const bool whole = r.firstMip == 0 && r.mipCount == s.mipLevels && r.firstSlice == 0 &&
                     (s.dimension == RESOURCE_DIMENSION_TEXTURE3D || r.sliceCount == s.arraySize);
  if (!stencil && v.format->internal == t.storage->internal && target == t.target && whole) {
    v.texture = t.name;
    v.target = t.target;
    return;
  }
  v.texture = MakeView(t, target, v.format->internal, r.firstMip, r.mipCount, r.firstSlice, r.sliceCount);
  v.ownsTexture = true;
  v.target = target;
  if (stencil) {
    // D3D returns stencil in .g (X24_TYPELESS_G8_UINT); GL's stencil texturing puts it in .r.
    glTextureParameteri(v.texture, GL_DEPTH_STENCIL_TEXTURE_MODE, GL_STENCIL_INDEX);
    glTextureParameteri(v.texture, GL_TEXTURE_SWIZZLE_G, GL_RED);
  }
}

// RTV/DSV: which texture, level and layer(s) the framebuffer attaches.
void CreateAttachmentView(GLView& v, const View& view, const GLTexture& t, const char* call) {
  const ViewRange& r = view.Range();
  const TextureShape& s = t.shape;
  const bool sameFormat = v.format->internal == t.storage->internal;
  if (s.dimension == RESOURCE_DIMENSION_TEXTURE3D) {
    const uint32_t depth = s.mipDepth(r.firstMip);
    if (r.sliceCount != 1 && !(r.firstSlice == 0 && r.sliceCount == depth))
      NotSupported(view, call, "OpenGL attaches one W slice or all W slices of a 3D mip; a partial range of " + std::to_string(r.sliceCount) + " slices cannot be attached");
    v.texture = t.name;
    v.level = GLint(r.firstMip);
    if (!sameFormat) {
      v.texture = MakeView(t, GL_TEXTURE_3D, v.format->internal, r.firstMip, 1, 0, 1);
      v.ownsTexture = true;
      v.level = 0;
    }
    v.layer = r.sliceCount == 1 ? GLint(r.firstSlice) : -1;
    v.layered = v.layer < 0;
    return;
  }
  if (!t.arrayed()) {
    v.texture = t.name;
    v.level = GLint(r.firstMip);
    if (!sameFormat) {
      v.texture = MakeView(t, t.target, v.format->internal, r.firstMip, 1, 0, 1);
      v.ownsTexture = true;
      v.level = 0;
    }
    return;
  }
  const bool allLayers = r.firstSlice == 0 && r.sliceCount == s.arraySize;
  if (sameFormat && (r.sliceCount == 1 || allLayers)) {
    v.texture = t.name;
    v.level = GLint(r.firstMip);
    v.layer = r.sliceCount == 1 ? GLint(r.firstSlice) : -1;
    v.layered = v.layer < 0;
    return;
  }
  const GLenum target = r.sliceCount == 1 ? SingleLayerTarget(t.target) : t.target;
  v.texture = MakeView(t, target, v.format->internal, r.firstMip, 1, r.firstSlice, r.sliceCount);
  v.ownsTexture = true;
  v.level = 0;
  v.layered = r.sliceCount > 1;
}

void CreateImageView(GLView& v, const UnorderedAccessView& view, const GLTexture& t) {
  const ViewRange& r = view.Range();
  const TextureShape& s = t.shape;
  const bool arrayDim = view.Shape() == ViewShape::Texture1DArray || view.Shape() == ViewShape::Texture2DArray;
  const bool sameFormat = v.format->internal == t.storage->internal;
  v.target = t.target;
  if (view.Shape() == ViewShape::Texture3D) {
    if (!(r.firstSlice == 0 && r.sliceCount == s.mipDepth(r.firstMip)))
      NotSupported(view, "CreateUnorderedAccessView", "OpenGL binds a 3D mip as an image only whole; FirstWSlice must be 0 and WSize all slices");
    v.texture = sameFormat ? t.name : MakeView(t, GL_TEXTURE_3D, v.format->internal, r.firstMip, 1, 0, 1);
    v.ownsTexture = !sameFormat;
    v.level = sameFormat ? GLint(r.firstMip) : 0;
    v.layered = true;
    v.layer = 0;
    return;
  }
  // Clears use the view's own format (float clears convert), so formats always match here, and
  // an image*Array in the shader needs a layered binding even of one layer.
  if (sameFormat && (!arrayDim || (t.arrayed() && r.firstSlice == 0 && r.sliceCount == s.arraySize))) {
    v.texture = t.name;
    v.level = GLint(r.firstMip);
    v.layered = arrayDim;
    v.layer = v.layered ? 0 : GLint(r.firstSlice);
    return;
  }
  const GLenum target = arrayDim ? ArrayTarget(t.target) : SingleLayerTarget(t.target);
  v.texture = MakeView(t, target, v.format->internal, r.firstMip, 1, r.firstSlice, arrayDim ? r.sliceCount : 1);
  v.ownsTexture = true;
  v.target = target;
  v.level = 0;
  v.layered = arrayDim;
  v.layer = 0;
}

}  // namespace

GLView::~GLView() {
  dev->MakeCurrent();
  if (ownsTexture) dev->DeleteTexture(texture);
  if (counter) dev->DeleteBuffer(counter);
  if (clearView) dev->DeleteTexture(clearView);
}

std::unique_ptr<detail::BackendObject> CreateGLView(GLDevice& dev, View& view) {
  auto v = std::make_unique<GLView>();
  v->dev = &dev;
  if (view.IsBuffer()) {
    CreateBufferView(dev, *v, view, view.Kind() == ViewKind::UnorderedAccess);
    return v;
  }
  const GLTexture& t = GL(static_cast<const Texture*>(view.GetResource()));
  // Depth textures are read through their depth-stencil format (the aspect is view state).
  v->format = t.storage->depth ? t.storage : &FormatOf(view.ViewFormat());
  switch (view.Kind()) {
    case ViewKind::ShaderResource: CreateShaderResourceView(*v, static_cast<ShaderResourceView&>(view), t); break;
    case ViewKind::UnorderedAccess: CreateImageView(*v, static_cast<UnorderedAccessView&>(view), t); break;
    case ViewKind::RenderTarget: CreateAttachmentView(*v, view, t, "CreateRenderTargetView"); break;
    case ViewKind::DepthStencil: CreateAttachmentView(*v, view, t, "CreateDepthStencilView"); break;
  }
  return v;
}

}  // namespace sp::gl
