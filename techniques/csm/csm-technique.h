// Cascaded shadow maps (parallel-split shadow maps): the camera's view range is split into up to
// eight intervals, each with its own orthographic light frustum fitted to its slice of the view
// and rendered into one slice of a Texture2DArray (storage=array) or one region of an atlas
// (storage=atlas: the same kind of texture with one slice, cascades side by side). One cascade is
// the plain focused shadow map. CPU fitting is in cascade-fit.h, lighting in
// shaders-hlsl/csm/shadow.hlsli, filtering in shaders-hlsl/common/shadow-filter.hlsli.
//
// Moment filters (filter=vsm|esm|evsm2|evsm4|msm, techniques/moments): the cascades render plain
// depth (4x MSAA with msaa=4) without depth bias, MomentMaps turns the array into mipmapped
// moments (resolve, blur of `blur` world units converted per cascade, mips), and the lighting
// samples them with a trilinear/anisotropic SampleGrad. Choices made for them:
//  - storage=array only: the blur and the mip chain would mix neighbouring atlas regions;
//  - of the bias modes only bias=normal applies (its normal offset moves the lookup); depth_bias,
//    slope_bias and the receiver plane are comparison-filter tools and are ignored, as `kernel` is;
//  - the fit pads each cascade by its own share of the blur (FitSettings::padWorld) and puts its
//    far plane behind everything in its region (farToRegion): moments average neighbouring
//    depths, so depths clamped at the far plane would make receivers near it shadow themselves;
//    the lookup's footprint is also kept inside the region (shadow.hlsli) for the same reason;
//  - msaa=4 renders a 4x D32 array (Texture2DMSArray; Configure names msaa when the device has
//    no 4x D32_FLOAT) that MomentMaps resolves into moments, never storing multisampled moments;
//  - msaa, blur, bleed, exponents, precision and anisotropy are validated for every filter but
//    ignored by the comparison filters, so one bench sweep over `filter` can share them;
//  - the lookups are trilinear unless anisotropy > 1. On Mesa 22.3 (llvmpipe and lavapipe alike)
//    an anisotropic sampler darkens every 2x2 quad that spans two cascades, a line along each
//    split, even with SampleGrad's explicit gradients or an explicit LOD (as if the footprint came
//    from the quad's own coordinates, which jump between regions there), and the lit pass takes
//    about 30 times longer.
#pragma once
#include <memory>

#include "cascade-fit.h"
#include "hpsm-maps.h"
#include "moments/moment-maps.h"
#include "pcf-params.h"
#include <sp/tech/technique.h>

namespace sp::tech::csm {

enum class Select { Interval, Map };
enum class Storage { Array, Atlas };
enum class Bias { Const, Slope, Normal, ReceiverPlane };

// Validated parameters in usable form.
struct CsmSettings {
  FitSettings fit;
  Select select = Select::Interval;
  Storage storage = Storage::Array;
  int filter = 0;  // SHADOW_FILTER: 0 hw2x2, 1 box, 2 gauss, 3 gathercmp, 4 poisson, 5 pcss (unused with moments)
  int kernel = 3;
  PcssSettings pcss;  // filter=pcss: the sun's angular size, search taps, widest kernel
  bool moments = false;  // a moment filter; `moment` holds its options
  MomentOptions moment;
  int anisotropy = 1;    // of the moment lookups' sampler; 1 = trilinear
  Bias bias = Bias::Slope;
  int depthBias = 100;
  float slopeBias = 2.0f;
  float normalOffset = 1.0f;  // texels of the selected cascade
  HpsmSettings hpsm;          // accel (comparison filters; sdsm leaves it at none)
};

std::vector<ParamSpec> CsmParams();
// Throws std::invalid_argument for what ParamValues::Parse cannot check (the manual split list,
// the moment parameters' values, moment filters with storage=atlas).
// `technique` names the caller in error messages (sdsm shares these parameters).
CsmSettings SettingsFrom(const ParamValues& params, const std::string& technique = "csm");

// Where a cascade lives in the shadow texture.
struct CascadeRegion {
  uint32_t slice = 0;     // array slice (always 0 for the atlas)
  uint32_t x = 0, y = 0;  // top-left texel of its region in the slice
};

class CsmTechnique final : public Technique, public HpsmCounterSource {
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
  // With a moment filter, the moments the lit pass reads (mip 0), else the depth array.
  Texture2D* ShadowMapTexture() const override { return moments_ ? moments_->Texture() : map_.get(); }
  HpsmCounts HpsmDecisions() const override;

  // For tests and debug views.
  const CsmSettings& settings() const { return settings_; }
  const CascadeSet& lastFit() const { return fit_; }
  const std::vector<uint64_t>& lastCascadeTriangles() const { return cascadeTriangles_; }
  // The depth the cascades render (with moment filters: MomentMaps' depth, 4x with msaa=4).
  Texture2D* shadowTexture() const { return map_.get(); }
  CascadeRegion region(int cascade) const;
  const MomentMaps* momentMaps() const { return moments_.get(); }
  // Blur radius per cascade, in its texels, of the last frame (moment filters).
  const std::vector<float>& lastBlurRadii() const { return blurRadii_; }

 private:
  void WriteConstants(DeviceContext& ctx, const FrameInputs& frame);
  void DrawCascades(DeviceContext& ctx, SceneDrawer& drawer, const FrameInputs& frame);

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
  std::unique_ptr<MomentMaps> moments_;
  Ref<ShaderResourceView> depthSrv_;  // map_ as MomentMaps::Convert reads it
  std::vector<float> blurRadii_;
  Device* device_ = nullptr;
  std::unique_ptr<HpsmMaps> hpsm_;  // accel: built from every slice after the cascades
};

}  // namespace sp::tech::csm
