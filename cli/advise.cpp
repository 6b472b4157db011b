// `shadowport advise`: the cheapest configuration meeting error budgets on a scene (eval/advise),
// printed as a front table, a --technique line and C++; a report page with the front's chart and
// the pictures of the recommendation beside the closest cheaper miss (eval/advise/advise_report.py).
#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <sys/wait.h>
#include <unistd.h>

#include "advise-search.h"
#include "bench.h"
#include "cli.h"

namespace sp::cli {

namespace {

namespace fs = std::filesystem;

std::atomic<bool> gInterrupt{false};

void OnInterrupt(int) { gInterrupt.store(true); }

std::string Row(const advise::Measurement& m, const advise::SelectOptions& o, const char* mark) {
  std::ostringstream s;
  s << std::fixed << "| " << mark << " | `" << advise::ShortText(m.config) << "` | " << std::setprecision(1) << m.metrics.at("ms") << " | "
    << m.metrics.at("memory") << " | " << std::setprecision(3) << m.metrics.at("misclassified") << " | " << m.metrics.at("false_lit")
    << " | " << m.metrics.at("false_shadow") << " | " << std::defaultfloat << std::setprecision(2) << m.metrics.at("flicker") << " | "
    << (advise::MeetsBudgets(m, o.budgets) ? "yes" : "no") << " |";
  return s.str();
}

const char* kHeader =
    "|   | configuration | GPU ms | memory MiB | misclassified % | false lit % | false shadow % | flicker | meets |\n"
    "|---|---|---|---|---|---|---|---|---|";

int RunPython(const std::vector<std::string>& args) {
  std::string python;
  if (const char* e = std::getenv("SHADOWPORT_PYTHON"); e && *e) python = e;
  else if (fs::exists("/usr/bin/python3")) python = "/usr/bin/python3";
  else python = std::string(SP_REPORT_PYTHON).empty() ? "python3" : SP_REPORT_PYTHON;
  std::vector<std::string> argv = {python};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<char*> c;
  for (std::string& s : argv) c.push_back(s.data());
  c.push_back(nullptr);
  std::fflush(stdout);
  std::fflush(stderr);
  pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("cannot start " + python);
  if (pid == 0) {
    execvp(c[0], c.data());
    _exit(127);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}

}  // namespace

int RunAdvise(const Args& a) {
  a.expectOnly({"scene", "path", "backend", "size", "frames", "budget", "minimize", "techniques", "axes", "out", "cache", "noise",
                "max-runs", "max-resolution", "confirm", "exhaustive", "no-report"});
  if (!a.positionals().empty()) throw std::invalid_argument("unexpected argument '" + a.positionals()[0] + "'");
  if (!a.has("scene")) throw std::invalid_argument("--scene is required (e.g. --scene ShadowColumns)");
  advise::SearchOptions o;
  o.scene = a.get("scene");
  o.path = a.get("path", "slow-pan");
  std::string backend = a.get("backend", "vulkan");
  o.backend = ParseRenderingBackend(backend, "vulkan or gl");
  ParseSize(a.get("size", "320x180"), &o.width, &o.height);
  o.frames = uint32_t(ParseCount(a.get("frames", "4"), "frames", 1, 1000));
  for (const std::string& b : a.getAll("budget")) {
    advise::Budget budget = advise::ParseBudget(b);
    for (const advise::Budget& x : o.select.budgets)
      if (x.metric == budget.metric) throw std::invalid_argument("--budget " + budget.metric + " is given twice");
    o.select.budgets.push_back(budget);
  }
  if (o.select.budgets.empty()) throw std::invalid_argument("--budget metric=value is required (e.g. --budget misclassified=0.5)");
  std::string minimize = a.get("minimize", "ms");
  if (minimize == "ms") o.select.minimize = advise::Minimize::Ms;
  else if (minimize == "memory") o.select.minimize = advise::Minimize::Memory;
  else throw std::invalid_argument("--minimize must be ms or memory (got '" + minimize + "')");
  o.techniques = SplitList(a.get("techniques", "basic,csm,sdsm"), "techniques");
  if (a.has("axes")) o.axes = SplitList(a.get("axes"), "axes");
  o.out = a.get("out", "out/advise");
  if (a.has("cache")) o.cache = a.get("cache");
  if (a.has("noise")) {
    std::string n = a.get("noise");
    char* end = nullptr;
    o.select.noise = std::strtod(n.c_str(), &end);
    if (end == n.c_str() || *end || !(o.select.noise >= 0 && o.select.noise < 1))
      throw std::invalid_argument("--noise '" + n + "' must be a fraction in [0, 1)");
  }
  o.maxRuns = ParseCount(a.get("max-runs", "200"), "max-runs", 1, 100000);
  o.maxResolution = int(ParseCount(a.get("max-resolution", "4096"), "max-resolution", 256, 16384));
  o.confirm = int(ParseCount(a.get("confirm", "3"), "confirm", 1, 20));
  o.exhaustive = a.has("exhaustive");
  o.interrupt = &gInterrupt;

  // The first Ctrl-C finishes the measurement in progress and stops with the cache written; a
  // second one kills at once (the cache is written atomically, so it stays whole either way).
  struct sigaction sa {};
  sa.sa_handler = OnInterrupt;
  sa.sa_flags = SA_RESETHAND;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);

  ProgressPrinter progress("advise: ");
  advise::SearchResult r;
  try {
    r = advise::Search(o, progress);
  } catch (const advise::Interrupted& e) {
    std::fprintf(stderr, "advise: %s; measurements are cached in %s: run the same command again to resume\n", e.what(),
                 (o.cache.empty() ? o.out / "cache" : o.cache).string().c_str());
    return 130;
  }
  signal(SIGINT, SIG_DFL);
  signal(SIGTERM, SIG_DFL);
  const advise::SelectOptions& so = o.select;
  const auto& m = r.measured;

  std::string budgets;
  for (const advise::Budget& b : so.budgets) {
    char limit[32];
    std::snprintf(limit, sizeof limit, "%g", b.limit);
    budgets += (budgets.empty() ? "" : ", ") + b.metric + " <= " + limit;
  }
  std::printf("advise: %s on %s, %ux%u, %u frames; budget %s; minimizing %s%s\n", o.scene.c_str(), BackendName(o.backend), o.width, o.height,
              o.frames, budgets.c_str(), advise::MinimizeName(so.minimize),
              so.minimize == advise::Minimize::Ms ? (" (GPU ms within " + std::to_string(int(so.noise * 100 + 0.5)) + " % are ties: less memory wins)").c_str() : "");
  std::printf("configurations: %zu measured by the search (%zu new, %zu from the cache), %zu refused by their technique; %zu further timing runs (%zu new)\n\n",
              m.size(), r.newMeasurements, r.fromCache, r.refused, r.timingRuns + r.timingRunsFromCache, r.timingRuns);
  std::printf("Pareto front (%s against %s):\n\n%s\n", advise::MinimizeName(so.minimize), so.budgets[0].metric.c_str(), kHeader);
  for (size_t i : r.front) std::printf("%s\n", Row(m[i], so, r.selection.best == i ? "**>**" : " ").c_str());

  int rc = 0;
  if (r.selection.best) {
    const advise::Measurement& best = m[*r.selection.best];
    std::printf("\nrecommendation: %s\n%s\n%s\n", advise::ShortText(best.config).c_str(), kHeader, Row(best, so, "**>**").c_str());
    if (r.selection.cheaperMiss) std::printf("%s  (the closest cheaper configuration, which misses the budget)\n", Row(m[*r.selection.cheaperMiss], so, "<").c_str());
    for (size_t d : r.defaults) std::printf("%s  (%s's defaults)\n", Row(m[d], so, "d").c_str(), m[d].config.technique.c_str());
    std::string params;
    const advise::Config shorter = advise::WithoutDefaults(best.config);
    for (const auto& [k, v] : shorter.params) params += " --param " + k + "=" + v;
    std::printf("\nas options:    --technique %s\n", advise::ShortText(best.config).c_str());
    std::printf("as --param:    --technique %s%s\n", best.config.technique.c_str(), params.c_str());
    std::printf("in C++:\n\n%s\n", advise::CppSnippet(shorter).c_str());
  } else {
    std::printf("\nno configuration meets the budget (%s); the closest:\n%s\n", budgets.c_str(), kHeader);
    for (size_t i : r.selection.closest) std::printf("%s\n", Row(m[i], so, " ").c_str());
    rc = 3;
  }

  // advise.json: everything the report draws, image paths relative to the out dir.
  nlohmann::json doc;
  doc["scene"] = o.scene;
  doc["backend"] = BackendName(o.backend);
  doc["size"] = {o.width, o.height};
  doc["frames"] = o.frames;
  doc["minimize"] = advise::MinimizeName(so.minimize);
  doc["noise"] = so.noise;
  doc["budgets"] = nlohmann::json::array();
  for (const advise::Budget& b : so.budgets) doc["budgets"].push_back({{"metric", b.metric}, {"limit", b.limit}});
  doc["revision"] = r.revision;
  doc["new_measurements"] = r.newMeasurements;
  doc["from_cache"] = r.fromCache;
  doc["refused"] = r.refused;
  doc["timing_runs"] = r.timingRuns + r.timingRunsFromCache;
  doc["new_timing_runs"] = r.timingRuns;
  doc["planned"] = r.planned;
  doc["exhaustive"] = o.exhaustive;
  fs::path relCache = fs::relative(fs::absolute(r.cacheDir), fs::absolute(o.out));
  doc["configurations"] = nlohmann::json::array();
  for (size_t i = 0; i < m.size(); ++i) {
    nlohmann::json c = {{"config", advise::ShortText(m[i].config)}, {"full_config", advise::ConfigText(m[i].config)}, {"technique", m[i].config.technique}, {"params", m[i].config.params},
                        {"metrics", m[i].metrics}, {"meets", advise::MeetsBudgets(m[i], so.budgets)}, {"ms_runs", m[i].msRuns}};
    if (m[i].sameAs) c["same_as"] = advise::ShortText(m[*m[i].sameAs].config);
    nlohmann::json images = m[i].record.value("images", nlohmann::json::object());
    for (auto& [k, v] : images.items()) v = (relCache / v.get<std::string>()).string();
    c["images"] = images;
    c["bench_record"] = m[i].record;
    doc["configurations"].push_back(c);
  }
  doc["front"] = r.front;
  doc["recommendation"] = r.selection.best ? nlohmann::json(*r.selection.best) : nlohmann::json(nullptr);
  doc["cheaper_miss"] = r.selection.cheaperMiss ? nlohmann::json(*r.selection.cheaperMiss) : nlohmann::json(nullptr);
  doc["closest"] = r.selection.closest;
  doc["defaults"] = r.defaults;
  if (r.selection.best) {
    doc["technique_option"] = advise::ShortText(m[*r.selection.best].config);
    doc["cpp"] = advise::CppSnippet(advise::WithoutDefaults(m[*r.selection.best].config));
  }
  advise::WriteAtomically(o.out / "advise.json", doc.dump(1) + "\n");

  if (!a.has("no-report")) {
    int prc = RunPython({SP_ADVISE_SCRIPT, (o.out / "advise.json").string(), "--out", o.out.string()});
    if (prc != 0) {
      std::fprintf(stderr, "advise: the report script failed (exit %d)\n", prc);
      return 1;
    }
    std::printf("report: %s\n", (o.out / "index.html").string().c_str());
  }
  return rc;
}

}  // namespace sp::cli
