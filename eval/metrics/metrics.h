// The lab's metrics, computed on the CPU from what the lab's lit pass wrote (tech::LabBuffers) and
// the ray-traced reference visibility of the same pixels (eval/reference). Every metric is over
// the pixels the lab judges: surfaces drawn and facing the light (LabBuffers::receiving), where
// shading uses the shadow term.
#pragma once
#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

#include <sp/tech/renderer.h>

namespace sp::eval {

// A filtered technique's visibility counts as lit from this value up.
constexpr float kLitThreshold = 0.5f;
// A pixel of the reference's umbra (visibility exactly 0) that a technique gives more than this is
// counted as light bleeding into the umbra (Accuracy::umbraLeaked): well above the bit-exact noise
// of a comparison filter, below anything an eye would take for a shadow.
constexpr float kUmbraLeakThreshold = 0.1f;

// --- Accuracy against the reference: per pixel the fraction of the light visible, 0..1 (0/1 for a
// hard light; fractional in the penumbra of an area light, ReferenceLight::size). A pixel is
// misclassified when it and the reference fall on different sides of kLitThreshold; the mean
// absolute error |visibility - reference| is what judges a penumbra's shape (a soft technique can
// classify every pixel right and still get the penumbra's width wrong). The uint8 overloads take
// 1 = lit, 0 = shadowed and judge exactly as the float ones.

struct Accuracy {
  uint64_t receiving = 0;    // pixels judged
  uint64_t falseLit = 0;     // lit although the reference is shadowed: leaks, peter-panning
  uint64_t falseShadow = 0;  // shadowed although the reference is lit: acne, over-darkening
  double absErrorSum = 0;    // sum of |visibility - reference|: meanAbsError, "mean_abs_error" in results
  // The same over the penumbra alone: pixels whose reference is strictly between 0 and 1 (an area
  // light's partial visibility), so a wrong penumbra width is not averaged away by the umbra and
  // the lit area ("penumbra_mean_abs_error", "penumbra_pixels"). None with a hard reference.
  uint64_t penumbra = 0;
  double penumbraAbsErrorSum = 0;
  // Light bleeding: pixels whose reference is exactly 0 (the umbra), those of them the technique
  // gives more than kUmbraLeakThreshold, and the sum of the technique's visibility over the umbra.
  uint64_t umbra = 0, umbraLeaked = 0;
  double umbraVisibilitySum = 0;

  void add(const Accuracy& o);
  double misclassifiedPct() const { return Pct(falseLit + falseShadow); }
  double falseLitPct() const { return Pct(falseLit); }
  double falseShadowPct() const { return Pct(falseShadow); }
  double meanAbsError() const { return receiving ? absErrorSum / double(receiving) : 0.0; }
  double penumbraMeanAbsError() const { return penumbra ? penumbraAbsErrorSum / double(penumbra) : 0.0; }
  double umbraLeakFraction() const { return umbra ? double(umbraLeaked) / double(umbra) : 0.0; }
  double umbraMeanVisibility() const { return umbra ? umbraVisibilitySum / double(umbra) : 0.0; }

 private:
  double Pct(uint64_t n) const { return receiving ? 100.0 * double(n) / double(receiving) : 0.0; }
};

// The surface points the lab judges, as the reference tracer takes them (ReferenceTracer::
// Visibility, ReferenceCache::Visibility): every pixel's world position and normal, valid where
// the pixel receives light and its point is finite with a unit normal (so the tracer never sees
// a sky pixel or a degenerate one).
struct LabSurfacePoints {
  std::vector<glm::vec3> position, normal;
  std::vector<uint8_t> valid;
  size_t size() const { return valid.size(); }
};
LabSurfacePoints SurfacePointsOf(const tech::LabBuffers& lab);

Accuracy MeasureAccuracy(const tech::LabBuffers& lab, const uint8_t* reference);
Accuracy MeasureAccuracy(const tech::LabBuffers& lab, const float* reference);
// The same over the judged pixels whose world point (LabBuffers::position) is in `region`.
Accuracy MeasureRegionAccuracy(const tech::LabBuffers& lab, const float* reference, const scene::Region& region);

// --- Seams: accuracy near the edges between the faces of a point light's shadow cube

// How far direction d (from the light) is from the nearest cube-face edge: (ma - second) / ma of
// the two largest of |x|, |y|, |z|. On face f this is 1 - |s| for the face coordinate s = sc / ma
// (or tc / ma) that reaches the edge, so it is the distance from the edge in face coordinates
// (a face spans [-1, 1]): 0 on an edge, 1 on the face's axis. D3D11's faces (+X, -X, +Y, -Y, +Z,
// -Z in world space) meet where two of |x|, |y|, |z| are equal, whatever the face's (s, t) axes.
float CubeEdgeGap(const glm::vec3& d);

// The seam band's half width in texels on each side of an edge: the 2x2 filter of a seamless
// cube lookup reads one texel across the edge, so an error of the seam itself sits within one
// texel of it. The band is kSeamBandTexels * 2 / faceTexels in CubeEdgeGap units.
constexpr float kSeamBandTexels = 1.0f;
inline float SeamBandFor(uint32_t faceTexels) { return 2.0f * kSeamBandTexels / float(faceTexels); }

struct SeamAccuracy {
  Accuracy band;       // judged pixels whose direction from the light has CubeEdgeGap < band
  Accuracy elsewhere;  // the other judged pixels
};

// MeasureAccuracy split by the seam band around the cube-face edges of a point light at `light`.
// `band` must be in (0, 1).
SeamAccuracy MeasureSeamAccuracy(const tech::LabBuffers& lab, const uint8_t* reference, const glm::vec3& light, float band);
SeamAccuracy MeasureSeamAccuracy(const tech::LabBuffers& lab, const float* reference, const glm::vec3& light, float band);

// --- Perspective aliasing: texels per pixel (LabBuffers::lookup.w)

// Percentiles of positive values over many frames in fixed memory: 512 logarithmic bins per
// octave from 2^-24 to 2^24 (values beyond go to the end bins), interpolated within a bin and
// clamped to the smallest and largest value added, so a percentile is within one bin (0.14%) of
// the exact one, and exact where all values are equal.
class LogHistogram {
 public:
  LogHistogram();
  void add(double value);
  void add(const LogHistogram& o);
  uint64_t count() const { return count_; }
  // p in [0, 1]; 0 when empty.
  double percentile(double p) const;

 private:
  static constexpr int kPerOctave = 512, kMinExp = -24, kMaxExp = 24;
  std::vector<uint64_t> bins_;
  uint64_t count_ = 0;
  double min_ = 0, max_ = 0;
};

// Adds the texels per pixel of receiving pixels whose lookup read a map (layer >= 0).
void AddTexelDensity(const tech::LabBuffers& lab, LogHistogram& histogram);

// D3D11's cube face of a direction: 0..5 for +X, -X, +Y, -Y, +Z, -Z (ties to z, then y), as
// techniques/cube/cube-faces.h selects it.
int CubeFace(const glm::vec3& d);
constexpr const char* kCubeFaceNames[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
// AddTexelDensity per cube face of the pixels' directions from a point light at `light`.
void AddTexelDensityByFace(const tech::LabBuffers& lab, const glm::vec3& light, std::array<LogHistogram, 6>& histograms);

// --- Utilization: fraction of all layers' texels that some receiving pixel's lookup is centred in.
double MeasureUtilization(const tech::LabBuffers& lab, const std::vector<tech::ShadowLayer>& layers);

// --- Temporal stability

struct Flicker {
  uint64_t pixels = 0;  // pixels compared
  double sum = 0;       // of |change of the shadow term|
  uint64_t unmatched = 0;

  void add(const Flicker& o);
  double mean() const { return pixels ? sum / double(pixels) : 0.0; }
};

// The change of the shadow term at exactly the same world points: `now` is frame t; `before` is
// the lit pass drawn with frame t's camera but frame t-1's shadow state (Renderer::RenderLitPass
// before frame t's RenderFrame), so both hold the same surface points. Pixels whose positions
// differ bit for bit (which same-camera rasterization never gives) are counted in `unmatched`
// and left out.
Flicker MeasureFlicker(const tech::LabBuffers& now, const tech::LabBuffers& before);

// The same by reprojection, as a viewer would see it: each receiving pixel of `cur` is projected
// into `prev`'s camera; the nearest pixel there counts when it receives too and its distance from
// the camera matches within kReprojectionTolerance of that distance. Compares curValue[i] with
// prevValue[j] (the technique's visibility, or the reference's). Sampling the nearest pixel of the
// other frame moves the compared point by up to half a pixel, so even the reference gets a
// non-zero value near shadow edges: the noise floor of this method.
constexpr float kReprojectionTolerance = 0.02f;
Flicker MeasureReprojectedFlicker(const tech::LabBuffers& prev, const float* prevValue, const tech::LabBuffers& cur,
                                  const float* curValue);

// --- Images (RGBA8, width x (height + legend)); a legend strip is drawn under the picture.

// Receiving pixels correct in grey, false lit in red, false shadow in blue (partial errors of
// filtered techniques as a partial tint); the rest darker grey.
std::vector<uint8_t> ErrorHeatMap(const tech::LabBuffers& lab, const uint8_t* reference, uint32_t* imageHeight);
std::vector<uint8_t> ErrorHeatMap(const tech::LabBuffers& lab, const float* reference, uint32_t* imageHeight);
// Texels per pixel in octave bands from <= 1/32 (dark red, undersampled) through 1 (white) to
// >= 32 (dark blue, oversampled).
std::vector<uint8_t> TexelDensityHeatMap(const tech::LabBuffers& lab, uint32_t* imageHeight);
// The frame shaded as the lit pass shades it, with the reference's visibility (no legend): with
// `judgedLocalLight` -1, ambient plus the directional light; otherwise ambient plus every light of
// `localLights` (tech::LocalLightsOf), the judged one with the reference's visibility, and the
// directional light unshadowed, as the lit pass draws a local-light technique's frame.
std::vector<uint8_t> ReferenceImage(const tech::LabBuffers& lab, const uint8_t* reference, const scene::DirectionalLight& light,
                                    const std::vector<tech::LocalLight>& localLights = {}, int judgedLocalLight = -1);
std::vector<uint8_t> ReferenceImage(const tech::LabBuffers& lab, const float* reference, const scene::DirectionalLight& light,
                                    const std::vector<tech::LocalLight>& localLights = {}, int judgedLocalLight = -1);
// The uint8 reference (0/1) as the float one, for the overloads above.
std::vector<float> ReferenceAsFloat(const tech::LabBuffers& lab, const uint8_t* reference);
// The band colours of TexelDensityHeatMap, index 0 (<= 1/32) to 10 (>= 32).
std::array<uint8_t, 3> TexelDensityColor(float texelsPerPixel);

// --- Cross-backend: two renderings of the same frame (RGBA8), compared channel by channel (RGB).
struct ImageDiff {
  uint64_t pixels = 0, differingPixels = 0;
  int maxDifference = 0;  // largest channel difference, 0..255
  uint32_t imageHeight = 0;
  std::vector<uint8_t> heatmap;  // `a` in dark grey, differing pixels in red (brighter = larger), legend under it
};
ImageDiff DiffImages(uint32_t width, uint32_t height, const uint8_t* a, const uint8_t* b);

// Writes an RGBA8 PNG; throws std::runtime_error naming the file.
void WritePng(const std::filesystem::path& path, uint32_t width, uint32_t height, const uint8_t* rgba);

}  // namespace sp::eval
