#include "hpsm-maps.h"

#include <cstring>
#include <stdexcept>

namespace sp::tech {
namespace {

// cbuffer HpsmBuild in shaders-hlsl/common/hpsm-build.hlsl.
struct BuildConstants {
  uint32_t mapSize[2];
  uint32_t block, planes;
  int32_t before, after;
  float eps, pad;
};
static_assert(sizeof(BuildConstants) == 32);

// kHpsmDecisions words, then common/shafts.hlsli's kShaftLookedUp and kShaftSkipped.
constexpr uint32_t kCounterBytes = HpsmMaps::kCounterWords * 4;
constexpr uint32_t kCounterSlot = 7;       // u7: above every render target the lit passes bind

[[noreturn]] void Bad(const std::string& param, const std::string& why) { throw std::invalid_argument(param + ": " + why); }

}  // namespace

int FilterReach(int filter, int kernel) {
  switch (filter) {
    case 0: return 0;
    case 1: case 2: case 3: return kernel / 2;
    case 4: return kernel / 2 + 1;
    // pcss: search and box both stay within M/2 of s, M = pcss_max_kernel, so they read texels
    // [floor(s) - ceil((M - 1)/2), floor(s) + ceil((M - 1)/2) + 1] (common/hpsm.hlsli); one more
    // because the search's last tap, s - r + 2r, is s + r only up to float rounding.
    case 5: return kernel / 2 + 1;
  }
  throw std::invalid_argument("accel: no footprint known for SHADOW_FILTER " + std::to_string(filter));
}

std::vector<ParamSpec> HpsmParams() {
  return {
      {ParamSpec::Choice, "accel", "skip the filter where a secondary map decides the whole footprint: hybrid min/max plane shadow maps, or the hierarchical min/max baseline", "none", 0, 0, {"none", "hpsm", "minmax"}},
      {ParamSpec::Int, "hpsm_block", "shadow-map texels per secondary texel and axis; 0: 4 for hpsm, the smallest power of two as wide as the filter's footprint for minmax", "0", 0, 256, {}},
      {ParamSpec::Float, "hpsm_eps", "hpsm: the largest depth residual of a block stored as a plane", "1e-6", 0, 0.5, {}},
      {ParamSpec::Choice, "hpsm_build", "how the build reads the shadow map into groupshared memory: GatherRed (4 texels a fetch) or Load (1); the maps are the same", "gather", 0, 0, {"gather", "load"}},
      {ParamSpec::Int, "hpsm_counters", "1: the lit pass counts its decisions for the lab (one atomic add per lookup); 0: no counting", "1", 0, 1, {}},
  };
}

ParamSpec UnofferedAccelParam(const std::string& why) {
  return {ParamSpec::Choice, "accel", "not offered (" + why + "): only none", "none", 0, 0, {"none", "hpsm", "minmax"}};
}

void RefuseAccel(const ParamValues& p, const std::string& technique, const std::string& why) {
  const std::string& a = p.getChoice("accel");
  if (a != "none") throw std::invalid_argument(technique + ": accel=" + a + " is not offered: " + why);
}

HpsmSettings ReadHpsmSettings(const ParamValues& p, int filter, int kernel, uint32_t resolution) {
  HpsmSettings s;
  const std::string& a = p.getChoice("accel");
  s.accel = a == "hpsm" ? ShadowAccel::Hpsm : a == "minmax" ? ShadowAccel::MinMax : ShadowAccel::None;
  if (s.accel != ShadowAccel::None) s.reach = FilterReach(filter, kernel);
  if (filter == 5) s.pcssMaxKernel = kernel;
  s.eps = p.getFloat("hpsm_eps");
  s.counters = p.getInt("hpsm_counters") != 0;
  s.gatherBuild = p.getChoice("hpsm_build") == "gather";
  int footprint = 2 * s.reach + 2;
  int block = p.getInt("hpsm_block");
  if (s.accel == ShadowAccel::MinMax) {
    if (block == 0) for (block = 1; block < footprint;) block *= 2;
    if ((block & (block - 1)) != 0 || block < footprint)
      Bad("hpsm_block", std::to_string(block) + " is not valid for accel=minmax: the level's texels are a power of two at least as wide as the filter's footprint (" +
                            std::to_string(footprint) + " texels)");
  } else if (block == 0) {
    block = 4;
  }
  if (s.accel != ShadowAccel::None && uint32_t(block) > resolution)
    Bad("hpsm_block", std::to_string(block) + " is wider than the shadow map (" + std::to_string(resolution) + " texels)");
  s.block = block;
  return s;
}

std::vector<hlsl::Define> HpsmDefines(const HpsmSettings& s) {
  if (s.accel == ShadowAccel::None) return {};
  return {{"SHADOW_ACCEL", s.accel == ShadowAccel::Hpsm ? "1" : "2"}, {"HPSM_BLOCK", std::to_string(s.block)}, {"HPSM_REACH", std::to_string(s.reach)},
          {"HPSM_COUNTERS", s.counters ? "1" : "0"}, {"HPSM_PCSS_MAX_KERNEL", std::to_string(s.pcssMaxKernel)}};
}

HpsmMaps::HpsmMaps(Device& device, const HpsmSettings& s, uint32_t width, uint32_t height, uint32_t layers)
    : device_(device), settings_(s), width_(width), height_(height), layers_(layers) {
  if (s.accel == ShadowAccel::None) throw std::invalid_argument("HpsmMaps: accel=none builds no maps");
  blocksX_ = (width + s.block - 1) / s.block;
  blocksY_ = (height + s.block - 1) / s.block;
  TEXTURE2D_DESC d;
  d.Width = blocksX_;
  d.Height = blocksY_;
  d.ArraySize = layers;
  d.Format = FORMAT_R32G32B32A32_FLOAT;
  d.BindFlags = BIND_SHADER_RESOURCE | BIND_UNORDERED_ACCESS;
  texture_ = device.CreateTexture2D(d);
  texture_->SetDebugName(s.accel == ShadowAccel::Hpsm ? "hpsm planes" : "hpsm min/max level");
  SHADER_RESOURCE_VIEW_DESC sd;
  sd.Format = d.Format;
  sd.ViewDimension = SRV_DIMENSION_TEXTURE2DARRAY;
  sd.Texture2DArray = {0, 1, 0, layers};
  srv_ = device.CreateShaderResourceView(texture_.get(), &sd);
  UNORDERED_ACCESS_VIEW_DESC ud;
  ud.Format = d.Format;
  ud.ViewDimension = UAV_DIMENSION_TEXTURE2DARRAY;
  ud.Texture2DArray = {0, 0, layers};
  uav_ = device.CreateUnorderedAccessView(texture_.get(), &ud);
  build_ = device.CreateComputeShader(CompileTechniqueShader("common/hpsm-build.hlsl", "cs_5_0", "main", {{"HPSM_BUILD_GATHER", s.gatherBuild ? "1" : "0"}}));
  if (s.gatherBuild) {
    SAMPLER_DESC pd;
    pd.Filter = FILTER_MIN_MAG_MIP_POINT;
    pd.AddressU = pd.AddressV = pd.AddressW = TEXTURE_ADDRESS_CLAMP;
    point_ = device.CreateSamplerState(pd);
  }
  constants_ = MakeConstantBuffer(device, sizeof(BuildConstants), "hpsm build constants");
  counters_ = MakeRawBuffer(device, kCounterBytes, BIND_UNORDERED_ACCESS, "hpsm decision counters");
  countersUav_ = MakeRawUav(device, counters_.get());
  BUFFER_DESC sb;
  sb.ByteWidth = kCounterBytes;
  sb.Usage = USAGE_STAGING;
  sb.CPUAccessFlags = CPU_ACCESS_READ;
  countersStaging_ = device.CreateBuffer(sb);
}

void HpsmMaps::Build(DeviceContext& ctx, ShaderResourceView* depth) {
  bool planes = settings_.accel == ShadowAccel::Hpsm;
  // The support: every texel a footprint starting in the block can read (hpsm.hlsli); the
  // min/max level needs none, its lookup reads the 2x2 texels the footprint touches.
  BuildConstants c{{width_, height_}, uint32_t(settings_.block), planes ? 1u : 0u, planes ? settings_.reach : 0, planes ? settings_.reach + 1 : 0, settings_.eps, 0};
  ctx.UpdateSubresource(constants_.get(), 0, nullptr, &c, 0, 0);
  // The lit pass reads the map as t-something of the PS: unbind every PS view before writing it.
  ShaderResourceView* none[16] = {};
  ctx.PSSetShaderResources(0, 16, none);
  ctx.CSSetShader(build_.get());
  ctx.CSSetConstantBuffers(0, {constants_.get()});
  ctx.CSSetShaderResources(0, {depth});
  ctx.CSSetUnorderedAccessViews(0, {uav_.get()});
  if (point_) ctx.CSSetSamplers(0, {point_.get()});
  ctx.Dispatch((blocksX_ + 7) / 8, (blocksY_ + 7) / 8, layers_);
  UnorderedAccessView* noUav = nullptr;
  ShaderResourceView* noSrv = nullptr;
  ctx.CSSetUnorderedAccessViews(0, 1, &noUav, nullptr);
  ctx.CSSetShaderResources(0, 1, &noSrv);
  const uint32_t zero[4] = {0, 0, 0, 0};
  ctx.ClearUnorderedAccessViewUint(countersUav_.get(), zero);
}

void HpsmMaps::BindCounters(DeviceContext& ctx) {
  if (!settings_.counters) return;
  UnorderedAccessView* uavs[] = {countersUav_.get()};
  ctx.OMSetRenderTargetsAndUnorderedAccessViews(KEEP_RENDER_TARGETS_AND_DEPTH_STENCIL, nullptr, nullptr, kCounterSlot, 1, uavs, nullptr);
}

std::array<uint32_t, HpsmMaps::kCounterWords> HpsmMaps::ReadCounterWords(DeviceContext& ctx) {
  ctx.CopyResource(countersStaging_.get(), counters_.get());
  MAPPED_SUBRESOURCE m;
  ctx.Map(countersStaging_.get(), 0, MAP_READ, 0, &m);
  std::array<uint32_t, kCounterWords> words;
  std::memcpy(words.data(), m.pData, sizeof(words));
  ctx.Unmap(countersStaging_.get(), 0);
  return words;
}

HpsmCounts HpsmMaps::ReadCounters(DeviceContext& ctx) {
  std::array<uint32_t, kCounterWords> words = ReadCounterWords(ctx);
  HpsmCounts c;
  for (int i = 0; i < 5; ++i) c.n[i] = words[i];
  return c;
}

uint64_t HpsmMaps::memoryBytes() const { return uint64_t(blocksX_) * blocksY_ * layers_ * 16 + kCounterBytes; }

}  // namespace sp::tech
