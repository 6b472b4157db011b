#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <stdexcept>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

#include <sp/rhi/device.h>

#include "cli.h"

namespace sp::cli {

Args::Args(std::vector<std::string> args, const std::vector<std::string>& flags) {
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a.rfind("--", 0) != 0) {
      positionals_.push_back(a);
      continue;
    }
    std::string name = a.substr(2), value;
    size_t eq = name.find('=');
    if (eq != std::string::npos) {
      value = name.substr(eq + 1);
      name = name.substr(0, eq);
    } else if (std::find(flags.begin(), flags.end(), name) == flags.end()) {
      if (i + 1 >= args.size()) throw std::invalid_argument("option --" + name + " needs a value");
      value = args[++i];
    }
    options_.emplace(name, value);
  }
}

bool Args::has(const std::string& name) const { return options_.count(name) > 0; }

std::string Args::get(const std::string& name, const std::string& fallback) const {
  auto [b, e] = options_.equal_range(name);
  if (b == e) return fallback;
  // Only the options read with getAll (--param, --budget) repeat; for the others a second value
  // would be silently ignored.
  if (std::next(b) != e)
    throw std::invalid_argument("--" + name + " is given twice ('" + b->second + "' and '" + std::next(b)->second + "'): give it once");
  return b->second;
}

std::vector<std::string> Args::getAll(const std::string& name) const {
  std::vector<std::string> v;
  auto [b, e] = options_.equal_range(name);
  for (auto it = b; it != e; ++it) v.push_back(it->second);
  return v;
}

void Args::expectOnly(const std::vector<std::string>& known) const {
  for (const auto& [name, value] : options_) {
    if (std::find(known.begin(), known.end(), name) != known.end()) continue;
    std::string list;
    for (const std::string& k : known) list += (list.empty() ? "--" : ", --") + k;
    throw std::invalid_argument("unknown option --" + name + " (valid: " + list + ")");
  }
}

Backend ParseRenderingBackend(const std::string& text, const std::string& valid) {
  Backend b;
  if (!ParseBackend(text, &b)) throw std::invalid_argument("--backend must be " + valid + " (got '" + text + "')");
  if (b == Backend::Null)
    throw std::invalid_argument("--backend null: the null backend draws nothing (it runs the validation tests without a driver); use " + valid);
  return b;
}

void ParseSize(const std::string& text, uint32_t* w, uint32_t* h) {
  size_t x = text.find('x');
  size_t used1 = 0, used2 = 0;
  long a = 0, b = 0;
  try {
    if (x == std::string::npos) throw std::invalid_argument("");
    a = std::stol(text.substr(0, x), &used1);
    b = std::stol(text.substr(x + 1), &used2);
  } catch (const std::exception&) {
    throw std::invalid_argument("--size '" + text + "' is not WIDTHxHEIGHT (e.g. 1280x720)");
  }
  if (used1 != x || used2 != text.size() - x - 1 || a < 1 || b < 1 || a > 16384 || b > 16384)
    throw std::invalid_argument("--size '" + text + "' must be WIDTHxHEIGHT with both in [1, 16384]");
  *w = uint32_t(a);
  *h = uint32_t(b);
}

std::map<std::string, std::string> ParseParams(const std::vector<std::string>& params) {
  std::map<std::string, std::string> out;
  for (const std::string& p : params) {
    size_t eq = p.find('=');
    if (eq == std::string::npos || eq == 0) throw std::invalid_argument("--param '" + p + "' is not name=value");
    out[p.substr(0, eq)] = p.substr(eq + 1);
  }
  return out;
}

std::vector<std::string> SplitList(const std::string& text, const std::string& option) {
  std::vector<std::string> out;
  size_t start = 0;
  while (true) {
    size_t comma = text.find(',', start);
    std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (item.empty()) throw std::invalid_argument("--" + option + " '" + text + "' has an empty item");
    out.push_back(item);
    if (comma == std::string::npos) return out;
    start = comma + 1;
  }
}

uint64_t ParseCount(const std::string& text, const std::string& option, uint64_t min, uint64_t max) {
  size_t used = 0;
  unsigned long long v = 0;
  try {
    v = std::stoull(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || text[0] == '-' || v < min || v > max)
    throw std::invalid_argument("--" + option + " '" + text + "' must be an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]");
  return v;
}

ProgressPrinter::ProgressPrinter(std::string prefix) : prefix_(std::move(prefix)), start_(std::chrono::steady_clock::now()) {}

double ProgressPrinter::Seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

void ProgressPrinter::operator()(const std::string& line) const {
  double t = Seconds();
  std::fprintf(stderr, "%s[%2d:%04.1f] %s\n", prefix_.c_str(), int(t) / 60, std::fmod(t, 60.0), line.c_str());
  std::fflush(stderr);
}

void WritePng(const std::string& path, uint32_t w, uint32_t h, const uint8_t* rgba) {
  std::filesystem::path p(path);
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
  if (!stbi_write_png(path.c_str(), int(w), int(h), 4, rgba, int(w * 4))) throw std::runtime_error("cannot write " + path);
}

}  // namespace sp::cli
