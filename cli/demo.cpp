// `shadowport demo`: what the project is for, in about two minutes. A small lab run (bench, then
// report): a few shadow techniques on a real scene, on both backends with validation on, judged
// against the ray-traced reference and charted as speed against accuracy on one HTML page, with a
// table of the headline figures on the terminal.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "bench.h"
#include "cli.h"

namespace sp::cli {

namespace {

namespace fs = std::filesystem;

// The scene CascadedShadowMaps11 renders: long, with tall columns, so one map fitted to the scene
// is undersampled near the camera, which is what cascades and sample distribution fix.
constexpr const char* kScene = "ShadowColumns";
// For a clone without ../shared/scenes: a built-in scene with a long view (a plaza and towers far
// behind it), cheap enough to stay within the time of the default run.
constexpr const char* kFallbackScene = "distant-occluder";
// The story a graphics engineer reads from it: one map fitted to the scene (cheap, undersampled
// near the camera); four stabilized PSSM cascades (denser, no shimmer); the same with a 5x5
// Gaussian PCF (softer edges, less acne, a dearer lit pass); moment shadow maps (MSM: filterable,
// but they bleed light and the resolve and blur cost); SDSM (the densest map, fitted to the visible
// samples each frame, so it pays in analysis time and shimmers). Five techniques at 960x540 on
// both backends take about a minute and a half here (2 cores, lavapipe and llvmpipe).
constexpr const char* kTechniques = "basic,csm,csm:filter=gauss:kernel=5,csm:filter=msm,sdsm";
constexpr const char* kSize = "960x540";
constexpr const char* kFrames = "8";
constexpr const char* kPath = "slow-pan";

bool IsSharedScene(const std::string& name) {
  for (const std::string& s : scene::SharedSceneNames())
    if (s == name) return true;
  return false;
}

// The scene to run: the one asked for or, where a shared scene cannot be loaded (the shared folder
// is not beside the project), the built-in fallback, with a one-line notice. Other names are left
// to the bench, which lists the valid ones.
std::string ChooseScene(const std::string& requested) {
  if (!IsSharedScene(requested)) return requested;
  try {
    scene::LoadScene(requested);
    return requested;
  } catch (const std::exception& e) {
    std::string why = e.what();
    if (why.size() > 160) why = why.substr(0, 157) + "...";
    std::fprintf(stderr, "demo: notice: scene %s is not available (%s); using the built-in scene %s instead\n", requested.c_str(),
                 why.c_str(), kFallbackScene);
    return kFallbackScene;
  }
}

// Adds each --param to every technique that has that parameter and does not set it itself; a
// parameter no technique has is an error (it would otherwise be silently ignored).
std::vector<std::string> ApplyParams(std::vector<std::string> specs, const std::map<std::string, std::string>& params) {
  for (const auto& [k, v] : params) {
    bool used = false;
    std::string names;
    for (std::string& text : specs) {
      bench::TechniqueSpec t = bench::ParseTechniqueSpec(text);
      if ((", " + names + ", ").find(", " + t.name + ", ") == std::string::npos) names += (names.empty() ? "" : ", ") + t.name;
      bool has = false;
      for (const tech::ParamSpec& p : tech::CreateTechnique(t.name)->Params()) has |= p.name == k;
      if (!has) continue;
      used = true;
      if (!t.params.count(k)) text += ":" + k + "=" + v;
    }
    if (!used) throw std::invalid_argument("--param " + k + ": none of the techniques (" + names + ") has this parameter");
  }
  return specs;
}

std::string Label(const std::string& specText) {
  bench::TechniqueSpec t = bench::ParseTechniqueSpec(specText);
  std::string s = t.name;
  for (const auto& [k, v] : t.params) s += " " + k + "=" + v;
  return s;
}

std::string Elapsed(double seconds) {
  char b[32];
  std::snprintf(b, sizeof b, "%d:%04.1f", int(seconds) / 60, std::fmod(seconds, 60.0));
  return b;
}

std::string Fixed(double v, int digits) {
  char b[32];
  std::snprintf(b, sizeof b, "%.*f", digits, v);
  return b;
}

// Flicker spans 0 to 1e-2 across techniques: scientific notation keeps small values readable.
std::string Sci(double v) {
  if (v == 0) return "0";
  char b[32];
  std::snprintf(b, sizeof b, "%.1e", v);
  return b;
}

// The headline figures of every run: the lab's speed and accuracy metrics, and validation.
std::string Table(const nlohmann::json& runs, const std::vector<std::string>& labels, size_t backends) {
  size_t width = 9;
  for (const std::string& l : labels) width = std::max(width, l.size());
  std::ostringstream o;
  char line[512];
  std::snprintf(line, sizeof line, "%-*s  %-7s %9s %8s %9s %9s %9s %9s %9s %10s\n", int(width), "technique", "backend", "GPU ms", "shadow",
                "misclass%", "false lit", "false shd", "flicker", "texels/px", "val.errors");
  o << line;
  for (size_t i = 0; i < runs.size(); ++i) {
    const nlohmann::json& r = runs[i];
    const nlohmann::json& m = r["metrics"];
    std::snprintf(line, sizeof line, "%-*s  %-7s %9s %8s %9s %9s %9s %9s %9s %10s\n", int(width), labels[i / backends].c_str(),
                  r["backend"].get<std::string>().c_str(), Fixed(m["gpu_ms"].value("total", 0.0), 1).c_str(),
                  Fixed(m["gpu_ms"].value("total", 0.0) - m["gpu_ms"].value("lit", 0.0), 1).c_str(), Fixed(m["misclassified_pct"].get<double>(), 3).c_str(),
                  Fixed(m["false_lit_pct"].get<double>(), 3).c_str(), Fixed(m["false_shadow_pct"].get<double>(), 3).c_str(),
                  Sci(m["flicker"].get<double>()).c_str(), Fixed(m["texels_per_pixel_median"].get<double>(), 3).c_str(),
                  (r["checks"]["validation_enabled"].get<bool>() ? std::to_string(r["checks"]["validation_errors"].get<uint64_t>()) : "off").c_str());
    o << line;
  }
  return o.str();
}

}  // namespace

int RunDemo(const Args& a) {
  a.expectOnly({"out", "size", "scene", "technique", "frames", "param"});
  if (!a.positionals().empty()) throw std::invalid_argument("unexpected argument '" + a.positionals()[0] + "'");
  ProgressPrinter say("demo: ");
  fs::path dir = a.get("out", "out/demo");

  bench::BenchOptions o;
  o.scenes = {ChooseScene(a.get("scene", kScene))};
  o.techniques = ApplyParams(SplitList(a.get("technique", kTechniques), "technique"), ParseParams(a.getAll("param")));
  o.backends = {Backend::Vulkan, Backend::OpenGL};
  ParseSize(a.get("size", kSize), &o.width, &o.height);
  o.frames = uint32_t(ParseCount(a.get("frames", kFrames), "frames", 1, 10000));
  o.path = kPath;
  // The bench's files go to a folder of their own so the page's files stay at the top.
  o.out = dir / "lab" / "results.json";
  o.validate = true;  // the demo doubles as a smoke test of both backends
  bench::ValidateBenchOptions(o);
  std::vector<std::string> labels;
  for (const std::string& t : o.techniques) labels.push_back(Label(t));

  std::string what = std::to_string(o.techniques.size()) + " technique(s) x 2 backends on " + o.scenes[0] + ", " + std::to_string(o.width) +
                     "x" + std::to_string(o.height) + ", " + std::to_string(o.frames) + " frames along the " + kPath + " camera path";
  say("running " + what + ", validation on; reference cache: " + bench::ReferenceCacheDir(o).string());
  nlohmann::json doc = bench::RunBench(o, [&](const std::string& line) { say(line); });
  const nlohmann::json& runs = doc["runs"];

  // matplotlib keeps a font cache under $HOME unless told otherwise; the demo writes under --out.
  if (const char* e = std::getenv("MPLCONFIGDIR"); !e || !*e) setenv("MPLCONFIGDIR", (dir / "lab" / "mplconfig").c_str(), 1);
  say("writing the report");
  std::string intro = "A small lab run of shadowport demo: " + what +
                      ", on Vulkan and OpenGL with validation on. Every pixel is judged against an Embree ray-traced reference "
                      "of the same frame; the images show the path's first frame.";
  int reportRc = RunReportScript({o.out.string()}, dir.string(), {"--title", "ShadowPort demo: " + o.scenes[0], "--intro", intro});

  uint64_t validationErrors = 0;
  bool validationOff = false;
  for (const auto& r : runs) {
    validationErrors += r["checks"]["validation_errors"].get<uint64_t>();
    validationOff |= !r["checks"]["validation_enabled"].get<bool>();
  }
  std::printf("\n%s\n%s", what.c_str(), Table(runs, labels, o.backends.size()).c_str());
  std::printf(
      "GPU ms: median frame time; shadow: all of it but the lit pass (shadow maps, moment resolve and blur, SDSM analysis).\n"
      "misclass%%: lit-facing pixels whose shadow state differs from the reference; false lit: leaks, peter-panning, light bleeding;\n"
      "false shd: acne, over-darkening. flicker: mean change of the shadow term at the same world points between frames\n"
      "(shimmering). texels/px: median shadow-map texels per screen pixel (below 1: undersampled, blocky edges).\n");
  for (size_t i = 0; i < runs.size(); ++i) {
    const nlohmann::json& r = runs[i];
    if (!r.contains("cross_backend")) continue;
    const nlohmann::json& c = r["cross_backend"];
    uint64_t n = c["differing_pixels"].get<uint64_t>();
    std::printf("cross-backend, %s: %s against %s, %llu of %llu pixels differ (max channel difference %d)%s\n",
                labels[i / o.backends.size()].c_str(), r["backend"].get<std::string>().c_str(),
                c["against"].get<std::string>().c_str(), (unsigned long long)n, (unsigned long long)c["pixels"].get<uint64_t>(),
                c["max_difference"].get<int>(), n == 0 ? ": bit-identical" : "");
  }
  if (validationErrors) std::printf("VALIDATION ERRORS: %llu (see the messages above and the report)\n", (unsigned long long)validationErrors);
  if (validationOff)
    std::printf("warning: validation was not available on every backend (Vulkan needs vulkan-validationlayers); its errors are not counted there\n");
  if (reportRc == 0) std::printf("report: open %s\n", (dir / "index.html").string().c_str());
  else std::printf("report: failed (exit status %d); results are in %s\n", reportRc, o.out.string().c_str());
  std::printf("demo: finished in %s\n", Elapsed(say.Seconds()).c_str());
  return (validationErrors || reportRc) ? 1 : 0;
}

}  // namespace sp::cli
