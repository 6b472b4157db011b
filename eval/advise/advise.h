// `shadowport advise`: the cheapest shadow configuration that meets an error budget.
//
// The pieces that need no GPU (budgets, the search space from ParamSpecs, the Pareto front and the
// choice under timing noise) are in advise-select.cpp and unit-tested on synthetic measurements;
// the search that measures configurations with the bench (bench::RunOne), its cache and state file
// are in advise-search.cpp.
#pragma once
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include <sp/tech/technique.h>

namespace sp::advise {

// --- Budgets: `--budget misclassified=0.2`; each is an upper bound on one bench metric.

struct BudgetMetric {
  const char* name;         // as typed after --budget
  const char* description;  // for messages and the report
};
const std::vector<BudgetMetric>& BudgetMetrics();

struct Budget {
  std::string metric;  // a BudgetMetrics() name
  double limit = 0;
};
// Throws std::invalid_argument naming the --budget text and, for an unknown metric, the valid ones.
Budget ParseBudget(const std::string& text);

// --- One measured configuration, as the selection sees it.

struct Config {
  std::string technique;
  std::map<std::string, std::string> params;  // the searched parameters only (the rest default)
  bool operator<(const Config& o) const { return technique != o.technique ? technique < o.technique : params < o.params; }
  bool operator==(const Config& o) const { return technique == o.technique && params == o.params; }
};
// `csm:cascades=2:resolution=1024` (bench's --technique form); `csm` when nothing is set.
std::string ConfigText(const Config& c);
// Without the parameters at their defaults (what a user types); needs the registry.
Config WithoutDefaults(const Config& c);
std::string ShortText(const Config& c);  // ConfigText(WithoutDefaults(c))

struct Measurement {
  Config config;
  std::map<std::string, double> metrics;  // BudgetMetrics() names -> value
  nlohmann::json record;                  // the bench record (RunToJson), images relative to the cache
  std::vector<double> msRuns;             // GPU ms of each run when the timing was confirmed
  std::string fingerprint;                // what it rendered (advise-search.cpp)
  // Set when it rendered exactly what an earlier configuration did: left out of the front and the
  // choice (only timing noise could tell them apart).
  std::optional<size_t> sameAs;
};
// A bench record's value for a budget metric name (gpu ms total for "ms", MiB for "memory").
double MetricOf(const nlohmann::json& record, const std::string& metric);
std::map<std::string, double> MetricsOf(const nlohmann::json& record);

enum class Minimize { Ms, Memory };
const char* MinimizeName(Minimize m);

struct SelectOptions {
  std::vector<Budget> budgets;  // the first one is the error axis of the front
  Minimize minimize = Minimize::Ms;
  // GPU ms within this fraction of each other are a tie (the CPU rasterizer's timings move 10-30 %
  // between runs); ties go to less memory, then to less error. Unused for Minimize::Memory.
  double noise = 0.15;
};

double CostOf(const Measurement& m, Minimize minimize);
double ErrorOf(const Measurement& m, const SelectOptions& o);  // the first budget's metric
bool MeetsBudgets(const Measurement& m, const std::vector<Budget>& budgets);
// True when a is cheaper than b beyond the noise margin (ms) or strictly (memory).
bool Cheaper(const Measurement& a, const Measurement& b, const SelectOptions& o);

// Indices of the measurements not dominated in (cost, error), cheapest first. Exact costs: noise
// only enters the choice, so the front drawn is what was measured.
std::vector<size_t> ParetoFront(const std::vector<Measurement>& all, const SelectOptions& o);

struct Selection {
  std::optional<size_t> best;            // the recommendation, if anything meets every budget
  std::optional<size_t> cheaperMiss;     // the closest configuration cheaper than it that misses
  std::vector<size_t> closest;           // when nothing meets: the nearest misses (by budget excess)
};
// The cheapest configuration meeting every budget; among those within the noise margin of the
// cheapest, the least memory, then the least error, then the config text (deterministic).
Selection Select(const std::vector<Measurement>& all, const SelectOptions& o);

// --- The search space, from each technique's ParamSpecs.

// The parameters that matter most for cost and error; the ones a technique declares are searched.
const std::vector<std::string>& DefaultAxes();

struct Axis {
  std::string name;
  std::vector<std::string> values;  // the lattice, in order (neighbours are adjacent)
  std::vector<std::string> coarse;  // the first sweep's values
  std::string defaultValue;
  // Numbers (resolution, cascades, kernel widths) have an order and a step is to the next value;
  // names (filter, bias) have none, so every other value is one step away: along an arbitrary
  // order the search missed bias=receiver-plane behind a bad bias=normal (docs/lab.md).
  bool ordered = true;
};
// The axes of `technique` among `names` (those it declares), each a lattice derived from its spec:
// Int resolution: powers of two and their midpoints (256, 384, 512, ... 4096) within the range,
// coarse 512, 1024, 2048; cascades: 1..4 within the range, coarse 1, 2, 4; depth_bias: the default
// times 1/4, 1/2, 1, 2, 4; Choice: every choice, coarse the default only (ordered when every
// choice is a number).
// `maxResolution` caps the resolution lattice (the default is kept even above it).
std::vector<Axis> AxesFor(const std::string& technique, const std::vector<tech::ParamSpec>& specs, const std::vector<std::string>& names,
                          int maxResolution = 4096);

// Every coarse combination of a technique's axes.
std::vector<Config> CoarseGrid(const std::string& technique, const std::vector<Axis>& axes);
// Every lattice combination (the exhaustive sweep).
std::vector<Config> FullGrid(const std::string& technique, const std::vector<Axis>& axes);
// The configurations one step away from `c` along one axis (see Axis::ordered).
std::vector<Config> Neighbours(const Config& c, const std::vector<Axis>& axes);

// --- Output helpers

// `sp::tech::ParamValues`-based C++ that makes the configuration with the technique library.
std::string CppSnippet(const Config& c);

}  // namespace sp::advise
