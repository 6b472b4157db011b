// MomentMaps: depth array -> moment array with compute passes (shaders-hlsl/moments/resolve.hlsl
// and blur.hlsl) and GenerateMips. The passes write through UAVs so one dispatch covers every
// layer (thread group z = layer), which render-target passes could not without a view per slice.
#include <algorithm>
#include <cstddef>
#include <cstring>
#include <stdexcept>

#include "moment-maps.h"

namespace sp::tech {

namespace {

// cbuffer MomentResolve (resolve.hlsl)
struct ResolveConstants {
  uint32_t width, height, layers, pad;
};
static_assert(sizeof(ResolveConstants) == 16);

// cbuffer MomentBlur (blur.hlsl)
struct BlurConstants {
  uint32_t width, height, layers, pad;
  int32_t dirX, dirY, pad2[2];
  float radius[kMaxMomentLayers];
};
static_assert(sizeof(BlurConstants) == 96);
static_assert(sizeof(BlurConstants::radius) == kMomentBlurRadiiBytes);

uint32_t MipCount(uint32_t w, uint32_t h) {
  uint32_t n = 1;
  while ((w | h) > 1) {
    w = std::max(1u, w / 2);
    h = std::max(1u, h / 2);
    ++n;
  }
  return n;
}

}  // namespace

MomentMaps::MomentMaps(Device& device, const MomentMapDesc& desc) : device_(device), desc_(desc) {
  if (desc.width == 0 || desc.height == 0 || desc.layers == 0 || desc.layers > kMaxMomentLayers)
    throw std::invalid_argument("MomentMaps: size " + std::to_string(desc.width) + "x" + std::to_string(desc.height) + " with " +
                                std::to_string(desc.layers) + " layers is not valid (layers in [1, " + std::to_string(kMaxMomentLayers) + "])");
  if (desc.options.msaa != 1 && desc.options.msaa != 4)
    throw std::invalid_argument("MomentMaps: msaa=" + std::to_string(desc.options.msaa) + " is not valid; msaa takes 1|4");
  format_ = MomentFormat(desc.options.kind, desc.options.precision);
  const std::string name = "moments " + MomentKindName(desc.options.kind);

  TEXTURE2D_DESC td;
  td.Width = desc.width;
  td.Height = desc.height;
  td.MipLevels = desc.mips ? MipCount(desc.width, desc.height) : 1;
  td.ArraySize = desc.layers;
  td.Format = format_;
  td.BindFlags = BIND_SHADER_RESOURCE | BIND_UNORDERED_ACCESS | (desc.mips ? BIND_RENDER_TARGET : 0u);
  td.MiscFlags = desc.mips ? RESOURCE_MISC_GENERATE_MIPS : 0u;
  map_ = device.CreateTexture2D(td);
  map_->SetDebugName(name);

  SHADER_RESOURCE_VIEW_DESC sd;
  sd.Format = format_;
  sd.ViewDimension = SRV_DIMENSION_TEXTURE2DARRAY;
  sd.Texture2DArray = {0, td.MipLevels, 0, desc.layers};
  srv_ = device.CreateShaderResourceView(map_.get(), &sd);
  sd.Texture2DArray = {0, 1, 0, desc.layers};
  srvTop_ = device.CreateShaderResourceView(map_.get(), &sd);
  UNORDERED_ACCESS_VIEW_DESC ud;
  ud.Format = format_;
  ud.ViewDimension = UAV_DIMENSION_TEXTURE2DARRAY;
  ud.Texture2DArray = {0, 0, desc.layers};
  uavTop_ = device.CreateUnorderedAccessView(map_.get(), &ud);

  std::vector<hlsl::Define> defines = MomentDefines(desc.options);
  defines.push_back({"MOMENT_MSAA", std::to_string(desc.options.msaa)});
  resolve_ = device.CreateComputeShader(CompileTechniqueShader("moments/resolve.hlsl", "cs_5_0", "main", defines));
  blur_ = device.CreateComputeShader(CompileTechniqueShader("moments/blur.hlsl", "cs_5_0", "main",
                                                            {{"MOMENT_BLUR_KERNEL", std::to_string(int(desc.options.blurKernel))}}));
  resolveConstants_ = MakeConstantBuffer(device, sizeof(ResolveConstants), "MomentResolve constants");
  blurConstants_ = MakeConstantBuffer(device, sizeof(BlurConstants), "MomentBlur constants");

  // Moments are filtered like colour: an ordinary sampler, trilinear or anisotropic. Clamp, not
  // border: lookups outside the map are the technique's business (cascade selection), and a
  // border colour would have to be the moments of depth 1 in this kind's warp.
  SAMPLER_DESC smp;
  smp.Filter = desc.anisotropy > 1 ? FILTER_ANISOTROPIC : FILTER_MIN_MAG_MIP_LINEAR;
  smp.MaxAnisotropy = std::clamp(desc.anisotropy, 1u, 16u);
  smp.AddressU = smp.AddressV = smp.AddressW = TEXTURE_ADDRESS_CLAMP;
  sampler_ = device.CreateSamplerState(smp);
}

TEXTURE2D_DESC MomentMaps::DepthDesc() const {
  TEXTURE2D_DESC td;
  td.Width = desc_.width;
  td.Height = desc_.height;
  td.MipLevels = 1;
  td.ArraySize = desc_.layers;
  td.Format = FORMAT_R32_TYPELESS;
  td.SampleDesc.Count = desc_.options.msaa;
  td.BindFlags = BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE;
  return td;
}

Ref<ShaderResourceView> MomentMaps::MakeDepthSrv(Device& device, Texture2D* depth) {
  const TEXTURE2D_DESC& td = depth->GetDesc();
  SHADER_RESOURCE_VIEW_DESC sd;
  sd.Format = FORMAT_R32_FLOAT;
  if (td.SampleDesc.Count > 1) {
    sd.ViewDimension = SRV_DIMENSION_TEXTURE2DMSARRAY;
    sd.Texture2DMSArray = {0, td.ArraySize};
  } else {
    sd.ViewDimension = SRV_DIMENSION_TEXTURE2DARRAY;
    sd.Texture2DArray = {0, 1, 0, td.ArraySize};
  }
  return device.CreateShaderResourceView(depth, &sd);
}

void MomentMaps::Dispatch(DeviceContext& ctx, ComputeShader* cs, ShaderResourceView* in, UnorderedAccessView* out) {
  ctx.CSSetShader(cs);
  ctx.CSSetShaderResources(0, {in});
  ctx.CSSetUnorderedAccessViews(0, {out});
  ctx.Dispatch((desc_.width + 7) / 8, (desc_.height + 7) / 8, desc_.layers);
  // Unbind both so the next pass can swap input and output without the hazard rules' warnings.
  ctx.CSSetShaderResources(0, {nullptr});
  ctx.CSSetUnorderedAccessViews(0, {nullptr});
}

void MomentMaps::CheckDepthSrv(ShaderResourceView* depthSrv) const {
  if (!depthSrv) throw std::invalid_argument("MomentMaps::Convert: depthSrv is null");
  const SRV_DIMENSION want = desc_.options.msaa > 1 ? SRV_DIMENSION_TEXTURE2DMSARRAY : SRV_DIMENSION_TEXTURE2DARRAY;
  if (depthSrv->GetDesc().ViewDimension != want)
    throw std::invalid_argument(std::string("MomentMaps::Convert: the depth SRV must be ") +
                                (desc_.options.msaa > 1 ? "SRV_DIMENSION_TEXTURE2DMSARRAY (msaa=4)" : "SRV_DIMENSION_TEXTURE2DARRAY (msaa=1)"));
}

void MomentMaps::Convert(DeviceContext& ctx, ShaderResourceView* depthSrv, const std::vector<float>& radii, GpuTimer* timer) {
  CheckDepthSrv(depthSrv);
  if (!radii.empty() && radii.size() != desc_.layers)
    throw std::invalid_argument("MomentMaps::Convert: " + std::to_string(radii.size()) + " blur radii for " + std::to_string(desc_.layers) +
                                " layers (give one per layer, or none)");
  bool blur = false;
  for (float r : radii) blur |= r >= 1e-3f;
  Resolve(ctx, depthSrv, timer);
  blurred_ = blur;
  if (blur) Blur(ctx, radii, nullptr, timer);
  FinishMips(ctx, timer);
}

void MomentMaps::ConvertWithGpuRadii(DeviceContext& ctx, ShaderResourceView* depthSrv, const GpuBlurRadii& radii, GpuTimer* timer) {
  CheckDepthSrv(depthSrv);
  if (!radii.buffer) throw std::invalid_argument("MomentMaps::ConvertWithGpuRadii: the radii buffer is null");
  if (radii.offset % 4 != 0 || uint64_t(radii.offset) + kMomentBlurRadiiBytes > radii.buffer->GetDesc().ByteWidth)
    throw std::invalid_argument("MomentMaps::ConvertWithGpuRadii: the radii at offset " + std::to_string(radii.offset) + " of a " +
                                std::to_string(radii.buffer->GetDesc().ByteWidth) + "-byte buffer are not " +
                                std::to_string(kMomentBlurRadiiBytes) + " bytes at a multiple of 4");
  Resolve(ctx, depthSrv, timer);
  blurred_ = true;
  Blur(ctx, {}, &radii, timer);
  FinishMips(ctx, timer);
}

void MomentMaps::Resolve(DeviceContext& ctx, ShaderResourceView* depthSrv, GpuTimer* timer) {
  GpuTimer::Scope timed(timer, ctx, "moments");
  ResolveConstants rc{desc_.width, desc_.height, desc_.layers, 0};
  ctx.UpdateSubresource(resolveConstants_.get(), 0, nullptr, &rc, 0, 0);
  ctx.CSSetConstantBuffers(0, {resolveConstants_.get()});
  Dispatch(ctx, resolve_.get(), depthSrv, uavTop_.get());
}

void MomentMaps::Blur(DeviceContext& ctx, const std::vector<float>& radii, const GpuBlurRadii* gpu, GpuTimer* timer) {
  GpuTimer::Scope timed(timer, ctx, "blur");
  if (!temp_) {
    TEXTURE2D_DESC td;
    td.Width = desc_.width;
    td.Height = desc_.height;
    td.ArraySize = desc_.layers;
    td.Format = format_;
    td.BindFlags = BIND_SHADER_RESOURCE | BIND_UNORDERED_ACCESS;
    temp_ = device_.CreateTexture2D(td);
    temp_->SetDebugName("moments blur temp");
    SHADER_RESOURCE_VIEW_DESC sd;
    sd.Format = format_;
    sd.ViewDimension = SRV_DIMENSION_TEXTURE2DARRAY;  // also for one layer: the shader declares an array
    sd.Texture2DArray = {0, 1, 0, desc_.layers};
    tempSrv_ = device_.CreateShaderResourceView(temp_.get(), &sd);
    UNORDERED_ACCESS_VIEW_DESC ud;
    ud.Format = format_;
    ud.ViewDimension = UAV_DIMENSION_TEXTURE2DARRAY;
    ud.Texture2DArray = {0, 0, desc_.layers};
    tempUav_ = device_.CreateUnorderedAccessView(temp_.get(), &ud);
  }
  BlurConstants bc{};
  bc.width = desc_.width;
  bc.height = desc_.height;
  bc.layers = desc_.layers;
  for (uint32_t i = 0; i < radii.size() && i < desc_.layers; ++i) bc.radius[i] = std::clamp(radii[i], 0.0f, kMaxBlurRadiusTexels);
  ctx.CSSetConstantBuffers(0, {blurConstants_.get()});
  // One buffer updated between the dispatches: each dispatch sees the contents at its time. The
  // whole-buffer update replaces the GPU radii too, so they are copied in again after each one.
  auto upload = [&] {
    ctx.UpdateSubresource(blurConstants_.get(), 0, nullptr, &bc, 0, 0);
    if (!gpu) return;
    BOX box{gpu->offset, 0, 0, gpu->offset + kMomentBlurRadiiBytes, 1, 1};
    ctx.CopySubresourceRegion(blurConstants_.get(), 0, uint32_t(offsetof(BlurConstants, radius)), 0, 0, gpu->buffer, 0, &box);
  };
  bc.dirX = 1;
  upload();
  Dispatch(ctx, blur_.get(), srvTop_.get(), tempUav_.get());
  bc.dirX = 0;
  bc.dirY = 1;
  upload();
  Dispatch(ctx, blur_.get(), tempSrv_.get(), uavTop_.get());
}

void MomentMaps::FinishMips(DeviceContext& ctx, GpuTimer* timer) {
  if (desc_.mips) {
    GpuTimer::Scope timed(timer, ctx, "moments");
    ctx.GenerateMips(srv_.get());
  }
  ctx.CSSetShader(nullptr);
}

std::vector<float> MomentMaps::ReadLastBlurRadii(DeviceContext& ctx) const {
  if (!blurred_) return {};
  BUFFER_DESC d;
  d.ByteWidth = sizeof(BlurConstants);
  d.Usage = USAGE_STAGING;
  d.CPUAccessFlags = CPU_ACCESS_READ;
  Ref<Buffer> staging = device_.CreateBuffer(d);
  ctx.CopyResource(staging.get(), blurConstants_.get());
  MAPPED_SUBRESOURCE m;
  ctx.Map(staging.get(), 0, MAP_READ, 0, &m);
  BlurConstants bc;
  std::memcpy(&bc, m.pData, sizeof(bc));
  ctx.Unmap(staging.get(), 0);
  return std::vector<float>(bc.radius, bc.radius + desc_.layers);
}

uint64_t MomentMaps::MemoryBytes() const {
  const uint64_t texel = GetFormatInfo(format_).bytesPerElement;
  const TEXTURE2D_DESC& td = map_->GetDesc();
  uint64_t bytes = 0;
  for (uint32_t m = 0; m < td.MipLevels; ++m)
    bytes += uint64_t(std::max(1u, desc_.width >> m)) * std::max(1u, desc_.height >> m) * desc_.layers * texel;
  if (temp_) bytes += uint64_t(desc_.width) * desc_.height * desc_.layers * texel;
  return bytes;
}

}  // namespace sp::tech
