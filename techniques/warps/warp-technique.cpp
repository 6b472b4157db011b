// The warp techniques (psm, lispsm, tsm): fitting, the shadow passes and the lighting bindings;
// see warp-technique.h.
#include "warp-technique.h"

#include <algorithm>

namespace sp::tech::warps {

namespace {

// cbuffer WarpShadow in shaders-hlsl/warps/shadow.hlsli.
struct Constants {
  glm::mat4 viewProj[kMaxWarpCascades];  // world -> clip of each cascade (perspective w)
  glm::vec4 linearDepth[kMaxWarpCascades];
  glm::vec4 splitFar;       // view depth where each cascade ends
  glm::vec4 cameraForward;  // w: cascade count
  glm::vec4 settings;       // linear depth (0/1), resolution, receiver-plane bias (0/1), unused
};
static_assert(sizeof(Constants) == 368);

// cbuffer WarpLinearDepth in shaders-hlsl/warps/depth-linear.hlsl.
struct LinearConstants {
  glm::vec4 linearDepth;
  glm::vec4 bias;  // constant, slope
};

// Whether a fit's map is a mirror image of the light view (x right, y up, as basic's): the sign
// of the determinant of its 2D homography on light-view (X, Y, 1). w > 0 over everything the
// fit maps, so this sign is the orientation of the whole map.
bool Mirrored(const WarpFit& fit) {
  glm::mat4 onLight = fit.viewProj * glm::inverse(fit.lightView);
  glm::mat3 h;
  const int rows[3] = {0, 1, 3};
  const int cols[3] = {0, 1, 3};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) h[c][r] = onLight[cols[c]][rows[r]];
  return glm::determinant(h) < 0.0f;
}

}  // namespace

void WarpTechnique::Configure(Device& device, const ParamValues& params) {
  settings_ = WarpSettingsFrom(warp_, params);
  const uint32_t n = settings_.resolution;
  TEXTURE2D_DESC td;
  td.Width = td.Height = n;
  td.ArraySize = uint32_t(settings_.cascades);
  td.Format = FORMAT_R32_TYPELESS;
  td.BindFlags = BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE;
  map_ = device.CreateTexture2D(td);
  map_->SetDebugName((std::string(WarpName(warp_)) + " cascade array").c_str());
  dsvs_ = MakeSliceDepthViews(device, map_.get());
  srv_ = MakeSliceArraySrv(device, map_.get());

  RASTERIZER_DESC rd;
  rd.FrontCounterClockwise = true;  // glTF winding, as in the lit pass
  if (!settings_.linearDepth) {
    rd.DepthBias = settings_.depthBias;
    rd.SlopeScaledDepthBias = settings_.slopeBias;
  }
  // Casters between the light and a cascade's near plane are pancaked onto it and still cast.
  rd.DepthClipEnable = false;
  rasterizer_ = device.CreateRasterizerState(rd);
  rd.FrontCounterClockwise = false;
  mirroredRasterizer_ = device.CreateRasterizerState(rd);

  sampler_ = MakeShadowComparisonSampler(device);
  constants_ = MakeConstantBuffer(device, sizeof(Constants), "WarpShadow constants");
  linearVs_ = nullptr;
  linearPs_ = nullptr;
  linearConstants_.clear();
  if (settings_.linearDepth) {
    linearVs_ = device.CreateVertexShader(CompileTechniqueShader("warps/depth-linear.hlsl", "vs_5_0", "VSMain"));
    linearPs_ = device.CreatePixelShader(CompileTechniqueShader("warps/depth-linear.hlsl", "ps_5_0", "PSMain"));
    // One buffer per cascade: each draw of the frame reads its own row.
    for (int c = 0; c < settings_.cascades; ++c)
      linearConstants_.push_back(MakeConstantBuffer(device, sizeof(LinearConstants), "WarpLinearDepth constants"));
  }
  fits_.clear();
  splits_.clear();
}

void WarpTechnique::RenderShadows(DeviceContext& ctx, SceneDrawer& drawer, const FrameInputs& frame) {
  GpuTimer::Scope timed(frame.timer, ctx, "shadow");
  const scene::Scene& scene = *frame.scene;
  const float aspect = frame.height ? float(frame.width) / float(frame.height) : 1.0f;
  // The view range as csm splits it (unstabilized: a warp is refitted every frame anyway).
  const float farZ = csm::ClippedFar(frame.camera, scene.bounds, false);
  splits_ = csm::SplitDistances(settings_.split, settings_.cascades, frame.camera.nearZ, std::max(farZ, frame.camera.nearZ * 1.001f), settings_.lambda);
  fits_.clear();
  Constants k{};
  for (int c = 0; c < settings_.cascades; ++c) {
    WarpInput in = MakeWarpInput(frame.camera, aspect, frame.light.direction, scene.bounds, splits_[c], splits_[c + 1]);
    fits_.push_back(FitWarp(in, warp_, settings_.params));
    k.viewProj[c] = fits_.back().viewProj;
    k.linearDepth[c] = fits_.back().linearDepth;
    k.splitFar[c] = splits_[c + 1];
  }
  k.cameraForward = glm::vec4(frame.camera.forward(), float(settings_.cascades));
  k.settings = glm::vec4(settings_.linearDepth ? 1.0f : 0.0f, float(settings_.resolution), settings_.receiverPlane ? 1.0f : 0.0f, 0.0f);
  ctx.UpdateSubresource(constants_.get(), 0, nullptr, &k, 0, 0);

  // The maps are read by the previous frame's lit pass; unbind them before writing.
  ShaderResourceView* none = nullptr;
  ctx.PSSetShaderResources(0, 1, &none);
  ctx.OMSetDepthStencilState(nullptr, 0);
  const float n = float(settings_.resolution);
  VIEWPORT vp{0, 0, n, n, 0, 1};
  ctx.RSSetViewports(1, &vp);
  triangles_ = 0;
  for (int c = 0; c < settings_.cascades; ++c) {
    // Only what can shadow this cascade's body: its map's trapezoid in the light view, not beyond
    // the body's far side.
    auto casts = [&](uint32_t i) { return MayCastInto(fits_[c], scene.instances[i].worldBounds); };
    ctx.OMSetRenderTargets(0, nullptr, dsvs_[c].get());
    ctx.ClearDepthStencilView(dsvs_[c].get(), CLEAR_DEPTH, 1.0f, 0);
    ctx.RSSetState(Mirrored(fits_[c]) ? mirroredRasterizer_.get() : rasterizer_.get());
    if (settings_.linearDepth) {
      LinearConstants lc{fits_[c].linearDepth, glm::vec4(settings_.linearBias, settings_.linearSlopeBias, 0.0f, 0.0f)};
      ctx.UpdateSubresource(linearConstants_[c].get(), 0, nullptr, &lc, 0, 0);
      ctx.VSSetConstantBuffers(2, {linearConstants_[c].get()});
      ctx.PSSetConstantBuffers(2, {linearConstants_[c].get()});
      triangles_ += drawer.DrawDepth(ctx, fits_[c].viewProj, casts, {linearVs_.get(), linearPs_.get()});
    } else {
      triangles_ += drawer.DrawDepth(ctx, fits_[c].viewProj, casts);
    }
  }
}

// The filter is compiled in (as csm's); depth mode and receiver plane are uniform branches.
std::vector<hlsl::Define> WarpTechnique::LightingDefines() const {
  return {{"SHADOW_FILTER", std::to_string(settings_.filter)}, {"SHADOW_KERNEL", std::to_string(settings_.filter == 0 ? 3 : settings_.kernel)}};
}

void WarpTechnique::BindLighting(DeviceContext& ctx) {
  ctx.PSSetConstantBuffers(2, {constants_.get()});
  ctx.PSSetShaderResources(0, {srv_.get()});
  ctx.PSSetSamplers(0, {sampler_.get()});
}

ShadowStats WarpTechnique::Stats() const {
  return {uint64_t(settings_.resolution) * settings_.resolution * uint32_t(settings_.cascades) * 4, triangles_};
}

std::vector<ShadowLayer> WarpTechnique::Layers() const {
  return std::vector<ShadowLayer>(size_t(settings_.cascades), ShadowLayer{settings_.resolution, settings_.resolution});
}

}  // namespace sp::tech::warps

namespace sp::tech {
std::unique_ptr<Technique> MakePsmTechnique() { return std::make_unique<warps::WarpTechnique>(warps::Warp::Psm); }
std::unique_ptr<Technique> MakeLispsmTechnique() { return std::make_unique<warps::WarpTechnique>(warps::Warp::Lispsm); }
std::unique_ptr<Technique> MakeTsmTechnique() { return std::make_unique<warps::WarpTechnique>(warps::Warp::Tsm); }
}  // namespace sp::tech
