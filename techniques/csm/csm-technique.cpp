#include "csm-technique.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sp::tech::csm {

namespace {

// cbuffer CsmShadow in shaders-hlsl/csm/shadow.hlsli.
struct Constants {
  glm::mat4 lightView;
  glm::vec4 toMapScale[8];   // xyz: light view -> (slice u, slice v, depth); w: map-select margin (region uv)
  glm::vec4 toMapOffset[8];
  glm::vec4 region[8];       // slice uv of the cascade's region: min.xy, size.xy
  glm::vec4 cascade[8];      // split near, split far (view depth), world texel size, array slice
  glm::vec4 cameraForward;   // w: cascade count
  glm::vec4 settings;        // select, blend, bias mode, normal offset (texels)
  glm::vec4 mapInfo;         // 1 / texture width, 1 / texture height, unused, region texels
  glm::vec4 pcss;            // filter=pcss: 2 tan(angle / 2), search taps, max kernel, unused
};
static_assert(sizeof(Constants) == 640);

}  // namespace

void CsmTechnique::Configure(Device& device, const ParamValues& params) {
  settings_ = SettingsFrom(params);
  const uint32_t n = settings_.fit.resolution;
  const uint32_t cascades = uint32_t(settings_.fit.cascades);
  if (settings_.storage == Storage::Atlas) {
    columns_ = uint32_t(std::ceil(std::sqrt(double(cascades))));
    rows_ = (cascades + columns_ - 1) / columns_;
    arraySize_ = 1;
  } else {
    columns_ = rows_ = 1;
    arraySize_ = cascades;
  }
  textureWidth_ = columns_ * n;
  textureHeight_ = rows_ * n;
  if (textureWidth_ > 16384 || textureHeight_ > 16384)
    throw std::invalid_argument("technique 'csm': an atlas of " + std::to_string(cascades) + " cascades of resolution=" + std::to_string(n) + " is " +
                                std::to_string(textureWidth_) + "x" + std::to_string(textureHeight_) +
                                " texels, over the 16384 limit; lower resolution or use storage=array");

  const uint32_t samples = settings_.moments ? settings_.moment.msaa : 1u;
  if (samples > 1 && device.CheckMultisampleQualityLevels(FORMAT_D32_FLOAT, samples) == 0)
    throw std::invalid_argument("technique 'csm': msaa=" + std::to_string(samples) + " needs " + std::to_string(samples) +
                                "x D32_FLOAT depth, which this device does not offer; use msaa=1");
  moments_.reset();
  depthSrv_ = nullptr;
  blurRadii_.assign(cascades, 0.0f);
  TEXTURE2D_DESC td;
  if (settings_.moments) {
    MomentMapDesc md;
    md.options = settings_.moment;
    md.width = md.height = n;
    md.layers = cascades;  // storage=array (SettingsFrom)
    md.anisotropy = uint32_t(settings_.anisotropy);
    moments_ = std::make_unique<MomentMaps>(device, md);
    td = moments_->DepthDesc();
  } else {
    td.Width = textureWidth_;
    td.Height = textureHeight_;
    td.ArraySize = arraySize_;
    td.Format = FORMAT_R32_TYPELESS;
    td.BindFlags = BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE;
  }
  map_ = device.CreateTexture2D(td);
  map_->SetDebugName(settings_.moments ? "csm cascade depth (moments)" : settings_.storage == Storage::Atlas ? "csm shadow atlas" : "csm cascade array");
  dsvs_ = MakeSliceDepthViews(device, map_.get());
  if (settings_.moments) {
    depthSrv_ = MomentMaps::MakeDepthSrv(device, map_.get());
    srv_ = nullptr;  // the lit pass reads the moments, not the depth
  } else {
    srv_ = MakeSliceArraySrv(device, map_.get());
  }
  device_ = &device;
  hpsm_.reset();
  if (settings_.hpsm.accel != ShadowAccel::None) hpsm_ = std::make_unique<HpsmMaps>(device, settings_.hpsm, textureWidth_, textureHeight_, arraySize_);

  RASTERIZER_DESC rd;
  rd.FrontCounterClockwise = true;  // glTF winding, as in the lit pass
  if (!settings_.moments) {
    // Moments need no depth bias: a receiver at the stored depth is lit by construction
    // (Chebyshev gives 1 at or in front of the mean, ESM saturates), and a bias would only move
    // the occluders away from their receivers (peter-panning) and widen the depth distribution.
    rd.DepthBias = settings_.depthBias;
    // The other bias modes correct the slope in the lookup instead (normal offset, receiver plane).
    rd.SlopeScaledDepthBias = settings_.bias == Bias::Slope ? settings_.slopeBias : 0.0f;
  }
  // Casters between the light and a cascade's near plane are pancaked onto it and still cast
  // (with moments too: the clamped depth 0 is a valid occluder depth for the warps).
  rd.DepthClipEnable = false;
  rasterizer_ = device.CreateRasterizerState(rd);

  sampler_ = MakeShadowComparisonSampler(device);
  constants_ = MakeConstantBuffer(device, sizeof(Constants), "CsmShadow constants");
  cascadeTriangles_.assign(cascades, 0);
}

std::vector<hlsl::Define> CsmTechnique::Defines(const CsmSettings& s) {
  // Everything else (selection, blending, bias mode, storage) is a uniform branch on constants, so
  // the parameter space compiles to 17 comparison variants instead of hundreds; the moment filters
  // add one per kind, precision, exponent and bleed setting (MomentDefines).
  if (s.moments) {
    std::vector<hlsl::Define> d = MomentDefines(s.moment);
    d.push_back({"CSM_MOMENTS", "1"});
    return d;
  }
  int kernel = s.filter == 0 || s.filter == kPcssFilter ? 3 : s.kernel;
  std::vector<hlsl::Define> d = {{"SHADOW_FILTER", std::to_string(s.filter)}, {"SHADOW_KERNEL", std::to_string(kernel)}};
  for (const hlsl::Define& h : HpsmDefines(s.hpsm)) d.push_back(h);
  return d;
}

CascadeRegion CsmTechnique::region(int c) const {
  const uint32_t n = settings_.fit.resolution;
  if (settings_.storage == Storage::Array) return {uint32_t(c), 0, 0};
  return {0, (uint32_t(c) % columns_) * n, (uint32_t(c) / columns_) * n};
}

void CsmTechnique::WriteConstants(DeviceContext& ctx, const FrameInputs& frame) {
  Constants k{};
  k.lightView = fit_.lightView;
  const float n = float(settings_.fit.resolution);
  const float w = float(textureWidth_), h = float(textureHeight_);
  for (size_t c = 0; c < fit_.cascades.size(); ++c) {
    const CascadeFit& f = fit_.cascades[c];
    CascadeRegion r = region(int(c));
    glm::vec2 rmin(float(r.x) / w, float(r.y) / h), rsize(n / w, n / h);
    // Light view -> region uv: u grows with x, v (row 0 at the top) against y; depth as the
    // orthographic projection (distance -z from zNear to zFar).
    glm::vec3 scale(1.0f / (f.max.x - f.min.x), -1.0f / (f.max.y - f.min.y), -1.0f / (f.zFar - f.zNear));
    glm::vec3 offset(-f.min.x * scale.x, f.max.y / (f.max.y - f.min.y), -f.zNear / (f.zFar - f.zNear));
    k.toMapScale[c] = glm::vec4(scale.x * rsize.x, scale.y * rsize.y, scale.z, float(f.padTexels) / n);
    k.toMapOffset[c] = glm::vec4(offset.x * rsize.x + rmin.x, offset.y * rsize.y + rmin.y, offset.z, 0.0f);
    k.region[c] = glm::vec4(rmin, rsize);
    k.cascade[c] = glm::vec4(f.splitNear, f.splitFar, f.texelWorld, float(r.slice));
  }
  k.cameraForward = glm::vec4(frame.camera.forward(), float(fit_.cascades.size()));
  k.settings = glm::vec4(settings_.select == Select::Map ? 1.0f : 0.0f, settings_.fit.blend, float(int(settings_.bias)), settings_.normalOffset);
  k.mapInfo = glm::vec4(1.0f / w, 1.0f / h, 0.0f, n);
  k.pcss = CascadePcssRow(settings_.pcss);
  ctx.UpdateSubresource(constants_.get(), 0, nullptr, &k, 0, 0);
}

void CsmTechnique::RenderShadows(DeviceContext& ctx, SceneDrawer& drawer, const FrameInputs& frame) {
  DrawCascades(ctx, drawer, frame);
  if (hpsm_) {
    ctx.OMSetRenderTargets(0, nullptr, nullptr);
    GpuTimer::Scope built(frame.timer, ctx, "hpsm");
    hpsm_->Build(ctx, srv_.get());
  }
  if (!moments_) return;
  // Convert reads the depth through an SRV: it must not stay bound for writing.
  ctx.OMSetRenderTargets(0, nullptr, nullptr);
  const uint32_t n = settings_.fit.resolution;
  for (size_t c = 0; c < fit_.cascades.size(); ++c) {
    const CascadeFit& f = fit_.cascades[c];
    // The same world radius in every cascade, within what the fit padded for it. (texelWorld is
    // the larger axis's texel: with stabilize=0 and oblong texels the other axis blurs less.)
    float padded = float(f.padTexels - settings_.fit.padTexels);
    blurRadii_[c] = std::min(BlurRadiusTexels(settings_.moment.blur, f.texelWorld * float(n), n), padded);
  }
  moments_->Convert(ctx, depthSrv_.get(), blurRadii_, frame.timer);
}

void CsmTechnique::DrawCascades(DeviceContext& ctx, SceneDrawer& drawer, const FrameInputs& frame) {
  GpuTimer::Scope timed(frame.timer, ctx, "shadow");
  const scene::Scene& scene = *frame.scene;
  float aspect = frame.height ? float(frame.width) / float(frame.height) : 1.0f;
  fit_ = FitCascades(scene, frame.camera, aspect, frame.light.direction, settings_.fit, fit_.cascades.empty() ? nullptr : &fit_);
  WriteConstants(ctx, frame);

  // Instance bounds in the shared light view, once for all cascades.
  std::vector<scene::Bounds> casters(scene.instances.size());
  for (size_t i = 0; i < casters.size(); ++i) casters[i] = scene.instances[i].worldBounds.transformed(fit_.lightView);

  // The maps (t0; with accel t1 too) are read by the previous frame's lit pass; unbind them before writing.
  ShaderResourceView* none[2] = {};
  ctx.PSSetShaderResources(0, 2, none);
  ctx.RSSetState(rasterizer_.get());
  ctx.OMSetDepthStencilState(nullptr, 0);
  if (settings_.storage == Storage::Atlas) {
    ctx.OMSetRenderTargets(0, nullptr, dsvs_[0].get());
    ctx.ClearDepthStencilView(dsvs_[0].get(), CLEAR_DEPTH, 1.0f, 0);
  }
  const float n = float(settings_.fit.resolution);
  for (size_t c = 0; c < fit_.cascades.size(); ++c) {
    const CascadeFit& f = fit_.cascades[c];
    CascadeRegion r = region(int(c));
    if (settings_.storage == Storage::Array) {
      ctx.OMSetRenderTargets(0, nullptr, dsvs_[c].get());
      ctx.ClearDepthStencilView(dsvs_[c].get(), CLEAR_DEPTH, 1.0f, 0);
    }
    VIEWPORT vp{float(r.x), float(r.y), n, n, 0, 1};
    ctx.RSSetViewports(1, &vp);
    // A slice with no receivers is read by no pixel under interval selection (map selection may
    // still find points of other slices in its map).
    bool unread = f.noReceivers && settings_.select == Select::Interval;
    cascadeTriangles_[c] = unread ? 0 : drawer.DrawDepth(ctx, f.viewProj, [&](uint32_t i) { return MayCastInto(f, casters[i]); });
  }
}

void CsmTechnique::BindLighting(DeviceContext& ctx) {
  ctx.PSSetConstantBuffers(2, {constants_.get()});
  ctx.PSSetShaderResources(0, {moments_ ? moments_->Srv() : srv_.get(), hpsm_ ? hpsm_->srv() : nullptr});
  ctx.PSSetSamplers(0, {moments_ ? moments_->Sampler() : sampler_.get()});
  if (hpsm_) hpsm_->BindCounters(ctx);
}

HpsmCounts CsmTechnique::HpsmDecisions() const { return hpsm_ ? hpsm_->ReadCounters(*device_->GetImmediateContext()) : HpsmCounts{}; }

ShadowStats CsmTechnique::Stats() const {
  ShadowStats s;
  if (!map_) return s;
  const TEXTURE2D_DESC& td = map_->GetDesc();
  // The depth (all its samples), and with moment filters the moment array, mips and blur target.
  s.memoryBytes = uint64_t(td.Width) * td.Height * td.ArraySize * td.SampleDesc.Count * 4;
  if (moments_) s.memoryBytes += moments_->MemoryBytes();
  if (hpsm_) s.memoryBytes += hpsm_->memoryBytes();
  for (uint64_t t : cascadeTriangles_) s.trianglesSubmitted += t;
  return s;
}

std::vector<ShadowLayer> CsmTechnique::Layers() const {
  return std::vector<ShadowLayer>(size_t(settings_.fit.cascades), ShadowLayer{settings_.fit.resolution, settings_.fit.resolution});
}

}  // namespace sp::tech::csm

namespace sp::tech {
std::unique_ptr<Technique> MakeCsmTechnique() { return std::make_unique<csm::CsmTechnique>(); }
}  // namespace sp::tech
