// The basic technique: one directional shadow map fitted to the whole scene (the naive fit),
// rendered depth-only into R32_TYPELESS with D3D11 rasterizer depth bias, sampled with the 2x2
// hardware comparison filter. The reference point every other technique is measured against.
// Optionally a wider filter (common/shadow-filter.hlsli) and, to test accelerating it, a secondary
// map that decides whole footprints (accel: hpsm or the min/max baseline; techniques/hpsm-maps.h).
#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>

#include <sp/tech/technique.h>

#include "hpsm-maps.h"

namespace sp::tech {
namespace {

class BasicTechnique final : public Technique, public HpsmCounterSource {
 public:
  std::string Name() const override { return "basic"; }

  std::vector<ParamSpec> Params() const override {
    std::vector<ParamSpec> specs = {
        {ParamSpec::Int, "resolution", "shadow map width and height in texels", "2048", 16, 16384, {}},
        {ParamSpec::Int, "depth_bias", "D3D11 DepthBias (units of the depth format)", "200", -1e7, 1e7, {}},
        {ParamSpec::Float, "slope_bias", "D3D11 SlopeScaledDepthBias", "2.0", -100, 100, {}},
        {ParamSpec::Float, "bias_clamp", "D3D11 DepthBiasClamp (0 = none)", "0", -1, 1, {}},
        {ParamSpec::Choice, "filter", "comparison filter (common/shadow-filter.hlsli)", "hw2x2", 0, 0, {"hw2x2", "box", "gauss", "gathercmp", "poisson"}},
        {ParamSpec::Choice, "kernel", "filter kernel width in texels (box, gauss, gathercmp, poisson)", "3", 0, 0, {"3", "5", "7", "9"}},
    };
    for (ParamSpec& h : HpsmParams()) specs.push_back(h);
    return specs;
  }

  void Configure(Device& device, const ParamValues& p) override {
    resolution_ = uint32_t(p.getInt("resolution"));
    map_ = MakeDepthMap(device, resolution_, resolution_, "basic shadow map");
    static const char* const kFilters[] = {"hw2x2", "box", "gauss", "gathercmp", "poisson"};
    for (int i = 0; i < 5; ++i)
      if (p.getChoice("filter") == kFilters[i]) filter_ = i;
    kernel_ = filter_ == 0 ? 3 : std::stoi(p.getChoice("kernel"));
    hpsm_ = ReadHpsmSettings(p, filter_, kernel_, resolution_);
    mapArray_ = Filtered() ? MakeSliceArraySrv(device, map_.texture.get()) : nullptr;
    hpsmMaps_.reset();
    if (hpsm_.accel != ShadowAccel::None) {
      device_ = &device;
      hpsmMaps_ = std::make_unique<HpsmMaps>(device, hpsm_, resolution_, resolution_, 1);
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
    lightViewProj_ = FitToScene(frame.scene->bounds, frame.light.direction);
    Constants c{lightViewProj_, glm::vec2(float(resolution_)), glm::vec2(0.0f)};
    ctx.UpdateSubresource(constants_.get(), 0, nullptr, &c, 0, 0);

    // The map (t0, t1) and the secondary map (t2) are read by the previous frame's lit pass;
    // unbind them before writing, as a D3D11 program does (the runtime would do it anyway, with a
    // warning).
    ShaderResourceView* none[3] = {};
    ctx.PSSetShaderResources(0, 3, none);
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
      hpsmMaps_->Build(ctx, mapArray_.get());
    }
  }

  std::string LightingInclude() const override { return "basic/shadow.hlsli"; }

  // None for the default (hw2x2, no accel): basic's original lookup, unchanged.
  std::vector<hlsl::Define> LightingDefines() const override {
    if (!Filtered()) return {};
    std::vector<hlsl::Define> d = {{"SHADOW_FILTER", std::to_string(filter_)}, {"SHADOW_KERNEL", std::to_string(kernel_)}};
    for (hlsl::Define& h : HpsmDefines(hpsm_)) d.push_back(h);
    return d;
  }

  void BindLighting(DeviceContext& ctx) override {
    ctx.PSSetConstantBuffers(2, {constants_.get()});
    ctx.PSSetShaderResources(0, {map_.srv.get(), mapArray_.get(), hpsmMaps_ ? hpsmMaps_->srv() : nullptr});
    ctx.PSSetSamplers(0, {sampler_.get()});
    if (hpsmMaps_) hpsmMaps_->BindCounters(ctx);
  }

  ShadowStats Stats() const override {
    return {uint64_t(resolution_) * resolution_ * 4 + (hpsmMaps_ ? hpsmMaps_->memoryBytes() : 0), trianglesSubmitted_};
  }

  HpsmCounts HpsmDecisions() const override { return hpsmMaps_ ? hpsmMaps_->ReadCounters(*device_->GetImmediateContext()) : HpsmCounts{}; }
  std::vector<ShadowLayer> Layers() const override { return {{resolution_, resolution_}}; }

 private:
  // An orthographic light frustum around the scene's bounding box.
  static glm::mat4 FitToScene(const scene::Bounds& bounds, const glm::vec3& direction) {
    glm::vec3 dir = glm::normalize(direction);
    glm::vec3 center = bounds.center();
    float radius = glm::length(bounds.extent()) * 0.5f;
    glm::vec3 up = std::abs(dir.y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    glm::mat4 view = glm::lookAtRH(center - dir * radius, center, up);
    scene::Bounds ls = bounds.transformed(view);
    // Right-handed view space looks down -z: near = -max.z, far = -min.z.
    glm::mat4 proj = glm::orthoRH_ZO(ls.min.x, ls.max.x, ls.min.y, ls.max.y, -ls.max.z, -ls.min.z);
    return proj * view;
  }

  // cbuffer BasicShadow in shaders-hlsl/basic/shadow.hlsli.
  struct Constants {
    glm::mat4 lightViewProj;
    glm::vec2 mapSize;
    glm::vec2 pad;
  };
  static_assert(sizeof(Constants) == 80);

  bool Filtered() const { return filter_ != 0 || hpsm_.accel != ShadowAccel::None; }

  uint32_t resolution_ = 0;
  int filter_ = 0, kernel_ = 3;
  HpsmSettings hpsm_;
  Device* device_ = nullptr;
  std::unique_ptr<HpsmMaps> hpsmMaps_;
  DepthMap map_;
  Ref<ShaderResourceView> mapArray_;  // the map as a one-layer Texture2DArray, for ShadowFilter
  Ref<RasterizerState> rasterizer_;
  Ref<SamplerState> sampler_;
  Ref<Buffer> constants_;
  glm::mat4 lightViewProj_{1.0f};
  uint64_t trianglesSubmitted_ = 0;
};

}  // namespace

std::unique_ptr<Technique> MakeBasicTechnique() { return std::make_unique<BasicTechnique>(); }

}  // namespace sp::tech
