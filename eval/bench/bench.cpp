// `shadowport bench` as a library: option checks, the loop over scenes, techniques, parameter
// sets and backends, the results file and the pictures.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "bench.h"

namespace sp::bench {

namespace fs = std::filesystem;

namespace {

// Every combination of the swept parameter values, in a stable order.
std::vector<std::map<std::string, std::string>> ParamSets(const std::map<std::string, std::vector<std::string>>& sweep) {
  std::vector<std::map<std::string, std::string>> sets = {{}};
  for (const auto& [name, values] : sweep) {
    std::vector<std::map<std::string, std::string>> next;
    for (const auto& s : sets)
      for (const std::string& v : values) {
        auto t = s;
        t[name] = v;
        next.push_back(std::move(t));
      }
    sets = std::move(next);
  }
  return sets;
}

bool IsBuiltin(const std::string& name) {
  for (const std::string& b : scene::BuiltinSceneNames())
    if (b == name) return true;
  return false;
}

bool IsKnownScene(const std::string& name) {
  if (IsBuiltin(name)) return true;
  for (const std::string& s : scene::SharedSceneNames())
    if (s == name) return true;
  fs::path p(name);
  return (p.extension() == ".gltf" || p.extension() == ".glb") && fs::exists(p);
}

std::string Join(const std::vector<std::string>& v) {
  std::string s;
  for (const std::string& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

// A file-name-safe rendering of a name.
std::string Slug(const std::string& text) {
  std::string s;
  for (char c : text) s += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '.' || c == '=') ? c : '_';
  return s;
}

}  // namespace

std::string ReferenceImageName(int judgedLocalLight) {
  return judgedLocalLight < 0 ? "reference.png" : "reference-light" + std::to_string(judgedLocalLight) + ".png";
}

namespace {

double Round(double v, double scale) { return std::round(v * scale) / scale; }

// The parameters of one run: the technique spec's, then the sweep's.
std::map<std::string, std::string> RunParams(const TechniqueSpec& t, const std::map<std::string, std::string>& sweep) {
  std::map<std::string, std::string> p = t.params;
  p.insert(sweep.begin(), sweep.end());
  return p;
}

}  // namespace

TechniqueSpec ParseTechniqueSpec(const std::string& text) {
  TechniqueSpec spec;
  std::string last;
  size_t start = 0;
  while (start <= text.size()) {
    size_t colon = text.find(':', start);
    std::string item = text.substr(start, colon == std::string::npos ? std::string::npos : colon - start);
    if (item.empty()) throw std::invalid_argument("technique '" + text + "' has an empty item (form: name[:param=value]...)");
    size_t eq = item.find('=');
    if (spec.name.empty()) {
      if (eq != std::string::npos) throw std::invalid_argument("technique '" + text + "' must start with a technique name, not '" + item + "'");
      spec.name = item;
    } else if (eq == std::string::npos) {
      if (last.empty()) throw std::invalid_argument("technique '" + text + "': '" + item + "' is not param=value");
      spec.params[last] += ":" + item;  // a list value: splits=0.1:0.3:0.6
    } else {
      std::string k = item.substr(0, eq);
      if (k.empty()) throw std::invalid_argument("technique '" + text + "': '" + item + "' has no parameter name");
      if (spec.params.count(k)) throw std::invalid_argument("technique '" + text + "' sets " + k + " twice");
      spec.params[k] = item.substr(eq + 1);
      last = k;
    }
    if (colon == std::string::npos) break;
    start = colon + 1;
  }
  return spec;
}

fs::path ReferenceCacheDir(const BenchOptions& o) {
  if (!o.referenceCache.empty()) return o.referenceCache;
  fs::path dir = o.out.has_parent_path() ? o.out.parent_path() : fs::path(".");
  return eval::DefaultReferenceCacheDir(dir / "reference-cache");
}

void ValidateBenchOptions(const BenchOptions& o) {
  if (o.scenes.empty()) throw std::invalid_argument("no scene given");
  for (const std::string& s : o.scenes) {
    if (!IsKnownScene(s))
      throw std::invalid_argument("unknown scene '" + s + "' (built-in: " + Join(scene::BuiltinSceneNames()) +
                                  "; shared: " + Join(scene::SharedSceneNames()) + "; or a path to a .gltf/.glb file)");
    if (o.triangles && !IsBuiltin(s))
      throw std::invalid_argument("--triangles applies to built-in scenes only; '" + s + "' has a fixed size");
  }
  if (o.triangles > scene::kMaxTargetTriangles)
    throw std::invalid_argument("--triangles " + std::to_string(o.triangles) + " is above the limit of " + std::to_string(scene::kMaxTargetTriangles));
  for (float g : o.lightGammas)
    if (!(g >= 0.0f && g <= 180.0f)) throw std::invalid_argument("--light-gamma values are degrees in [0, 180] (got " + std::to_string(g) + ")");
  if (o.lightSize) {
    scene::Scene probe;
    probe.name = "(any)";
    SetLightSize(probe, *o.lightSize);  // throws for a bad value before anything loads
  }
  if (o.lightSamples < 1 || o.lightSamples > 65535)
    throw std::invalid_argument("--light-samples must be in 1..65535 (got " + std::to_string(o.lightSamples) + ")");
  if (o.techniques.empty()) throw std::invalid_argument("no technique given");
  if (o.backends.empty()) throw std::invalid_argument("no backend given");
  if (o.frames < 1) throw std::invalid_argument("--frames must be at least 1");
  if (scene::IsCameraPathFile(o.path)) scene::LoadCameraPath(o.path);  // a malformed recording fails before anything runs
  for (const std::string& text : o.techniques) {
    TechniqueSpec t = ParseTechniqueSpec(text);
    std::unique_ptr<tech::Technique> technique = tech::CreateTechnique(t.name);  // throws listing the names
    for (const auto& [k, v] : o.params)
      if (t.params.count(k)) throw std::invalid_argument("parameter " + k + " is set both in --technique " + text + " and by --param");
    for (const auto& set : ParamSets(o.params))
      tech::ParamValues::Parse(t.name, technique->Params(), MatchLightSize(t.name, technique->Params(), RunParams(t, set), o.lightSize));
  }
}

nlohmann::json RunToJson(const RunResult& r, const std::map<std::string, std::string>& images) {
  using nlohmann::json;
  json gpu = json::object();
  for (const auto& [pass, ms] : r.gpuMs) gpu[pass] = Round(ms, 1e4);
  json m = {
      {"misclassified_pct", Round(r.accuracy.misclassifiedPct(), 1e4)},
      {"false_lit_pct", Round(r.accuracy.falseLitPct(), 1e4)},
      {"false_shadow_pct", Round(r.accuracy.falseShadowPct(), 1e4)},
      {"mean_abs_error", Round(r.accuracy.meanAbsError(), 1e6)},
      {"penumbra_mean_abs_error", Round(r.accuracy.penumbraMeanAbsError(), 1e6)},
      {"penumbra_pixels", r.accuracy.penumbra},
      {"texels_per_pixel_median", r.texelsPerPixelMedian},
      {"texels_per_pixel_p05", r.texelsPerPixelP05},
      {"max_aliasing_error", r.maxAliasingError},
      {"storage_factor", r.storageFactor},
      {"utilization", r.utilization},
      {"flicker", r.flicker.mean()},
      {"flicker_reprojected", r.flickerReprojected.mean()},
      {"flicker_reprojected_reference", r.flickerReprojectedReference.mean()},
      {"gpu_ms", gpu},
      {"cpu_ms", Round(r.cpuMs, 1e4)},
      {"shadow_memory_bytes", r.shadowMemoryBytes},
      {"shadow_triangles", r.shadowTriangles},
      {"shadow_layers_rendered", r.shadowLayersRendered},
  };
  if (!r.regions.empty()) {
    json regions = json::object();
    for (const auto& [name, a] : r.regions)
      regions[name] = {{"pixels", a.receiving},
                       {"mean_abs_error", Round(a.meanAbsError(), 1e6)},
                       {"penumbra_mean_abs_error", Round(a.penumbraMeanAbsError(), 1e6)},
                       {"penumbra_pixels", a.penumbra},
                       {"umbra_pixels", a.umbra},
                       {"umbra_leak_fraction", Round(a.umbraLeakFraction(), 1e6)},
                       {"umbra_mean_visibility", Round(a.umbraMeanVisibility(), 1e6)}};
    m["regions"] = regions;
  }
  if (!r.asmRefinement.empty()) {
    json frames = json::array();
    int converged = -1;
    uint64_t unserved = 0;
    for (size_t i = 0; i < r.asmRefinement.size(); ++i) {
      const tech::AsmCounters& c = r.asmRefinement[i];
      frames.push_back({{"iterations", c.iterations}, {"requests", c.requests}, {"pages_rendered", c.pagesRendered},
                        {"evicted", c.evicted}, {"unserved", c.unserved}, {"resident", c.resident}});
      if (converged < 0 && c.pagesRendered == 0) converged = int(i);
      unserved += c.unserved;
    }
    m["asm_refinement"] = {{"frames", frames}, {"converged_frame", converged}, {"unserved_total", unserved}, {"pages_by_level", r.asmPagesByLevel}};
  }
  if (!r.hpsmDecisions.empty()) {
    json h = json::object();
    for (const auto& [k, v] : r.hpsmDecisions) h[k] = Round(v, 1e4);
    m["hpsm_decisions"] = h;
  }
  json params = json::object(), given = json::object();
  for (const auto& [k, v] : r.params) params[k] = v;
  for (const auto& [k, v] : r.paramsGiven) given[k] = v;
  json series = {{"misclassified_pct", r.misclassifiedSeries}, {"gpu_ms_total", r.gpuTotalSeries}, {"cpu_ms", r.cpuSeries}};
  if (!r.flickerSeries.empty()) series["flicker"] = r.flickerSeries;
  json run = {
      {"scene", r.scene},
      {"technique", r.technique},
      {"params", params},
      {"params_given", given},
      {"backend", r.backend},
      {"size", {r.width, r.height}},
      {"frames", r.frames},
      {"device", r.device},
      {"path", r.path},
      {"scene_triangles", r.sceneTriangles},
      {"metrics", m},
      {"series", series},
      {"checks",
       {{"judged_pixels", r.accuracy.receiving},
        {"texel_density_samples", r.densitySamples},
        {"flicker_pixels", r.flicker.pixels},
        {"flicker_unmatched_pixels", r.flicker.unmatched},
        {"reference_epsilon", r.referenceEpsilon},
        {"light_size", r.lightSize},
        {"warmup_frames_dropped", r.frames > kWarmupFrames ? kWarmupFrames : 0u},
        {"disjoint_frames", r.disjointFrames},
        {"validation_enabled", r.validationEnabled},
        {"validation_errors", r.validationErrors}}},
  };
  // Local-light techniques are judged on one local light (index into the scene's point lights, then spot lights).
  if (r.judgedLocalLight >= 0) run["checks"]["judged_local_light"] = r.judgedLocalLight;
  if (r.lightSamples) run["checks"]["reference_light_samples"] = r.lightSamples;
  // A judged point light: misclassification within the band around its cube-face edges and away
  // from it (docs/local-lights.md, "Seam metric").
  if (r.seamBand > 0) {
    run["metrics"]["seam_misclassified_pct"] = Round(r.seam.band.misclassifiedPct(), 1e4);
    run["metrics"]["off_seam_misclassified_pct"] = Round(r.seam.elsewhere.misclassifiedPct(), 1e4);
    run["checks"]["seam_band"] = r.seamBand;
    run["checks"]["seam_pixels"] = r.seam.band.receiving;
    run["checks"]["off_seam_pixels"] = r.seam.elsewhere.receiving;
    nlohmann::json byFace = nlohmann::json::object();
    for (int f = 0; f < 6; ++f) byFace[eval::kCubeFaceNames[f]] = r.texelsPerPixelMedianByFace[f];
    run["metrics"]["texels_per_pixel_median_by_face"] = byFace;
  }
  if (!r.lastValidationError.empty()) run["checks"]["last_validation_error"] = r.lastValidationError;
  if (!images.empty()) run["images"] = images;
  return run;
}

void SetLightSize(scene::Scene& scene, float size) {
  if (!std::isfinite(size) || size < 0.0f)
    throw std::invalid_argument("--light-size must be a finite number >= 0 (got " + std::to_string(size) + ") for scene '" + scene.name + "'");
  if (!(size < 180.0f))
    throw std::invalid_argument("--light-size " + std::to_string(size) + " is the directional light's angular diameter in degrees, which must be below 180 (scene '" +
                                scene.name + "')");
  scene.light.angularDiameterDegrees = size;
  for (scene::PointLight& l : scene.pointLights) l.radius = size;
  for (scene::SpotLight& l : scene.spotLights) l.radius = size;
}

std::map<std::string, std::string> MatchLightSize(const std::string& technique, const std::vector<tech::ParamSpec>& specs,
                                                  std::map<std::string, std::string> params, std::optional<float> lightSize) {
  if (!lightSize) return params;
  bool has = std::any_of(specs.begin(), specs.end(), [](const tech::ParamSpec& p) { return p.name == "light_size"; });
  if (!has) return params;
  char text[32];
  std::snprintf(text, sizeof text, "%g", double(*lightSize));
  if (auto given = params.find("light_size"); given != params.end()) {
    char* end = nullptr;
    float v = std::strtof(given->second.c_str(), &end);
    if (end == given->second.c_str() || *end || v != std::strtof(text, nullptr))
      throw std::invalid_argument("technique '" + technique + "' sets light_size=" + given->second + " but --light-size is " + text +
                                  ": the technique and the reference would judge different lights");
    return params;
  }
  if (*lightSize > 0.0f) params["light_size"] = text;
  return params;
}

glm::vec3 LightAtGamma(const glm::vec3& viewForward, float gammaDegrees) {
  glm::vec3 f = glm::normalize(viewForward);
  // The turn goes towards world down, so at 90 degrees the light comes from above the view axis;
  // a camera looking straight down turns towards its own world z instead.
  glm::vec3 down = glm::vec3(0, -1, 0) - f * glm::dot(glm::vec3(0, -1, 0), f);
  if (glm::length(down) < 1e-4f) down = glm::vec3(0, 0, 1) - f * glm::dot(glm::vec3(0, 0, 1), f);
  down = glm::normalize(down);
  float g = glm::radians(gammaDegrees);
  return glm::normalize(std::cos(g) * f + std::sin(g) * down);
}

nlohmann::json RunBench(const BenchOptions& o, const Progress& progress) {
  ValidateBenchOptions(o);
  fs::path out = o.out;
  fs::path dir = out.has_parent_path() ? out.parent_path() : fs::path(".");
  fs::create_directories(dir);
  std::string imageDir = out.stem().string() + "-images";
  std::vector<std::map<std::string, std::string>> sets = ParamSets(o.params);

  nlohmann::json doc = {{"runs", nlohmann::json::array()}};
  size_t total = o.scenes.size() * std::max<size_t>(1, o.lightGammas.size()) * o.techniques.size() * sets.size() * o.backends.size(),
         done = 0;
  // Every scene is loaded (and its path checked) before the first run, so a bad name fails at once.
  std::vector<scene::Scene> scenes;
  for (const std::string& name : o.scenes) {
    if (progress) progress("loading scene " + name);
    scene::SceneOptions so;
    so.targetTriangles = o.triangles;
    scene::Scene sc = scene::LoadScene(name, so);
    if (sc.name.empty()) sc.name = fs::path(name).stem().string();
    if (sc.cameraPaths.empty()) sc.cameraPaths = scene::CameraPathsFor(sc);
    // Throws listing the scene's paths; a recorded path file (the viewer's) is added to the scene.
    const scene::CameraPath& path = sc.cameraPathOrFile(o.path);
    if (!sc.useRecordedLight(path) && progress)
      progress(o.path + ": the recorded light turns along the path; each frame takes its direction there, in the techniques and the reference");
    if (o.lightSize) SetLightSize(sc, *o.lightSize);
    if (o.lightGammas.empty()) {
      scenes.push_back(std::move(sc));
      continue;
    }
    glm::vec3 forward = sc.cameraPath(o.path).at(0.0).forward();
    for (float g : o.lightGammas) {
      scene::Scene v = sc;
      char label[32];
      std::snprintf(label, sizeof label, "-gamma%g", double(g));
      v.name = sc.name + label;
      v.light.direction = LightAtGamma(forward, g);
      v.regions.clear();  // laid out for the scene's own light (scene::Region)
      scenes.push_back(std::move(v));
    }
  }
  for (size_t si = 0; si < scenes.size(); ++si) {
    const scene::Scene& sc = scenes[si];
    if (progress) progress("scene " + std::to_string(si + 1) + "/" + std::to_string(scenes.size()) + ": " + sc.name);
    const scene::CameraPath& path = sc.cameraPath(o.path);
    eval::ReferenceOptions ro;
    ro.lightSamples = o.lightSamples;
    eval::ReferenceCache cache(sc, ReferenceCacheDir(o), ro);
    std::map<int, std::string> referenceImages;
    for (size_t ti = 0; ti < o.techniques.size(); ++ti)
      for (const auto& set : sets) {
        const TechniqueSpec t = ParseTechniqueSpec(o.techniques[ti]);
        const std::map<std::string, std::string> params =
            MatchLightSize(t.name, tech::CreateTechnique(t.name)->Params(), RunParams(t, set), o.lightSize);
        // The first backend's picture, which the others' are compared with.
        std::vector<uint8_t> firstColor;
        std::string firstBackend;
        for (Backend b : o.backends) {
          ++done;
          RunSpec spec;
          spec.scene = &sc;
          spec.technique = t.name;
          spec.params = params;
          spec.backend = b;
          spec.width = o.width;
          spec.height = o.height;
          spec.frames = o.frames;
          spec.path = &path;
          spec.validate = o.validate;
          if (progress)
            progress("run " + std::to_string(done) + "/" + std::to_string(total) + ": technique " + std::to_string(ti + 1) + "/" +
                     std::to_string(o.techniques.size()) + " (" + o.techniques[ti] + ") on " + BackendName(b));
          RunResult r = RunOne(spec, cache, progress);

          // Pictures of the path's first frame; the reference once per scene.
          std::string stem = Slug(sc.name) + "/" + Slug(t.name);
          for (const auto& [k, v] : params) stem += "-" + Slug(k + "=" + v);
          stem += std::string("-") + BackendName(b);
          std::map<std::string, std::string> images;
          const tech::LabBuffers& f = r.firstFrame;
          auto write = [&](const std::string& kind, const std::string& rel, uint32_t h, const std::vector<uint8_t>& rgba) {
            eval::WritePng(dir / rel, f.width, h, rgba.data());
            images[kind] = rel;
          };
          write("color", imageDir + "/" + stem + "-color.png", f.height, f.color);
          uint32_t h = 0;
          std::vector<uint8_t> err = eval::ErrorHeatMap(f, r.firstReference.data(), &h);
          write("error", imageDir + "/" + stem + "-error.png", h, err);
          std::vector<uint8_t> dens = eval::TexelDensityHeatMap(f, &h);
          write("texel_density", imageDir + "/" + stem + "-density.png", h, dens);
          // One reference picture per scene and judged light: a local light's is shaded with it.
          std::string& referenceImage = referenceImages[r.judgedLocalLight];
          if (referenceImage.empty()) {
            referenceImage = imageDir + "/" + Slug(sc.name) + "/" + ReferenceImageName(r.judgedLocalLight);
            eval::WritePng(dir / referenceImage, f.width, f.height,
                           eval::ReferenceImage(f, r.firstReference.data(), r.light, tech::LocalLightsOf(sc), r.judgedLocalLight).data());
          }
          images["reference"] = referenceImage;
          nlohmann::json crossBackend;
          if (firstColor.empty()) {
            firstColor = f.color;
            firstBackend = r.backend;
          } else {
            eval::ImageDiff d = eval::DiffImages(f.width, f.height, firstColor.data(), f.color.data());
            write("backend_diff", imageDir + "/" + stem + "-vs-" + firstBackend + "-diff.png", d.imageHeight, d.heatmap);
            crossBackend = {{"against", firstBackend},
                            {"image", "color"},
                            {"pixels", d.pixels},
                            {"differing_pixels", d.differingPixels},
                            {"max_difference", d.maxDifference}};
          }
          nlohmann::json run = RunToJson(r, images);
          if (!crossBackend.is_null()) run["cross_backend"] = crossBackend;
          doc["runs"].push_back(std::move(run));
          // Written after every run, so an interrupted bench keeps what it measured.
          std::ofstream(out) << doc.dump(1) << "\n";
          if (progress) {
            std::ostringstream s;
            std::string variant = t.name;
            for (const auto& [k, v] : params) variant += " " + k + "=" + v;
            s << std::fixed << std::setprecision(3) << "  " << sc.name << " / " << variant << " / " << r.backend
              << ": misclassified " << r.accuracy.misclassifiedPct() << " %, texels/px median " << r.texelsPerPixelMedian
              << ", GPU total " << std::setprecision(1) << r.gpuMs["total"] << " ms, flicker " << std::defaultfloat << std::setprecision(2)
              << r.flicker.mean();
            if (r.seamBand > 0)
              s << std::setprecision(3) << "; seam band " << r.seam.band.misclassifiedPct() << " % of " << r.seam.band.receiving
                << " px, elsewhere " << r.seam.elsewhere.misclassifiedPct() << " % of " << r.seam.elsewhere.receiving << " px";
            if (!crossBackend.is_null())
              s << "; first frame against " << firstBackend << ": " << crossBackend["differing_pixels"].get<uint64_t>()
                << " pixels differ (max " << crossBackend["max_difference"].get<int>() << ")";
            progress(s.str());
          }
        }
      }
  }
  std::ofstream file(out);
  file << doc.dump(1) << "\n";
  if (!file) throw std::runtime_error("cannot write " + out.string());
  return doc;
}

}  // namespace sp::bench
