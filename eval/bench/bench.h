// The bench runner: renders techniques along a camera path on a backend, measures them against the
// ray-traced reference (eval/metrics) and writes `{"runs": [...]}` results for `shadowport report`.
//
// One run = one (scene, technique, parameters, backend):
//  1. timing: `frames` frames along the path with the normal lit pass, GPU time per pass from
//     timestamp queries (GpuTimer) and CPU time of RenderFrame + Flush (recording and submission),
//     one frame at a time (the GPU idle when each starts); medians over the frames after the first
//     kWarmupFrames;
//  2. measurement: the same frames again with the lab's lit pass, read back, judged against the
//     reference (cached on disk) for accuracy, texel density and utilization; before each frame
//     after the first, the lab lit pass is drawn once more with the new camera and the previous
//     frame's shadow state, which gives the shadow term of the previous frame at exactly this
//     frame's surface points (flicker).
// The two phases are separate so the lab's extra render targets and read-backs never inflate the
// timings.
#pragma once
#include <array>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "metrics.h"
#include <sp/tech/asm-counters.h>
#include "reference.h"

namespace sp::bench {

constexpr uint32_t kWarmupFrames = 2;

using Progress = std::function<void(const std::string&)>;

struct RunSpec {
  const scene::Scene* scene = nullptr;
  std::string technique;                                     // registry name
  std::function<std::unique_ptr<tech::Technique>()> make;    // instead of the registry (tests)
  std::map<std::string, std::string> params;                 // as given; validated against the technique
  Backend backend = Backend::Vulkan;
  uint32_t width = 640, height = 360, frames = 8;
  const scene::CameraPath* path = nullptr;                   // null: the scene camera, static
  bool validate = false;                                     // validation layers / GL debug output
};

struct RunResult {
  std::string scene, technique, backend, device, path;
  std::map<std::string, std::string> params;  // every parameter, defaults filled in
  std::map<std::string, std::string> paramsGiven;  // those the caller set (what names a variant)
  uint32_t width = 0, height = 0, frames = 0;
  uint64_t sceneTriangles = 0;

  eval::Accuracy accuracy;
  // The same per region of the scene (scene::Scene::regions, in that order), over all frames.
  std::vector<std::pair<std::string, eval::Accuracy>> regions;
  double texelsPerPixelMedian = 0, texelsPerPixelP05 = 0;
  // Lloyd et al.'s measures, of the worst frame: the largest projected size of a shadow texel in
  // pixels over the visible receivers (1 / texels per pixel; the 99.9th percentile over pixels,
  // so single-pixel derivative spikes at silhouettes do not decide it), and the storage factor
  // it implies: the map texels needed for that error to be 1, per screen pixel.
  double maxAliasingError = 0, storageFactor = 0;
  uint64_t densitySamples = 0;
  double utilization = 0;                   // mean over frames
  eval::Flicker flicker;                    // exact, same world points
  eval::Flicker flickerReprojected, flickerReprojectedReference;
  std::map<std::string, double> gpuMs;      // pass -> median ms, and "total"
  double cpuMs = 0;                         // median
  uint64_t shadowMemoryBytes = 0, shadowTriangles = 0;
  uint64_t shadowLayersRendered = 0;  // median per frame; 0 when the technique does not count them
  // Accelerated filters (accel=hpsm|minmax with counters): fractions of the last timed frame's
  // lookups decided by min/max ("minmax"), by a plane ("plane"), sent to the filter ("filtered").
  std::map<std::string, double> hpsmDecisions;
  // Adaptive shadow maps (asm): what each timed frame's refinement did, frames 0..N-1 (empty for
  // other techniques). The JSON adds the frame the refinement first rendered no page in
  // ("converged_frame", -1 if none) and the unserved requests over all frames.
  std::vector<tech::AsmCounters> asmRefinement;
  // ... and the pages resident after the last timed frame, per page-table level (0 the coarsest).
  std::vector<uint32_t> asmPagesByLevel;

  std::vector<double> flickerSeries;        // frames 1..N-1
  std::vector<double> misclassifiedSeries, gpuTotalSeries, cpuSeries;  // frames 0..N-1

  tech::LabBuffers firstFrame;              // frame 0 (the path's start), for the pictures
  std::vector<float> firstReference;        // fraction of the light visible (0/1 for a hard light)
  scene::DirectionalLight light;
  int judgedLocalLight = -1;                // Technique::LabLocalLight: -1 the directional light
  // Where a point light is judged: accuracy inside the band around its cube-face edges and
  // elsewhere (eval::MeasureSeamAccuracy), over all frames; seamBand (the first frame's) 0 when
  // not measured.
  eval::SeamAccuracy seam;
  float seamBand = 0;
  // Texels per pixel per cube face of the pixels' directions from that point light (median over
  // all frames, 0 for a face no judged pixel read; eval::kCubeFaceNames order).
  std::array<double, 6> texelsPerPixelMedianByFace{};

  uint64_t validationErrors = 0, disjointFrames = 0;
  bool validationEnabled = false;           // the layers / debug output were really on
  std::string lastValidationError;
  float referenceEpsilon = 0;
  // The judged light's size (eval::ReferenceLight::size: degrees for the directional light, a
  // radius for a local one); 0 = hard.
  float lightSize = 0;
  unsigned lightSamples = 0;  // reference rays per pixel for an area light; 0 for a hard light
};

// Runs one (scene, technique, parameters, backend). Throws std::invalid_argument for an unknown
// technique or invalid parameters (listing the valid ones).
RunResult RunOne(const RunSpec& spec, eval::ReferenceCache& reference, const Progress& progress = {});

// --- The whole bench: what `shadowport bench` does

// A technique with fixed parameters: `name[:k=v[:k=v]...]`, e.g. `csm:filter=gauss:kernel=5`.
// An item without '=' continues the previous value, so list values keep their ':' form
// (`csm:split=manual:splits=0.1:0.3:0.6`). Throws std::invalid_argument for a malformed spec.
struct TechniqueSpec {
  std::string name;
  std::map<std::string, std::string> params;
};
TechniqueSpec ParseTechniqueSpec(const std::string& text);

struct BenchOptions {
  std::vector<std::string> scenes = {"default"};
  std::vector<std::string> techniques = {"basic"};  // TechniqueSpec texts
  std::vector<Backend> backends = {Backend::Vulkan, Backend::OpenGL};
  uint32_t width = 640, height = 360, frames = 8;
  // name -> values; several values make a sweep (every combination is a run).
  std::map<std::string, std::vector<std::string>> params;
  uint64_t triangles = 0;  // scene size knob, built-in scenes only
  std::string path = "slow-pan";
  std::filesystem::path out = "results.json";
  // Empty: $SHADOWPORT_REFERENCE_CACHE, else reference-cache/ beside `out`.
  std::filesystem::path referenceCache;
  bool validate = false;
  // Degrees; each value makes a variant of every scene whose light travels at that angle to the
  // camera's view direction at the path's start (0: from behind the viewer, 90: across the view,
  // 180: towards the viewer, duelling frusta), turned in the plane of the view and world down.
  // Empty: the scenes' own lights.
  std::vector<float> lightGammas;
  // When set, replaces every light's size in every scene (`--light-size`): the directional light's
  // angular diameter in degrees (scene::DirectionalLight::angularDiameterDegrees) and the point and
  // spot lights' radius in world units, so techniques and the reference see the same source.
  std::optional<float> lightSize;
  // Reference rays per pixel for area lights (`--light-samples`, eval::ReferenceOptions).
  unsigned lightSamples = eval::ReferenceOptions{}.lightSamples;
};

// Sets every light of `scene` to `size` (see BenchOptions::lightSize). Throws
// std::invalid_argument naming --light-size and the scene for a negative or non-finite size, or a
// directional angular diameter of 180 degrees or more.
void SetLightSize(scene::Scene& scene, float size);

// A technique that models the light's size itself (a `light_size` parameter, e.g. csm's
// filter=pcss, with the same units as --light-size) gets --light-size's value unless its own is
// given, so it and the reference see the same light. Returns `params` with it filled in; size 0
// (hard) leaves the technique's default. Throws std::invalid_argument when `params` sets a
// different light_size, naming both.
std::map<std::string, std::string> MatchLightSize(const std::string& technique, const std::vector<tech::ParamSpec>& specs,
                                                  std::map<std::string, std::string> params, std::optional<float> lightSize);

// The light direction at `gammaDegrees` to `viewForward` (see BenchOptions::lightGammas).
glm::vec3 LightAtGamma(const glm::vec3& viewForward, float gammaDegrees);

// Checks scene, technique and parameter names and values before anything runs; throws
// std::invalid_argument listing the valid names.
void ValidateBenchOptions(const BenchOptions& options);
// The reference cache a bench with these options uses.
std::filesystem::path ReferenceCacheDir(const BenchOptions& options);
// Runs everything, writes options.out and the images beside it (<stem>-images/), returns the
// document written. Where a technique and parameter set ran on several backends, every run after
// the first carries `cross_backend` (its first frame's colour against the first backend's: pixels,
// differing_pixels, max_difference) and a `backend_diff` image.
nlohmann::json RunBench(const BenchOptions& options, const Progress& progress);

// The file name of a scene's reference picture: "reference.png" for the directional light,
// "reference-light<k>.png" for judged local light k (shaded with that light, eval::ReferenceImage).
std::string ReferenceImageName(int judgedLocalLight);

// One run as a results record; `images` maps kind -> path relative to the results file.
nlohmann::json RunToJson(const RunResult& r, const std::map<std::string, std::string>& images);

}  // namespace sp::bench
