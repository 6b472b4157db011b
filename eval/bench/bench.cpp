// `shadowport bench` as a library: option checks, the loop over scenes, techniques, parameter
// sets and backends, the results file and the pictures.
#include <cctype>
#include <cmath>
#include <fstream>
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

double Round(double v, double scale) { return std::round(v * scale) / scale; }

}  // namespace

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
  if (o.techniques.empty()) throw std::invalid_argument("no technique given");
  if (o.backends.empty()) throw std::invalid_argument("no backend given");
  if (o.frames < 1) throw std::invalid_argument("--frames must be at least 1");
  for (const std::string& t : o.techniques) {
    std::unique_ptr<tech::Technique> technique = tech::CreateTechnique(t);  // throws listing the names
    for (const auto& set : ParamSets(o.params)) tech::ParamValues::Parse(t, technique->Params(), set);
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
      {"texels_per_pixel_median", r.texelsPerPixelMedian},
      {"texels_per_pixel_p05", r.texelsPerPixelP05},
      {"utilization", r.utilization},
      {"flicker", r.flicker.mean()},
      {"flicker_reprojected", r.flickerReprojected.mean()},
      {"flicker_reprojected_reference", r.flickerReprojectedReference.mean()},
      {"gpu_ms", gpu},
      {"cpu_ms", Round(r.cpuMs, 1e4)},
      {"shadow_memory_bytes", r.shadowMemoryBytes},
      {"shadow_triangles", r.shadowTriangles},
  };
  json params = json::object();
  for (const auto& [k, v] : r.params) params[k] = v;
  json series = {{"misclassified_pct", r.misclassifiedSeries}, {"gpu_ms_total", r.gpuTotalSeries}, {"cpu_ms", r.cpuSeries}};
  if (!r.flickerSeries.empty()) series["flicker"] = r.flickerSeries;
  json run = {
      {"scene", r.scene},
      {"technique", r.technique},
      {"params", params},
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
        {"warmup_frames_dropped", r.frames > kWarmupFrames ? kWarmupFrames : 0u},
        {"disjoint_frames", r.disjointFrames},
        {"validation_errors", r.validationErrors}}},
  };
  if (!images.empty()) run["images"] = images;
  return run;
}

nlohmann::json RunBench(const BenchOptions& o, const Progress& progress) {
  ValidateBenchOptions(o);
  fs::path out = o.out;
  fs::path dir = out.has_parent_path() ? out.parent_path() : fs::path(".");
  fs::create_directories(dir);
  std::string imageDir = out.stem().string() + "-images";
  std::vector<std::map<std::string, std::string>> sets = ParamSets(o.params);

  nlohmann::json doc = {{"runs", nlohmann::json::array()}};
  size_t total = o.scenes.size() * o.techniques.size() * sets.size() * o.backends.size(), done = 0;
  // Every scene is loaded (and its path checked) before the first run, so a bad name fails at once.
  std::vector<scene::Scene> scenes;
  for (const std::string& name : o.scenes) {
    if (progress) progress("loading scene " + name);
    scene::SceneOptions so;
    so.targetTriangles = o.triangles;
    scene::Scene sc = scene::LoadScene(name, so);
    if (sc.name.empty()) sc.name = fs::path(name).stem().string();
    if (sc.cameraPaths.empty()) sc.cameraPaths = scene::CameraPathsFor(sc);
    sc.cameraPath(o.path);  // throws listing the scene's paths
    scenes.push_back(std::move(sc));
  }
  for (size_t si = 0; si < scenes.size(); ++si) {
    const scene::Scene& sc = scenes[si];
    if (progress) progress("scene " + std::to_string(si + 1) + "/" + std::to_string(scenes.size()) + ": " + sc.name);
    const scene::CameraPath& path = sc.cameraPath(o.path);
    eval::ReferenceCache cache(sc, o.referenceCache.empty() ? eval::DefaultReferenceCacheDir() : o.referenceCache);
    std::string referenceImage;
    for (const std::string& t : o.techniques)
      for (const auto& set : sets)
        for (Backend b : o.backends) {
          ++done;
          RunSpec spec;
          spec.scene = &sc;
          spec.technique = t;
          spec.params = set;
          spec.backend = b;
          spec.width = o.width;
          spec.height = o.height;
          spec.frames = o.frames;
          spec.path = &path;
          spec.validate = o.validate;
          if (progress) progress("run " + std::to_string(done) + "/" + std::to_string(total));
          RunResult r = RunOne(spec, cache, progress);

          // Pictures of the path's first frame; the reference once per scene.
          std::string stem = Slug(sc.name) + "/" + Slug(t);
          for (const auto& [k, v] : set) stem += "-" + Slug(k + "=" + v);
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
          if (referenceImage.empty()) {
            referenceImage = imageDir + "/" + Slug(sc.name) + "/reference.png";
            eval::WritePng(dir / referenceImage, f.width, f.height, eval::ReferenceImage(f, r.firstReference.data(), r.light).data());
          }
          images["reference"] = referenceImage;
          doc["runs"].push_back(RunToJson(r, images));
          // Written after every run, so an interrupted bench keeps what it measured.
          std::ofstream(out) << doc.dump(1) << "\n";
          if (progress) {
            std::ostringstream s;
            s << "  " << sc.name << " / " << r.technique << " / " << r.backend << ": misclassified " << r.accuracy.misclassifiedPct()
              << "%, texels/px median " << r.texelsPerPixelMedian << ", flicker " << r.flicker.mean() << ", GPU total " << r.gpuMs["total"]
              << " ms";
            progress(s.str());
          }
        }
  }
  std::ofstream file(out);
  file << doc.dump(1) << "\n";
  if (!file) throw std::runtime_error("cannot write " + out.string());
  return doc;
}

}  // namespace sp::bench
