// On-disk cache of compiled shaders: <key>.json (reflection + dependencies), <key>.spv, <key>.glsl,
// the same three files `shadowport hlslc` writes. An entry is used only if every file it
// #included still has the content hash recorded.
#pragma once
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <sp/rhi/shader.h>
#include <string>
#include <vector>

namespace sp::hlsl {

struct Dependency {
  std::string path;  // absolute
  uint64_t hash = 0;
};

std::optional<ShaderBytecode> CacheLoad(const std::filesystem::path& dir, const std::string& key);
void CacheStore(const std::filesystem::path& dir, const std::string& key, const ShaderBytecode& b, const std::vector<Dependency>& deps);
void CacheCountMiss();

// hlslc and the cache write the same files.
void WriteBytecodeFiles(const std::filesystem::path& base, const ShaderBytecode& b, const nlohmann::json* extra = nullptr);

}  // namespace sp::hlsl
