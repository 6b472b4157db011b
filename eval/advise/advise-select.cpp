// Budgets, the search space and the choice of `shadowport advise`: no GPU here, so the unit tests
// can hold it to synthetic measurements.
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>

#include "advise.h"

namespace sp::advise {

const std::vector<BudgetMetric>& BudgetMetrics() {
  static const std::vector<BudgetMetric> m = {
      {"misclassified", "misclassified_pct: % of lit-receiving pixels whose shadow state differs from the reference"},
      {"false_lit", "false_lit_pct: % lit where the reference is shadowed"},
      {"false_shadow", "false_shadow_pct: % shadowed where the reference is lit"},
      {"mean_abs_error", "mean_abs_error: mean |visibility - reference|"},
      {"flicker", "flicker: mean change of the shadow term at the same world points between frames"},
      {"ms", "gpu_ms.total: median GPU ms per frame"},
      {"memory", "shadow_memory_bytes in MiB"},
  };
  return m;
}

Budget ParseBudget(const std::string& text) {
  size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw std::invalid_argument("--budget '" + text + "' is not metric=value (e.g. --budget misclassified=0.5)");
  Budget b;
  b.metric = text.substr(0, eq);
  bool known = false;
  std::string names;
  for (const BudgetMetric& m : BudgetMetrics()) {
    known |= b.metric == m.name;
    names += (names.empty() ? "" : ", ") + std::string(m.name);
  }
  if (!known) throw std::invalid_argument("--budget '" + text + "': unknown metric '" + b.metric + "' (valid: " + names + ")");
  std::string v = text.substr(eq + 1);
  size_t used = 0;
  try {
    b.limit = std::stod(v, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != v.size() || !std::isfinite(b.limit) || b.limit < 0)
    throw std::invalid_argument("--budget '" + text + "': '" + v + "' is not a number >= 0");
  return b;
}

std::string ConfigText(const Config& c) {
  std::string s = c.technique;
  for (const auto& [k, v] : c.params) s += ":" + k + "=" + v;
  return s;
}

Config WithoutDefaults(const Config& c) {
  Config shorter = c;
  for (const tech::ParamSpec& p : tech::CreateTechnique(c.technique)->Params()) {
    auto it = shorter.params.find(p.name);
    if (it != shorter.params.end() && it->second == p.defaultValue) shorter.params.erase(it);
  }
  return shorter;
}

std::string ShortText(const Config& c) { return ConfigText(WithoutDefaults(c)); }

double MetricOf(const nlohmann::json& r, const std::string& metric) {
  const nlohmann::json& m = r.at("metrics");
  if (metric == "ms") return m.at("gpu_ms").at("total").get<double>();
  if (metric == "memory") return m.at("shadow_memory_bytes").get<double>() / (1024.0 * 1024.0);
  if (metric == "misclassified" || metric == "false_lit" || metric == "false_shadow") return m.at(metric + "_pct").get<double>();
  return m.at(metric).get<double>();
}

std::map<std::string, double> MetricsOf(const nlohmann::json& record) {
  std::map<std::string, double> out;
  for (const BudgetMetric& m : BudgetMetrics()) out[m.name] = MetricOf(record, m.name);
  return out;
}

const char* MinimizeName(Minimize m) { return m == Minimize::Ms ? "ms" : "memory"; }

double CostOf(const Measurement& m, Minimize minimize) { return m.metrics.at(MinimizeName(minimize)); }

double ErrorOf(const Measurement& m, const SelectOptions& o) {
  return o.budgets.empty() ? m.metrics.at("misclassified") : m.metrics.at(o.budgets[0].metric);
}

bool MeetsBudgets(const Measurement& m, const std::vector<Budget>& budgets) {
  for (const Budget& b : budgets)
    if (!(m.metrics.at(b.metric) <= b.limit)) return false;
  return true;
}

bool Cheaper(const Measurement& a, const Measurement& b, const SelectOptions& o) {
  double ca = CostOf(a, o.minimize), cb = CostOf(b, o.minimize);
  if (o.minimize == Minimize::Memory) return ca < cb;
  return ca < cb * (1.0 - o.noise);
}

std::vector<size_t> ParetoFront(const std::vector<Measurement>& all, const SelectOptions& o) {
  std::vector<size_t> order(all.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    double ca = CostOf(all[a], o.minimize), cb = CostOf(all[b], o.minimize);
    if (ca != cb) return ca < cb;
    double ea = ErrorOf(all[a], o), eb = ErrorOf(all[b], o);
    if (ea != eb) return ea < eb;
    return all[a].config < all[b].config;
  });
  std::vector<size_t> front;
  double bestError = std::numeric_limits<double>::infinity();
  for (size_t i : order) {
    if (all[i].sameAs) continue;
    double e = ErrorOf(all[i], o);
    if (e < bestError) {
      front.push_back(i);
      bestError = e;
    }
  }
  return front;
}

namespace {

// How far a measurement is outside its budgets: the sum of relative excesses (0 when it meets).
double Excess(const Measurement& m, const std::vector<Budget>& budgets) {
  double x = 0;
  for (const Budget& b : budgets) {
    double v = m.metrics.at(b.metric);
    if (v > b.limit) x += b.limit > 0 ? (v - b.limit) / b.limit : v;
  }
  return x;
}

}  // namespace

Selection Select(const std::vector<Measurement>& all, const SelectOptions& o) {
  Selection s;
  std::vector<size_t> ok;
  std::vector<size_t> order;
  for (size_t i = 0; i < all.size(); ++i) {
    if (all[i].sameAs) continue;
    order.push_back(i);
    if (MeetsBudgets(all[i], o.budgets)) ok.push_back(i);
  }
  if (ok.empty()) {
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
      double xa = Excess(all[a], o.budgets), xb = Excess(all[b], o.budgets);
      if (xa != xb) return xa < xb;
      return CostOf(all[a], o.minimize) < CostOf(all[b], o.minimize);
    });
    if (order.size() > 3) order.erase(order.begin() + 3, order.end());
    s.closest = order;
    return s;
  }
  double cheapest = std::numeric_limits<double>::infinity();
  for (size_t i : ok) cheapest = std::min(cheapest, CostOf(all[i], o.minimize));
  // The tie band: anything the noise margin cannot tell from the cheapest.
  double band = o.minimize == Minimize::Ms ? cheapest / (1.0 - o.noise) : cheapest;
  std::vector<size_t> ties;
  for (size_t i : ok)
    if (CostOf(all[i], o.minimize) <= band) ties.push_back(i);
  std::sort(ties.begin(), ties.end(), [&](size_t a, size_t b) {
    const Measurement &ma = all[a], &mb = all[b];
    if (ma.metrics.at("memory") != mb.metrics.at("memory")) return ma.metrics.at("memory") < mb.metrics.at("memory");
    if (ErrorOf(ma, o) != ErrorOf(mb, o)) return ErrorOf(ma, o) < ErrorOf(mb, o);
    if (CostOf(ma, o.minimize) != CostOf(mb, o.minimize)) return CostOf(ma, o.minimize) < CostOf(mb, o.minimize);
    return ma.config < mb.config;
  });
  s.best = ties.front();
  // What the budget buys: the dearest configuration that is cheaper than the recommendation and
  // misses, i.e. the one just below it on the cost axis.
  const double bestCost = CostOf(all[*s.best], o.minimize);
  for (size_t i = 0; i < all.size(); ++i) {
    if (all[i].sameAs || MeetsBudgets(all[i], o.budgets) || CostOf(all[i], o.minimize) >= bestCost) continue;
    if (!s.cheaperMiss || CostOf(all[i], o.minimize) > CostOf(all[*s.cheaperMiss], o.minimize) ||
        (CostOf(all[i], o.minimize) == CostOf(all[*s.cheaperMiss], o.minimize) && ErrorOf(all[i], o) < ErrorOf(all[*s.cheaperMiss], o)))
      s.cheaperMiss = i;
  }
  return s;
}

// --- Search space

const std::vector<std::string>& DefaultAxes() {
  static const std::vector<std::string> a = {"resolution", "cascades", "filter", "kernel", "bias"};
  return a;
}

namespace {

std::string Num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

bool InRange(const tech::ParamSpec& p, double v) { return v >= p.min && v <= p.max; }

// A lattice value equal to the default keeps the default's spelling, so the default configuration
// is one of the lattice's points.
void AddDefault(Axis& a) {
  if (std::find(a.values.begin(), a.values.end(), a.defaultValue) == a.values.end()) {
    a.values.push_back(a.defaultValue);
    std::sort(a.values.begin(), a.values.end(), [](const std::string& x, const std::string& y) { return std::stod(x) < std::stod(y); });
  }
}

}  // namespace

std::vector<Axis> AxesFor(const std::string& technique, const std::vector<tech::ParamSpec>& specs, const std::vector<std::string>& names,
                          int maxResolution) {
  std::vector<Axis> axes;
  for (const std::string& name : names) {
    const tech::ParamSpec* p = nullptr;
    for (const tech::ParamSpec& s : specs)
      if (s.name == name) p = &s;
    if (!p) continue;
    Axis a;
    a.name = name;
    a.defaultValue = p->defaultValue;
    if (p->kind == tech::ParamSpec::Choice) {
      a.values = p->choices;
      a.coarse = {p->defaultValue};
      for (const std::string& v : p->choices) {
        size_t used = 0;
        try {
          std::stod(v, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used == 0 || used != v.size()) a.ordered = false;
      }
    } else if (p->kind == tech::ParamSpec::Int && name == "resolution") {
      for (int r = 256; r <= maxResolution; r *= 2) {
        if (InRange(*p, r)) a.values.push_back(Num(r));
        if (r * 3 / 2 <= maxResolution && InRange(*p, r * 3 / 2)) a.values.push_back(Num(r * 3 / 2));
      }
      for (int r : {512, 1024, 2048})
        if (InRange(*p, r) && r <= maxResolution) a.coarse.push_back(Num(r));
      AddDefault(a);
    } else if (p->kind == tech::ParamSpec::Int && name == "cascades") {
      for (int c = 1; c <= 4; ++c)
        if (InRange(*p, c)) a.values.push_back(Num(c));
      for (int c : {1, 2, 4})
        if (InRange(*p, c)) a.coarse.push_back(Num(c));
      AddDefault(a);
    } else if (p->kind == tech::ParamSpec::Int || p->kind == tech::ParamSpec::Float) {
      double d = std::stod(p->defaultValue);
      for (double f : {0.25, 0.5, 1.0, 2.0, 4.0}) {
        double v = p->kind == tech::ParamSpec::Int ? std::round(d * f) : d * f;
        if (InRange(*p, v) && std::find(a.values.begin(), a.values.end(), Num(v)) == a.values.end()) a.values.push_back(Num(v));
      }
      a.coarse = {p->defaultValue};
      if (std::find(a.values.begin(), a.values.end(), Num(d)) != a.values.end()) *std::find(a.values.begin(), a.values.end(), Num(d)) = p->defaultValue;
    } else {
      throw std::invalid_argument("advise: parameter '" + name + "' of " + technique + " is free text and cannot be searched");
    }
    if (a.coarse.empty()) a.coarse = {p->defaultValue};
    axes.push_back(std::move(a));
  }
  return axes;
}

namespace {

std::vector<Config> Product(const std::string& technique, const std::vector<Axis>& axes, bool coarse) {
  std::vector<Config> out = {Config{technique, {}}};
  for (const Axis& a : axes) {
    std::vector<Config> next;
    for (const Config& c : out)
      for (const std::string& v : coarse ? a.coarse : a.values) {
        Config n = c;
        n.params[a.name] = v;
        next.push_back(std::move(n));
      }
    out = std::move(next);
  }
  return out;
}

}  // namespace

std::vector<Config> CoarseGrid(const std::string& technique, const std::vector<Axis>& axes) { return Product(technique, axes, true); }
std::vector<Config> FullGrid(const std::string& technique, const std::vector<Axis>& axes) { return Product(technique, axes, false); }

std::vector<Config> Neighbours(const Config& c, const std::vector<Axis>& axes) {
  std::vector<Config> out;
  for (const Axis& a : axes) {
    auto it = c.params.find(a.name);
    if (it == c.params.end()) continue;
    auto pos = std::find(a.values.begin(), a.values.end(), it->second);
    if (pos == a.values.end()) continue;
    size_t i = size_t(pos - a.values.begin());
    for (size_t j = 0; j < a.values.size(); ++j) {
      if (j == i || (a.ordered && j + 1 != i && j != i + 1)) continue;
      Config n = c;
      n.params[a.name] = a.values[j];
      out.push_back(std::move(n));
    }
  }
  return out;
}

std::string CppSnippet(const Config& c) {
  std::ostringstream s;
  s << "// " << ConfigText(c) << "\n"
    << "std::unique_ptr<sp::tech::Technique> technique = sp::tech::CreateTechnique(\"" << c.technique << "\");\n"
    << "const std::map<std::string, std::string> given = {";
  bool first = true;
  for (const auto& [k, v] : c.params) {
    s << (first ? "" : ", ") << "{\"" << k << "\", \"" << v << "\"}";
    first = false;
  }
  s << "};\n"
    << "technique->Configure(*device, sp::tech::ParamValues::Parse(\"" << c.technique << "\", technique->Params(), given));\n"
    << "sp::tech::Renderer renderer(*device, scene, std::move(technique), width, height);\n";
  return s.str();
}

}  // namespace sp::advise
