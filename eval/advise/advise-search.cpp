// The search: a coarse sweep over each technique's axes, then rounds of refinement around the
// Pareto front, every configuration measured once by the bench and kept in a JSON cache.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <set>
#include <sstream>
#include <unistd.h>

#include "advise-search.h"
#include "bench.h"

namespace sp::advise {

namespace fs = std::filesystem;

namespace {

uint64_t Fnv(uint64_t h, const char* data, size_t n) {
  for (size_t i = 0; i < n; ++i) {
    h ^= uint8_t(data[i]);
    h *= 1099511628211ull;
  }
  return h;
}

uint64_t HashFile(uint64_t h, const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::vector<char> buf(1 << 20);
  while (f) {
    f.read(buf.data(), std::streamsize(buf.size()));
    h = Fnv(h, buf.data(), size_t(f.gcount()));
  }
  return h;
}

std::string Hex(uint64_t v) {
  char b[17];
  std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(v));
  return b;
}

std::string ReadFile(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// The measurement store: key (the JSON text of everything that decides the figures) -> the bench
// record. Saved after every new measurement, atomically.
class Cache {
 public:
  explicit Cache(fs::path dir) : dir_(std::move(dir)), file_(dir_ / "advise-cache.json") {
    fs::create_directories(dir_);
    if (!fs::exists(file_)) return;
    try {
      doc_ = nlohmann::json::parse(ReadFile(file_));
    } catch (const std::exception& e) {
      throw std::runtime_error("advise: cache " + file_.string() + " is not valid JSON (" + e.what() + "); remove it to start afresh");
    }
  }
  const nlohmann::json* find(const std::string& key) const {
    if (!doc_.contains("entries") || !doc_["entries"].contains(key)) return nullptr;
    return &doc_["entries"][key];
  }
  void put(const std::string& key, nlohmann::json record) {
    doc_["entries"][key] = std::move(record);
    WriteAtomically(file_, doc_.dump(1) + "\n");
  }
  const fs::path& dir() const { return dir_; }

 private:
  fs::path dir_, file_;
  nlohmann::json doc_ = {{"version", 1}, {"entries", nlohmann::json::object()}};
};

std::string Slug(const std::string& text) {
  std::string s;
  for (char c : text) s += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '.' || c == '=') ? c : '_';
  return s;
}

std::string Duration(double s) {
  char b[32];
  if (s < 60) std::snprintf(b, sizeof b, "%.0f s", s);
  else std::snprintf(b, sizeof b, "%d min %02d s", int(s) / 60, int(s) % 60);
  return b;
}

std::string Figures(const Measurement& m, const SelectOptions& o) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(1) << m.metrics.at("ms") << " ms, " << m.metrics.at("memory") << " MiB, "
    << (o.budgets.empty() ? "misclassified" : o.budgets[0].metric) << " " << std::setprecision(3) << ErrorOf(m, o);
  return s.str();
}

// What a configuration rendered: its accuracy, density and memory figures and the bytes of its
// first frame's colour and error pictures.
std::string Fingerprint(const Measurement& m, const fs::path& cacheDir) {
  const nlohmann::json& r = m.record.at("metrics");
  std::string text;
  for (const char* k : {"misclassified_pct", "false_lit_pct", "false_shadow_pct", "mean_abs_error", "flicker", "texels_per_pixel_median",
                        "utilization", "shadow_memory_bytes", "shadow_triangles"})
    text += r.value(k, nlohmann::json()).dump() + ";";
  uint64_t h = Fnv(14695981039346656037ull, text.data(), text.size());
  nlohmann::json images = m.record.value("images", nlohmann::json::object());
  for (const char* k : {"color", "error"})
    if (images.contains(k)) h = HashFile(h, cacheDir / images[k].get<std::string>());
  return Hex(h);
}

}  // namespace

void WriteAtomically(const fs::path& path, const std::string& text) {
  fs::path tmp = path;
  tmp += ".tmp" + std::to_string(getpid());
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    f << text;
    f.flush();
    if (!f) throw std::runtime_error("cannot write " + tmp.string());
  }
  fs::rename(tmp, path);
}

std::string BuildRevision() {
  uint64_t h = 14695981039346656037ull;
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) h = HashFile(h, exe);
  fs::path shaders = tech::ShaderDirectory();
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(shaders))
    if (e.is_regular_file()) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const fs::path& f : files) {
    std::string rel = fs::relative(f, shaders).string();
    h = Fnv(h, rel.data(), rel.size());
    h = HashFile(h, f);
  }
  return Hex(h);
}

SearchResult Search(const SearchOptions& o, const std::function<void(const std::string&)>& progress) {
  auto say = [&](const std::string& s) {
    if (progress) progress(s);
  };
  if (o.techniques.empty()) throw std::invalid_argument("--techniques: no technique given");
  if (o.select.budgets.empty()) throw std::invalid_argument("no --budget given (e.g. --budget misclassified=0.5)");
  // The bench's own checks give the same messages for unknown scenes, techniques and parameters.
  bench::BenchOptions check;
  check.scenes = {o.scene};
  check.techniques = o.techniques;
  check.backends = {o.backend};
  bench::ValidateBenchOptions(check);

  // Each technique's axes: the default ones it declares, less those the --techniques text fixes.
  struct Tech {
    bench::TechniqueSpec spec;
    std::vector<tech::ParamSpec> specs;
    std::vector<Axis> axes;
  };
  std::vector<Tech> techs;
  for (const std::string& text : o.techniques) {
    Tech t;
    t.spec = bench::ParseTechniqueSpec(text);
    t.specs = tech::CreateTechnique(t.spec.name)->Params();
    std::vector<std::string> names;
    for (const std::string& a : o.axes)
      if (!t.spec.params.count(a)) names.push_back(a);
    t.axes = AxesFor(t.spec.name, t.specs, names, o.maxResolution);
    techs.push_back(std::move(t));
  }
  for (const std::string& a : o.axes) {
    bool any = false;
    for (const Tech& t : techs)
      for (const Axis& x : t.axes) any |= x.name == a;
    if (!any) throw std::invalid_argument("--axes: no technique searched has a parameter '" + a + "'");
  }

  scene::Scene sc = scene::LoadScene(o.scene, scene::SceneOptions{});
  if (sc.name.empty()) sc.name = fs::path(o.scene).stem().string();
  if (sc.cameraPaths.empty()) sc.cameraPaths = scene::CameraPathsFor(sc);
  const scene::CameraPath& path = sc.cameraPathOrFile(o.path);  // throws listing the scene's paths; loads a recorded path file
  if (!sc.useRecordedLight(path)) say(o.path + ": the recorded light turns along the path; each frame takes its direction there");
  // A recorded file can be recorded again under the same name: its contents key the cache.
  const std::string pathContents = scene::IsCameraPathFile(o.path) ? Hex(HashFile(14695981039346656037ull, o.path)) : "";

  SearchResult res;
  res.cacheDir = o.cache.empty() ? o.out / "cache" : o.cache;
  Cache cache(res.cacheDir);
  eval::ReferenceCache reference(sc, eval::DefaultReferenceCacheDir(res.cacheDir / "reference-cache"));
  res.revision = BuildRevision();
  fs::create_directories(o.out);

  std::map<Config, size_t> index;  // config -> position in res.measured
  std::vector<Config> planned;
  std::set<Config> plannedSet;
  auto plan = [&](const Config& c) {
    if (plannedSet.insert(c).second) planned.push_back(c);
  };
  std::string phase = "coarse";
  double newSeconds = 0;
  auto writeState = [&](bool complete) {
    nlohmann::json s = {{"scene", o.scene},         {"path", o.path},  {"backend", BackendName(o.backend)},
                        {"size", {o.width, o.height}}, {"frames", o.frames}, {"techniques", o.techniques},
                        {"phase", phase},           {"measured", res.measured.size()}, {"planned", planned.size()},
                        {"new_measurements", res.newMeasurements}, {"complete", complete}, {"cache", res.cacheDir.string()}};
    WriteAtomically(o.out / "advise-state.json", s.dump(1) + "\n");
  };
  if (fs::exists(o.out / "advise-state.json")) {
    try {
      nlohmann::json s = nlohmann::json::parse(ReadFile(o.out / "advise-state.json"));
      if (!s.value("complete", true))
        say("resuming an interrupted search (" + std::to_string(s.value("measured", 0)) + " configurations were measured; they come from the cache)");
    } catch (const std::exception&) {
    }
  }

  // The bench record of one configuration: from the cache, or measured and cached. `repeat` > 0
  // is a further timing of the same configuration (the confirmation below).
  auto record = [&](const Config& c, int repeat) -> nlohmann::json {
    if (o.interrupt && o.interrupt->load()) {
      writeState(false);
      throw Interrupted("interrupted after " + std::to_string(res.measured.size()) + " configurations");
    }
    tech::ParamValues full = tech::ParamValues::Parse(c.technique, tech::CreateTechnique(c.technique)->Params(), c.params);
    nlohmann::json key = {{"scene", sc.name},    {"scene_arg", o.scene}, {"path", o.path}, {"backend", BackendName(o.backend)},
                          {"size", {o.width, o.height}}, {"frames", o.frames}, {"technique", c.technique},
                          {"params", full.all()}, {"revision", res.revision}};
    if (repeat) key["repeat"] = repeat;
    if (!pathContents.empty()) key["path_contents"] = pathContents;
    std::string k = key.dump();
    if (const nlohmann::json* hit = cache.find(k)) {
      ++(repeat ? res.timingRunsFromCache : res.fromCache);
      return *hit;
    }
    auto t0 = std::chrono::steady_clock::now();
    bench::RunSpec spec;
    spec.scene = &sc;
    spec.technique = c.technique;
    spec.params = c.params;
    spec.backend = o.backend;
    spec.width = o.width;
    spec.height = o.height;
    spec.frames = o.frames;
    spec.path = &path;
    bench::RunResult r = bench::RunOne(spec, reference);
    // Pictures of the path's first frame, as bench writes them, named by the key's hash.
    std::map<std::string, std::string> images;
    if (!repeat) {
      std::string stem = "images/" + Hex(Fnv(14695981039346656037ull, k.data(), k.size())) + "-" + Slug(ShortText(c));
      const tech::LabBuffers& f = r.firstFrame;
      uint32_t h = 0;
      eval::WritePng(cache.dir() / (stem + "-color.png"), f.width, f.height, f.color.data());
      images["color"] = stem + "-color.png";
      std::vector<uint8_t> err = eval::ErrorHeatMap(f, r.firstReference.data(), &h);
      eval::WritePng(cache.dir() / (stem + "-error.png"), f.width, h, err.data());
      images["error"] = stem + "-error.png";
      std::vector<uint8_t> dens = eval::TexelDensityHeatMap(f, &h);
      eval::WritePng(cache.dir() / (stem + "-density.png"), f.width, h, dens.data());
      images["texel_density"] = stem + "-density.png";
      std::string refImage = "images/reference-" + Slug(sc.name) + "-" + std::to_string(o.width) + "x" + std::to_string(o.height) +
                             (r.judgedLocalLight < 0 ? "" : "-light" + std::to_string(r.judgedLocalLight)) + ".png";
      if (!fs::exists(cache.dir() / refImage))
        eval::WritePng(cache.dir() / refImage, f.width, f.height,
                       eval::ReferenceImage(f, r.firstReference.data(), r.light, tech::LocalLightsOf(sc), r.judgedLocalLight).data());
      images["reference"] = refImage;
    }
    nlohmann::json rec = bench::RunToJson(r, images);
    rec["advise_key"] = key;
    cache.put(k, rec);
    ++(repeat ? res.timingRuns : res.newMeasurements);
    newSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return rec;
  };

  // A lattice step can reach a combination the technique refuses (filter=box with kernel=17, an
  // accel with filter=pcss): not a point of the space, so it is skipped and said why. A refused
  // default configuration is the user's error and stops the search.
  std::set<Config> refused, defaults;
  std::vector<Config> defaultList;  // in the order of --techniques
  for (const Tech& t : techs) {
    Config d{t.spec.name, t.spec.params};
    for (const Axis& a : t.axes) d.params[a.name] = a.defaultValue;
    if (defaults.insert(d).second) defaultList.push_back(d);
  }
  auto measure = [&](const Config& c) {
    if (index.count(c) || refused.count(c)) return;
    Measurement m;
    m.config = c;
    try {
      m.record = record(c, 0);
    } catch (const std::invalid_argument& e) {
      if (defaults.count(c)) throw;
      refused.insert(c);
      ++res.refused;
      say("skipped " + ShortText(c) + ": the technique refuses it (" + e.what() + ")");
      return;
    }
    m.metrics = MetricsOf(m.record);
    // A parameter that does nothing in this configuration (kernel under the 2x2 hardware filter)
    // renders the same pictures: such a configuration is the earlier one again, and only timing
    // noise could tell them apart, so it is kept out of the choice and not refined around.
    m.fingerprint = Fingerprint(m, cache.dir());
    for (size_t i = 0; i < res.measured.size(); ++i)
      if (res.measured[i].config.technique == c.technique && !res.measured[i].sameAs && res.measured[i].fingerprint == m.fingerprint) {
        m.sameAs = i;
        break;
      }
    index[c] = res.measured.size();
    res.measured.push_back(std::move(m));
    writeState(false);

    // Progress: n / planned, best so far, time left at the mean time of a new measurement.
    std::ostringstream line;
    line << "measured " << res.measured.size() << "/" << planned.size() << " (" << phase << "; " << res.newMeasurements << " new, "
         << res.fromCache << " cached): " << ShortText(c) << ": " << Figures(res.measured.back(), o.select);
    Selection s = Select(res.measured, o.select);
    if (s.best) line << "; best so far " << ShortText(res.measured[*s.best].config) << " (" << Figures(res.measured[*s.best], o.select) << ")";
    else line << "; nothing meets the budget yet";
    if (res.newMeasurements) {
      size_t left = 0;
      for (const Config& p : planned) left += index.count(p) ? 0 : 1;
      line << "; about " << Duration(left * newSeconds / double(res.newMeasurements)) << " left of this phase";
    }
    say(line.str());
  };

  // Each technique's all-default configuration: what the recommendation is judged against.
  for (const Config& d : defaultList) plan(d);
  for (const Tech& t : techs)
    for (Config c : o.exhaustive ? FullGrid(t.spec.name, t.axes) : CoarseGrid(t.spec.name, t.axes)) {
      c.params.insert(t.spec.params.begin(), t.spec.params.end());
      plan(c);
    }
  if (o.exhaustive) phase = "exhaustive";
  say(std::string(o.exhaustive ? "exhaustive sweep: " : "coarse sweep: ") + std::to_string(planned.size()) + " configurations of " +
      std::to_string(techs.size()) + " technique(s) on " + sc.name + " (" + BackendName(o.backend) + ", " + std::to_string(o.width) + "x" +
      std::to_string(o.height) + ", " + std::to_string(o.frames) + " frames)");
  for (size_t i = 0; i < planned.size() && res.measured.size() < o.maxRuns; ++i) measure(planned[i]);

  // Refinement: one lattice step around the configurations that could change the answer, most
  // promising first (so --max-runs cuts the least useful): the current choice, the closest cheaper
  // miss, the front members cheaper than the choice, and the next front member above it; until a
  // round adds nothing. Without a choice yet: around the whole front and the closest misses.
  auto axesOf = [&](const std::string& name) -> const std::vector<Axis>& {
    for (const Tech& t : techs)
      if (t.spec.name == name) return t.axes;
    throw std::logic_error("no technique " + name);
  };
  for (int round = 1; !o.exhaustive && res.measured.size() < o.maxRuns; ++round) {
    std::vector<size_t> front = ParetoFront(res.measured, o.select);
    Selection s = Select(res.measured, o.select);
    std::vector<size_t> seeds;
    if (s.best) {
      seeds.push_back(*s.best);
      if (s.cheaperMiss) seeds.push_back(*s.cheaperMiss);
      const double bestCost = CostOf(res.measured[*s.best], o.select.minimize);
      bool above = false;
      for (size_t i : front) {
        double c = CostOf(res.measured[i], o.select.minimize);
        if (c < bestCost) seeds.push_back(i);
        else if (c > bestCost && !above && MeetsBudgets(res.measured[i], o.select.budgets)) {
          seeds.push_back(i);
          above = true;
        }
      }
    } else {
      seeds = s.closest;
      seeds.insert(seeds.end(), front.begin(), front.end());
    }
    size_t before = planned.size();
    for (size_t i : seeds)
      for (const Config& n : Neighbours(res.measured[i].config, axesOf(res.measured[i].config.technique))) plan(n);
    if (planned.size() == before) break;
    phase = "refinement round " + std::to_string(round);
    say(phase + ": " + std::to_string(planned.size() - before) + " neighbours of " + std::to_string(seeds.size()) + " configurations on or near the front");
    for (size_t i = before; i < planned.size() && res.measured.size() < o.maxRuns; ++i) measure(planned[i]);
  }
  if (res.measured.size() >= o.maxRuns && res.measured.size() < planned.size())
    say("stopped at --max-runs " + std::to_string(o.maxRuns) + " configurations");

  // Confirmation: GPU ms of one run moves 10-30 % with the other jobs on a CPU rasterizer, so the
  // configurations the answer and the comparison rest on (every one meeting the budgets within
  // twice the noise margin of the choice, the closest cheaper miss, the defaults) are timed again,
  // `confirm` runs in all, and their ms is the median over the runs. Then the choice is made again.
  if (o.select.minimize == Minimize::Ms && o.confirm > 1) {
    Selection s = Select(res.measured, o.select);
    std::set<size_t> which;
    for (const Tech& t : techs) {
      Config d{t.spec.name, t.spec.params};
      for (const Axis& a : t.axes) d.params[a.name] = a.defaultValue;
      if (index.count(d)) which.insert(index[d]);
    }
    if (s.best) {
      double limit = CostOf(res.measured[*s.best], Minimize::Ms) / std::pow(1.0 - o.select.noise, 2.0);
      for (size_t i = 0; i < res.measured.size(); ++i)
        if (!res.measured[i].sameAs && MeetsBudgets(res.measured[i], o.select.budgets) && CostOf(res.measured[i], Minimize::Ms) <= limit)
          which.insert(i);
      if (s.cheaperMiss) which.insert(*s.cheaperMiss);
    }
    phase = "confirming the timings";
    say(phase + " of " + std::to_string(which.size()) + " configurations (" + std::to_string(o.confirm) + " runs each, median GPU ms)");
    // Interleaved (every configuration once, then again), so a burst of load from other jobs
    // falls on all of them rather than on one.
    std::map<size_t, std::vector<double>> runs;
    for (size_t i : which) runs[i] = {MetricOf(res.measured[i].record, "ms")};
    for (int rep = 1; rep < o.confirm; ++rep)
      for (size_t i : which) runs[i].push_back(MetricOf(record(res.measured[i].config, rep), "ms"));
    for (size_t i : which) {
      Measurement& m = res.measured[i];
      const std::vector<double>& ms = runs[i];
      std::vector<double> sorted = ms;
      std::sort(sorted.begin(), sorted.end());
      size_t n = sorted.size();
      m.metrics["ms"] = n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
      m.msRuns = ms;
      std::ostringstream line;
      line << "  " << ShortText(m.config) << ": GPU ms";
      for (double v : ms) line << " " << std::fixed << std::setprecision(1) << v;
      line << " -> median " << m.metrics["ms"];
      say(line.str());
    }
  }

  res.planned = planned.size();
  res.front = ParetoFront(res.measured, o.select);
  res.selection = Select(res.measured, o.select);
  for (const Tech& t : techs) {
    Config d{t.spec.name, t.spec.params};
    for (const Axis& a : t.axes) d.params[a.name] = a.defaultValue;
    if (index.count(d)) res.defaults.push_back(index[d]);
  }
  phase = "done";
  writeState(true);
  return res;
}

}  // namespace sp::advise
