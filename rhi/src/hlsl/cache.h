// Caches of compiled shaders. On disk: <key>.json (reflection, dependencies, warnings),
// <key>.spv, <key>.glsl, the same three files `shadowport hlslc` writes. In memory (when no disk
// cache is configured): the same, for the life of the process. An entry is used only if every
// file it #included still has the content hash recorded.
#pragma once
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <sp/hlsl/compiler.h>
#include <sp/rhi/shader.h>
#include <string>
#include <vector>

namespace sp::hlsl {

struct Dependency {
  std::string path;  // absolute
  uint64_t hash = 0;
};

struct CachedShader {
  ShaderBytecode bytecode;
  std::vector<Diagnostic> warnings;  // replayed on a hit, so -WX and callers see them again
};

std::optional<CachedShader> CacheLoad(const std::filesystem::path& dir, const std::string& key);
void CacheStore(const std::filesystem::path& dir, const std::string& key, const CachedShader& s, const std::vector<Dependency>& deps);
std::optional<CachedShader> MemoryCacheLoad(const std::string& key);
void MemoryCacheStore(const std::string& key, const CachedShader& s, const std::vector<Dependency>& deps);
void CacheCountMiss();

// hlslc and the cache write the same files.
void WriteBytecodeFiles(const std::filesystem::path& base, const ShaderBytecode& b, const nlohmann::json* extra = nullptr);

}  // namespace sp::hlsl
