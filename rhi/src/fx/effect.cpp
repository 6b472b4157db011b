// Effect objects on a device, Apply, and lookups by name and index.
#include <functional>

#include "effect-parse.h"

namespace sp::fx {
namespace {

std::string Names(size_t n, const std::function<std::string(size_t)>& name) {
  std::string s;
  for (size_t i = 0; i < n; ++i) s += (i ? ", " : "") + (name(i).empty() ? "#" + std::to_string(i) : name(i));
  return s.empty() ? "none" : s;
}

}  // namespace

Effect::~Effect() = default;

EffectTechnique* Effect::FindTechnique(const std::string& name) {
  for (auto& t : techniques_)
    if (t->name_ == name) return t.get();
  return nullptr;
}

EffectTechnique* Effect::GetTechniqueByName(const std::string& name) {
  if (EffectTechnique* t = FindTechnique(name)) return t;
  throw Error(ErrorId::INVALID_ARGUMENT, "Effect::GetTechniqueByName", fileName_,
              "no technique '" + name + "' (the effect has: " + Names(techniques_.size(), [&](size_t i) { return techniques_[i]->name_; }) + ")");
}

EffectTechnique* Effect::GetTechniqueByIndex(uint32_t index) {
  if (index < techniques_.size()) return techniques_[index].get();
  throw Error(ErrorId::INVALID_ARGUMENT, "Effect::GetTechniqueByIndex", fileName_,
              "index " + std::to_string(index) + " is out of range (" + std::to_string(techniques_.size()) + " techniques)");
}

EffectPass* EffectTechnique::GetPassByName(const std::string& name) {
  for (auto& p : passes_)
    if (p->Name() == name) return p.get();
  throw Error(ErrorId::INVALID_ARGUMENT, "EffectTechnique::GetPassByName", name_ + " (" + location_.ToString() + ")",
              "no pass '" + name + "' (the technique has: " + Names(passes_.size(), [&](size_t i) { return passes_[i]->Name(); }) + ")");
}

EffectPass* EffectTechnique::GetPassByIndex(uint32_t index) {
  if (index < passes_.size()) return passes_[index].get();
  throw Error(ErrorId::INVALID_ARGUMENT, "EffectTechnique::GetPassByIndex", name_ + " (" + location_.ToString() + ")",
              "index " + std::to_string(index) + " is out of range (" + std::to_string(passes_.size()) + " passes)");
}

const StateObjectDesc* Effect::FindState(const std::string& name) const {
  for (const StateObjectDesc& s : states_)
    if (s.name == name) return &s;
  return nullptr;
}

size_t Effect::StateIndex(const std::string& name) const {
  for (size_t i = 0; i < states_.size(); ++i)
    if (states_[i].name == name) return i;
  return states_.size();
}

void Effect::CreateObjects(Device& device) {
  // Refused before anything is created, so a failed call leaves the effect as it was.
  for (auto& t : techniques_)
    for (auto& p : t->passes_)
      for (const std::optional<ShaderDesc>& sh : p->desc_.shaders)
        if (sh && !sh->error.empty())
          throw Error(ErrorId::SHADER_COMPILE_FAILED, "Effect::CreateObjects", fileName_,
                      "technique " + t->name_ + ", pass " + p->desc_.name + ": the " + ShaderStageName(sh->stage) +
                          " shader did not compile: " + sh->error);
  std::vector<Ref<Object>> objects;
  for (const StateObjectDesc& s : states_) {
    switch (s.type) {
      case StateType::Rasterizer: objects.push_back(device.CreateRasterizerState(s.rasterizer)); break;
      case StateType::DepthStencil: objects.push_back(device.CreateDepthStencilState(s.depthStencil)); break;
      case StateType::Blend: objects.push_back(device.CreateBlendState(s.blend)); break;
      default: objects.push_back(device.CreateSamplerState(s.sampler)); break;
    }
  }
  // Passes that compile the same function share bytecode; each gets its own shader object,
  // which is cheap next to the compile and keeps passes independent.
  for (auto& t : techniques_)
    for (auto& p : t->passes_) {
      auto& sh = p->desc_.shaders;
      auto has = [&](ShaderStage s) { return sh[size_t(s)] && !sh[size_t(s)]->isNull; };
      p->vs_ = has(ShaderStage::Vertex) ? device.CreateVertexShader(sh[0]->bytecode) : nullptr;
      p->ps_ = has(ShaderStage::Pixel) ? device.CreatePixelShader(sh[1]->bytecode) : nullptr;
      p->gs_ = has(ShaderStage::Geometry) ? device.CreateGeometryShader(sh[2]->bytecode) : nullptr;
      p->cs_ = has(ShaderStage::Compute) ? device.CreateComputeShader(sh[3]->bytecode) : nullptr;
    }
  stateObjects_ = std::move(objects);
  created_ = true;
}

void EffectPass::Apply(uint32_t flags, DeviceContext* ctx) const {
  if (flags != 0)
    throw Error(ErrorId::INVALID_ARGUMENT, "EffectPass::Apply", desc_.name + " (" + desc_.location.ToString() + ")",
                "flags must be 0, as for ID3DX11EffectPass::Apply");
  if (!ctx) throw Error(ErrorId::INVALID_ARGUMENT, "EffectPass::Apply", desc_.name + " (" + desc_.location.ToString() + ")", "the context is null");
  Apply(*ctx);
}

void EffectPass::Apply(DeviceContext& ctx) const {
  const Effect& fx = *effect_;
  if (!fx.created_)
    throw Error(ErrorId::INVALID_ARGUMENT, "EffectPass::Apply", desc_.name + " (" + desc_.location.ToString() + ")",
                "the effect has no device objects: call Effect::CreateObjects(device) first");
  auto state = [&](const std::string& name) -> Object* {
    return name.empty() ? nullptr : fx.stateObjects_[fx.StateIndex(name)].get();
  };
  const auto& sh = desc_.shaders;
  if (sh[0]) ctx.VSSetShader(vs_.get());
  if (sh[1]) ctx.PSSetShader(ps_.get());
  if (sh[2]) ctx.GSSetShader(gs_.get());
  if (sh[3]) ctx.CSSetShader(cs_.get());
  if (desc_.rasterizerState) ctx.RSSetState(static_cast<RasterizerState*>(state(*desc_.rasterizerState)));
  if (desc_.depthStencilState)
    ctx.OMSetDepthStencilState(static_cast<DepthStencilState*>(state(*desc_.depthStencilState)), desc_.stencilRef);
  if (desc_.blendState) ctx.OMSetBlendState(static_cast<BlendState*>(state(*desc_.blendState)), desc_.blendFactor.data(), desc_.sampleMask);
  for (size_t i = 0; i < desc_.samplers.size(); ++i) {
    const SamplerBindingDesc& b = desc_.samplers[i];
    SamplerState* s = static_cast<SamplerState*>(fx.stateObjects_[samplerStates_[i]].get());
    switch (b.stage) {
      case ShaderStage::Vertex: ctx.VSSetSamplers(b.slot, 1, &s); break;
      case ShaderStage::Pixel: ctx.PSSetSamplers(b.slot, 1, &s); break;
      case ShaderStage::Geometry: ctx.GSSetSamplers(b.slot, 1, &s); break;
      case ShaderStage::Compute: ctx.CSSetSamplers(b.slot, 1, &s); break;
    }
  }
}

}  // namespace sp::fx
