// Cascaded shadow maps (parallel-split shadow maps): the camera's view range is split into up to
// eight intervals, each with its own orthographic light frustum fitted to its slice of the view
// and rendered into one slice of a Texture2DArray (storage=array) or one region of an atlas
// (storage=atlas: the same kind of texture with one slice, cascades side by side). One cascade is
// the plain focused shadow map. CPU fitting is in cascade-fit.h, lighting in
// shaders-hlsl/csm/shadow.hlsli, filtering in shaders-hlsl/common/shadow-filter.hlsli.
#pragma once
#include "cascade-fit.h"
#include "technique.h"

namespace sp::tech::csm {

enum class Select { Interval, Map };
enum class Storage { Array, Atlas };
enum class Bias { Const, Slope, Normal, ReceiverPlane };

// Validated parameters in usable form.
struct CsmSettings {
  FitSettings fit;
  Select select = Select::Interval;
  Storage storage = Storage::Array;
  int filter = 0;  // SHADOW_FILTER: 0 hw2x2, 1 box, 2 gauss, 3 gathercmp, 4 poisson
  int kernel = 3;
  Bias bias = Bias::Slope;
  int depthBias = 100;
  float slopeBias = 2.0f;
  float normalOffset = 1.0f;  // texels of the selected cascade
};

std::vector<ParamSpec> CsmParams();
// Throws std::invalid_argument for what ParamValues::Parse cannot check (the manual split list).
CsmSettings SettingsFrom(const ParamValues& params);

// Where a cascade lives in the shadow texture.
struct CascadeRegion {
  uint32_t slice = 0;     // array slice (always 0 for the atlas)
  uint32_t x = 0, y = 0;  // top-left texel of its region in the slice
};

class CsmTechnique final : public Technique {
 public:
  std::string Name() const override { return "csm"; }
  std::vector<ParamSpec> Params() const override { return CsmParams(); }
  void Configure(Device& device, const ParamValues& params) override;
  void RenderShadows(DeviceContext& ctx, SceneDrawer& drawer, const FrameInputs& frame) override;
  std::string LightingInclude() const override { return "csm/shadow.hlsli"; }
  std::vector<hlsl::Define> LightingDefines() const override { return Defines(settings_); }
  // The lighting shader's defines for some settings: the lit-pass variant they select.
  static std::vector<hlsl::Define> Defines(const CsmSettings& settings);
  void BindLighting(DeviceContext& ctx) override;
  ShadowStats Stats() const override;
  std::vector<ShadowLayer> Layers() const override;

  // For tests and debug views.
  const CsmSettings& settings() const { return settings_; }
  const CascadeSet& lastFit() const { return fit_; }
  const std::vector<uint64_t>& lastCascadeTriangles() const { return cascadeTriangles_; }
  Texture2D* shadowTexture() const { return map_.get(); }
  CascadeRegion region(int cascade) const;

 private:
  void WriteConstants(DeviceContext& ctx, const FrameInputs& frame);

  CsmSettings settings_;
  uint32_t columns_ = 1, rows_ = 1;  // atlas grid
  uint32_t textureWidth_ = 0, textureHeight_ = 0, arraySize_ = 0;
  Ref<Texture2D> map_;
  std::vector<Ref<DepthStencilView>> dsvs_;  // one per slice
  Ref<ShaderResourceView> srv_;
  Ref<RasterizerState> rasterizer_;
  Ref<SamplerState> sampler_;
  Ref<Buffer> constants_;
  CascadeSet fit_;
  std::vector<uint64_t> cascadeTriangles_;
};

}  // namespace sp::tech::csm
