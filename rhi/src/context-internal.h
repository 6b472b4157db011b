// Internal pieces of the immediate context: D3D11's input/output hazard rules, draw-time
// validation and the null bindings that stand in for unbound registers. All work on the core's
// PipelineState only.
#pragma once
#include <sp/rhi/context.h>

#include <vector>

#include "pipeline-state.h"

namespace sp {

std::string SlotName(ShaderStage stage, char cls, uint32_t slot);  // "PS slot t3"

template <class T>
Ref<T> RefOf(T* p) {
  return p ? std::static_pointer_cast<T>(p->shared_from_this()) : Ref<T>();
}

namespace detail {

class ContextHazards {
 public:
  // D3D11 refuses an input binding of a resource currently bound for output: the slot gets NULL.
  // Returns the view to bind (null when refused) and reports a warning.
  static ShaderResourceView* FilterInput(DeviceContext& ctx, ShaderResourceView* srv, const char* call, ShaderStage stage, uint32_t slot);
  static Buffer* FilterInputBuffer(DeviceContext& ctx, Buffer* buffer, const char* call, const char* what, uint32_t slot);
  // Binding for output unbinds every overlapping input binding (and other output bindings that
  // D3D11 cannot hold at the same time), with a warning each.
  static void UnbindForOutput(DeviceContext& ctx, const View* output, bool outputIsCompute, const char* call);
  static bool ViewWritesOverlap(const View* output, const View* other);
};

// A register the bound shader reads with nothing bound there. `binding` is null for constant
// buffers (`cbuffer` names them) and set for t, s and u registers.
struct UnboundRead {
  const Shader* shader = nullptr;
  ShaderStage stage = ShaderStage::Vertex;
  RegisterClass registerClass = RegisterClass::ShaderResource;
  uint32_t registerIndex = 0;
  const ShaderResourceBinding* binding = nullptr;
  const CBufferInfo* cbuffer = nullptr;
};

class DrawValidator {
 public:
  // Throw for what D3D11's debug layer reports as an error. Registers the shaders read with
  // nothing bound are collected in `unbound` (or throw SP_UNBOUND_RESOURCE on a strict device).
  // False when a warning was given: the next draw must check (and warn) again. `recheck`: the
  // dirty bits since a draw that passed with nothing unbound (DIRTY_ALL: check everything);
  // only the rules that read that state run again.
  static bool CheckDraw(DeviceContext& ctx, const DrawArgs& args, const char* call, std::vector<UnboundRead>& unbound, uint32_t recheck);
  static bool CheckDispatch(DeviceContext& ctx, const char* call, std::vector<UnboundRead>& unbound);
};

// For one draw or dispatch: puts the device's null resources into the unbound slots the shaders
// read (so the backend sees a complete state), warns once per shader and register, and empties
// the slots again when it goes out of scope, so the application's state is unchanged.
class NullBindings {
 public:
  NullBindings(DeviceContext& ctx, const std::vector<UnboundRead>& unbound);
  ~NullBindings();
  NullBindings(const NullBindings&) = delete;
  NullBindings& operator=(const NullBindings&) = delete;
  // Dirty bits for the stages whose slots were filled: the backend may have cached other objects
  // there.
  uint32_t Dirty() const { return dirty_; }

 private:
  PipelineState& state_;
  std::vector<Ref<Buffer>*> buffers_;
  std::vector<Ref<ShaderResourceView>*> views_;
  std::vector<Ref<SamplerState>*> samplers_;
  std::vector<Ref<UnorderedAccessView>*> uavs_;
  uint32_t dirty_ = 0;
};

}  // namespace detail
}  // namespace sp
