#include <cmath>
#include <stdexcept>

#include <sp/tech/technique.h>

namespace sp::tech {

namespace {

std::string ListNames(const std::vector<ParamSpec>& specs) {
  std::string s;
  for (const ParamSpec& p : specs) s += (s.empty() ? "" : ", ") + p.name;
  return s.empty() ? "(none)" : s;
}

std::string Describe(const ParamSpec& p) {
  if (p.kind == ParamSpec::Text) return p.help;
  if (p.kind == ParamSpec::Choice) {
    std::string s;
    for (const std::string& c : p.choices) s += (s.empty() ? "" : "|") + c;
    return s;
  }
  auto num = [&](double v) {
    if (p.kind == ParamSpec::Int) return std::to_string(int64_t(v));
    std::string t = std::to_string(v);
    t.erase(t.find_last_not_of('0') + 1);
    if (!t.empty() && t.back() == '.') t.pop_back();
    return t;
  };
  return (p.kind == ParamSpec::Int ? "an integer in [" : "a number in [") + num(p.min) + ", " + num(p.max) + "]";
}

void Check(const std::string& technique, const ParamSpec& p, const std::string& v) {
  auto bad = [&]() { throw std::invalid_argument("technique '" + technique + "': " + p.name + "=" + v + " is not valid; " + p.name + " takes " + Describe(p)); };
  if (p.kind == ParamSpec::Text) return;
  if (p.kind == ParamSpec::Choice) {
    for (const std::string& c : p.choices)
      if (c == v) return;
    bad();
  }
  size_t used = 0;
  double d = 0;
  try {
    d = p.kind == ParamSpec::Int ? double(std::stoll(v, &used)) : std::stod(v, &used);
  } catch (const std::exception&) {
    bad();
  }
  if (used != v.size() || !std::isfinite(d) || d < p.min || d > p.max) bad();
}

}  // namespace

ParamValues ParamValues::Parse(const std::string& technique, const std::vector<ParamSpec>& specs,
                               const std::map<std::string, std::string>& given) {
  ParamValues out;
  for (const auto& [name, value] : given) {
    const ParamSpec* spec = nullptr;
    for (const ParamSpec& p : specs)
      if (p.name == name) spec = &p;
    if (!spec) throw std::invalid_argument("technique '" + technique + "' has no parameter '" + name + "' (valid: " + ListNames(specs) + ")");
    Check(technique, *spec, value);
    out.values_[name] = value;
  }
  for (const ParamSpec& p : specs)
    if (!out.values_.count(p.name)) out.values_[p.name] = p.defaultValue;
  return out;
}

int ParamValues::getInt(const std::string& name) const { return std::stoi(values_.at(name)); }
float ParamValues::getFloat(const std::string& name) const { return std::stof(values_.at(name)); }
const std::string& ParamValues::getChoice(const std::string& name) const { return values_.at(name); }

}  // namespace sp::tech
