// The spot technique: one spot light's shadow in one perspective depth map whose frustum holds the
// light's cone (field of view twice the outer cone angle, near to range), rendered depth-only with
// D3D11 rasterizer depth bias and read with SampleCmpLevelZero (2x2 hardware PCF), as basic does
// for the directional light, or with the PCF library's filters, PCSS included (the light as a disc
// of radius `light_size`); optionally a secondary map decides whole footprints before the filter
// runs (accel; techniques/hpsm-maps.h: post-projective depth of a plane is affine in texel space,
// so planes fit a perspective map as they fit an orthographic one). Casters outside the frustum are
// culled. The directional light and the other local lights are unshadowed.
#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <stdexcept>

#include "cube/cube-culling.h"
#include "hpsm-maps.h"
#include "pcf-params.h"
#include <sp/tech/technique.h>

namespace sp::tech {
namespace {

// One perspective map cannot hold a cone much wider than this; the cube technique can.
constexpr float kMaxOuterDegrees = 80.0f;

class SpotTechnique final : public Technique, public HpsmCounterSource {
 public:
  std::string Name() const override { return "spot"; }

  std::vector<ParamSpec> Params() const override {
    std::vector<ParamSpec> specs = {
        {ParamSpec::Int, "light", "the spot light shadowed (index into the scene's spot lights)", "0", 0, kMaxLocalLights - 1, {}},
        {ParamSpec::Int, "resolution", "shadow map width and height in texels", "1024", 16, 16384, {}},
        {ParamSpec::Float, "near", "near plane in world units (casters closer to the light are not drawn)", "0.05", 1e-4, 1e3, {}},
        {ParamSpec::Int, "depth_bias", "D3D11 DepthBias (units of the depth format)", "200", -1e7, 1e7, {}},
        {ParamSpec::Float, "slope_bias", "D3D11 SlopeScaledDepthBias", "2.0", -100, 100, {}},
        // No poisson: its per-pixel rotation needs the pixel, which local-light lookups lack.
        {ParamSpec::Choice, "filter", "shadow filter (common/shadow-filter.hlsli; pcss: common/shadow-pcss.hlsli)", "hw2x2", 0, 0,
         {"hw2x2", "box", "gauss", "gathercmp", "pcss"}},
        PcfKernelParam("box, gauss, gathercmp"),
    };
    for (const ParamSpec& p : PcssParamSpecs(PcssLight::Local)) specs.push_back(p);
    for (ParamSpec& h : HpsmParams()) specs.push_back(h);
    return specs;
  }

  void Configure(Device& device, const ParamValues& p) override {
    light_ = uint32_t(p.getInt("light"));
    resolution_ = uint32_t(p.getInt("resolution"));
    near_ = p.getFloat("near");
    filter_ = PcfFilterIndex(p.getChoice("filter"));
    kernel_ = std::stoi(p.getChoice("kernel"));
    CheckPcfKernel("spot", filter_, kernel_);
    pcss_ = PcssSettingsFrom(p);
    map_ = MakeDepthMap(device, resolution_, resolution_, "spot shadow map");
    arraySrv_ = MakeSliceArraySrv(device, map_.texture.get());
    hpsm_ = ReadHpsmSettings(p, filter_, filter_ == kPcssFilter ? pcss_.maxKernel : kernel_, resolution_);
    hpsmMaps_.reset();
    device_ = &device;
    if (hpsm_.accel != ShadowAccel::None) hpsmMaps_ = std::make_unique<HpsmMaps>(device, hpsm_, resolution_, resolution_, 1);
    RASTERIZER_DESC rd;
    rd.FrontCounterClockwise = true;  // glTF winding, as in the lit pass
    rd.DepthBias = p.getInt("depth_bias");
    rd.SlopeScaledDepthBias = p.getFloat("slope_bias");
    rasterizer_ = device.CreateRasterizerState(rd);
    sampler_ = MakeShadowComparisonSampler(device);
    constants_ = MakeConstantBuffer(device, sizeof(Constants), "SpotShadow constants");
  }

  void RenderShadows(DeviceContext& ctx, SceneDrawer& drawer, const FrameInputs& frame) override {
    GpuTimer::Scope timed(frame.timer, ctx, "shadow");
    const scene::Scene& s = *frame.scene;
    if (light_ >= s.spotLights.size())
      throw std::invalid_argument("spot: light=" + std::to_string(light_) + " but scene '" + s.name + "' has " + std::to_string(s.spotLights.size()) +
                                  " spot light(s)");
    uint32_t index = uint32_t(s.pointLights.size()) + light_;  // LocalLightsOf: point lights first
    const LocalLight& l = frame.localLights.at(index);
    float outer = std::acos(glm::clamp(l.cosOuter, -1.0f, 1.0f));
    if (glm::degrees(outer) > kMaxOuterDegrees)
      throw std::invalid_argument("spot: spot light " + std::to_string(light_) + " of scene '" + s.name + "' has an outer cone angle of " +
                                  std::to_string(glm::degrees(outer)) + " degrees; one perspective map holds at most " +
                                  std::to_string(int(kMaxOuterDegrees)) + " (shadow it with the cube technique)");
    if (!(near_ < l.range))
      throw std::invalid_argument("spot: near=" + std::to_string(near_) + " is not below the range of spot light " + std::to_string(light_) + " (" +
                                  std::to_string(l.range) + ")");
    glm::vec3 up = std::abs(l.direction.y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    glm::mat4 view = glm::lookAtRH(l.position, l.position + l.direction, up);
    // A square frustum whose inscribed cone is the outer cone.
    glm::mat4 proj = glm::perspectiveRH_ZO(2.0f * outer, 1.0f, near_, l.range);
    viewProj_ = proj * view;
    Constants c{viewProj_, glm::vec2(float(resolution_)), index, 0.0f,
                PerspectivePcssConstants(pcss_, near_, l.range, 2.0f * outer, float(resolution_))};
    ctx.UpdateSubresource(constants_.get(), 0, nullptr, &c, 0, 0);

    ShaderResourceView* none[2] = {};
    ctx.PSSetShaderResources(0, 2, none);
    ctx.OMSetRenderTargets(0, nullptr, map_.dsv.get());
    ctx.ClearDepthStencilView(map_.dsv.get(), CLEAR_DEPTH, 1.0f, 0);
    VIEWPORT vp{0, 0, float(resolution_), float(resolution_), 0, 1};
    ctx.RSSetViewports(1, &vp);
    ctx.RSSetState(rasterizer_.get());
    ctx.OMSetDepthStencilState(nullptr, 0);
    const std::vector<scene::Instance>& instances = s.instances;
    trianglesSubmitted_ = drawer.DrawDepth(ctx, viewProj_, [&](uint32_t i) { return cube::BoxMayMeetFrustum(viewProj_, instances[i].worldBounds); });
    if (hpsmMaps_) {
      ctx.OMSetRenderTargets(0, nullptr, nullptr);
      GpuTimer::Scope built(frame.timer, ctx, "hpsm");
      hpsmMaps_->Build(ctx, arraySrv_.get());
    }
  }

  std::string LightingInclude() const override { return "spot/shadow.hlsli"; }
  std::vector<hlsl::Define> LightingDefines() const override {
    bool sized = filter_ != 0 && filter_ != kPcssFilter;
    std::vector<hlsl::Define> d = {{"SHADOW_FILTER", std::to_string(filter_)}, {"SHADOW_KERNEL", std::to_string(sized ? kernel_ : 3)}};
    for (hlsl::Define& h : HpsmDefines(hpsm_)) d.push_back(h);
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
  std::vector<ShadowLayer> Layers() const override { return {{resolution_, resolution_}}; }
  Texture2D* ShadowMapTexture() const override { return map_.texture.get(); }
  int LabLocalLight(const scene::Scene& scene) const override { return int(scene.pointLights.size() + light_); }

 private:
  // cbuffer SpotShadow in shaders-hlsl/spot/shadow.hlsli.
  struct Constants {
    glm::mat4 viewProj;
    glm::vec2 mapSize;
    uint32_t lightIndex;
    float pad;
    PcssConstants pcss;
  };
  static_assert(sizeof(Constants) == 112);

  uint32_t light_ = 0, resolution_ = 0;
  float near_ = 0.05f;
  int filter_ = 0, kernel_ = 3;
  PcssSettings pcss_;
  HpsmSettings hpsm_;
  Device* device_ = nullptr;
  std::unique_ptr<HpsmMaps> hpsmMaps_;
  DepthMap map_;
  Ref<ShaderResourceView> arraySrv_;
  Ref<RasterizerState> rasterizer_;
  Ref<SamplerState> sampler_;
  Ref<Buffer> constants_;
  glm::mat4 viewProj_{1.0f};
  uint64_t trianglesSubmitted_ = 0;
};

}  // namespace

std::unique_ptr<Technique> MakeSpotTechnique() { return std::make_unique<SpotTechnique>(); }

}  // namespace sp::tech
