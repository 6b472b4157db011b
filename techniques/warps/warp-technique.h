// The perspective-warp techniques psm, lispsm and tsm (issue 12): one class, parameterised by
// the warp, registered three times. Each cascade (1 to 4: the view range split as csm does, so
// cascades > 1 is cascaded LiSPSM / TSM / PSM) is one FitWarp (warp-fit.h) on its slice of the
// view, rendered into one slice of an R32_TYPELESS Texture2DArray. Depth, per the depth
// parameter:
//   warped  the post-projective z of the warped viewProj, rendered by depth-only with D3D11
//           rasterizer bias (depth_bias, slope_bias), compared after the divide by w;
//   linear  WarpFit::linearDepth, light-space linear depth, written by depth-linear.hlsl's pixel
//           shader through SV_Depth. Interpolated per pixel (perspective-correct, exact for an
//           affine function of the world position): a vertex shader writing z * w to clip z
//           would be interpolated linearly in screen space, which under a perspective warp is
//           not linear depth inside a triangle. Its bias is D3D11's formula applied in the
//           shader: linear_bias + linear_slope_bias * max(|ddx|, |ddy|) of the linear depth.
// Lighting in shaders-hlsl/warps/shadow.hlsli.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "csm/cascade-fit.h"
#include "warp-fit.h"
#include <sp/tech/technique.h>

namespace sp::tech::warps {

constexpr int kMaxWarpCascades = 4;

// Validated parameters in usable form.
struct WarpSettings {
  Warp warp = Warp::Lispsm;
  uint32_t resolution = 2048;
  int cascades = 1;
  csm::SplitScheme split = csm::SplitScheme::Pssm;
  float lambda = 0.75f;
  WarpParams params;
  bool linearDepth = false;
  int depthBias = 100;      // depth=warped: D3D11 DepthBias
  float slopeBias = 2.0f;   // depth=warped: D3D11 SlopeScaledDepthBias
  // depth=linear: D3D11's formula applied in the depth shader, in linear depth ([0, 1] over the
  // cascade's body and casters): constant + slope * the largest change per map texel.
  float linearBias = 0.0f;
  float linearSlopeBias = 1.0f;
  // The comparison filter of common/shadow-filter.hlsli (0 hw2x2, 1 box, 2 gauss, 3 gathercmp,
  // 4 poisson) and its kernel, as csm's `filter` and `kernel`.
  int filter = 0;
  int kernel = 3;
  // Receiver-plane depth bias: each filter tap compares against the receiver's plane, from the
  // screen derivatives of the warped map coordinates (King's "bias in warped space" alternative).
  bool receiverPlane = false;
};

const char* WarpName(Warp warp);
std::vector<ParamSpec> WarpTechniqueParams(Warp warp);
WarpSettings WarpSettingsFrom(Warp warp, const ParamValues& params);

class WarpTechnique final : public Technique {
 public:
  explicit WarpTechnique(Warp warp) : warp_(warp) {}
  std::string Name() const override { return WarpName(warp_); }
  std::vector<ParamSpec> Params() const override { return WarpTechniqueParams(warp_); }
  void Configure(Device& device, const ParamValues& params) override;
  void RenderShadows(DeviceContext& ctx, SceneDrawer& drawer, const FrameInputs& frame) override;
  std::string LightingInclude() const override { return "warps/shadow.hlsli"; }
  std::vector<hlsl::Define> LightingDefines() const override;
  void BindLighting(DeviceContext& ctx) override;
  ShadowStats Stats() const override;
  std::vector<ShadowLayer> Layers() const override;
  Texture2D* ShadowMapTexture() const override { return map_.get(); }

  // For tests and the lab.
  const WarpSettings& settings() const { return settings_; }
  const std::vector<WarpFit>& lastFits() const { return fits_; }
  const std::vector<float>& lastSplits() const { return splits_; }

 private:
  Warp warp_;
  WarpSettings settings_;
  Ref<Texture2D> map_;
  std::vector<Ref<DepthStencilView>> dsvs_;
  Ref<ShaderResourceView> srv_;
  // FitWarp's maps put the body's near side on the top rows, a mirror image of basic's light view,
  // which turns every triangle's winding around: the mirrored state culls what basic culls.
  Ref<RasterizerState> rasterizer_, mirroredRasterizer_;
  Ref<SamplerState> sampler_;
  Ref<Buffer> constants_;
  // depth=linear: the depth shaders and one constant buffer per cascade (its linear-depth row).
  Ref<VertexShader> linearVs_;
  Ref<PixelShader> linearPs_;
  std::vector<Ref<Buffer>> linearConstants_;
  std::vector<WarpFit> fits_;
  std::vector<float> splits_;
  uint64_t triangles_ = 0;
};

}  // namespace sp::tech::warps
