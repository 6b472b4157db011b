// Sample Distribution Shadow Maps (Lauritzen, Salvi, Lefohn, I3D 2011) as a technique. Per frame:
//  1. camera depth pre-pass into the technique's own D32 buffer ("depth prepass");
//  2. DepthAnalysis on it ("analysis"): tight view-depth range, log histogram, K partitions by
//     the chosen scheme, tight light-space box per partition in the light frame of MakeLightView
//     (x = the camera's view direction projected onto the light plane);
//  3. one orthographic projection per partition (sdsm-technique-fit.h);
//  4. one depth pass per partition into a slice of a Texture2DArray ("shadow"), depth clip off;
//  5. lighting by csm's include (shaders-hlsl/sdsm/shadow.hlsli), whose CsmShadow constants hold
//     the SDSM light frame, each partition's scale/offset and its split interval.
//
// cull= decides where the projections come from and how casters are culled:
//  conservative  no analysis is used (none is run): log splits of the camera's near plane to the
//                far end of the scene, each partition the box of its frustum slice; casters culled
//                on the CPU against the union of those boxes. The cost baseline (PSSM-like).
//  readback      the analysis results mapped this frame (a stall), fitted and culled on the CPU.
//  latent        results from `latency` frames ago (AnalysisReadback Latent: no stall). They are
//                in that frame's light frame, which the technique then uses, with that frame's
//                splits: while the camera moves the partitions lag it and pixels at their edges
//                may fall outside (lit) or into a coarser map. The first `latency` frames use
//                conservative.
//  gpu           nothing waits for the CPU: sdsm/fit.hlsl turns the results into the CsmShadow
//                constants (copied into the lit pass's constant buffer with
//                CopySubresourceRegion) and per-partition matrices, CasterCuller compacts the
//                casters of each partition on the GPU and VSCasterGpu draws them indirectly with
//                the matrix read from the fit buffer.
//
// Moment filters (filter=vsm|...) work as in csm (MomentMaps over the partition array): the blur
// radius is in world units, each partition blurs it in its own texels within the padding its fit
// reserved. With cull=gpu only the GPU knows the partitions' sizes, so fit.hlsl writes the radii
// too and MomentMaps copies them into the blur's constants; every mode blurs the same distance.
#pragma once
#include <memory>

#include "csm/csm-technique.h"
#include "moments/moment-maps.h"
#include "sdsm/analysis-readback.h"
#include "sdsm/caster-culling.h"
#include "sdsm/depth-analysis.h"
#include "sdsm/sdsm-technique-fit.h"
#include <sp/tech/technique.h>

namespace sp::tech::sdsm {

enum class CullMode { Conservative, Readback, Latent, Gpu };

struct SdsmSettings {
  csm::CsmSettings csm;  // cascades (K), resolution, blend, filter, bias, moments; fit.padTexels
  PartitionScheme partition = PartitionScheme::Log;
  bool tight = true;
  CullMode cull = CullMode::Gpu;
  uint32_t latency = 2;
  bool quantize = false;
  float dilation = 0.0f;
  uint32_t partitions() const { return uint32_t(csm.fit.cascades); }
};

std::vector<ParamSpec> SdsmParams();
SdsmSettings SdsmSettingsFrom(const ParamValues& params);

// What the debug views need from one frame (read back on request, never during a frame).
struct SdsmDebugFrame {
  AnalysisResults results;
  std::vector<uint32_t> histogram;
  std::vector<glm::vec3> samples;  // light-view x, y of every analysed pixel; z: its partition
  std::vector<PartitionFit> fits;
};

class SdsmTechnique final : public Technique, public HpsmCounterSource {
 public:
  std::string Name() const override { return "sdsm"; }
  std::vector<ParamSpec> Params() const override { return SdsmParams(); }
  void Configure(Device& device, const ParamValues& params) override;
  void RenderShadows(DeviceContext& ctx, SceneDrawer& drawer, const FrameInputs& frame) override;
  std::string LightingInclude() const override { return "sdsm/shadow.hlsli"; }
  std::vector<hlsl::Define> LightingDefines() const override { return csm::CsmTechnique::Defines(settings_.csm); }
  void BindLighting(DeviceContext& ctx) override;
  // cull=gpu: the triangle count is read back from the indirect arguments here (once per frame),
  // never during the frame.
  ShadowStats Stats() const override;
  HpsmCounts HpsmDecisions() const override;
  std::vector<ShadowLayer> Layers() const override;
  // With a moment filter, the moments the lit pass reads (mip 0), else the depth array.
  Texture2D* ShadowMapTexture() const override { return moments_ ? moments_->Texture() : map_.get(); }

  // For tests and debug views.
  const SdsmSettings& settings() const { return settings_; }
  // The fits of the last frame as the CPU made them (empty with cull=gpu; see ReadGpuFits).
  const std::vector<PartitionFit>& lastFits() const { return fits_; }
  const glm::mat4& lastLightView() const { return lightView_; }
  // Map(READ)s of GPU data made while rendering frames (the analysis readbacks); cull=gpu keeps
  // it at 0. Reads for Stats() and the debug accessors are counted apart.
  uint64_t frameReadbacks() const { return frameReadbacks_; }
  uint64_t statsReadbacks() const { return statsReadbacks_; }
  // cull=gpu: the fits the GPU made last frame (reads the fit buffer back).
  std::vector<PartitionFit> ReadGpuFits(DeviceContext& ctx);
  // Moment blur radii (texels, one per partition) of the last frame: the CPU's (empty with
  // cull=gpu), and those fit.hlsl wrote with cull=gpu (reads the fit buffer back).
  const std::vector<float>& lastBlurRadii() const { return blurRadii_; }
  std::vector<float> ReadGpuBlurRadii(DeviceContext& ctx);
  MomentMaps* moments() const { return moments_.get(); }
  // The analysis of the last frame (not with cull=conservative), for Figures 2 and 4.
  SdsmDebugFrame ReadDebugFrame(DeviceContext& ctx);
  Texture2D* shadowTexture() const { return map_.get(); }

 private:
  void EnsureCameraDepth(Device& device, uint32_t width, uint32_t height);
  void DepthPrepass(DeviceContext& ctx, SceneDrawer& drawer, const FrameInputs& frame);
  std::vector<PartitionFit> ConservativeFits(const FrameInputs& frame, const glm::mat4& lightView) const;
  std::vector<PartitionFit> FitsFrom(const AnalysisResults& r, const glm::mat4& lightView, const glm::mat4& cameraView,
                                     const glm::mat4& cameraProj, float cameraFar) const;
  FitParams MakeFitParams(const glm::mat4& lightView) const;
  void RunGpuFit(DeviceContext& ctx, const FrameInputs& frame);
  void ClearSlices(DeviceContext& ctx);
  void DrawCpu(DeviceContext& ctx, SceneDrawer& drawer, const FrameInputs& frame, bool unionCull);
  void DrawGpu(DeviceContext& ctx, const FrameInputs& frame);
  void ConvertMoments(DeviceContext& ctx, const FrameInputs& frame);
  glm::vec4 LightingSettings() const;
  std::vector<uint32_t> ReadBufferWords(DeviceContext& ctx, Buffer* buffer) const;

  struct FrameRecord {  // what the latent results of a frame must be fitted with
    glm::mat4 lightView{1.0f}, cameraView{1.0f}, cameraProj{1.0f};
    float cameraFar = 0;
  };

  Device* device_ = nullptr;
  SdsmSettings settings_;
  uint32_t n_ = 0, k_ = 0;
  Ref<Texture2D> map_;
  std::vector<Ref<DepthStencilView>> dsvs_;
  Ref<ShaderResourceView> srv_, depthSrvForMoments_;
  Ref<RasterizerState> shadowRasterizer_, prepassRasterizer_;
  Ref<SamplerState> sampler_;
  Ref<Buffer> constants_;
  std::unique_ptr<MomentMaps> moments_;
  std::unique_ptr<HpsmMaps> hpsm_;  // accel: built from every slice after the partitions
  std::vector<float> blurRadii_;

  // Camera depth and the analysis.
  uint32_t depthWidth_ = 0, depthHeight_ = 0;
  DepthMap cameraDepth_;
  std::unique_ptr<DepthAnalysis> analysis_;
  std::unique_ptr<AnalysisReadback> readback_;
  AnalysisFrame analysisFrame_;
  std::vector<FrameRecord> records_;  // by capture number modulo the ring

  // cull=gpu.
  std::unique_ptr<CasterCuller> culler_;
  const scene::GpuScene* cullerScene_ = nullptr;
  Ref<Buffer> fitBuffer_, fitConstants_;
  Ref<UnorderedAccessView> fitUav_;
  Ref<ShaderResourceView> fitSrv_;
  Ref<ComputeShader> fitCs_;

  uint64_t frame_ = 0;
  glm::mat4 lightView_{1.0f};
  scene::Bounds sceneBounds_;  // this frame's scene: filter=pcss raises the partitions' tops to it (FitParams::casterTop)
  std::vector<PartitionFit> fits_;
  std::vector<uint64_t> partitionTriangles_;
  mutable uint64_t gpuTriangles_ = 0;
  mutable uint64_t gpuTrianglesFrame_ = ~0ull;
  uint64_t frameReadbacks_ = 0;
  mutable uint64_t statsReadbacks_ = 0;
};

}  // namespace sp::tech::sdsm
