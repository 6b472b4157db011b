#include "sdsm/sdsm-technique.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace sp::tech::sdsm {
namespace {

// cbuffer SdsmFit in shaders-hlsl/sdsm/fit.hlsl.
struct FitConstants {
  glm::mat4 lightView;  // as stored by glm: the shader copies the columns verbatim
  glm::vec4 cornerRay[4];
  glm::vec4 cameraOrigin;
  glm::vec4 gridOrigin;
  glm::vec4 cameraForward;
  glm::vec4 settings;
  glm::vec4 params;
  glm::vec4 blur;
  glm::vec4 pcss;  // csmPcss, written into the CsmShadow copy as is
};
static_assert(sizeof(FitConstants) == 240);
static_assert(kFitBytes - kFitBlurOffset == kMomentBlurRadiiBytes);
static_assert(kMaxPartitions <= kMaxMomentLayers);

}  // namespace

void SdsmTechnique::Configure(Device& device, const ParamValues& params) {
  settings_ = SdsmSettingsFrom(params);
  device_ = &device;
  const csm::CsmSettings& cs = settings_.csm;
  n_ = cs.fit.resolution;
  k_ = settings_.partitions();

  const uint32_t samples = cs.moments ? cs.moment.msaa : 1u;
  if (samples > 1 && device.CheckMultisampleQualityLevels(FORMAT_D32_FLOAT, samples) == 0)
    throw std::invalid_argument("technique 'sdsm': msaa=" + std::to_string(samples) + " needs " + std::to_string(samples) +
                                "x D32_FLOAT depth, which this device does not offer; use msaa=1");
  moments_.reset();
  TEXTURE2D_DESC td;
  if (cs.moments) {
    MomentMapDesc md;
    md.options = cs.moment;
    md.width = md.height = n_;
    md.layers = k_;
    md.anisotropy = uint32_t(cs.anisotropy);
    moments_ = std::make_unique<MomentMaps>(device, md);
    td = moments_->DepthDesc();
  } else {
    td.Width = td.Height = n_;
    td.ArraySize = k_;
    td.Format = FORMAT_R32_TYPELESS;
    td.BindFlags = BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE;
  }
  map_ = device.CreateTexture2D(td);
  map_->SetDebugName(cs.moments ? "sdsm partition depth (moments)" : "sdsm partition array");
  dsvs_ = MakeSliceDepthViews(device, map_.get());
  srv_ = depthSrvForMoments_ = nullptr;
  if (cs.moments) {
    depthSrvForMoments_ = MomentMaps::MakeDepthSrv(device, map_.get());
  } else {
    srv_ = MakeSliceArraySrv(device, map_.get());
  }
  hpsm_.reset();
  if (cs.hpsm.accel != ShadowAccel::None) hpsm_ = std::make_unique<HpsmMaps>(device, cs.hpsm, n_, n_, k_);

  // Shadow passes as csm's: bias for the comparison filters only, and depth clamping so casters
  // above a partition's box (tight boxes hold receivers only) are pancaked onto its near plane.
  RASTERIZER_DESC rd;
  rd.FrontCounterClockwise = true;
  if (!cs.moments) {
    rd.DepthBias = cs.depthBias;
    rd.SlopeScaledDepthBias = cs.bias == csm::Bias::Slope ? cs.slopeBias : 0.0f;
  }
  rd.DepthClipEnable = false;
  shadowRasterizer_ = device.CreateRasterizerState(rd);
  RASTERIZER_DESC pd;
  pd.FrontCounterClockwise = true;  // the lit pass's state: the pre-pass must see the same surfaces
  prepassRasterizer_ = device.CreateRasterizerState(pd);

  sampler_ = MakeShadowComparisonSampler(device);
  constants_ = MakeConstantBuffer(device, sizeof(CsmShadowConstants), "sdsm CsmShadow constants");

  analysis_.reset();
  readback_.reset();
  if (settings_.cull != CullMode::Conservative) analysis_ = std::make_unique<DepthAnalysis>(device);
  if (settings_.cull == CullMode::Readback) readback_ = std::make_unique<AnalysisReadback>(device, ReadbackMode::Stall);
  if (settings_.cull == CullMode::Latent) readback_ = std::make_unique<AnalysisReadback>(device, ReadbackMode::Latent, settings_.latency);
  records_.assign(settings_.latency + 1, FrameRecord{});

  culler_.reset();
  cullerScene_ = nullptr;
  fitBuffer_ = fitConstants_ = nullptr;
  fitUav_ = nullptr;
  fitSrv_ = nullptr;
  if (settings_.cull == CullMode::Gpu) {
    fitBuffer_ = MakeRawBuffer(device, kFitBytes, BIND_UNORDERED_ACCESS | BIND_SHADER_RESOURCE, "sdsm fit (bounds, CsmShadow, matrices, blur radii)");
    fitUav_ = MakeRawUav(device, fitBuffer_.get());
    fitSrv_ = MakeRawSrv(device, fitBuffer_.get());
    fitConstants_ = MakeConstantBuffer(device, sizeof(FitConstants), "SdsmFit constants");
    fitCs_ = device.CreateComputeShader(CompileTechniqueShader("sdsm/fit.hlsl", "cs_5_0", "FitPartitions"));
  }
  partitionTriangles_.assign(k_, 0);
  blurRadii_.assign(k_, 0.0f);
  fits_.clear();
  frame_ = 0;
}

glm::vec4 SdsmTechnique::LightingSettings() const {
  const csm::CsmSettings& cs = settings_.csm;
  return glm::vec4(0.0f /* interval selection */, cs.fit.blend, float(int(cs.bias)), cs.normalOffset);
}

FitParams SdsmTechnique::MakeFitParams(const glm::mat4& lightView) const {
  FitParams p;
  p.resolution = n_;
  p.padTexels = settings_.csm.fit.padTexels;
  p.dilation = settings_.dilation;
  p.quantize = settings_.quantize;
  p.gridOrigin = glm::vec3(lightView[3]);  // the world origin's light-view position
  p.blurWorld = settings_.csm.moments ? settings_.csm.moment.blur : 0.0f;
  p.blurMaxTexels = settings_.csm.fit.padWorldMaxTexels;
  if (settings_.csm.filter == kPcssFilter && !settings_.csm.moments) p.casterTop = sceneBounds_.transformed(lightView).max.z;
  return p;
}

std::vector<PartitionFit> SdsmTechnique::ConservativeFits(const FrameInputs& frame, const glm::mat4& lightView) const {
  const scene::Camera& cam = frame.camera;
  float nearZ = cam.nearZ;
  float farZ = std::max(csm::ClippedFar(cam, frame.scene->bounds, false), nearZ * 1.001f);
  std::vector<float> splits = csm::SplitDistances(csm::SplitScheme::Log, int(k_), nearZ, farZ, 0.0f);
  FitParams fp = MakeFitParams(lightView);
  FrustumRays rays = MakeFrustumRays(lightView, frame.cameraView, frame.cameraProj);
  std::vector<PartitionFit> fits;
  for (uint32_t p = 0; p < k_; ++p) {
    LightBounds b = SliceBounds(rays, splits[p], splits[p + 1]);
    float splitFar = p + 1 == k_ ? std::max(splits[p + 1], cam.farZ) : splits[p + 1];
    fits.push_back(FitPartition(b, splits[p], splitFar, lightView, fp));
  }
  return fits;
}

std::vector<PartitionFit> SdsmTechnique::FitsFrom(const AnalysisResults& r, const glm::mat4& lightView, const glm::mat4& cameraView,
                                                  const glm::mat4& cameraProj, float cameraFar) const {
  FitParams fp = MakeFitParams(lightView);
  FrustumRays rays = MakeFrustumRays(lightView, cameraView, cameraProj);
  std::vector<PartitionFit> fits;
  bool valid = r.partitionCount == k_ && r.splits.size() == k_ + 1;
  for (uint32_t p = 0; p < k_; ++p) {
    LightBounds b = valid ? r.bounds[p] : LightBounds{};
    float s0 = valid ? r.splits[p] : 0.0f, s1 = valid ? r.splits[p + 1] : 0.0f;
    if (!settings_.tight && !b.empty()) {
      uint32_t samples = b.samples;
      b = SliceBounds(rays, s0, s1);
      b.samples = samples;
    }
    // As fit.hlsl: the last partition takes everything behind it.
    float splitFar = p + 1 == k_ ? std::max(s1, cameraFar) : s1;
    fits.push_back(FitPartition(b, s0, splitFar, lightView, fp));
  }
  return fits;
}

void SdsmTechnique::EnsureCameraDepth(Device& device, uint32_t w, uint32_t h) {
  if (cameraDepth_.texture && depthWidth_ == w && depthHeight_ == h) return;
  depthWidth_ = w;
  depthHeight_ = h;
  cameraDepth_ = MakeDepthMap(device, w, h, "sdsm camera depth");
}

void SdsmTechnique::DepthPrepass(DeviceContext& ctx, SceneDrawer& drawer, const FrameInputs& frame) {
  GpuTimer::Scope timed(frame.timer, ctx, "depth prepass");
  EnsureCameraDepth(*device_, frame.width, frame.height);
  ctx.OMSetRenderTargets(0, nullptr, cameraDepth_.dsv.get());
  ctx.ClearDepthStencilView(cameraDepth_.dsv.get(), CLEAR_DEPTH, 1.0f, 0);
  ctx.OMSetDepthStencilState(nullptr, 0);
  VIEWPORT vp{0, 0, float(frame.width), float(frame.height), 0, 1};
  ctx.RSSetViewports(1, &vp);
  ctx.RSSetState(prepassRasterizer_.get());
  drawer.DrawDepth(ctx, frame.cameraProj * frame.cameraView);
  ctx.OMSetRenderTargets(0, nullptr, nullptr);  // the analysis reads it
}

void SdsmTechnique::RenderShadows(DeviceContext& ctx, SceneDrawer& drawer, const FrameInputs& frame) {
  const scene::Camera& cam = frame.camera;
  glm::mat4 lightView = MakeLightView(cam.position, cam.forward(), cam.up, frame.light.direction);
  sceneBounds_ = frame.scene->bounds;
  // The maps are read by the previous frame's lit pass; unbind them before writing.
  ShaderResourceView* none[2] = {};
  ctx.PSSetShaderResources(0, 2, none);

  if (analysis_) {
    DepthPrepass(ctx, drawer, frame);
    analysisFrame_ = AnalysisFrame::Make(frame.cameraView, frame.cameraProj, lightView, frame.width, frame.height);
    analysisFrame_.nearZ = cam.nearZ;
    analysisFrame_.farZ = cam.farZ;
    AnalysisSettings as;
    as.partitions.scheme = settings_.partition;
    as.partitions.count = k_;
    analysis_->Run(ctx, cameraDepth_.srv.get(), analysisFrame_, as, frame.timer);
  }

  const CullMode mode = settings_.cull;
  bool unionCull = false;
  lightView_ = lightView;
  if (mode == CullMode::Gpu) {
    if (!culler_ || cullerScene_ != &drawer.gpu()) {
      culler_ = std::make_unique<CasterCuller>(*device_, drawer.gpu());
      cullerScene_ = &drawer.gpu();
    }
    RunGpuFit(ctx, frame);
    DrawGpu(ctx, frame);
  } else {
    if (mode == CullMode::Conservative) {
      fits_ = ConservativeFits(frame, lightView);
      unionCull = true;
    } else {
      int64_t capture = readback_->Captures(), before = readback_->LatestCapture();
      records_[size_t(capture) % records_.size()] = {lightView, frame.cameraView, frame.cameraProj, cam.farZ};
      {
        GpuTimer::Scope timed(frame.timer, ctx, "analysis");
        readback_->Capture(ctx, analysis_->results());
      }
      if (readback_->LatestCapture() != before) ++frameReadbacks_;
      if (readback_->Latest()) {
        // Latent results belong to their own frame's light frame and camera: fitted there.
        const FrameRecord& rec = records_[size_t(readback_->LatestCapture()) % records_.size()];
        lightView_ = rec.lightView;
        fits_ = FitsFrom(*readback_->Latest(), rec.lightView, rec.cameraView, rec.cameraProj, std::max(rec.cameraFar, cam.farZ));
      } else {
        fits_ = ConservativeFits(frame, lightView);  // latent, warming up
        unionCull = true;
      }
    }
    CsmShadowConstants k = MakeConstants(fits_, lightView_, cam.forward(), LightingSettings(), n_, CascadePcssRow(settings_.csm.pcss));
    ctx.UpdateSubresource(constants_.get(), 0, nullptr, &k, 0, 0);
    DrawCpu(ctx, drawer, frame, unionCull);
  }
  ConvertMoments(ctx, frame);
  if (hpsm_) {
    ctx.OMSetRenderTargets(0, nullptr, nullptr);
    GpuTimer::Scope built(frame.timer, ctx, "hpsm");
    hpsm_->Build(ctx, srv_.get());
  }
  ++frame_;
}

void SdsmTechnique::RunGpuFit(DeviceContext& ctx, const FrameInputs& frame) {
  {
    GpuTimer::Scope timed(frame.timer, ctx, "analysis");
    FrustumRays rays = MakeFrustumRays(lightView_, frame.cameraView, frame.cameraProj);
    FitConstants c{};
    c.lightView = lightView_;
    for (int i = 0; i < 4; ++i) c.cornerRay[i] = glm::vec4(rays.corner[i], 0.0f);
    FitParams fp = MakeFitParams(lightView_);
    c.cameraOrigin = glm::vec4(rays.origin, frame.camera.farZ);
    c.gridOrigin = glm::vec4(fp.gridOrigin, fp.quantize ? 1.0f : 0.0f);
    c.cameraForward = glm::vec4(frame.camera.forward(), float(k_));
    c.settings = LightingSettings();
    c.params = glm::vec4(float(n_), float(fp.padTexels), fp.dilation, settings_.tight ? 1.0f : 0.0f);
    c.blur = glm::vec4(fp.blurWorld, float(fp.blurMaxTexels), kMaxBlurRadiusTexels, 0.0f);
    c.pcss = glm::vec4(glm::vec3(CascadePcssRow(settings_.csm.pcss)), fp.casterTop);
    ctx.UpdateSubresource(fitConstants_.get(), 0, nullptr, &c, 0, 0);
    ctx.VSSetShaderResources(2, {nullptr});  // last frame's draws read the matrices there
    ctx.CSSetConstantBuffers(0, {fitConstants_.get()});
    ctx.CSSetShaderResources(0, {analysis_->resultsSrv()});
    ctx.CSSetUnorderedAccessViews(0, {fitUav_.get()});
    ctx.CSSetShader(fitCs_.get());
    ctx.Dispatch(1, 1, 1);
    ctx.CSSetUnorderedAccessViews(0, {nullptr});
    ctx.CSSetShaderResources(0, {nullptr});
    // The lit pass's constants straight from the GPU: a buffer-to-buffer copy, no CPU round trip.
    BOX box{kFitConstantsOffset, 0, 0, kFitMatricesOffset, 1, 1};
    ctx.CopySubresourceRegion(constants_.get(), 0, 0, 0, 0, fitBuffer_.get(), 0, &box);
  }
  // The culler reads the fitted boxes (padding, quantization and dilation included) in the
  // results layout at the start of the fit buffer.
  culler_->Cull(ctx, fitSrv_.get(), lightView_, k_, 0.0f, frame.timer);
}

void SdsmTechnique::ClearSlices(DeviceContext& ctx) {
  for (const Ref<DepthStencilView>& dsv : dsvs_) ctx.ClearDepthStencilView(dsv.get(), CLEAR_DEPTH, 1.0f, 0);
  ctx.RSSetState(shadowRasterizer_.get());
  ctx.OMSetDepthStencilState(nullptr, 0);
  VIEWPORT vp{0, 0, float(n_), float(n_), 0, 1};
  ctx.RSSetViewports(1, &vp);
}

void SdsmTechnique::DrawCpu(DeviceContext& ctx, SceneDrawer& drawer, const FrameInputs& frame, bool unionCull) {
  GpuTimer::Scope timed(frame.timer, ctx, "shadow");
  const scene::Scene& scene = *frame.scene;
  std::vector<scene::Bounds> casters(scene.instances.size());
  for (size_t i = 0; i < casters.size(); ++i) casters[i] = scene.instances[i].worldBounds.transformed(lightView_);
  std::vector<uint8_t> inUnion;
  if (unionCull) {
    inUnion.assign(casters.size(), 0);
    for (size_t i = 0; i < casters.size(); ++i)
      for (const PartitionFit& f : fits_) inUnion[i] |= f.MayCast(casters[i]) ? 1 : 0;
  }
  ClearSlices(ctx);
  for (uint32_t p = 0; p < k_; ++p) {
    partitionTriangles_[p] = 0;
    const PartitionFit& f = fits_[p];
    if (f.empty) continue;  // no pixel reads it
    ctx.OMSetRenderTargets(0, nullptr, dsvs_[p].get());
    auto keep = [&](uint32_t i) { return unionCull ? inUnion[i] != 0 : f.MayCast(casters[i]); };
    partitionTriangles_[p] = drawer.DrawDepth(ctx, f.viewProj, keep);
  }
}

void SdsmTechnique::DrawGpu(DeviceContext& ctx, const FrameInputs& frame) {
  GpuTimer::Scope timed(frame.timer, ctx, "shadow");
  ClearSlices(ctx);
  ctx.PSSetShader(nullptr);
  // Every partition is drawn: the CPU does not know which are empty (their records hold 0).
  for (uint32_t p = 0; p < k_; ++p) {
    ctx.OMSetRenderTargets(0, nullptr, dsvs_[p].get());
    culler_->DrawPartition(ctx, p, fitSrv_.get(), kFitMatricesOffset + p * 64);
  }
  ctx.VSSetShaderResources(0, {nullptr, nullptr, nullptr});
}

void SdsmTechnique::ConvertMoments(DeviceContext& ctx, const FrameInputs& frame) {
  if (!moments_) return;
  ctx.OMSetRenderTargets(0, nullptr, nullptr);
  if (settings_.cull == CullMode::Gpu) {
    // Only the GPU knows the partitions' sizes: fit.hlsl turned the world radius into each one's
    // texels next to its padding, and the blur reads them from there.
    blurRadii_.clear();
    if (settings_.csm.moment.blur > 0.0f) {
      moments_->ConvertWithGpuRadii(ctx, depthSrvForMoments_.get(), GpuBlurRadii{fitBuffer_.get(), kFitBlurOffset}, frame.timer);
    } else {
      moments_->Convert(ctx, depthSrvForMoments_.get(), blurRadii_, frame.timer);
    }
    return;
  }
  blurRadii_.assign(k_, 0.0f);
  const float base = float(settings_.csm.fit.padTexels);
  for (uint32_t p = 0; p < k_; ++p) {
    const PartitionFit& f = fits_[p];
    blurRadii_[p] = f.empty ? 0.0f : std::min(BlurRadiusTexels(settings_.csm.moment.blur, f.texelWorld * float(n_), n_), f.padTexels - base);
  }
  moments_->Convert(ctx, depthSrvForMoments_.get(), blurRadii_, frame.timer);
}

void SdsmTechnique::BindLighting(DeviceContext& ctx) {
  ctx.PSSetConstantBuffers(2, {constants_.get()});
  ctx.PSSetShaderResources(0, {moments_ ? moments_->Srv() : srv_.get(), hpsm_ ? hpsm_->srv() : nullptr});
  ctx.PSSetSamplers(0, {moments_ ? moments_->Sampler() : sampler_.get()});
  if (hpsm_) hpsm_->BindCounters(ctx);
}

HpsmCounts SdsmTechnique::HpsmDecisions() const { return hpsm_ ? hpsm_->ReadCounters(*device_->GetImmediateContext()) : HpsmCounts{}; }

std::vector<uint32_t> SdsmTechnique::ReadBufferWords(DeviceContext& ctx, Buffer* buffer) const {
  BUFFER_DESC d;
  d.ByteWidth = buffer->GetDesc().ByteWidth;
  d.Usage = USAGE_STAGING;
  d.CPUAccessFlags = CPU_ACCESS_READ;
  Ref<Buffer> staging = device_->CreateBuffer(d);
  ctx.CopyResource(staging.get(), buffer);
  MAPPED_SUBRESOURCE m;
  ctx.Map(staging.get(), 0, MAP_READ, 0, &m);
  std::vector<uint32_t> words(d.ByteWidth / 4);
  std::memcpy(words.data(), m.pData, d.ByteWidth);
  ctx.Unmap(staging.get(), 0);
  return words;
}

ShadowStats SdsmTechnique::Stats() const {
  ShadowStats s;
  if (!map_) return s;
  const TEXTURE2D_DESC& td = map_->GetDesc();
  s.memoryBytes = uint64_t(td.Width) * td.Height * td.ArraySize * td.SampleDesc.Count * 4;
  if (moments_) s.memoryBytes += moments_->MemoryBytes();
  if (hpsm_) s.memoryBytes += hpsm_->memoryBytes();
  s.memoryBytes += constants_->GetDesc().ByteWidth;
  if (cameraDepth_.texture) s.memoryBytes += uint64_t(depthWidth_) * depthHeight_ * 4;
  if (analysis_) {
    // Results, histogram and the two-pass reduction's tile buffer (8 bytes per 16x16 tile).
    uint64_t tiles = uint64_t((depthWidth_ + 15) / 16) * ((depthHeight_ + 15) / 16);
    s.memoryBytes += kResultBytes + analysis_->histogramBins() * 4ull + tiles * 8;
  }
  if (readback_) s.memoryBytes += uint64_t(readback_->mode() == ReadbackMode::Latent ? readback_->latency() + 1 : 1) * kResultBytes;
  if (fitBuffer_) s.memoryBytes += kFitBytes + sizeof(FitConstants);
  if (culler_) {
    // Per caster: bounds (32), transform (48); batches (16 each); visible lists and draw records.
    s.memoryBytes += culler_->casterCount() * 80ull + culler_->batches().size() * 16ull + culler_->visible()->GetDesc().ByteWidth +
                     culler_->args()->GetDesc().ByteWidth;
  }
  if (settings_.cull != CullMode::Gpu) {
    for (uint64_t t : partitionTriangles_) s.trianglesSubmitted += t;
    return s;
  }
  // cull=gpu: the survivors' counts are in the indirect records; read once per frame, on request.
  if (culler_ && frame_ > 0 && gpuTrianglesFrame_ != frame_) {
    std::vector<uint32_t> args = ReadBufferWords(*device_->GetImmediateContext(), culler_->args());
    ++statsReadbacks_;
    const size_t B = culler_->batches().size();
    gpuTriangles_ = 0;
    for (size_t r = 0; r < k_ * B; ++r) gpuTriangles_ += uint64_t(args[r * 5 + 1]) * (args[r * 5] / 3);
    gpuTrianglesFrame_ = frame_;
  }
  s.trianglesSubmitted = gpuTriangles_;
  return s;
}

std::vector<ShadowLayer> SdsmTechnique::Layers() const { return std::vector<ShadowLayer>(k_, ShadowLayer{n_, n_}); }

std::vector<PartitionFit> SdsmTechnique::ReadGpuFits(DeviceContext& ctx) {
  if (!fitBuffer_) return {};
  return DecodeFitBuffer(ReadBufferWords(ctx, fitBuffer_.get()), k_);
}

std::vector<float> SdsmTechnique::ReadGpuBlurRadii(DeviceContext& ctx) {
  if (!fitBuffer_) return {};
  return DecodeFitBlurRadii(ReadBufferWords(ctx, fitBuffer_.get()), k_);
}

SdsmDebugFrame SdsmTechnique::ReadDebugFrame(DeviceContext& ctx) {
  SdsmDebugFrame d;
  if (!analysis_ || !cameraDepth_.texture) return d;
  std::vector<uint32_t> words = ReadBufferWords(ctx, analysis_->results());
  d.results = DecodeResults(words.data());
  d.histogram = ReadBufferWords(ctx, analysis_->histogram());
  d.fits = settings_.cull == CullMode::Gpu ? ReadGpuFits(ctx) : fits_;
  TEXTURE2D_DESC sd = cameraDepth_.texture->GetDesc();
  sd.BindFlags = 0;
  sd.Usage = USAGE_STAGING;
  sd.CPUAccessFlags = CPU_ACCESS_READ;
  Ref<Texture2D> staging = device_->CreateTexture2D(sd);
  ctx.CopyResource(staging.get(), cameraDepth_.texture.get());
  MAPPED_SUBRESOURCE m;
  ctx.Map(staging.get(), 0, MAP_READ, 0, &m);
  for (uint32_t y = 0; y < depthHeight_; ++y) {
    const float* row = reinterpret_cast<const float*>(static_cast<const uint8_t*>(m.pData) + size_t(y) * m.RowPitch);
    for (uint32_t x = 0; x < depthWidth_; ++x) {
      if (row[x] >= 1.0f) continue;  // sky
      float z = analysisFrame_.ViewDepth(row[x]);
      glm::vec3 l = analysisFrame_.LightPosition(x, y, z);
      d.samples.push_back(glm::vec3(l.x, l.y, float(d.results.splits.empty() ? 0 : PartitionOf(z, d.results.splits))));
    }
  }
  ctx.Unmap(staging.get(), 0);
  return d;
}

}  // namespace sp::tech::sdsm

namespace sp::tech {
std::unique_ptr<Technique> MakeSdsmTechnique() { return std::make_unique<sdsm::SdsmTechnique>(); }
}  // namespace sp::tech
