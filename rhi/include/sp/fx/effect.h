// FX11 effect files (.fx): techniques, passes and state objects, for ports of D3D11 samples that
// use ID3DX11Effect. The effect's shaders are ordinary HLSL compiled by sp::hlsl (the effect
// blocks are hidden from the shader compiler); the blocks are read into plain descs here.
//
//   auto fx = sp::fx::Effect::Load("shaders/tutorial.fx", {});
//   fx->CreateObjects(*device);
//   fx->GetTechniqueByName("Render")->GetPassByIndex(0)->Apply(*ctx);   // ID3DX11EffectPass::Apply(0, ctx)
//   ctx->Draw(3, 0);
//
// Naming follows FX11 where it helps (GetTechniqueByName, GetPassByIndex, Apply). What is not
// provided: effect variables (GetVariableByName and its setters): constant buffers, textures and
// samplers the shader code declares are bound through the DeviceContext as in plain D3D11 code,
// except that Apply binds the effect's own sampler states at the registers the shaders use.
// See docs/porting.md, "Effect files (FX11)".
#pragma once
#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>
#include <sp/hlsl/compiler.h>
#include <sp/rhi/context.h>
#include <sp/rhi/device.h>
#include <sp/rhi/shader.h>
#include <sp/rhi/state.h>

namespace sp::fx {

struct EffectOptions {
  std::vector<hlsl::Define> defines;
  std::vector<std::filesystem::path> includeDirs;
  uint32_t flags1 = 0;  // hlsl::COMPILE_*
  std::filesystem::path cacheDir;  // see sp/hlsl/compiler.h; empty: the default rule
  // false: a pass whose shader does not compile keeps the error in ShaderDesc::error instead of
  // failing Load (what `shadowport hlslc --fx` uses to list every pass); CreateObjects then
  // refuses the effect.
  bool failOnCompileError = true;
};

struct SourceLocation {
  std::string file;
  int line = 0;
  std::string ToString() const { return file + ":" + std::to_string(line); }
};

enum class StateType { Rasterizer, DepthStencil, Blend, Sampler, SamplerComparison };
const char* StateTypeName(StateType t);  // "RasterizerState", ..., "SamplerComparisonState"

// A state-object variable of the effect. Fields the effect does not set keep D3D11's defaults
// (those of the sp::*_DESC initialisers); `setFields` lists those it sets, normalised:
// "CullMode = NONE", "BlendEnable[0] = TRUE".
struct StateObjectDesc {
  StateType type = StateType::Rasterizer;
  std::string name;
  SourceLocation location;
  RASTERIZER_DESC rasterizer;      // type Rasterizer
  DEPTH_STENCIL_DESC depthStencil; // type DepthStencil
  BLEND_DESC blend;                // type Blend
  SAMPLER_DESC sampler;            // types Sampler and SamplerComparison
  std::vector<std::string> setFields;
};

// One stage of a pass: SetVertexShader(CompileShader(vs_5_0, VS())), SetGeometryShader(NULL), or
// SetPixelShader(psVariable).
struct ShaderDesc {
  ShaderStage stage = ShaderStage::Vertex;
  bool isNull = false;               // Set*Shader(NULL): Apply unbinds the stage
  std::string target;                // "vs_5_0"
  std::string function;              // "VS"
  std::vector<std::string> arguments;  // literal arguments to the function's uniform parameters
  std::string variable;              // the shader variable, when set through one
  std::string entryPoint;            // what was compiled: `function`, or a generated wrapper
  SourceLocation location;           // of the CompileShader
  ShaderBytecode bytecode;
  std::string error;                 // with EffectOptions::failOnCompileError = false
};

// An effect sampler state a pass's shader uses, at the register the compiled shader reads it
// from (reflection), which Apply binds it to.
struct SamplerBindingDesc {
  ShaderStage stage = ShaderStage::Pixel;
  uint32_t slot = 0;  // the N of sN
  std::string sampler;
};

struct PassDesc {
  std::string name;
  SourceLocation location;
  // Indexed by ShaderStage; unset: the pass leaves that stage as it is.
  std::array<std::optional<ShaderDesc>, SHADER_STAGE_COUNT> shaders;
  // Unset: the pass leaves the state as it is; "" (NULL): D3D11's default state.
  std::optional<std::string> rasterizerState, depthStencilState, blendState;
  uint32_t stencilRef = 0;
  std::array<float, 4> blendFactor{1, 1, 1, 1};
  uint32_t sampleMask = 0xffffffffu;
  std::vector<SamplerBindingDesc> samplers;
};

class Effect;

class EffectPass {
 public:
  const std::string& Name() const { return desc_.name; }
  const PassDesc& GetDesc() const { return desc_; }
  // ID3DX11EffectPass::Apply(0, ctx): binds the pass's shaders (NULL unbinds), its rasterizer,
  // depth-stencil (with the stencil reference) and blend state (with factor and sample mask),
  // and the effect's sampler states at the registers the pass's shaders use them. Stages and
  // states the pass does not name are left as they are. Needs Effect::CreateObjects first.
  void Apply(DeviceContext& ctx) const;
  void Apply(uint32_t flags, DeviceContext* ctx) const;  // FX11's shape; flags must be 0

 private:
  friend class Effect;
  const Effect* effect_ = nullptr;
  PassDesc desc_;
  std::vector<size_t> samplerStates_;  // parallel to desc_.samplers: indices into the effect's states
  Ref<VertexShader> vs_;
  Ref<PixelShader> ps_;
  Ref<GeometryShader> gs_;
  Ref<ComputeShader> cs_;
};

class EffectTechnique {
 public:
  const std::string& Name() const { return name_; }
  const std::string& Group() const { return group_; }  // the fxgroup, "" when none
  const SourceLocation& Location() const { return location_; }
  uint32_t GetPassCount() const { return uint32_t(passes_.size()); }
  // Throw sp::Error (INVALID_ARGUMENT) naming the technique, its file:line and the valid passes.
  EffectPass* GetPassByIndex(uint32_t index);
  EffectPass* GetPassByName(const std::string& name);
  const EffectPass* GetPassByIndex(uint32_t index) const { return const_cast<EffectTechnique*>(this)->GetPassByIndex(index); }

 private:
  friend class Effect;
  std::string name_, group_;
  SourceLocation location_;
  std::vector<std::unique_ptr<EffectPass>> passes_;
};

class Effect {
 public:
  // Preprocesses (defines, includes), reads the effect blocks, and compiles every pass's shaders.
  // Throws hlsl::CompileError with the user's file:line (syntax, unknown state fields or values,
  // unknown state or shader variables, CompileShader with a bad target or function).
  static std::unique_ptr<Effect> Load(const std::filesystem::path& file, const EffectOptions& options = {});
  static std::unique_ptr<Effect> LoadFromSource(std::string_view source, const std::string& fileName,
                                                const EffectOptions& options = {});

  // Creates the shaders and state objects on `device` (once; again on another device replaces them).
  void CreateObjects(Device& device);
  bool HasObjects() const { return created_; }

  const std::string& FileName() const { return fileName_; }
  uint32_t GetTechniqueCount() const { return uint32_t(techniques_.size()); }
  // Throw sp::Error (INVALID_ARGUMENT) naming the effect file and the techniques it has.
  EffectTechnique* GetTechniqueByIndex(uint32_t index);
  EffectTechnique* GetTechniqueByName(const std::string& name);
  EffectTechnique* FindTechnique(const std::string& name);  // nullptr when there is none

  const std::vector<StateObjectDesc>& States() const { return states_; }
  const StateObjectDesc* FindState(const std::string& name) const;

  Effect(const Effect&) = delete;
  Effect& operator=(const Effect&) = delete;
  ~Effect();

 private:
  friend class EffectPass;
  Effect() = default;
  size_t StateIndex(const std::string& name) const;

  std::string fileName_;
  std::vector<StateObjectDesc> states_;
  std::vector<std::unique_ptr<EffectTechnique>> techniques_;
  std::vector<Ref<Object>> stateObjects_;  // parallel to states_, after CreateObjects
  bool created_ = false;
};

}  // namespace sp::fx
