// The sdsm technique's partition fit: from a partition's light-space box (analysed, or a frustum
// slice) to the orthographic projection its shadow map is rendered with and the csm lighting's
// per-cascade constants. FitPartition here and FitPartitions in shaders-hlsl/sdsm/fit.hlsl (the
// cull=gpu path) do the same float operations in the same order, so both paths give the same maps.
//
// Steps, per partition (light view: right-handed, looking down -z, analysis-frame.h):
//  1. grow the box by `dilation` on every side;
//  2. x/y: pad for the filter's reach (padTexels, csm's rule) and the moment blur, so a kernel
//     centred on any receiver reads only this map: size *= N / (N - 2 pad);
//  3. quantize: round each side up to a power of two (with one texel to spare) and snap the
//     centre to a grid of the texel size anchored at the world origin: under camera translation
//     (the light frame keeps its axes) the texel grid stays put and sizes change in octave steps
//     only, the paper's option for temporal stability;
//  4. z: pad by the same texels (the normal offset moves lookups below the lowest receiver) and a
//     relative epsilon; casters above the box are pancaked (DepthClipEnable = FALSE), except with
//     filter=pcss, where the top is raised to casterTop so blockers keep their depths.
#pragma once
#include <glm/glm.hpp>
#include <vector>

#include <sp/scene/scene.h>
#include "sdsm/analysis-frame.h"

namespace sp::tech::sdsm {

// The fit buffer of cull=gpu (fit.hlsl): fitted boxes in the results layout for CasterCuller,
// the CsmShadow constants, each partition's world -> clip matrix as four rows, and the moment
// blur's radius per layer (texels, one float each, kMaxMomentLayers of them: the radius block of
// MomentMaps' blur constants, which ConvertWithGpuRadii copies from here).
constexpr uint32_t kFitConstantsOffset = 384, kFitMatricesOffset = 1024, kFitBlurOffset = 1536, kFitBytes = 1600;

// cbuffer CsmShadow of shaders-hlsl/csm/shadow.hlsli (D3D packing).
struct CsmShadowConstants {
  glm::mat4 lightView;
  glm::vec4 toMapScale[8];   // xyz: light view -> (u, v, depth); w: margin (padding) in region uv
  glm::vec4 toMapOffset[8];
  glm::vec4 region[8];       // whole slice: 0, 0, 1, 1
  glm::vec4 cascade[8];      // split near, split far, world texel size, array slice
  glm::vec4 cameraForward;   // w: partition count
  glm::vec4 settings;        // select (0: interval), blend, bias mode, normal offset (texels)
  glm::vec4 mapInfo;         // 1 / N, 1 / N, 0, N
  // filter=pcss: 2 tan(angle / 2), search taps, max kernel, unused. Always present (the shader
  // declares it for pcss only): every partition derives its own texel size and depth range from
  // its toMapScale/toMapOffset, so this row is the same for all and the fit writes it as given.
  glm::vec4 pcss;
};
static_assert(sizeof(CsmShadowConstants) == 640);
static_assert(kFitMatricesOffset - kFitConstantsOffset == sizeof(CsmShadowConstants));
static_assert(kFitBlurOffset - kFitMatricesOffset == kMaxPartitions * 64);

struct FitParams {
  uint32_t resolution = 1024;
  uint32_t padTexels = 1;      // the filter's reach and normal offset (csm's FitSettings::padTexels)
  float dilation = 0.0f;       // world units on every side
  bool quantize = false;
  glm::vec3 gridOrigin{0.0f};  // the world origin in the light view: quantize's grid anchor
  float blurWorld = 0.0f;      // moment blur radius (world); padded for in texels of each partition
  uint32_t blurMaxTexels = 0;
  // filter=pcss: the light-view z every box's top is raised to (the scene's top). A tight box holds
  // receivers only and pancakes the casters above it onto its near plane, where PCSS would read a
  // blocker depth just above the receiver: no penumbra. -3e38 leaves the boxes as fitted.
  float casterTop = -3.0e38f;
};

struct PartitionFit {
  bool empty = true;                  // no receiver: nothing drawn, no pixel reads it
  float splitNear = 0, splitFar = 0;  // view-depth interval the lighting selects it for
  glm::vec3 min{0.0f}, max{0.0f};     // light-view box the map covers, padding included
  float texelWorld = 0;               // the larger side of a texel
  float padTexels = 0;                // the margin kept for filter, normal offset and blur
  glm::vec3 scale{0.0f}, offset{0.0f};  // light view -> (u, v, depth)
  glm::mat4 viewProj{1.0f};           // world -> clip (depth 0 at the box's top)

  glm::vec2 size() const { return glm::vec2(max - min); }
  float area() const { return size().x * size().y; }
  // CasterCuller's rule on the CPU: a caster's light-view box overlaps the map in x/y and reaches
  // down to the box's bottom; casters above it are kept (pancaked).
  bool MayCast(const scene::Bounds& lightViewBounds) const;
};

// The camera frustum in the light view: its origin and, per corner (bit 0 right, bit 1 up), the
// offset per unit of view depth. fit.hlsl gets these and builds slices the same way.
struct FrustumRays {
  glm::vec3 origin{0.0f};
  glm::vec3 corner[4];
};
FrustumRays MakeFrustumRays(const glm::mat4& lightView, const glm::mat4& cameraView, const glm::mat4& cameraProj);
// The light-view box of the frustum between view depths z0 and z1 (FrustumSliceBounds in the
// arithmetic fit.hlsl repeats), marked as holding samples.
LightBounds SliceBounds(const FrustumRays& rays, float z0, float z1);

// `bounds` empty gives an empty fit (with its splits).
PartitionFit FitPartition(const LightBounds& bounds, float splitNear, float splitFar, const glm::mat4& lightView, const FitParams& params);

// The lighting's constants for a set of fits (K = fits.size(); the last one's split far should
// already reach past every receiver). settings: csmSettings.
CsmShadowConstants MakeConstants(const std::vector<PartitionFit>& fits, const glm::mat4& lightView, const glm::vec3& cameraForward,
                                 const glm::vec4& settings, uint32_t resolution, const glm::vec4& pcss);

// The fits a fit buffer holds (kFitBytes / 4 words), K partitions.
std::vector<PartitionFit> DecodeFitBuffer(const std::vector<uint32_t>& words, uint32_t partitions);
// The blur radii (texels) a fit buffer holds for K partitions.
std::vector<float> DecodeFitBlurRadii(const std::vector<uint32_t>& words, uint32_t partitions);

// The paper's Figure 4: the analysed samples in light space (x right, y up; z of each sample =
// its partition) as dots tinted by partition, with each partition's fitted box outlined in its
// colour, scaled to fit the union of boxes and samples. RGBA8, w x h.
std::vector<uint8_t> RenderLightSpaceImage(const std::vector<glm::vec3>& samples, const std::vector<PartitionFit>& fits, uint32_t width,
                                           uint32_t height);

}  // namespace sp::tech::sdsm
