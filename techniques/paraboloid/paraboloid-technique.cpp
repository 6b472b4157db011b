// The paraboloid technique: omnidirectional shadows of one point light in two paraboloid depth
// maps (Brabec, Annen and Seidel 2002; the non-linear projection King contrasts with cube maps).
// Each hemisphere around a light axis maps onto the unit disk of one slice of a Texture2DArray;
// two passes instead of six, but the mapping is applied per vertex and the rasterizer
// interpolates linearly between vertices, so large triangles' edges and depths come out wrong
// (docs/local-lights.md measures how much). The lit pass picks the hemisphere by the receiver's
// side of the seam plane and compares with SampleCmpLevelZero (2x2 hardware PCF). D3D11
// rasterizer depth bias as in cube. The directional light is unshadowed.
#include <stdexcept>

#include "hpsm-maps.h"
#include "local-lights.h"
#include "paraboloid/paraboloid-map.h"
#include <sp/tech/technique.h>

namespace sp::tech {
namespace {

// Why accel (techniques/hpsm-maps.h) is refused here.
const char* const kParaboloidAccelRefusal =
    "a paraboloid map is not a projective view, so a receiver plane is no plane in its texels, and its only filter is the one-fetch hardware 2x2";

// How far past the rim each hemisphere is drawn, in texels: the 2x2 filter reads one texel
// beyond a receiver's own, and one more absorbs the rasterizer's edge rule.
constexpr float kRimTexels = 2.0f;

class ParaboloidTechnique final : public Technique {
 public:
  std::string Name() const override { return "paraboloid"; }

  std::vector<ParamSpec> Params() const override {
    return {
        {ParamSpec::Int, "light", "the point light shadowed (index into the scene's point lights = local light index)", "0", 0, kMaxLocalLights - 1, {}},
        {ParamSpec::Int, "resolution", "width and height of each hemisphere's map in texels", "1024", 16, 8192, {}},
        {ParamSpec::Float, "near", "distance from the light below which casters are not drawn, in world units", "0.05", 1e-4, 1e3, {}},
        {ParamSpec::Choice, "axis", "world axis of the front hemisphere (+axis) and normal of the seam plane through the light", "y", 0, 0, {"x", "y", "z"}},
        {ParamSpec::Int, "depth_bias", "D3D11 DepthBias (units of the depth format)", "200", -1e7, 1e7, {}},
        {ParamSpec::Float, "slope_bias", "D3D11 SlopeScaledDepthBias (depth=exact: the shader applies it to the depth it writes)", "2.0", -100, 100, {}},
        {ParamSpec::Choice, "depth", "vertex: depth interpolated from the vertices (the classic method); exact: the pixel shader writes the distance to the triangle's plane along the texel's direction", "vertex", 0, 0, {"vertex", "exact"}},
        {ParamSpec::Float, "exact_bias", "depth=exact: world units added to the distance written (no rasterizer bias reaches a written depth)", "0.01", 0, 1e3, {}},
        UnofferedAccelParam(kParaboloidAccelRefusal),
    };
  }

  void Configure(Device& device, const ParamValues& p) override {
    RefuseAccel(p, "paraboloid", kParaboloidAccelRefusal);
    light_ = uint32_t(p.getInt("light"));
    resolution_ = uint32_t(p.getInt("resolution"));
    near_ = p.getFloat("near");
    const std::string& axis = p.getChoice("axis");
    axis_ = axis == "x" ? 0 : axis == "y" ? 1 : 2;
    exact_ = p.getChoice("depth") == "exact";
    exactBias_ = p.getFloat("exact_bias");
    slopeBias_ = p.getFloat("slope_bias");

    TEXTURE2D_DESC td;
    td.Width = td.Height = resolution_;
    td.ArraySize = 2;
    td.Format = FORMAT_R32_TYPELESS;
    td.BindFlags = BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE;
    maps_ = device.CreateTexture2D(td);
    maps_->SetDebugName("paraboloid shadow maps");
    slices_ = MakeSliceDepthViews(device, maps_.get());
    srv_ = MakeSliceArraySrv(device, maps_.get());

    std::vector<hlsl::Define> defines = {{"SP_PARABOLOID_EXACT", exact_ ? "1" : "0"}};
    vs_ = device.CreateVertexShader(CompileTechniqueShader("paraboloid/pass.hlsl", "vs_5_0", "VSMain", defines));
    ps_ = device.CreatePixelShader(CompileTechniqueShader("paraboloid/pass.hlsl", "ps_5_0", "PSMain", defines));

    RASTERIZER_DESC rd;
    // The back hemisphere is a mirror image, and open meshes cast from either side: both sides.
    rd.CullMode = CULL_NONE;
    rd.FrontCounterClockwise = true;
    if (!exact_) {
      rd.DepthBias = p.getInt("depth_bias");
      rd.SlopeScaledDepthBias = p.getFloat("slope_bias");
    }
    rasterizer_ = device.CreateRasterizerState(rd);
    sampler_ = MakeShadowComparisonSampler(device);
    constants_ = MakeConstantBuffer(device, sizeof(Constants), "ParaboloidShadow constants");
  }

  void RenderShadows(DeviceContext& ctx, SceneDrawer& drawer, const FrameInputs& frame) override {
    GpuTimer::Scope timed(frame.timer, ctx, "shadow");
    const LocalLight& l = ShadowedPointLight("paraboloid", light_, near_, frame);
    const float discardZ = paraboloid::DiscardZ(resolution_, kRimTexels);
    Constants c{};
    glm::mat4 front = paraboloid::HemisphereView(axis_, 0, l.position);
    for (int r = 0; r < 3; ++r) c.frame[r] = glm::vec4(front[0][r], front[1][r], front[2][r], front[3][r]);
    c.nearZ = near_;
    c.range = l.range;
    c.mapSize = float(resolution_);
    c.lightIndex = light_;
    c.discardZ = discardZ;
    c.exactBias = exactBias_;
    c.exactSlope = slopeBias_;
    ctx.UpdateSubresource(constants_.get(), 0, nullptr, &c, 0, 0);

    ShaderResourceView* none = nullptr;
    ctx.PSSetShaderResources(0, 1, &none);
    VIEWPORT vp{0, 0, float(resolution_), float(resolution_), 0, 1};
    ctx.RSSetViewports(1, &vp);
    ctx.RSSetState(rasterizer_.get());
    ctx.OMSetDepthStencilState(nullptr, 0);
    ctx.VSSetConstantBuffers(2, {constants_.get()});
    ctx.PSSetConstantBuffers(2, {constants_.get()});
    trianglesSubmitted_ = 0;
    const std::vector<scene::Instance>& instances = frame.scene->instances;
    for (int h = 0; h < 2; ++h) {
      glm::mat4 view = paraboloid::HemisphereView(axis_, h, l.position);
      auto keep = [&](uint32_t i) { return Drawn(view, instances[i].worldBounds, discardZ, l.range); };
      ctx.OMSetRenderTargets(0, nullptr, slices_[h].get());
      ctx.ClearDepthStencilView(slices_[h].get(), CLEAR_DEPTH, 1.0f, 0);
      trianglesSubmitted_ += drawer.DrawDepth(ctx, view, keep, {vs_.get(), ps_.get()});
    }
  }

  std::string LightingInclude() const override { return "paraboloid/shadow.hlsli"; }

  void BindLighting(DeviceContext& ctx) override {
    ctx.PSSetConstantBuffers(2, {constants_.get()});
    ctx.PSSetShaderResources(0, {srv_.get()});
    ctx.PSSetSamplers(0, {sampler_.get()});
  }

  ShadowStats Stats() const override { return {uint64_t(resolution_) * resolution_ * 4 * 2, trianglesSubmitted_}; }
  std::vector<ShadowLayer> Layers() const override { return std::vector<ShadowLayer>(2, {resolution_, resolution_}); }
  Texture2D* ShadowMapTexture() const override { return maps_.get(); }
  int LabLocalLight(const scene::Scene&) const override { return int(light_); }  // point lights come first

 private:
  // Whether a world box may leave fragments in a hemisphere: not when it lies beyond the range, or
  // wholly in the cone the pass discards ({z < discardZ |d|}, convex for discardZ < 0, so the box
  // is inside it when its 8 corners are).
  static bool Drawn(const glm::mat4& view, const scene::Bounds& b, float discardZ, float range) {
    glm::vec3 corners[8];
    b.corners(corners);
    bool allDiscarded = true;
    for (const glm::vec3& w : corners) {
      glm::vec3 d(view * glm::vec4(w, 1.0f));
      allDiscarded = allDiscarded && d.z < discardZ * glm::length(d);
    }
    glm::vec3 lightPos(glm::inverse(view)[3]);
    glm::vec3 nearest = glm::clamp(lightPos, b.min, b.max);
    return !allDiscarded && glm::distance(nearest, lightPos) < range;
  }

  // cbuffer ParaboloidShadow in shaders-hlsl/paraboloid/constants.hlsli.
  struct Constants {
    glm::vec4 frame[3];
    float nearZ, range, mapSize;
    uint32_t lightIndex;
    float discardZ, exactBias, exactSlope;
    float pad;
  };
  static_assert(sizeof(Constants) == 80);

  uint32_t light_ = 0, resolution_ = 0;
  float near_ = 0.05f;
  int axis_ = 1;
  bool exact_ = false;
  float exactBias_ = 0, slopeBias_ = 0;
  Ref<Texture2D> maps_;
  std::vector<Ref<DepthStencilView>> slices_;
  Ref<ShaderResourceView> srv_;
  Ref<VertexShader> vs_;
  Ref<PixelShader> ps_;
  Ref<RasterizerState> rasterizer_;
  Ref<SamplerState> sampler_;
  Ref<Buffer> constants_;
  uint64_t trianglesSubmitted_ = 0;
};

}  // namespace

std::unique_ptr<Technique> MakeParaboloidTechnique() { return std::make_unique<ParaboloidTechnique>(); }

}  // namespace sp::tech
