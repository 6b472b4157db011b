#include "cache.h"

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <fstream>
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

fs::path DefaultCacheDir() {
  if (const char* e = std::getenv("SHADOWPORT_SHADER_CACHE"); e && *e) return e;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return fs::path(x) / "shadowport" / "shaders";
  if (const char* h = std::getenv("HOME"); h && *h) return fs::path(h) / ".cache" / "shadowport" / "shaders";
  return fs::temp_directory_path() / "shadowport-shaders";
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

std::optional<ShaderBytecode> CacheLoad(const fs::path& dir, const std::string& key) {
  std::string js, spv, glsl;
  if (!ReadAll(dir / (key + ".json"), &js) || !ReadAll(dir / (key + ".spv"), &spv) || !ReadAll(dir / (key + ".glsl"), &glsl)) return std::nullopt;
  if (spv.size() % 4 || spv.empty()) return std::nullopt;
  try {
    std::vector<uint32_t> words(spv.size() / 4);
    std::memcpy(words.data(), spv.data(), spv.size());
    json extra;
    ShaderBytecode b = BytecodeFromJson(js, std::move(words), std::move(glsl), &extra);
    for (const json& d : extra.at("dependencies")) {
      std::string content;
      if (!ReadAll(d.at("path").get<std::string>(), &content)) return std::nullopt;
      if (HexHash(Hash64(content.data(), content.size())) != d.at("hash").get<std::string>()) return std::nullopt;
    }
    ++gHits;
    return b;
  } catch (const std::exception&) {
    return std::nullopt;  // a stale or damaged entry is simply recompiled
  }
}

void CacheStore(const fs::path& dir, const std::string& key, const ShaderBytecode& b, const std::vector<Dependency>& deps) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) return;  // a read-only cache location only costs compile time
  json extra;
  extra["dependencies"] = json::array();
  for (const Dependency& d : deps) extra["dependencies"].push_back({{"path", d.path}, {"hash", HexHash(d.hash)}});
  WriteBytecodeFiles(dir / key, b, &extra);
}

}  // namespace sp::hlsl
