// The core's stand-ins for unbound shader registers. D3D11 reads zeros from a register with
// nothing bound (a sampler slot behaves as D3D11's default sampler state, a UAV slot drops
// writes); Vulkan and GL have no such rule, so the core binds zero-filled resources of the kind
// the shader declares before the backend sees the state. They are made on first use through the
// public API and live as long as the device.
#pragma once
#include <map>
#include <set>
#include <string>
#include <tuple>

#include "backend.h"

namespace sp::detail {

class NullResources {
 public:
  explicit NullResources(Device& device) : dev_(device) {}

  // A zero-filled view of the dimension, texel type or stride `binding` declares. `compared`:
  // the shader compares the texture (SampleCmp), which needs a depth format; it holds depth 0.
  ShaderResourceView* ShaderResource(const ShaderResourceBinding& binding, bool compared);
  // 64 KiB of zeros, the largest cbuffer D3D11 allows.
  Buffer* ConstantBuffer();
  // D3D11's default sampler state; with comparison, ComparisonFunc NEVER (every compare gives 0).
  SamplerState* Sampler(bool comparison);
  // One per slot and kind, so two unbound registers of a shader never alias. `counter`: the
  // shader uses the hidden counter (Append/Consume/IncrementCounter). Cleared before each use.
  UnorderedAccessView* UnorderedAccess(const ShaderResourceBinding& binding, bool pixelStage, uint32_t slot, bool counter);

  // True the first time a register of a shader is reported; the warning is given once.
  bool FirstReport(const Shader* shader, RegisterClass cls, uint32_t reg);

 private:
  Ref<ShaderResourceView> MakeTextureView(const ShaderResourceBinding& b, bool compared, const std::string& name);
  Ref<ShaderResourceView> MakeBufferView(const ShaderResourceBinding& b, const std::string& name);
  Ref<UnorderedAccessView> MakeUav(const ShaderResourceBinding& b, bool counter, const std::string& name);

  Device& dev_;
  std::map<std::string, Ref<ShaderResourceView>> views_;
  std::map<std::string, Ref<UnorderedAccessView>> uavs_;
  Ref<Buffer> constants_;
  Ref<SamplerState> samplers_[2];
  std::set<std::tuple<uint64_t, RegisterClass, uint32_t>> reported_;
};

}  // namespace sp::detail
