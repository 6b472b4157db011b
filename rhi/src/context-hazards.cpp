// D3D11's read/write hazard rules for bindings. A subresource may not be bound for input (SRV,
// vertex/index/constant buffer) while it is bound for output (RTV, writable DSV aspect, UAV):
//  - binding it for output unbinds it from every input slot;
//  - binding it for input while it is bound for output binds NULL instead.
// Both print the warning the D3D11 debug layer prints. Backends can then rely on a subresource
// never being read and written by the same draw, except through UAVs.
#include "context-internal.h"
#include "validate.h"

namespace sp {
using namespace detail;
namespace {

// The part of a view that is written when it is bound for output.
bool WrittenRange(const View* v, ViewRange* out) {
  *out = v->Range();
  if (v->Kind() == ViewKind::DepthStencil) {
    uint32_t f = static_cast<const DepthStencilView*>(v)->GetDesc().Flags;
    out->depth = !(f & DSV_READ_ONLY_DEPTH);
    out->stencil = out->stencil && !(f & DSV_READ_ONLY_STENCIL);
    return out->depth || out->stencil;
  }
  return true;
}

bool Overlaps(const View* output, const Resource* res, const ViewRange& inputRange) {
  if (output->GetResource() != res) return false;
  ViewRange w;
  if (!WrittenRange(output, &w)) return false;
  return w.overlaps(inputRange);
}

ViewRange WholeBuffer(const Buffer* b) {
  ViewRange r;
  r.firstByte = 0;
  r.byteCount = b->GetDesc().ByteWidth;
  return r;
}

// An output binding, named only when a message needs it (the hazard checks run on every bind).
struct OutputSlot {
  const char* what = nullptr;
  int index = -1;
  std::string name() const { return index < 0 ? std::string(what) : what + std::to_string(index); }
};

// Calls fn(view, slot) for every output binding.
template <class Fn>
void ForEachOutput(const PipelineState& s, Fn fn) {
  for (uint32_t i = 0; i < SIMULTANEOUS_RENDER_TARGET_COUNT; ++i)
    if (s.renderTargets[i]) fn(s.renderTargets[i].get(), OutputSlot{"render target ", int(i)});
  if (s.depthStencil) fn(s.depthStencil.get(), OutputSlot{"depth-stencil target", -1});
  for (uint32_t i = 0; i < PS_CS_UAV_REGISTER_COUNT; ++i) {
    if (s.pixelUavs[i]) fn(s.pixelUavs[i].get(), OutputSlot{"pixel shader UAV u", int(i)});
    if (s.computeUavs[i]) fn(s.computeUavs[i].get(), OutputSlot{"compute shader UAV u", int(i)});
  }
}

}  // namespace

bool detail::ContextHazards::ViewWritesOverlap(const View* a, const View* b) {
  ViewRange wb;
  if (!WrittenRange(b, &wb)) return false;
  return Overlaps(a, b->GetResource(), wb);
}

ShaderResourceView* detail::ContextHazards::FilterInput(DeviceContext& ctx, ShaderResourceView* srv, const char* call, ShaderStage stage, uint32_t slot) {
  if (!srv) return nullptr;
  OutputSlot conflict;
  ForEachOutput((*ctx.state_), [&](const View* out, OutputSlot where) {
    if (!conflict.what && Overlaps(out, srv->GetResource(), srv->Range())) conflict = where;
  });
  if (!conflict.what) return srv;
  ctx.device_->Message(MessageSeverity::Warning,
                       std::string(call) + ": " + Describe(srv->GetResource()) + " is bound as " + conflict.name() +
                           "; as in D3D11, NULL is bound to " + SlotName(stage, 't', slot) + " instead");
  return nullptr;
}

Buffer* detail::ContextHazards::FilterInputBuffer(DeviceContext& ctx, Buffer* buffer, const char* call, const char* what, uint32_t slot) {
  if (!buffer) return nullptr;
  OutputSlot conflict;
  ViewRange whole = WholeBuffer(buffer);
  ForEachOutput((*ctx.state_), [&](const View* out, OutputSlot where) {
    if (!conflict.what && Overlaps(out, buffer, whole)) conflict = where;
  });
  if (!conflict.what) return buffer;
  ctx.device_->Message(MessageSeverity::Warning, std::string(call) + ": " + Describe(buffer) + " is bound as " + conflict.name() +
                                                     "; as in D3D11, NULL is bound to " + what + " " + std::to_string(slot) + " instead");
  return nullptr;
}

void detail::ContextHazards::UnbindForOutput(DeviceContext& ctx, const View* output, bool outputIsCompute, const char* call) {
  PipelineState& s = (*ctx.state_);
  auto warn = [&](const std::string& where) {
    ctx.device_->Message(MessageSeverity::Warning, std::string(call) + ": " + Describe(output->GetResource()) +
                                                       " is now bound for output; as in D3D11 it was unbound from " + where);
  };
  const Resource* res = output->GetResource();
  // Only slots the resource's bind flags admit can hold it (the Set calls and view creation check
  // the flags): this runs on every output bind, and most outputs are never vertex or index buffers.
  // Constant buffers need no walk: BIND_CONSTANT_BUFFER admits no other flag (CreateBuffer), so a
  // constant buffer is never bound for output.
  const Buffer* asBuffer = AsBuffer(res);
  const uint32_t bind = asBuffer ? asBuffer->GetDesc().BindFlags : static_cast<const Texture*>(res)->Shape().bindFlags;
  const uint32_t stagesWithViews = bind & BIND_SHADER_RESOURCE ? SHADER_STAGE_COUNT : 0;
  for (uint32_t st = 0; st < stagesWithViews; ++st) {
    StageBindings& b = s.stages[st];
    for (uint32_t i = 0; i < b.shaderResourceEnd; ++i) {
      if (b.shaderResources[i] && Overlaps(output, b.shaderResources[i]->GetResource(), b.shaderResources[i]->Range())) {
        b.shaderResources[i].reset();
        ctx.dirty_ |= DIRTY_BINDINGS_VS << st;
        warn(SlotName(ShaderStage(st), 't', i));
      }
    }
  }
  if (const Buffer* buf = bind & (BIND_VERTEX_BUFFER | BIND_INDEX_BUFFER) ? asBuffer : nullptr) {
    for (uint32_t i = 0; i < IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT; ++i) {
      if (s.vertexBuffers[i].get() == buf && Overlaps(output, buf, WholeBuffer(buf))) {
        s.vertexBuffers[i].reset();
        ctx.dirty_ |= DIRTY_VERTEX_BUFFERS;
        warn("vertex buffer slot " + std::to_string(i));
      }
    }
    if (s.indexBuffer.get() == buf && Overlaps(output, buf, WholeBuffer(buf))) {
      s.indexBuffer.reset();
      ctx.dirty_ |= DIRTY_INDEX_BUFFER;
      warn("the index buffer");
    }
  }
  // The graphics pipeline's outputs and the compute UAVs cannot hold the same subresource.
  if (outputIsCompute) {
    for (uint32_t i = 0; i < SIMULTANEOUS_RENDER_TARGET_COUNT; ++i) {
      if (s.renderTargets[i] && ViewWritesOverlap(output, s.renderTargets[i].get())) {
        s.renderTargets[i].reset();
        ctx.dirty_ |= DIRTY_RENDER_TARGETS;
        warn("render target " + std::to_string(i));
      }
    }
    if (s.depthStencil && ViewWritesOverlap(output, s.depthStencil.get())) {
      s.depthStencil.reset();
      ctx.dirty_ |= DIRTY_RENDER_TARGETS;
      warn("the depth-stencil target");
    }
    for (uint32_t i = 0; i < PS_CS_UAV_REGISTER_COUNT; ++i) {
      if (s.pixelUavs[i] && ViewWritesOverlap(output, s.pixelUavs[i].get())) {
        s.pixelUavs[i].reset();
        ctx.dirty_ |= DIRTY_PIXEL_UAVS;
        warn("pixel shader UAV u" + std::to_string(i));
      }
    }
  } else {
    for (uint32_t i = 0; i < PS_CS_UAV_REGISTER_COUNT; ++i) {
      if (s.computeUavs[i] && ViewWritesOverlap(output, s.computeUavs[i].get())) {
        s.computeUavs[i].reset();
        ctx.dirty_ |= DIRTY_COMPUTE_UAVS;
        warn("compute shader UAV u" + std::to_string(i));
      }
    }
  }
}

}  // namespace sp
