#include "cache.h"

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>
#include <unordered_map>
#include <sstream>
#include <unistd.h>

#include "bytecode-json.h"
#include "toolchain.h"

namespace sp::hlsl {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {
std::atomic<uint64_t> gHits{0}, gMisses{0};

bool ReadAll(const fs::path& p, std::string* out) {
  std::ifstream f(p, std::ios::binary);
  if (!f) return false;
  std::stringstream ss;
  ss << f.rdbuf();
  *out = ss.str();
  return true;
}

// Write to a temporary name and rename, so a concurrent reader never sees half a file.
void WriteAtomically(const fs::path& p, const void* data, size_t size) {
  fs::path tmp = p;
  tmp += ".tmp" + std::to_string(::getpid());
  {
    std::ofstream f(tmp, std::ios::binary);
    f.write(static_cast<const char*>(data), std::streamsize(size));
    if (!f) return;
  }
  std::error_code ec;
  fs::rename(tmp, p, ec);
  if (ec) fs::remove(tmp, ec);
}
}  // namespace

uint64_t Hash64(const void* data, size_t size, uint64_t seed) {
  uint64_t h = seed;
  const unsigned char* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < size; ++i) {
    h ^= p[i];
    h *= 1099511628211ull;
  }
  return h;
}

std::string HexHash(uint64_t h) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

// A library writes to the user's disk only where it was told to: no $HOME fallback.
fs::path DefaultCacheDir() {
  if (const char* e = std::getenv("SHADOWPORT_SHADER_CACHE"); e && *e) return e;
  return {};
}

CacheStats GetCacheStats() { return {gHits.load(), gMisses.load()}; }
void CacheCountMiss() { ++gMisses; }

void WriteBytecodeFiles(const fs::path& base, const ShaderBytecode& b, const json* extra) {
  std::string js = BytecodeToJson(b, extra ? *extra : json::object());
  fs::path j = base, s = base, g = base;
  j += ".json";
  s += ".spv";
  g += ".glsl";
  WriteAtomically(s, b.spirv.data(), b.spirv.size() * 4);
  WriteAtomically(g, b.glsl.data(), b.glsl.size());
  WriteAtomically(j, js.data(), js.size());  // last: its presence marks a complete entry
}

void WriteCompiledFiles(const fs::path& base, const ShaderBytecode& b) {
  if (base.has_parent_path()) fs::create_directories(base.parent_path());
  WriteBytecodeFiles(base, b, nullptr);
}

namespace {

json WarningsToJson(const std::vector<Diagnostic>& warnings) {
  json a = json::array();
  for (const Diagnostic& d : warnings) a.push_back({{"file", d.file}, {"line", d.line}, {"message", d.message}});
  return a;
}

std::vector<Diagnostic> WarningsFromJson(const json& a) {
  std::vector<Diagnostic> out;
  for (const json& d : a) out.push_back({d.at("file").get<std::string>(), d.at("line").get<int>(), d.at("message").get<std::string>()});
  return out;
}

bool DependenciesUnchanged(const std::vector<Dependency>& deps) {
  for (const Dependency& d : deps) {
    std::string content;
    if (!ReadAll(d.path, &content) || Hash64(content.data(), content.size()) != d.hash) return false;
  }
  return true;
}

struct MemoryEntry {
  CachedShader shader;
  std::vector<Dependency> deps;
};
std::mutex gMemoryMutex;
std::unordered_map<std::string, MemoryEntry> gMemory;
// A process compiles a bounded set of shaders; the bound only guards against runaway growth
// (e.g. a tool compiling generated variants forever).
constexpr size_t kMemoryEntries = 1024;

}  // namespace

std::optional<CachedShader> CacheLoad(const fs::path& dir, const std::string& key) {
  std::string js, spv, glsl;
  if (!ReadAll(dir / (key + ".json"), &js) || !ReadAll(dir / (key + ".spv"), &spv) || !ReadAll(dir / (key + ".glsl"), &glsl)) return std::nullopt;
  if (spv.size() % 4 || spv.empty()) return std::nullopt;
  try {
    std::vector<uint32_t> words(spv.size() / 4);
    std::memcpy(words.data(), spv.data(), spv.size());
    json extra;
    CachedShader s;
    s.bytecode = BytecodeFromJson(js, std::move(words), std::move(glsl), &extra);
    std::vector<Dependency> deps;
    for (const json& d : extra.at("dependencies")) {
      uint64_t hash = std::stoull(d.at("hash").get<std::string>(), nullptr, 16);
      deps.push_back({d.at("path").get<std::string>(), hash});
    }
    if (!DependenciesUnchanged(deps)) return std::nullopt;
    s.warnings = WarningsFromJson(extra.at("warnings"));
    ++gHits;
    return s;
  } catch (const std::exception&) {
    return std::nullopt;  // a stale or damaged entry is simply recompiled
  }
}

void CacheStore(const fs::path& dir, const std::string& key, const CachedShader& s, const std::vector<Dependency>& deps) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) return;  // a read-only cache location only costs compile time
  json extra;
  extra["dependencies"] = json::array();
  for (const Dependency& d : deps) extra["dependencies"].push_back({{"path", d.path}, {"hash", HexHash(d.hash)}});
  extra["warnings"] = WarningsToJson(s.warnings);
  WriteBytecodeFiles(dir / key, s.bytecode, &extra);
}

std::optional<CachedShader> MemoryCacheLoad(const std::string& key) {
  MemoryEntry e;
  {
    std::lock_guard lock(gMemoryMutex);
    auto it = gMemory.find(key);
    if (it == gMemory.end()) return std::nullopt;
    e = it->second;
  }
  if (!DependenciesUnchanged(e.deps)) return std::nullopt;
  ++gHits;
  return std::move(e.shader);
}

void MemoryCacheStore(const std::string& key, const CachedShader& s, const std::vector<Dependency>& deps) {
  std::lock_guard lock(gMemoryMutex);
  if (gMemory.size() >= kMemoryEntries) gMemory.erase(gMemory.begin());
  gMemory[key] = {s, deps};
}

}  // namespace sp::hlsl
