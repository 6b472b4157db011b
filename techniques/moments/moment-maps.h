// Moment-based shadow filtering shared by the techniques that offer `filter=vsm|evsm2|evsm4|esm|msm`
// (csm, sdsm). Not a technique itself: a technique renders its depth array as usual, then
// MomentMaps turns it into a filterable moment array (resolve of 1x or 4x depth, separable blur
// with a per-layer radius, mip chain) that the lighting include samples with an ordinary
// trilinear/anisotropic sampler and evaluates with shaders-hlsl/moments/moments.hlsli.
//
// Formats (texel size in parentheses):
//   kind    fp32                 16-bit
//   vsm     R32G32_FLOAT (8)     R16G16_FLOAT (4)
//   esm     R32_FLOAT (4)        R16_FLOAT (2)
//   evsm2   R32G32_FLOAT (8)     R16G16_FLOAT (4)
//   evsm4   R32G32B32A32 (16)    R16G16B16A16_FLOAT (8)
//   msm     R32G32B32A32 (16)    R16G16B16A16_UNORM (8) of the quantised moments, as in the paper
//
// Use, per frame: render depth into a texture made from DepthDesc() (one DSV per slice), unbind
// Srv() from the lit pass's slots (Convert writes the map through a UAV), Convert(ctx,
// MakeDepthSrv(depth), radii) with radii from BlurRadiusTexels() (or ConvertWithGpuRadii where
// only the GPU knows the layers' sizes), then bind Srv() and Sampler() for lighting, compiled
// with LightingDefines(), and call MomentSampleVisibility() from moments.hlsli with the
// receiver's depth in the same [0, 1] space.
#pragma once
#include <glm/glm.hpp>
#include <map>
#include <sp/rhi/rhi.h>
#include <string>
#include <vector>

#include <sp/tech/gpu-timer.h>
#include <sp/tech/technique.h>

namespace sp::tech {

enum class MomentKind { Vsm = 0, Esm = 1, Evsm2 = 2, Evsm4 = 3, Msm = 4 };  // = MOMENT_KIND
enum class MomentPrecision { Fp16, Fp32 };
enum class MomentBlurKernel { Box = 0, Gaussian = 1 };  // = MOMENT_BLUR_KERNEL

// Exponent limits (derivation in moments.hlsli, which has the same numbers).
constexpr float kMomentMinExponent = 0.1f;
constexpr float kEvsmMaxExponentFp16 = 5.54f, kEvsmMaxExponentFp32 = 42.0f;
constexpr float kEsmMaxExponentFp16 = 11.08f, kEsmMaxExponentFp32 = 88.72f;
// The blur shader's loop bound (MOMENT_MAX_BLUR_RADIUS); larger radii are clamped to it.
constexpr float kMaxBlurRadiusTexels = 32.0f;
// Layers whose blur radius the blur cbuffer holds.
constexpr uint32_t kMaxMomentLayers = 16;
// The blur cbuffer's radius block: one float (texels) per layer, layer i at byte 4 i.
constexpr uint32_t kMomentBlurRadiiBytes = kMaxMomentLayers * 4;

glm::vec2 ClampEvsmExponents(glm::vec2 requested, bool fp16);
float ClampEsmExponent(float requested, bool fp16);

// The parsed `filter msaa blur bleed exponents precision` parameters; every field has its final
// value (defaults for the kind and precision applied, exponents clamped).
struct MomentOptions {
  MomentKind kind = MomentKind::Evsm4;
  MomentPrecision precision = MomentPrecision::Fp32;
  uint32_t msaa = 1;               // samples of the depth the technique renders: 1 or 4
  float blur = 0.0f;               // radius in world units; the technique turns it into texels per layer
  float bleed = 0.0f;              // light-bleeding reduction, [0, 1)
  glm::vec2 exponents{0.0f};       // esm: (c, unused); evsm: (c+, c-); vsm, msm: unused
  float minVariance = 0.0f;        // vsm, evsm: depth units squared
  float msmBias = 0.0f;            // msm moment bias alpha
  MomentBlurKernel blurKernel = MomentBlurKernel::Gaussian;
};

// The filter names, in the order of MomentKind.
const std::vector<std::string>& MomentFilterNames();
bool IsMomentFilter(const std::string& name);
std::string MomentKindName(MomentKind kind);

// Reads `filter`, `msaa`, `blur`, `bleed`, `exponents`, `precision` from `params` (other keys are
// ignored, so a technique can pass all its values); evsm's two exponents are separated by a comma
// or a colon (bench sweeps split values at commas). Missing keys and the value "auto" take the
// defaults: msaa 1, blur 0, precision fp32, and per kind
//   bleed      vsm 0.2, esm 0, evsm2 0.1, evsm4 0.05, msm 0.03
//   exponents  esm 80 (fp32) / 11.08 (16-bit); evsm (40, 5), clamped for 16-bit to (5.54, 5)
// Throws std::invalid_argument naming the parameter and listing the valid values.
MomentOptions ParseMomentOptions(const std::map<std::string, std::string>& params);

// Specs of msaa, blur, bleed, exponents and precision for a technique's Params() (the technique
// declares `filter` itself, merging MomentFilterNames() with its other filters).
std::vector<ParamSpec> MomentParamSpecs();

// The defines moments.hlsli needs (MOMENT_KIND, MOMENT_FP16, MOMENT_EXP_POS/NEG, MOMENT_BLEED,
// MOMENT_MIN_VARIANCE, MOMENT_MSM_BIAS), for the lighting include and the resolve shader.
std::vector<hlsl::Define> MomentDefines(const MomentOptions& options);

FORMAT MomentFormat(MomentKind kind, MomentPrecision precision);

// World-space blur radius -> texels of a layer covering `layerWorldWidth` with `layerTexels`
// texels, clamped to [0, kMaxBlurRadiusTexels].
float BlurRadiusTexels(float worldRadius, float layerWorldWidth, uint32_t layerTexels);

// Radii a GPU pass wrote, for a technique whose layer sizes only the GPU knows: the
// kMomentBlurRadiiBytes at `offset` of `buffer` in the blur cbuffer's radius layout, each already
// in [0, kMaxBlurRadiusTexels] (the blur shader clamps to its loop bound again).
struct GpuBlurRadii {
  Buffer* buffer = nullptr;
  uint32_t offset = 0;  // a multiple of 4
};

struct MomentMapDesc {
  MomentOptions options;
  uint32_t width = 0, height = 0, layers = 1;
  bool mips = true;         // full mip chain (for trilinear and anisotropic lookups)
  // Of Sampler(); 1 = trilinear. Mesa 22.3 darkens partition splits with anisotropic lookups and is
  // ~30x slower, so techniques default to 1 and offer it as a parameter.
  uint32_t anisotropy = 1;
};

class MomentMaps {
 public:
  MomentMaps(Device& device, const MomentMapDesc& desc);

  // The depth texture a technique renders for this map: R32_TYPELESS (D32_FLOAT DSV, R32_FLOAT
  // SRV), the map's size and layers, options.msaa samples.
  TEXTURE2D_DESC DepthDesc() const;
  // An SRV of such a depth texture in the dimension Convert expects (TEXTURE2DARRAY or
  // TEXTURE2DMSARRAY with R32_FLOAT; also accepted: any R32_FLOAT array of the map's size).
  static Ref<ShaderResourceView> MakeDepthSrv(Device& device, Texture2D* depth);

  // Resolve `depthSrv` into moments, blur each layer by its radius (texels; empty = no blur,
  // else one per layer) and build the mips. The depth SRV is unbound again afterwards; the
  // map is unbound from the compute stage. Timed as "moments" and "blur" when `timer` is set.
  void Convert(DeviceContext& ctx, ShaderResourceView* depthSrv, const std::vector<float>& blurRadiusTexelsPerLayer,
               GpuTimer* timer = nullptr);
  // Convert with the radii copied from GPU memory into the blur's constants
  // (CopySubresourceRegion, no CPU round trip). The CPU cannot tell whether every radius is 0, so
  // the blur passes always run (a layer of radius 0 is copied through).
  void ConvertWithGpuRadii(DeviceContext& ctx, ShaderResourceView* depthSrv, const GpuBlurRadii& radii, GpuTimer* timer = nullptr);
  // The radii the last Convert's blur read, copied back from its constants (a stall: for tests);
  // empty when it did not blur.
  std::vector<float> ReadLastBlurRadii(DeviceContext& ctx) const;

  ShaderResourceView* Srv() const { return srv_.get(); }  // Texture2DArray, all mips
  Texture2D* Texture() const { return map_.get(); }
  SamplerState* Sampler() const { return sampler_.get(); }
  uint64_t MemoryBytes() const;
  const MomentMapDesc& Desc() const { return desc_; }
  FORMAT Format() const { return format_; }
  std::vector<hlsl::Define> LightingDefines() const { return MomentDefines(desc_.options); }

 private:
  void Dispatch(DeviceContext& ctx, ComputeShader* cs, ShaderResourceView* in, UnorderedAccessView* out);
  void CheckDepthSrv(ShaderResourceView* depthSrv) const;
  void Resolve(DeviceContext& ctx, ShaderResourceView* depthSrv, GpuTimer* timer);
  // Both blur directions; `gpu` set: its radii replace those of `radii` in the constants.
  void Blur(DeviceContext& ctx, const std::vector<float>& radii, const GpuBlurRadii* gpu, GpuTimer* timer);
  void FinishMips(DeviceContext& ctx, GpuTimer* timer);

  Device& device_;
  MomentMapDesc desc_;
  FORMAT format_ = FORMAT_UNKNOWN;
  Ref<Texture2D> map_, temp_;
  Ref<ShaderResourceView> srv_, srvTop_, tempSrv_;
  Ref<UnorderedAccessView> uavTop_, tempUav_;
  Ref<ComputeShader> resolve_, blur_;
  Ref<Buffer> resolveConstants_, blurConstants_;
  Ref<SamplerState> sampler_;
  bool blurred_ = false;  // the last Convert ran the blur
};

}  // namespace sp::tech
