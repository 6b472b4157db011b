// Rasterizer, viewport, depth-stencil and blend state: D3D11 descriptions as GL state, set
// through the context's cache so that only changes reach the driver.
#include "gl-context.h"

namespace sp::gl {
namespace {

GLenum StencilOp(STENCIL_OP op) {
  switch (op) {
    case STENCIL_OP_ZERO: return GL_ZERO;
    case STENCIL_OP_REPLACE: return GL_REPLACE;
    case STENCIL_OP_INCR_SAT: return GL_INCR;
    case STENCIL_OP_DECR_SAT: return GL_DECR;
    case STENCIL_OP_INVERT: return GL_INVERT;
    case STENCIL_OP_INCR: return GL_INCR_WRAP;
    case STENCIL_OP_DECR: return GL_DECR_WRAP;
    default: return GL_KEEP;
  }
}

GLenum BlendFactor(BLEND b) {
  switch (b) {
    case BLEND_ZERO: return GL_ZERO;
    case BLEND_ONE: return GL_ONE;
    case BLEND_SRC_COLOR: return GL_SRC_COLOR;
    case BLEND_INV_SRC_COLOR: return GL_ONE_MINUS_SRC_COLOR;
    case BLEND_SRC_ALPHA: return GL_SRC_ALPHA;
    case BLEND_INV_SRC_ALPHA: return GL_ONE_MINUS_SRC_ALPHA;
    case BLEND_DEST_ALPHA: return GL_DST_ALPHA;
    case BLEND_INV_DEST_ALPHA: return GL_ONE_MINUS_DST_ALPHA;
    case BLEND_DEST_COLOR: return GL_DST_COLOR;
    case BLEND_INV_DEST_COLOR: return GL_ONE_MINUS_DST_COLOR;
    case BLEND_SRC_ALPHA_SAT: return GL_SRC_ALPHA_SATURATE;
    // As an alpha factor GL's CONSTANT_COLOR uses the constant's alpha, like D3D's BLEND_FACTOR.
    case BLEND_BLEND_FACTOR: return GL_CONSTANT_COLOR;
    case BLEND_INV_BLEND_FACTOR: return GL_ONE_MINUS_CONSTANT_COLOR;
    case BLEND_SRC1_COLOR: return GL_SRC1_COLOR;
    case BLEND_INV_SRC1_COLOR: return GL_ONE_MINUS_SRC1_COLOR;
    case BLEND_SRC1_ALPHA: return GL_SRC1_ALPHA;
    case BLEND_INV_SRC1_ALPHA: return GL_ONE_MINUS_SRC1_ALPHA;
  }
  return GL_ONE;
}

GLenum BlendOp(BLEND_OP op) {
  switch (op) {
    case BLEND_OP_SUBTRACT: return GL_FUNC_SUBTRACT;
    case BLEND_OP_REV_SUBTRACT: return GL_FUNC_REVERSE_SUBTRACT;
    case BLEND_OP_MIN: return GL_MIN;
    case BLEND_OP_MAX: return GL_MAX;
    default: return GL_FUNC_ADD;
  }
}

void Toggle(GLenum cap, bool on) { on ? glEnable(cap) : glDisable(cap); }

}  // namespace

GLenum CompareFunc(COMPARISON_FUNC f) {
  switch (f) {
    case COMPARISON_NEVER: return GL_NEVER;
    case COMPARISON_LESS: return GL_LESS;
    case COMPARISON_EQUAL: return GL_EQUAL;
    case COMPARISON_LESS_EQUAL: return GL_LEQUAL;
    case COMPARISON_GREATER: return GL_GREATER;
    case COMPARISON_NOT_EQUAL: return GL_NOTEQUAL;
    case COMPARISON_GREATER_EQUAL: return GL_GEQUAL;
    default: return GL_ALWAYS;
  }
}

void GLContext::ApplyRasterizer(const PipelineState& s) {
  const RASTERIZER_DESC& r = s.rasterizer();
  const bool cull = r.CullMode != CULL_NONE;
  SetCached(cache_.cull, cull, [&] { Toggle(GL_CULL_FACE, cull); });
  if (cull) {
    GLenum face = r.CullMode == CULL_FRONT ? GL_FRONT : GL_BACK;
    SetCached(cache_.cullFace, face, [&] { glCullFace(face); });
  }
  // The VS flips y, which flips the winding: D3D's clockwise front face is GL's CCW.
  GLenum front = r.FrontCounterClockwise ? GL_CW : GL_CCW;
  SetCached(cache_.frontFace, front, [&] { glFrontFace(front); });
  GLenum fill = r.FillMode == FILL_WIREFRAME ? GL_LINE : GL_FILL;
  SetCached(cache_.polygonMode, fill, [&] { glPolygonMode(GL_FRONT_AND_BACK, fill); });

  // D3D11 biases triangles only (wireframe ones too), never line or point primitives.
  const PipelineState::DepthBias b = s.depthBias(dev_.info());
  SetCached(cache_.polygonOffsetFill, b.enable, [&] { Toggle(GL_POLYGON_OFFSET_FILL, b.enable); });
  SetCached(cache_.polygonOffsetLine, b.enable, [&] { Toggle(GL_POLYGON_OFFSET_LINE, b.enable); });
  if (b.enable) {
    std::array<float, 3> offset{b.slope, b.constant, b.clamp};
    SetCached(cache_.polygonOffset, offset, [&] {
      if (dev_.polygonOffsetClamp) dev_.polygonOffsetClamp(offset[0], offset[1], offset[2]);
      else glPolygonOffset(offset[0], offset[1]);
    });
  }
  // GL_DEPTH_CLAMP turns clipping off and clamps, which D3D always does to the viewport range.
  SetCached(cache_.depthClamp, !r.DepthClipEnable, [&] { Toggle(GL_DEPTH_CLAMP, !r.DepthClipEnable); });
  SetScissorTest(r.ScissorEnable);
}

void GLContext::ApplyViewports(const PipelineState& s) {
  // Row 0 of every target is D3D's top row (see DEVELOPERS.md): rectangles apply as given.
  for (uint32_t i = 0; i < s.numViewports; ++i) {
    const VIEWPORT& v = s.viewports[i];
    std::array<float, 4> rect{v.TopLeftX, v.TopLeftY, v.Width, v.Height};
    SetCached(cache_.viewports[i], rect, [&] { glViewportIndexedf(i, rect[0], rect[1], rect[2], rect[3]); });
    std::array<double, 2> range{v.MinDepth, v.MaxDepth};
    SetCached(cache_.depthRanges[i], range, [&] { glDepthRangeIndexed(i, range[0], range[1]); });
  }
  if (!s.rasterizer().ScissorEnable) return;
  for (uint32_t i = 0; i < std::max(s.numViewports, 1u); ++i) {
    RECT r = i < s.numScissorRects ? s.scissorRects[i] : RECT{};  // no rect: D3D culls everything
    std::array<GLint, 4> box{r.left, r.top, std::max(0, r.right - r.left), std::max(0, r.bottom - r.top)};
    SetCached(cache_.scissors[i], box, [&] { glScissorIndexed(i, box[0], box[1], box[2], box[3]); });
  }
}

void GLContext::ApplyDepthStencil(const PipelineState& s) {
  const DEPTH_STENCIL_DESC& d = s.depthStencilDesc();
  const uint32_t flags = s.depthStencil ? s.depthStencil->GetDesc().Flags : 0;
  SetCached(cache_.depthTest, d.DepthEnable, [&] { Toggle(GL_DEPTH_TEST, d.DepthEnable); });
  if (d.DepthEnable) {
    GLenum func = CompareFunc(d.DepthFunc);
    SetCached(cache_.depthFunc, func, [&] { glDepthFunc(func); });
  }
  SetDepthMask(d.DepthEnable && d.DepthWriteMask == DEPTH_WRITE_MASK_ALL && !(flags & DSV_READ_ONLY_DEPTH));
  SetCached(cache_.stencilTest, d.StencilEnable, [&] { Toggle(GL_STENCIL_TEST, d.StencilEnable); });
  if (!d.StencilEnable) return;
  const GLuint writeMask = (flags & DSV_READ_ONLY_STENCIL) ? 0u : d.StencilWriteMask;
  const DEPTH_STENCILOP_DESC* ops[2] = {&d.FrontFace, &d.BackFace};
  const GLenum faces[2] = {GL_FRONT, GL_BACK};
  for (int i = 0; i < 2; ++i) {
    // The winding that decides the face is the one culling uses, so GL_FRONT is D3D's front.
    StencilFace f{CompareFunc(ops[i]->StencilFunc), GLint(s.stencilRef & 0xff), d.StencilReadMask, StencilOp(ops[i]->StencilFailOp),
                  StencilOp(ops[i]->StencilDepthFailOp), StencilOp(ops[i]->StencilPassOp), writeMask};
    SetCached(cache_.stencil[i], f, [&] {
      glStencilFuncSeparate(faces[i], f.func, f.ref, f.readMask);
      glStencilOpSeparate(faces[i], f.fail, f.depthFail, f.pass);
      glStencilMaskSeparate(faces[i], f.writeMask);
    });
  }
}

void GLContext::ApplyBlend(const PipelineState& s, bool hasPixelShader) {
  const BLEND_DESC& bd = s.blend();
  for (uint32_t i = 0; i < SIMULTANEOUS_RENDER_TARGET_COUNT; ++i) {
    const RENDER_TARGET_BLEND_DESC& rt = bd.RenderTarget[bd.IndependentBlendEnable ? i : 0];
    const bool on = rt.BlendEnable && s.renderTargets[i];
    SetCached(cache_.blend[i], on, [&] { on ? glEnablei(GL_BLEND, i) : glDisablei(GL_BLEND, i); });
    if (on) {
      BlendEquation e{BlendFactor(rt.SrcBlend), BlendFactor(rt.DestBlend), BlendFactor(rt.SrcBlendAlpha),
                      BlendFactor(rt.DestBlendAlpha), BlendOp(rt.BlendOp), BlendOp(rt.BlendOpAlpha)};
      SetCached(cache_.blendEquations[i], e, [&] {
        glBlendFuncSeparatei(i, e.srcRGB, e.dstRGB, e.srcAlpha, e.dstAlpha);
        glBlendEquationSeparatei(i, e.opRGB, e.opAlpha);
      });
    }
    // Without a pixel shader D3D writes no colour; GL's outputs would be undefined.
    SetColorMask(i, hasPixelShader ? rt.RenderTargetWriteMask : 0);
  }
  SetCached(cache_.blendColor, s.blendFactor, [&] { glBlendColor(s.blendFactor[0], s.blendFactor[1], s.blendFactor[2], s.blendFactor[3]); });
  SetCached(cache_.alphaToCoverage, bd.AlphaToCoverageEnable, [&] { Toggle(GL_SAMPLE_ALPHA_TO_COVERAGE, bd.AlphaToCoverageEnable); });
  const bool masked = s.sampleMask != 0xffffffffu;
  SetCached(cache_.sampleMaskEnabled, masked, [&] { Toggle(GL_SAMPLE_MASK, masked); });
  if (masked) SetCached(cache_.sampleMask, s.sampleMask, [&] { glSampleMaski(0, s.sampleMask); });
}

void GLContext::SetScissorTest(bool enabled) {
  SetCached(cache_.scissorTest, enabled, [&] {
    Toggle(GL_SCISSOR_TEST, enabled);
    disturbed_ |= DIRTY_RASTERIZER;
  });
}

void GLContext::SetPrimitiveRestart(bool enabled) {
  SetCached(cache_.primitiveRestart, enabled, [&] { Toggle(GL_PRIMITIVE_RESTART_FIXED_INDEX, enabled); });
}

void GLContext::SetColorMask(uint32_t i, uint8_t m) {
  SetCached(cache_.colorMasks[i], m, [&] {
    glColorMaski(i, (m & 1) != 0, (m & 2) != 0, (m & 4) != 0, (m & 8) != 0);
    disturbed_ |= DIRTY_BLEND;
  });
}

void GLContext::SetDepthMask(bool write) {
  SetCached(cache_.depthMask, write, [&] {
    glDepthMask(write ? GL_TRUE : GL_FALSE);
    disturbed_ |= DIRTY_DEPTH_STENCIL;
  });
}

void GLContext::SetStencilWriteMask(GLuint mask) {
  bool known = cache_.stencil[0] && cache_.stencil[1] && cache_.stencil[0]->writeMask == mask && cache_.stencil[1]->writeMask == mask;
  if (known) return;
  glStencilMaskSeparate(GL_FRONT_AND_BACK, mask);
  disturbed_ |= DIRTY_DEPTH_STENCIL;
  for (auto& f : cache_.stencil)
    if (f) f->writeMask = mask;
}

}  // namespace sp::gl
