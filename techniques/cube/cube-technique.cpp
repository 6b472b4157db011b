// The cube technique: omnidirectional shadows of one point light in a TextureCube of depth (King,
// "Shadow Mapping Algorithms"). Six 90-degree faces, one DSV per face, each storing planar window z
// with the same near and far on every face, so the lit pass computes the reference depth from the
// major axis alone (z = a + b / max(|x|, |y|, |z|)) and compares with SampleCmpLevelZero on the
// TextureCube: seamless 2x2 hardware PCF across face edges. Casters are culled per face against
// the face frustum, and faces whose frustum does not meet the camera's are skipped (cull_faces);
// D3D11 rasterizer depth bias as in basic. The directional light is unshadowed.
//
// storage=radial: the variant for hardware without depth cube maps, to measure the difference: an
// R32_FLOAT cube of light-to-caster distance (rendered with a D32 depth buffer per face), compared
// in the shader on a 2x2 Gather with bilinear weights and a receiver slope bias (no rasterizer
// bias reaches a colour target).
#include <stdexcept>

#include "cube/cube-faces.h"
#include "local-lights.h"
#include <sp/tech/technique.h>

namespace sp::tech {
namespace {

class CubeTechnique final : public Technique {
 public:
  std::string Name() const override { return "cube"; }

  std::vector<ParamSpec> Params() const override {
    return {
        {ParamSpec::Int, "light", "the point light shadowed (index into the scene's point lights = local light index)", "0", 0, kMaxLocalLights - 1, {}},
        {ParamSpec::Int, "resolution", "width and height of each cube face in texels", "512", 16, 8192, {}},
        {ParamSpec::Float, "near", "near plane of every face, in world units (casters closer to the light are not drawn)", "0.05", 1e-4, 1e3, {}},
        {ParamSpec::Int, "depth_bias", "D3D11 DepthBias (units of the depth format)", "200", -1e7, 1e7, {}},
        {ParamSpec::Float, "slope_bias", "D3D11 SlopeScaledDepthBias (storage=depth)", "2.0", -100, 100, {}},
        {ParamSpec::Choice, "storage", "depth: planar window z in a depth cube, hardware comparison; radial: distance in an R32_FLOAT cube, compared in the shader", "depth", 0, 0, {"depth", "radial"}},
        {ParamSpec::Float, "radial_bias", "storage=radial: constant bias in world units", "0.01", 0, 1e3, {}},
        {ParamSpec::Int, "cull_faces", "1: skip the faces whose frustum (widened by two texels, for the filter across edges) does not meet the camera's", "1", 0, 1, {}},
        {ParamSpec::Float, "radial_slope_bias", "storage=radial: bias in texel footprints times tan(angle to the light), at most 10", "1.5", 0, 100, {}},
    };
  }

  void Configure(Device& device, const ParamValues& p) override {
    light_ = uint32_t(p.getInt("light"));
    resolution_ = uint32_t(p.getInt("resolution"));
    near_ = p.getFloat("near");
    radial_ = p.getChoice("storage") == "radial";
    radialBias_ = p.getFloat("radial_bias");
    radialSlope_ = p.getFloat("radial_slope_bias");
    cullFaces_ = p.getInt("cull_faces") != 0;

    TEXTURE2D_DESC td;
    td.Width = td.Height = resolution_;
    td.ArraySize = 6;
    td.Format = radial_ ? FORMAT_R32_FLOAT : FORMAT_R32_TYPELESS;
    td.BindFlags = (radial_ ? BIND_RENDER_TARGET : BIND_DEPTH_STENCIL) | BIND_SHADER_RESOURCE;
    td.MiscFlags = RESOURCE_MISC_TEXTURECUBE;
    cube_ = device.CreateTexture2D(td);
    cube_->SetDebugName(radial_ ? "cube shadow map (radial distance)" : "cube shadow map");
    if (radial_) {
      for (uint32_t f = 0; f < 6; ++f) {
        RENDER_TARGET_VIEW_DESC rv;
        rv.Format = FORMAT_R32_FLOAT;
        rv.ViewDimension = RTV_DIMENSION_TEXTURE2DARRAY;
        rv.Texture2DArray = {0, f, 1};
        faceRtvs_.push_back(device.CreateRenderTargetView(cube_.get(), &rv));
      }
      TEXTURE2D_DESC dd;
      dd.Width = dd.Height = resolution_;
      dd.Format = FORMAT_D32_FLOAT;
      dd.BindFlags = BIND_DEPTH_STENCIL;
      radialDepth_ = device.CreateTexture2D(dd);
      radialDepth_->SetDebugName("cube radial pass depth");
      faces_.push_back(device.CreateDepthStencilView(radialDepth_.get()));
      ShaderBytecode vs = CompileTechniqueShader("cube/radial.hlsl", "vs_5_0", "VSMain");
      radialVs_ = device.CreateVertexShader(vs);
      radialPs_ = device.CreatePixelShader(CompileTechniqueShader("cube/radial.hlsl", "ps_5_0", "PSMain"));
    } else {
      faces_ = MakeSliceDepthViews(device, cube_.get());
    }
    SHADER_RESOURCE_VIEW_DESC sd;
    sd.Format = FORMAT_R32_FLOAT;
    sd.ViewDimension = SRV_DIMENSION_TEXTURECUBE;
    sd.TextureCube = {0, 1};
    srv_ = device.CreateShaderResourceView(cube_.get(), &sd);

    RASTERIZER_DESC rd;
    // The faces' (s, t, major) bases are mirror images of a camera's, so winding flips between
    // faces' conventions; draw both sides (open meshes cast from either side anyway).
    rd.CullMode = CULL_NONE;
    rd.FrontCounterClockwise = true;
    if (!radial_) {
      rd.DepthBias = p.getInt("depth_bias");
      rd.SlopeScaledDepthBias = p.getFloat("slope_bias");
    }
    rasterizer_ = device.CreateRasterizerState(rd);

    SAMPLER_DESC smp;
    smp.Filter = radial_ ? FILTER_MIN_MAG_MIP_POINT : FILTER_COMPARISON_MIN_MAG_LINEAR_MIP_POINT;
    smp.AddressU = smp.AddressV = smp.AddressW = TEXTURE_ADDRESS_CLAMP;
    smp.ComparisonFunc = radial_ ? COMPARISON_NEVER : COMPARISON_LESS_EQUAL;
    sampler_ = device.CreateSamplerState(smp);
    constants_ = MakeConstantBuffer(device, sizeof(Constants), "CubeShadow constants");
  }

  void RenderShadows(DeviceContext& ctx, SceneDrawer& drawer, const FrameInputs& frame) override {
    GpuTimer::Scope timed(frame.timer, ctx, "shadow");
    const LocalLight& l = ShadowedPointLight("cube", light_, near_, frame);
    Constants c{l.position, cube::DepthA(near_, l.range), cube::DepthB(near_, l.range), float(resolution_), light_, l.range, radialBias_, radialSlope_, {}};
    ctx.UpdateSubresource(constants_.get(), 0, nullptr, &c, 0, 0);

    ShaderResourceView* none = nullptr;
    ctx.PSSetShaderResources(0, 1, &none);
    VIEWPORT vp{0, 0, float(resolution_), float(resolution_), 0, 1};
    ctx.RSSetViewports(1, &vp);
    ctx.RSSetState(rasterizer_.get());
    ctx.OMSetDepthStencilState(nullptr, 0);
    trianglesSubmitted_ = 0;
    const std::vector<scene::Instance>& instances = frame.scene->instances;
    const glm::mat4 camera = frame.cameraProj * frame.cameraView;
    for (int f = 0; f < 6; ++f) {
      glm::mat4 viewProj = cube::FaceViewProj(f, l.position, near_, l.range);
      // A skipped face is still cleared (to lit), so no earlier frame's depths remain in it.
      bool skip = cullFaces_ && !FaceMeetsCamera(f, l, camera);
      auto keep = [&](uint32_t i) { return !skip && InFrustum(viewProj, instances[i].worldBounds); };
      if (radial_) {
        RenderTargetView* rtv = faceRtvs_[f].get();
        ctx.OMSetRenderTargets(1, &rtv, faces_[0].get());
        const float far[4] = {3.0e38f, 0, 0, 0};  // nothing: lit at any distance
        ctx.ClearRenderTargetView(rtv, far);
        ctx.ClearDepthStencilView(faces_[0].get(), CLEAR_DEPTH, 1.0f, 0);
        ctx.PSSetConstantBuffers(2, {constants_.get()});
        trianglesSubmitted_ += drawer.DrawDepth(ctx, viewProj, keep, {radialVs_.get(), radialPs_.get()});
      } else {
        ctx.OMSetRenderTargets(0, nullptr, faces_[f].get());
        ctx.ClearDepthStencilView(faces_[f].get(), CLEAR_DEPTH, 1.0f, 0);
        trianglesSubmitted_ += drawer.DrawDepth(ctx, viewProj, keep);
      }
    }
  }

  std::string LightingInclude() const override { return "cube/shadow.hlsli"; }
  std::vector<hlsl::Define> LightingDefines() const override { return {{"SP_CUBE_RADIAL", radial_ ? "1" : "0"}}; }

  void BindLighting(DeviceContext& ctx) override {
    ctx.PSSetConstantBuffers(2, {constants_.get()});
    ctx.PSSetShaderResources(0, {srv_.get()});
    ctx.PSSetSamplers(0, {sampler_.get()});
  }

  // The cube, and with storage=radial the depth buffer of its passes.
  ShadowStats Stats() const override { return {uint64_t(resolution_) * resolution_ * 4 * (radial_ ? 7 : 6), trianglesSubmitted_}; }
  std::vector<ShadowLayer> Layers() const override { return std::vector<ShadowLayer>(6, {resolution_, resolution_}); }
  int LabLocalLight(const scene::Scene&) const override { return int(light_); }  // point lights come first

 private:
  // A world box is outside a face's frustum when its 8 corners are all outside one clip plane
  // (each plane is linear in the world point, so this is exact for the box).
  static bool InFrustum(const glm::mat4& viewProj, const scene::Bounds& b) {
    glm::vec3 corners[8];
    b.corners(corners);
    glm::vec4 c[8];
    for (int i = 0; i < 8; ++i) c[i] = viewProj * glm::vec4(corners[i], 1.0f);
    auto allOutside = [&](auto outside) {
      for (const glm::vec4& p : c)
        if (!outside(p)) return false;
      return true;
    };
    return !(allOutside([](const glm::vec4& p) { return p.x > p.w; }) || allOutside([](const glm::vec4& p) { return p.x < -p.w; }) ||
             allOutside([](const glm::vec4& p) { return p.y > p.w; }) || allOutside([](const glm::vec4& p) { return p.y < -p.w; }) ||
             allOutside([](const glm::vec4& p) { return p.z < 0; }) || allOutside([](const glm::vec4& p) { return p.z > p.w; }));
  }

  // Whether face f's frustum, widened by two texels each side (the seamless 2x2 filter reads one
  // texel past an edge), may meet the camera's: false when the camera frustum's 8 corners lie
  // outside one plane of the face frustum, or the face pyramid's 5 corners (light, far corners)
  // outside one plane of the camera's (a conservative separating-plane test).
  bool FaceMeetsCamera(int f, const LocalLight& l, const glm::mat4& camera) const {
    const float widen = 1.0f + 4.0f / float(resolution_);
    glm::mat4 face = cube::FaceViewProj(f, l.position, near_, l.range);
    glm::mat4 inv = glm::inverse(camera);
    glm::vec4 cam[8];
    for (int i = 0; i < 8; ++i) {
      glm::vec4 p = inv * glm::vec4(i & 1 ? 1.0f : -1.0f, i & 2 ? 1.0f : -1.0f, i & 4 ? 1.0f : 0.0f, 1.0f);
      cam[i] = face * (p / p.w);
    }
    auto allOutside = [](const glm::vec4* c, int n, auto outside) {
      for (int i = 0; i < n; ++i)
        if (!outside(c[i])) return false;
      return true;
    };
    if (allOutside(cam, 8, [&](const glm::vec4& p) { return p.x > widen * p.w; }) || allOutside(cam, 8, [&](const glm::vec4& p) { return p.x < -widen * p.w; }) ||
        allOutside(cam, 8, [&](const glm::vec4& p) { return p.y > widen * p.w; }) || allOutside(cam, 8, [&](const glm::vec4& p) { return p.y < -widen * p.w; }) ||
        allOutside(cam, 8, [](const glm::vec4& p) { return p.w < 0; }) || allOutside(cam, 8, [](const glm::vec4& p) { return p.z > p.w; }))
      return false;
    cube::FaceAxes ax = cube::Face(f);
    glm::vec4 pyr[5] = {camera * glm::vec4(l.position, 1.0f)};
    for (int i = 0; i < 4; ++i) {
      glm::vec3 d = ax.major + widen * ((i & 1 ? 1.0f : -1.0f) * ax.s + (i & 2 ? 1.0f : -1.0f) * ax.t);
      pyr[i + 1] = camera * glm::vec4(l.position + l.range * d, 1.0f);
    }
    return !(allOutside(pyr, 5, [](const glm::vec4& p) { return p.x > p.w; }) || allOutside(pyr, 5, [](const glm::vec4& p) { return p.x < -p.w; }) ||
             allOutside(pyr, 5, [](const glm::vec4& p) { return p.y > p.w; }) || allOutside(pyr, 5, [](const glm::vec4& p) { return p.y < -p.w; }) ||
             allOutside(pyr, 5, [](const glm::vec4& p) { return p.z < 0; }) || allOutside(pyr, 5, [](const glm::vec4& p) { return p.z > p.w; }));
  }

  // cbuffer CubeShadow in shaders-hlsl/cube/shadow.hlsli.
  struct Constants {
    glm::vec3 lightPosition;
    float depthA;
    float depthB;
    float faceSize;
    uint32_t lightIndex;
    float range;
    float radialBias, radialSlope;
    float pad[2];
  };
  static_assert(sizeof(Constants) == 48);

  uint32_t light_ = 0, resolution_ = 0;
  float near_ = 0.05f;
  bool radial_ = false;
  float radialBias_ = 0, radialSlope_ = 0;
  Ref<Texture2D> cube_, radialDepth_;
  std::vector<Ref<DepthStencilView>> faces_;  // depth: one per face; radial: the passes' depth buffer
  std::vector<Ref<RenderTargetView>> faceRtvs_;
  Ref<VertexShader> radialVs_;
  Ref<PixelShader> radialPs_;
  Ref<ShaderResourceView> srv_;
  Ref<RasterizerState> rasterizer_;
  Ref<SamplerState> sampler_;
  Ref<Buffer> constants_;
  bool cullFaces_ = true;
  uint64_t trianglesSubmitted_ = 0;
};

}  // namespace

std::unique_ptr<Technique> MakeCubeTechnique() { return std::make_unique<CubeTechnique>(); }

}  // namespace sp::tech
