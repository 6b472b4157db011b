// The CPU side of cascaded shadow maps: where the camera's view range is split, and the
// orthographic light frustum of each cascade. Pure math on the scene description, so tests can
// check it without a device.
//
// Spaces: every cascade shares one light view (CascadeSet::lightView, fixed by the scene's bounds
// and the light direction, not by the camera), right-handed and looking down -z; a cascade is an
// orthographic projection of that space onto a rectangle [min, max] in x/y and a range of
// distances [zNear, zFar] from its origin along the light. Sharing the view lets the shader take
// derivatives of one light-view position and scale them per cascade, and makes texel snapping a
// matter of rounding x/y offsets in that fixed frame.
#pragma once
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include <sp/scene/scene.h>

namespace sp::tech::csm {

enum class SplitScheme { Uniform, Log, Pssm, Manual };

// "uniform", "log", "pssm", "manual"; throws std::invalid_argument otherwise.
SplitScheme ParseSplitScheme(const std::string& name);

// The `splits` parameter: cascades - 1 strictly increasing fractions in (0, 1) of the view range,
// separated by commas ("0.05,0.15,0.4") or colons ("0.05:0.15:0.4", for `shadowport bench`, where
// commas separate the values of a sweep). Throws std::invalid_argument naming the parameter.
std::vector<float> ParseManualSplits(const std::string& text, int cascades);

// Split distances along the view axis: cascades + 1 values from nearZ to farZ.
//   uniform: n + (f - n) i / N          log: n (f / n)^(i / N)
//   pssm:    lambda * log + (1 - lambda) * uniform (Zhang et al.)
//   manual:  n + (f - n) * fraction[i - 1]
std::vector<float> SplitDistances(SplitScheme scheme, int cascades, float nearZ, float farZ, float lambda,
                                  const std::vector<float>& manualFractions = {});

struct FitSettings {
  int cascades = 4;
  SplitScheme split = SplitScheme::Pssm;
  float lambda = 0.75f;
  std::vector<float> manualFractions;
  bool fitToScene = false;     // fit=scene: every cascade covers the view from the camera's near plane
  // focus=receivers: x/y to the part of the slice inside the scene bounds, z from those receivers
  // towards the light to their casters; focus=scene: x/y to the slice, z to the scene bounds.
  bool focusReceivers = true;
  // x/y to the slice's bounding sphere (the receivers' square, on a ladder of sizes, where the
  // slice leaves the scene), snapped to whole texels; depth range on a fixed grid.
  bool stabilize = true;
  float blend = 0.0f;          // each cascade also covers this fraction of the previous one's interval
  uint32_t resolution = 1024;  // texels across a cascade's region
  uint32_t padTexels = 2;      // texels kept between the fitted area and the region's edge
  // A reach given in world units (the moment blur radius), added to padTexels in each cascade's
  // own texels, rounded up and at most padWorldMaxTexels: the blur covers the same world distance
  // in every cascade, so its share of the padding differs per cascade (CascadeFit::padTexels).
  float padWorld = 0.0f;
  uint32_t padWorldMaxTexels = 0;
  // focus=receivers: the far plane also behind every surface in the region (x/y with padding),
  // not only behind the slice's receivers. Beyond it depth is clamped to 1 (depth clip is off),
  // which comparisons do not mind but moment filters do: a receiver near the far plane would
  // average its neighbours' clamped depths, no longer its own plane, and shadow itself.
  bool farToRegion = false;
};

struct CascadeFit {
  float splitNear = 0, splitFar = 0;  // view-depth interval that interval selection assigns to it
  float sliceNear = 0, sliceFar = 0;  // view-depth range of the frustum slice it was fitted to
  glm::vec2 min{0.0f}, max{0.0f};     // light-view x/y the region covers, padding included
  float zNear = 0, zFar = 1;          // distances from the light-view origin along the light
  glm::mat4 proj{1.0f};               // light view -> clip (orthographic, depth 0..1)
  glm::mat4 viewProj{1.0f};           // world -> clip
  float texelWorld = 0;               // world size of one texel (the larger of x and y)
  float fitSize = 0;                  // stabilized: side of the fitted square before padding
  bool noReceivers = false;           // the slice misses the scene's bounds (fitted to the slice alone)
  uint32_t padTexels = 0;             // this region's padding: FitSettings::padTexels + its share of padWorld

  // World point -> texel coordinates of the region (row 0 at the top) and depth in [0, 1].
  glm::vec3 texel(const glm::vec3& world, uint32_t resolution) const;
};

struct CascadeSet {
  glm::mat4 lightView{1.0f};
  float nearZ = 0, farZ = 0;  // the view range that was split (far clipped to the scene)
  std::vector<float> splits;  // cascades + 1 distances
  std::vector<CascadeFit> cascades;
};

// The light view every cascade shares: looking along `direction` at the bounds' centre from
// outside the bounds.
glm::mat4 SharedLightView(const scene::Bounds& bounds, const glm::vec3& direction);

// The far end of the range worth splitting: the camera's far plane, clipped to the farthest the
// scene reaches along the view. With `stabilize`, the clip uses the bounding sphere (independent of
// the camera's orientation) rounded up to a step of 2^(1/8), so small camera motions leave the
// splits, and the cascades' sizes, unchanged.
float ClippedFar(const scene::Camera& camera, const scene::Bounds& bounds, bool stabilize);

// Corners of the view-frustum slice between view depths d0 and d1: bit 0 right, bit 1 up,
// bit 2 far.
void SliceCorners(const scene::Camera& camera, float aspect, float d0, float d1, glm::vec3 out[8]);

// Vertices of the intersection of a slice (corners as SliceCorners) with an axis-aligned box;
// empty when they do not meet.
std::vector<glm::vec3> SliceBoxIntersection(const glm::vec3 corners[8], const scene::Bounds& box);

// Fits every cascade for one frame. `previous`, the last frame's fit with the same settings,
// lets stabilized receiver squares keep their size while it still fits.
CascadeSet FitCascades(const scene::Scene& scene, const scene::Camera& camera, float aspect, const glm::vec3& lightDirection,
                       const FitSettings& settings, const CascadeSet* previous = nullptr);

// Whether an instance can cast into a cascade, given its bounds in the shared light view (world
// bounds transformed by CascadeSet::lightView): it overlaps the region in x/y and begins before
// the far plane. Casters nearer than zNear are kept: depth clamping pancakes them.
bool MayCastInto(const CascadeFit& cascade, const scene::Bounds& lightViewBounds);

}  // namespace sp::tech::csm
