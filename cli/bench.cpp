// `shadowport bench` (runs techniques against the reference, writes results JSON and pictures) and
// `shadowport report` (charts and an HTML page from results, by eval/report/report.py).
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <sys/wait.h>
#include <unistd.h>

#include "bench.h"
#include "cli.h"

namespace sp::cli {

int RunBench(const Args& a) {
  a.expectOnly({"scene", "technique", "backend", "size", "frames", "param", "triangles", "path", "out", "reference-cache", "validate",
                "light-gamma", "light-size", "light-samples"});
  if (!a.positionals().empty()) throw std::invalid_argument("unexpected argument '" + a.positionals()[0] + "'");
  bench::BenchOptions o;
  o.scenes = SplitList(a.get("scene", "default"), "scene");
  o.techniques = SplitList(a.get("technique", "basic"), "technique");
  std::string backend = a.get("backend", "both");
  if (backend == "both") {
    o.backends = {Backend::Vulkan, Backend::OpenGL};
  } else {
    o.backends = {ParseRenderingBackend(backend, "vulkan, gl or both")};
  }
  ParseSize(a.get("size", "640x360"), &o.width, &o.height);
  o.frames = uint32_t(ParseCount(a.get("frames", "8"), "frames", 1, 100000));
  // --param k=v1,v2 sweeps: every combination of the listed values is a run.
  for (const auto& [k, v] : ParseParams(a.getAll("param"))) o.params[k] = SplitList(v, "param " + k);
  if (a.has("triangles")) o.triangles = ParseCount(a.get("triangles"), "triangles", 1, scene::kMaxTargetTriangles);
  o.path = a.get("path", "slow-pan");
  o.out = a.get("out", "out/bench/results.json");
  o.referenceCache = a.get("reference-cache", "");  // empty: bench::ReferenceCacheDir decides
  o.validate = a.has("validate");
  if (a.has("light-gamma"))
    for (const std::string& g : SplitList(a.get("light-gamma"), "light-gamma")) {
      char* end = nullptr;
      float v = std::strtof(g.c_str(), &end);
      if (end == g.c_str() || *end) throw std::invalid_argument("--light-gamma takes degrees (got '" + g + "')");
      o.lightGammas.push_back(v);
    }
  if (a.has("light-size")) {
    const std::string t = a.get("light-size");
    char* end = nullptr;
    float v = std::strtof(t.c_str(), &end);
    if (end == t.c_str() || *end) throw std::invalid_argument("--light-size takes a number (degrees for the directional light, world units for local lights; got '" + t + "')");
    o.lightSize = v;  // range checked by bench::ValidateBenchOptions
  }
  if (a.has("light-samples")) o.lightSamples = unsigned(ParseCount(a.get("light-samples"), "light-samples", 1, 65535));

  ProgressPrinter progress("bench: ");
  nlohmann::json doc = bench::RunBench(o, progress);
  uint64_t validationErrors = 0;
  for (const auto& run : doc["runs"]) validationErrors += run["checks"]["validation_errors"].get<uint64_t>();
  std::printf("bench: %zu runs -> %s\n", doc["runs"].size(), o.out.string().c_str());
  return validationErrors ? 1 : 0;
}

int RunReportScript(const std::vector<std::string>& results, const std::string& out, const std::vector<std::string>& extraArgs) {
  // Debian's interpreter first: python3-matplotlib installs into it, while a python3 earlier on
  // PATH (pyenv, a venv) usually lacks matplotlib.
  std::string python;
  if (const char* e = std::getenv("SHADOWPORT_PYTHON"); e && *e) python = e;
  else if (std::filesystem::exists("/usr/bin/python3")) python = "/usr/bin/python3";
  else if (std::string(SP_REPORT_PYTHON).size()) python = SP_REPORT_PYTHON;
  else python = "python3";
  std::string script = SP_REPORT_SCRIPT;
  if (const char* e = std::getenv("SHADOWPORT_REPORT_SCRIPT"); e && *e) script = e;
  if (script.empty() || !std::filesystem::exists(script)) throw std::runtime_error("report script not found ('" + script + "'); set SHADOWPORT_REPORT_SCRIPT");
  std::vector<std::string> argv = {python, script};
  argv.insert(argv.end(), results.begin(), results.end());
  argv.push_back("--out");
  argv.push_back(out);
  argv.insert(argv.end(), extraArgs.begin(), extraArgs.end());
  std::vector<char*> cargv;
  for (std::string& s : argv) cargv.push_back(s.data());
  cargv.push_back(nullptr);
  std::fflush(stdout);
  std::fflush(stderr);
  pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("cannot start " + python);
  if (pid == 0) {
    execvp(cargv[0], cargv.data());
    std::fprintf(stderr, "shadowport report: cannot run %s\n", cargv[0]);
    _exit(127);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}

int RunReport(const Args& a) {
  a.expectOnly({"out", "title"});
  if (a.positionals().empty()) throw std::invalid_argument("no results file given (usage: shadowport report results.json... --out dir)");
  if (!a.has("out")) throw std::invalid_argument("--out dir is required");
  std::vector<std::string> extra;
  if (a.has("title")) extra = {"--title", a.get("title")};
  int rc = RunReportScript(a.positionals(), a.get("out"), extra);
  if (rc != 0) return rc;
  std::printf("report: open %s\n", (std::filesystem::path(a.get("out")) / "index.html").string().c_str());
  return 0;
}

}  // namespace sp::cli
