// Internal pieces of the immediate context: D3D11's input/output hazard rules and draw-time
// validation. Both work on the core's PipelineState only.
#pragma once
#include <sp/rhi/context.h>

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

class DrawValidator {
 public:
  static void CheckDraw(DeviceContext& ctx, const DrawArgs& args, const char* call);
  static void CheckDispatch(DeviceContext& ctx, const char* call);
};

}  // namespace detail
}  // namespace sp
