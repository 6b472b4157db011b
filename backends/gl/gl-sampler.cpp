// Sampler objects for every D3D11 filter, address mode, comparison and reduction.
#include <algorithm>

#include "gl-context.h"

namespace sp::gl {
namespace {

GLenum AddressMode(TEXTURE_ADDRESS_MODE m) {
  switch (m) {
    case TEXTURE_ADDRESS_WRAP: return GL_REPEAT;
    case TEXTURE_ADDRESS_MIRROR: return GL_MIRRORED_REPEAT;
    case TEXTURE_ADDRESS_BORDER: return GL_CLAMP_TO_BORDER;
    case TEXTURE_ADDRESS_MIRROR_ONCE: return GL_MIRROR_CLAMP_TO_EDGE;
    default: return GL_CLAMP_TO_EDGE;
  }
}

}  // namespace

GLSampler::~GLSampler() {
  dev->MakeCurrent();
  dev->DeleteSampler(name);
}

std::unique_ptr<detail::BackendObject> CreateGLSampler(GLDevice& dev, SamplerState& sampler) {
  const SAMPLER_DESC& d = sampler.GetDesc();
  auto s = std::make_unique<GLSampler>();
  s->dev = &dev;
  glCreateSamplers(1, &s->name);
  const GLuint n = s->name;
  // Anisotropic filtering is linear in every direction in D3D11.
  const bool aniso = FilterIsAnisotropic(d.Filter);
  const bool minLinear = aniso || FilterMinLinear(d.Filter), magLinear = aniso || FilterMagLinear(d.Filter);
  const bool mipLinear = aniso || FilterMipLinear(d.Filter);
  const GLenum minFilter = minLinear ? (mipLinear ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR_MIPMAP_NEAREST)
                                     : (mipLinear ? GL_NEAREST_MIPMAP_LINEAR : GL_NEAREST_MIPMAP_NEAREST);
  glSamplerParameteri(n, GL_TEXTURE_MIN_FILTER, GLint(minFilter));
  glSamplerParameteri(n, GL_TEXTURE_MAG_FILTER, magLinear ? GL_LINEAR : GL_NEAREST);
  glSamplerParameterf(n, GL_TEXTURE_MAX_ANISOTROPY, aniso ? float(std::clamp(d.MaxAnisotropy, 1u, 16u)) : 1.0f);
  glSamplerParameteri(n, GL_TEXTURE_WRAP_S, GLint(AddressMode(d.AddressU)));
  glSamplerParameteri(n, GL_TEXTURE_WRAP_T, GLint(AddressMode(d.AddressV)));
  glSamplerParameteri(n, GL_TEXTURE_WRAP_R, GLint(AddressMode(d.AddressW)));
  if (FilterIsComparison(d.Filter)) {
    // Both APIs compare `reference OP texel`.
    glSamplerParameteri(n, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glSamplerParameteri(n, GL_TEXTURE_COMPARE_FUNC, GLint(CompareFunc(d.ComparisonFunc)));
  } else {
    glSamplerParameteri(n, GL_TEXTURE_COMPARE_MODE, GL_NONE);
  }
  const uint32_t reduction = FilterReduction(d.Filter);
  if (reduction >= 2) {
    // The core refuses these when FormatSupportBackend says min/max filtering is unavailable.
    glSamplerParameteri(n, GL_TEXTURE_REDUCTION_MODE_ARB, reduction == 2 ? GL_MIN : GL_MAX);
  }
  glSamplerParameterfv(n, GL_TEXTURE_BORDER_COLOR, d.BorderColor);
  glSamplerParameterf(n, GL_TEXTURE_LOD_BIAS, d.MipLODBias);
  glSamplerParameterf(n, GL_TEXTURE_MIN_LOD, d.MinLOD);
  glSamplerParameterf(n, GL_TEXTURE_MAX_LOD, d.MaxLOD);
  return s;
}

}  // namespace sp::gl
