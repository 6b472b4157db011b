// The basic technique: one directional shadow map fitted to the whole scene (the naive fit),
// rendered depth-only into R32_TYPELESS with D3D11 rasterizer depth bias, sampled with the 2x2
// hardware comparison filter (the default, the reference point every other technique is measured
// against) or with the PCF library's filters, PCSS included (the sun as a disc of `light_size`
// degrees; docs/techniques.md); optionally a secondary map decides whole footprints before the
// filter runs (accel: hpsm or the min/max baseline; techniques/hpsm-maps.h). shafts=1 adds sun
// shafts marched through the map, optionally walked per secondary texel (shaders-hlsl/common/shafts.hlsli).
#include <stdexcept>

#include "pcf-params.h"
#include <sp/tech/shaft-counters.h>
#include <sp/tech/technique.h>

#include "hpsm-maps.h"
#include "scene-fit.h"

namespace sp::tech {
namespace {

class BasicTechnique final : public Technique, public HpsmCounterSource, public ShaftCounterSource {
 public:
  std::string Name() const override { return "basic"; }

  std::vector<ParamSpec> Params() const override {
    std::vector<ParamSpec> specs = {
        {ParamSpec::Int, "resolution", "shadow map width and height in texels", "2048", 16, 16384, {}},
        {ParamSpec::Int, "depth_bias", "D3D11 DepthBias (units of the depth format)", "200", -1e7, 1e7, {}},
        {ParamSpec::Float, "slope_bias", "D3D11 SlopeScaledDepthBias", "2.0", -100, 100, {}},
        {ParamSpec::Float, "bias_clamp", "D3D11 DepthBiasClamp (0 = none)", "0", -1, 1, {}},
        {ParamSpec::Choice, "filter", "shadow filter (common/shadow-filter.hlsli; pcss: common/shadow-pcss.hlsli)", "hw2x2", 0, 0, PcfFilterNames()},
        PcfKernelParam("box, gauss, gathercmp, poisson"),
    };
    for (const ParamSpec& p : PcssParamSpecs(PcssLight::Directional)) specs.push_back(p);
    for (ParamSpec& h : HpsmParams()) specs.push_back(h);
    specs.push_back({ParamSpec::Int, "shafts", "1: add sun shafts, single scattering of the sun in a homogeneous medium marched through the shadow map", "0", 0, 1, {}});
    specs.push_back({ParamSpec::Int, "shaft_steps", "shafts: samples per view ray, camera to surface", "64", 1, 4096, {}});
    specs.push_back({ParamSpec::Float, "shaft_density", "shafts: scattering coefficient per world unit (isotropic, no phase function)", "0.02", 0, 100, {}});
    specs.push_back({ParamSpec::Choice, "shaft_accel", "shafts: decide runs of steps per secondary-map texel without lookups (the map of accel, or one built for the shafts)", "none", 0, 0, {"none", "hpsm", "minmax"}});
    return specs;
  }

  void Configure(Device& device, const ParamValues& p) override {
    resolution_ = uint32_t(p.getInt("resolution"));
    filter_ = PcfFilterIndex(p.getChoice("filter"));
    kernel_ = std::stoi(p.getChoice("kernel"));
    CheckPcfKernel("basic", filter_, kernel_);
    pcss_ = PcssSettingsFrom(p);
    map_ = MakeDepthMap(device, resolution_, resolution_, "basic shadow map");
    // The PCF library reads Texture2DArray; a one-slice array view of the same map.
    arraySrv_ = MakeSliceArraySrv(device, map_.texture.get());
    hpsm_ = ReadHpsmSettings(p, filter_, filter_ == kPcssFilter ? pcss_.maxKernel : kernel_, resolution_);
    ReadShaftSettings(p);
    hpsmMaps_.reset();
    if (maps_.accel != ShadowAccel::None) {
      device_ = &device;
      hpsmMaps_ = std::make_unique<HpsmMaps>(device, maps_, resolution_, resolution_, 1);
    }

    RASTERIZER_DESC rd;
    rd.FrontCounterClockwise = true;  // glTF winding, as in the lit pass
    rd.DepthBias = p.getInt("depth_bias");
    rd.SlopeScaledDepthBias = p.getFloat("slope_bias");
    rd.DepthBiasClamp = p.getFloat("bias_clamp");
    // Casters between the light and the fitted near plane still cast: pancake them onto it.
    rd.DepthClipEnable = false;
    rasterizer_ = device.CreateRasterizerState(rd);

    sampler_ = MakeShadowComparisonSampler(device);
    constants_ = MakeConstantBuffer(device, sizeof(Constants), "BasicShadow constants");
  }

  void RenderShadows(DeviceContext& ctx, SceneDrawer& drawer, const FrameInputs& frame) override {
    GpuTimer::Scope timed(frame.timer, ctx, "shadow");
    OrthoFit fit = FitOrthoToBounds(frame.scene->bounds, frame.light.direction);
    lightViewProj_ = fit.viewProj;
    Constants c{lightViewProj_, glm::vec2(float(resolution_)), glm::vec2(0.0f),
                OrthoPcssConstants(pcss_, fit.nearZ, fit.farZ, fit.extent / float(resolution_)), glm::vec4(shaftDensity_, float(shaftSteps_), 0, 0)};
    ctx.UpdateSubresource(constants_.get(), 0, nullptr, &c, 0, 0);

    // The map (t0) and the secondary map (t1) are read by the previous frame's lit pass; unbind
    // them before writing, as a D3D11 program does (the runtime would do it anyway, with a warning).
    ShaderResourceView* none[2] = {};
    ctx.PSSetShaderResources(0, 2, none);
    ctx.OMSetRenderTargets(0, nullptr, map_.dsv.get());
    ctx.ClearDepthStencilView(map_.dsv.get(), CLEAR_DEPTH, 1.0f, 0);
    VIEWPORT vp{0, 0, float(resolution_), float(resolution_), 0, 1};
    ctx.RSSetViewports(1, &vp);
    ctx.RSSetState(rasterizer_.get());
    ctx.OMSetDepthStencilState(nullptr, 0);
    trianglesSubmitted_ = drawer.DrawDepth(ctx, lightViewProj_);
    if (hpsmMaps_) {
      ctx.OMSetRenderTargets(0, nullptr, nullptr);
      GpuTimer::Scope built(frame.timer, ctx, "hpsm");
      hpsmMaps_->Build(ctx, arraySrv_.get());
    }
  }

  std::string LightingInclude() const override { return "basic/shadow.hlsli"; }
  // hw2x2 and pcss ignore the kernel: one variant each.
  std::vector<hlsl::Define> LightingDefines() const override {
    bool sized = filter_ != 0 && filter_ != kPcssFilter;
    std::vector<hlsl::Define> d = {{"SHADOW_FILTER", std::to_string(filter_)}, {"SHADOW_KERNEL", std::to_string(sized ? kernel_ : 3)}};
    for (hlsl::Define& h : HpsmDefines(hpsm_)) d.push_back(h);
    if (shafts_) {
      bool accel = shaftAccel_ != ShadowAccel::None;
      d.push_back({"SHAFTS", "1"});
      d.push_back({"SHAFT_ACCEL", !accel ? "0" : shaftAccel_ == ShadowAccel::Hpsm ? "1" : "2"});
      d.push_back({"SHAFT_BLOCK", std::to_string(maps_.block)});
      d.push_back({"SHAFT_REACH", std::to_string(maps_.reach)});
      d.push_back({"SHAFT_COUNTERS", accel && maps_.counters ? "1" : "0"});
    }
    return d;
  }

  void BindLighting(DeviceContext& ctx) override {
    ctx.PSSetConstantBuffers(2, {constants_.get()});
    ctx.PSSetShaderResources(0, {arraySrv_.get(), hpsmMaps_ ? hpsmMaps_->srv() : nullptr});
    ctx.PSSetSamplers(0, {sampler_.get()});
    if (hpsmMaps_) hpsmMaps_->BindCounters(ctx);
  }

  ShadowStats Stats() const override {
    return {uint64_t(resolution_) * resolution_ * 4 + (hpsmMaps_ ? hpsmMaps_->memoryBytes() : 0), trianglesSubmitted_};
  }

  HpsmCounts HpsmDecisions() const override { return hpsmMaps_ ? hpsmMaps_->ReadCounters(*device_->GetImmediateContext()) : HpsmCounts{}; }
  ShaftCounts ShaftSteps() const override {
    if (!hpsmMaps_) return {};
    auto w = hpsmMaps_->ReadCounterWords(*device_->GetImmediateContext());
    return {w[5], w[6]};  // kShaftLookedUp, kShaftSkipped
  }
  std::vector<ShadowLayer> Layers() const override { return {{resolution_, resolution_}}; }
  Texture2D* ShadowMapTexture() const override { return map_.texture.get(); }

 private:
  // shafts, shaft_steps, shaft_density, shaft_accel; maps_: the secondary map's settings, accel's
  // or, with accel=none, one built for the shafts alone (no filter reach, blocks of 8 by default).
  void ReadShaftSettings(const ParamValues& p) {
    shafts_ = p.getInt("shafts") != 0;
    shaftSteps_ = p.getInt("shaft_steps");
    shaftDensity_ = p.getFloat("shaft_density");
    const std::string& a = p.getChoice("shaft_accel");
    shaftAccel_ = a == "hpsm" ? ShadowAccel::Hpsm : a == "minmax" ? ShadowAccel::MinMax : ShadowAccel::None;
    maps_ = hpsm_;
    if (!shafts_) {
      if (shaftAccel_ != ShadowAccel::None) throw std::invalid_argument("shaft_accel: " + a + " needs shafts=1");
      return;
    }
    if (!(shaftDensity_ > 0.0f)) throw std::invalid_argument("shaft_density: must be above 0 with shafts=1");
    if (shaftAccel_ == ShadowAccel::None) return;
    if (hpsm_.accel != ShadowAccel::None) {
      if (hpsm_.accel != shaftAccel_)
        throw std::invalid_argument("shaft_accel: " + a + " differs from accel=" + p.getChoice("accel") + "; one secondary map serves both, use the same or none");
      return;
    }
    maps_.accel = shaftAccel_;
    maps_.reach = 0;
    int block = p.getInt("hpsm_block");
    maps_.block = block == 0 ? 8 : block;
    if (shaftAccel_ == ShadowAccel::MinMax && (maps_.block & (maps_.block - 1)) != 0)
      throw std::invalid_argument("hpsm_block: " + std::to_string(maps_.block) + " is not a power of two, as shaft_accel=minmax needs");
    if (uint32_t(maps_.block) > resolution_)
      throw std::invalid_argument("hpsm_block: " + std::to_string(maps_.block) + " is wider than the shadow map (" + std::to_string(resolution_) + " texels)");
  }

  // cbuffer BasicShadow in shaders-hlsl/basic/shadow.hlsli.
  struct Constants {
    glm::mat4 lightViewProj;
    glm::vec2 mapSize;
    glm::vec2 pad;
    PcssConstants pcss;
    glm::vec4 shafts;  // density, steps
  };
  static_assert(sizeof(Constants) == 128);

  uint32_t resolution_ = 0;
  int filter_ = 0, kernel_ = 3;
  PcssSettings pcss_;
  HpsmSettings hpsm_, maps_;
  bool shafts_ = false;
  int shaftSteps_ = 64;
  float shaftDensity_ = 0.02f;
  ShadowAccel shaftAccel_ = ShadowAccel::None;
  Device* device_ = nullptr;
  std::unique_ptr<HpsmMaps> hpsmMaps_;
  DepthMap map_;
  Ref<ShaderResourceView> arraySrv_;
  Ref<RasterizerState> rasterizer_;
  Ref<SamplerState> sampler_;
  Ref<Buffer> constants_;
  glm::mat4 lightViewProj_{1.0f};
  uint64_t trianglesSubmitted_ = 0;
};

}  // namespace

std::unique_ptr<Technique> MakeBasicTechnique() { return std::make_unique<BasicTechnique>(); }

}  // namespace sp::tech
