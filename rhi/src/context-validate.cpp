// Draw- and dispatch-time checks: what the D3D11 debug layer reports as errors when a draw would
// read something of the wrong kind. Here they throw, so a port fails loudly instead of rendering a
// silently wrong image. Registers read with nothing bound are collected for NullBindings (D3D11
// reads zeros there), or throw on a device created with strictUnboundResources.
#include "context-internal.h"
#include "null-resources.h"
#include "validate.h"

namespace sp {
using namespace detail;
namespace {

const char* ComponentName(ComponentType t) {
  switch (t) {
    case ComponentType::Float: return "float";
    case ComponentType::UInt: return "uint";
    case ComponentType::SInt: return "int";
    default: return "unknown";
  }
}

bool FormatReturns(FORMAT f, ComponentType t) {
  switch (GetFormatInfo(f).kind) {
    case FormatKind::UInt: return t == ComponentType::UInt;
    case FormatKind::SInt: return t == ComponentType::SInt;
    case FormatKind::Float:
    case FormatKind::UNorm:
    case FormatKind::SNorm:
    case FormatKind::UNormSRGB: return t == ComponentType::Float;
    default: return true;
  }
}


struct Checker {
  DeviceContext& ctx;
  const PipelineState& s;
  const char* call;
  std::vector<UnboundRead>& unbound;
  bool strict;
  mutable bool warned = false;  // a warning is due at every draw, so such a draw is not repeatable

  [[noreturn]] void fail(ErrorId id, const Shader* sh, const std::string& detail) const { Fail(id, call, Describe(sh), detail); }

  void missing(const Shader* sh, ShaderStage stage, RegisterClass cls, uint32_t reg, const ShaderResourceBinding* r,
               const CBufferInfo* cb, const std::string& detail) const {
    if (strict) fail(ErrorId::UNBOUND_RESOURCE, sh, detail);
    for (UnboundRead& u : unbound) {
      if (u.stage != stage || u.registerClass != cls || u.registerIndex != reg) continue;
      // A UAV and its hidden counter share the register: keep the binding that describes the UAV.
      if (r && u.binding && u.binding->type == ShaderResourceType::UavCounter) u.binding = r;
      return;
    }
    unbound.push_back({sh, stage, cls, reg, r, cb});
  }

  void checkSrv(const Shader* sh, ShaderStage stage, const ShaderResourceBinding& r, const ShaderResourceView* v) const {
    // Built only for a message: this runs for every binding of every draw.
    auto slot = [&] { return SlotName(stage, 't', r.registerIndex) + " ('" + r.name + "')"; };
    if (!v) return missing(sh, stage, RegisterClass::ShaderResource, r.registerIndex, &r, nullptr,
                           "the shader reads " + slot() + " but no shader resource view is bound there");
    const SHADER_RESOURCE_VIEW_DESC& d = v->GetDesc();
    const Buffer* buf = AsBuffer(v->GetResource());
    bool structured = buf && (buf->GetDesc().MiscFlags & RESOURCE_MISC_BUFFER_STRUCTURED);
    bool raw = d.ViewDimension == SRV_DIMENSION_BUFFEREX && (d.BufferEx.Flags & BUFFEREX_SRV_FLAG_RAW);
    switch (r.type) {
      case ShaderResourceType::Texture:
        if (d.ViewDimension != r.dimension)
          fail(ErrorId::RESOURCE_TYPE_MISMATCH, sh, slot() + " is declared " + SrvDimensionName(r.dimension) + " but " + Describe(v) + " is a " + SrvDimensionName(d.ViewDimension) + " view");
        if (!FormatReturns(d.Format, r.returnType))
          fail(ErrorId::RESOURCE_TYPE_MISMATCH, sh, slot() + " returns " + ComponentName(r.returnType) + " but the view's format is " + std::string(FormatName(d.Format)));
        break;
      case ShaderResourceType::TypedBuffer:
        if (!buf || structured || raw) fail(ErrorId::RESOURCE_TYPE_MISMATCH, sh, slot() + " is a typed Buffer<> but " + Describe(v) + " is not a typed buffer view");
        if (!FormatReturns(d.Format, r.returnType))
          fail(ErrorId::RESOURCE_TYPE_MISMATCH, sh, slot() + " returns " + ComponentName(r.returnType) + " but the view's format is " + std::string(FormatName(d.Format)));
        break;
      case ShaderResourceType::StructuredBuffer:
        // glslang compiles ByteAddressBuffer exactly like StructuredBuffer<uint> (a runtime array
        // of 4-byte elements), so reflection cannot tell them apart: accept a raw view there.
        if (raw && r.structureStride == 4) break;
        if (!structured) fail(ErrorId::RESOURCE_TYPE_MISMATCH, sh, slot() + " is a StructuredBuffer but " + Describe(v) + " is not a view of a structured buffer");
        if (r.structureStride && buf->GetDesc().StructureByteStride != r.structureStride)
          fail(ErrorId::RESOURCE_TYPE_MISMATCH, sh, slot() + " has a stride of " + std::to_string(r.structureStride) + " bytes but the buffer's StructureByteStride is " +
                                                        std::to_string(buf->GetDesc().StructureByteStride));
        break;
      case ShaderResourceType::ByteAddressBuffer:
        if (!raw) fail(ErrorId::RESOURCE_TYPE_MISMATCH, sh, slot() + " is a ByteAddressBuffer but " + Describe(v) + " is not a raw view (BUFFEREX_SRV_FLAG_RAW)");
        break;
      default:
        break;
    }
  }

  void checkUav(const Shader* sh, ShaderStage stage, const ShaderResourceBinding& r, const UnorderedAccessView* v) const {
    // Built only for a message: this runs for every binding of every draw.
    auto slot = [&] { return SlotName(stage, 'u', r.registerIndex) + " ('" + r.name + "')"; };
    if (!v)
      return missing(sh, stage, RegisterClass::UnorderedAccess, r.registerIndex, &r, nullptr,
                     "the shader writes " + slot() + " but no unordered access view is bound there (" +
                         (stage == ShaderStage::Compute ? "CSSetUnorderedAccessViews" : "OMSetRenderTargetsAndUnorderedAccessViews") + ")");
    const UNORDERED_ACCESS_VIEW_DESC& d = v->GetDesc();
    const Buffer* buf = AsBuffer(v->GetResource());
    bool structured = buf && (buf->GetDesc().MiscFlags & RESOURCE_MISC_BUFFER_STRUCTURED);
    bool raw = buf && (d.Buffer.Flags & BUFFER_UAV_FLAG_RAW);
    switch (r.type) {
      case ShaderResourceType::RWTexture:
        if (buf || uint32_t(d.ViewDimension) != uint32_t(r.dimension))
          fail(ErrorId::RESOURCE_TYPE_MISMATCH, sh, slot() + " is declared RW" + SrvDimensionName(r.dimension) + " but " + Describe(v) + " does not match");
        if (!FormatReturns(d.Format, r.returnType))
          fail(ErrorId::RESOURCE_TYPE_MISMATCH, sh, slot() + " holds " + ComponentName(r.returnType) + " but the view's format is " + std::string(FormatName(d.Format)));
        break;
      case ShaderResourceType::RWTypedBuffer:
        if (!buf || structured || raw) fail(ErrorId::RESOURCE_TYPE_MISMATCH, sh, slot() + " is an RWBuffer<> but " + Describe(v) + " is not a typed buffer view");
        break;
      case ShaderResourceType::RWStructuredBuffer:
        if (raw && r.structureStride == 4 && !r.appendConsume) break;  // RWByteAddressBuffer, as above
        if (!structured) fail(ErrorId::RESOURCE_TYPE_MISMATCH, sh, slot() + " is a structured UAV but " + Describe(v) + " is not a view of a structured buffer");
        if (r.appendConsume && !(d.Buffer.Flags & (BUFFER_UAV_FLAG_APPEND | BUFFER_UAV_FLAG_COUNTER)))
          fail(ErrorId::RESOURCE_TYPE_MISMATCH, sh, slot() + " uses Append/Consume/IncrementCounter but the view was created without BUFFER_UAV_FLAG_APPEND or _COUNTER");
        break;
      case ShaderResourceType::RWByteAddressBuffer:
        if (!raw) fail(ErrorId::RESOURCE_TYPE_MISMATCH, sh, slot() + " is an RWByteAddressBuffer but " + Describe(v) + " is not a raw view (BUFFER_UAV_FLAG_RAW)");
        break;
      default:
        break;
    }
  }

  void checkStage(ShaderStage stage) const {
    const StageBindings& b = s.stage(stage);
    const Shader* sh = b.shader.get();
    if (!sh) return;
    const ShaderReflection& refl = sh->Reflection();
    for (const CBufferInfo& cb : refl.cbuffers) {
      const Buffer* buf = b.constantBuffers[cb.registerIndex].get();
      if (!buf) {
        missing(sh, stage, RegisterClass::ConstantBuffer, cb.registerIndex, nullptr, &cb,
                "the shader reads " + SlotName(stage, 'b', cb.registerIndex) + " ('" + cb.name + "', " + std::to_string(cb.size) +
                    " bytes) but no constant buffer is bound there");
        continue;
      }
      if (buf->GetDesc().ByteWidth < cb.size) {
        warned = true;
        ctx.GetDevice()->Message(MessageSeverity::Warning, std::string(call) + ": " + Describe(buf) + " at " + SlotName(stage, 'b', cb.registerIndex) +
                                                               " is smaller than cbuffer '" + cb.name + "' (" + std::to_string(cb.size) +
                                                               " bytes); the rest reads as 0 as in D3D11");
      }
    }
    for (const ShaderResourceBinding& r : refl.resources) {
      switch (r.registerClass) {
        case RegisterClass::ShaderResource:
          checkSrv(sh, stage, r, b.shaderResources[r.registerIndex].get());
          break;
        case RegisterClass::Sampler: {
          const SamplerState* smp = b.samplers[r.registerIndex].get();
          // Built only for a message: this runs for every binding of every draw.
          auto slot = [&] { return SlotName(stage, 's', r.registerIndex) + " ('" + r.name + "')"; };
          if (!smp) {
            missing(sh, stage, RegisterClass::Sampler, r.registerIndex, &r, nullptr, "the shader samples with " + slot() + " but no sampler state is bound there");
            break;
          }
          bool cmp = FilterIsComparison(smp->GetDesc().Filter);
          if (r.type == ShaderResourceType::ComparisonSampler && !cmp)
            fail(ErrorId::RESOURCE_TYPE_MISMATCH, sh, slot() + " is a SamplerComparisonState but " + Describe(smp) + " has no comparison filter");
          if (r.type == ShaderResourceType::Sampler && cmp)
            fail(ErrorId::RESOURCE_TYPE_MISMATCH, sh, slot() + " is a SamplerState but " + Describe(smp) + " has a comparison filter");
          break;
        }
        case RegisterClass::UnorderedAccess:
          if (r.type == ShaderResourceType::UavCounter && (stage == ShaderStage::Pixel || stage == ShaderStage::Compute)) {
            // A UAV used only through IncrementCounter/DecrementCounter appears as its counter alone.
            const UnorderedAccessView* v = (stage == ShaderStage::Pixel ? s.pixelUavs : s.computeUavs)[r.registerIndex].get();
            // Built only for a message: this runs for every binding of every draw.
            auto slot = [&] { return SlotName(stage, 'u', r.registerIndex) + " ('" + r.name + "')"; };
            if (!v) {
              missing(sh, stage, RegisterClass::UnorderedAccess, r.registerIndex, &r, nullptr,
                      "the shader uses the counter of " + slot() + " but no unordered access view is bound there");
              break;
            }
            if (!AsBuffer(v->GetResource()) || !(v->GetDesc().Buffer.Flags & (BUFFER_UAV_FLAG_APPEND | BUFFER_UAV_FLAG_COUNTER)))
              fail(ErrorId::RESOURCE_TYPE_MISMATCH, sh, slot() + " uses the hidden counter but " + Describe(v) + " was created without BUFFER_UAV_FLAG_APPEND or _COUNTER");
            break;
          }
          if (stage == ShaderStage::Pixel) checkUav(sh, stage, r, s.pixelUavs[r.registerIndex].get());
          else if (stage == ShaderStage::Compute) checkUav(sh, stage, r, s.computeUavs[r.registerIndex].get());
          else fail(ErrorId::NOT_SUPPORTED, sh, "UAVs are only available to pixel and compute shaders in D3D11.0");
          break;
        default:
          break;
      }
    }
  }
};

}  // namespace

bool DrawValidator::CheckDraw(DeviceContext& ctx, const DrawArgs& args, const char* call, std::vector<UnboundRead>& unbound, uint32_t recheck) {
  const PipelineState& s = *ctx.state_;
  auto changed = [&](uint32_t bits) { return (recheck & bits) != 0; };
  Checker c{ctx, s, call, unbound, DeviceAccess::StrictUnboundResources(*ctx.GetDevice())};
  const Shader* vs = s.stage(ShaderStage::Vertex).shader.get();
  if (!vs) Fail(ErrorId::DRAW_STATE_INVALID, call, "pipeline", "no vertex shader is bound (VSSetShader)");
  if (s.topology == PRIMITIVE_TOPOLOGY_UNDEFINED) Fail(ErrorId::DRAW_STATE_INVALID, call, "pipeline", "no primitive topology is set (IASetPrimitiveTopology)");
  if (s.numViewports == 0) Fail(ErrorId::DRAW_STATE_INVALID, call, "pipeline", "no viewport is set (RSSetViewports)");
  if (s.rasterizer().ScissorEnable && s.numScissorRects == 0)
    Fail(ErrorId::DRAW_STATE_INVALID, call, "pipeline", "ScissorEnable is set but no scissor rect is set (RSSetScissorRects)");

  // Input assembler
  bool needsLayout = false;
  if (changed(DIRTY_SHADERS | DIRTY_INPUT_LAYOUT | DIRTY_VERTEX_BUFFERS)) {
    for (const SignatureElement& in : vs->Reflection().inputs) needsLayout |= !in.systemValue;
  }
  if (needsLayout) {
    if (!s.inputLayout) Fail(ErrorId::DRAW_STATE_INVALID, call, Describe(vs), "the vertex shader has vertex inputs but no input layout is set (IASetInputLayout)");
    for (const SignatureElement& in : vs->Reflection().inputs) {
      if (in.systemValue) continue;
      const VertexAttribute* attr = nullptr;
      for (const VertexAttribute& a : s.inputLayout->Attributes())
        if (a.location == in.location && a.semanticName == in.semanticName && a.semanticIndex == in.semanticIndex) attr = &a;
      if (!attr)
        Fail(ErrorId::INPUT_LAYOUT_MISMATCH, call, Describe(s.inputLayout.get()),
             "the bound vertex shader reads " + in.semanticName + std::to_string(in.semanticIndex) + ", which the input layout does not provide (it was made for another shader)");
      if (!s.vertexBuffers[attr->slot])
        Fail(ErrorId::DRAW_STATE_INVALID, call, Describe(vs), in.semanticName + std::to_string(in.semanticIndex) + " comes from vertex buffer slot " +
                                                                  std::to_string(attr->slot) + " but no vertex buffer is bound there");
    }
  }
  bool indexed = args.kind == DrawArgs::DrawIndexed || args.kind == DrawArgs::DrawIndexedInstancedIndirect;
  if (indexed && !s.indexBuffer) Fail(ErrorId::DRAW_STATE_INVALID, call, "pipeline", "indexed draw without an index buffer (IASetIndexBuffer)");

  // Shader interface: what the pixel shader reads must be written by the vertex shader.
  const Shader* ps = s.stage(ShaderStage::Pixel).shader.get();
  if (ps && changed(DIRTY_SHADERS)) {
    for (const SignatureElement& in : ps->Reflection().inputs) {
      if (in.systemValue) continue;
      const SignatureElement* out = nullptr;
      for (const SignatureElement& o : vs->Reflection().outputs)
        if (o.semanticName == in.semanticName && o.semanticIndex == in.semanticIndex) out = &o;
      if (!out)
        Fail(ErrorId::SHADER_INTERFACE_MISMATCH, call, Describe(ps),
             "the pixel shader reads " + in.semanticName + std::to_string(in.semanticIndex) + ", which " + Describe(vs) + " does not write");
      if (out->location != in.location)
        Fail(ErrorId::SHADER_INTERFACE_MISMATCH, call, Describe(ps),
             in.semanticName + std::to_string(in.semanticIndex) + " is at location " + std::to_string(in.location) + " in the pixel shader but " +
                 std::to_string(out->location) + " in " + Describe(vs) +
                 "; declare the vertex output and pixel input with the same members in the same order (a shared struct)");
    }
  }
  if (changed(DIRTY_BINDINGS_VS)) c.checkStage(ShaderStage::Vertex);
  if (changed(DIRTY_BINDINGS_PS | DIRTY_PIXEL_UAVS)) c.checkStage(ShaderStage::Pixel);
  if (!changed(DIRTY_SHADERS | DIRTY_RENDER_TARGETS)) return !c.warned;

  // D3D11 renders an out-of-range SV_RenderTargetArrayIndex into slice 0; Vulkan leaves a layer
  // at or past the framebuffer's layer count undefined and GL ignores the index on a single-layer
  // attachment. Only layered (array) targets keep the three alike, so require them.
  if (const char* arrayIndex = ArrayIndexOutput(vs->Reflection()); arrayIndex && std::string_view(arrayIndex) == "SV_RenderTargetArrayIndex") {
    const View* target = s.depthStencil.get();
    for (uint32_t i = 0; i < s.numRenderTargets && !target; ++i) target = s.renderTargets[i].get();
    if (target && target->Range().sliceCount < 2)
      Fail(ErrorId::OUTPUT_MISMATCH, call, Describe(vs),
           "the vertex shader writes SV_RenderTargetArrayIndex but " + Describe(target) +
               " has one array slice; bind a layered view (e.g. DSV_DIMENSION_TEXTURE2DARRAY with ArraySize > 1) so every index it writes exists");
  }

  // Render targets written by the pixel shader must match in kind (float/int) when bound.
  if (ps) {
    for (const SignatureElement& o : ps->Reflection().outputs) {
      if (o.semanticName != "SV_TARGET" || o.semanticIndex >= SIMULTANEOUS_RENDER_TARGET_COUNT) continue;
      const RenderTargetView* rtv = s.renderTargets[o.semanticIndex].get();
      if (rtv && !FormatReturns(rtv->ViewFormat(), o.componentType))
        Fail(ErrorId::RESOURCE_TYPE_MISMATCH, call, Describe(ps),
             "SV_Target" + std::to_string(o.semanticIndex) + " is " + ComponentName(o.componentType) + " but render target " +
                 std::to_string(o.semanticIndex) + " is " + std::string(FormatName(rtv->ViewFormat())));
    }
  }
  return !c.warned;
}

bool DrawValidator::CheckDispatch(DeviceContext& ctx, const char* call, std::vector<UnboundRead>& unbound) {
  const PipelineState& s = *ctx.state_;
  if (!s.stage(ShaderStage::Compute).shader) Fail(ErrorId::DRAW_STATE_INVALID, call, "pipeline", "no compute shader is bound (CSSetShader)");
  Checker c{ctx, s, call, unbound, DeviceAccess::StrictUnboundResources(*ctx.GetDevice())};
  c.checkStage(ShaderStage::Compute);
  return !c.warned;
}

const char* SrvDimensionName(SRV_DIMENSION d) {
  switch (d) {
    case SRV_DIMENSION_BUFFER: return "Buffer";
    case SRV_DIMENSION_TEXTURE1D: return "Texture1D";
    case SRV_DIMENSION_TEXTURE1DARRAY: return "Texture1DArray";
    case SRV_DIMENSION_TEXTURE2D: return "Texture2D";
    case SRV_DIMENSION_TEXTURE2DARRAY: return "Texture2DArray";
    case SRV_DIMENSION_TEXTURE2DMS: return "Texture2DMS";
    case SRV_DIMENSION_TEXTURE2DMSARRAY: return "Texture2DMSArray";
    case SRV_DIMENSION_TEXTURE3D: return "Texture3D";
    case SRV_DIMENSION_TEXTURECUBE: return "TextureCube";
    case SRV_DIMENSION_TEXTURECUBEARRAY: return "TextureCubeArray";
    case SRV_DIMENSION_BUFFEREX: return "raw buffer";
    default: return "unknown";
  }
}

}  // namespace sp
