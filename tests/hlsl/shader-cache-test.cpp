// Where compiled shaders are cached: CompileOptions::cacheDir, else $SHADOWPORT_SHADER_CACHE,
// else only in memory. Nothing is written under $HOME or $XDG_CACHE_HOME unless asked.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <optional>

#include "backend-test.h"

namespace sp::test {
namespace {

namespace fs = std::filesystem;

fs::path Fresh(const std::string& name) {
  fs::path p = fs::path(SHADOWPORT_TEST_OUTPUT_DIR) / "shader-cache-location" / name;
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

size_t FilesUnder(const fs::path& dir) {
  size_t n = 0;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir)) n += e.is_regular_file();
  return n;
}

// Sources no earlier compile has seen (in this process or an earlier run), so the first compile
// is a miss.
std::string UniqueToken() {
  static int counter = 0;
  return std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()) + "-" + std::to_string(++counter);
}
std::string UniqueSource() { return "float4 main() : SV_Target { return float4(1, 0, 0, 1); } // " + UniqueToken() + "\n"; }

hlsl::CompileOptions Options() {
  hlsl::CompileOptions o;
  o.target = "ps_5_0";
  return o;
}

TEST(ShaderCacheLocation, NothingIsWrittenToHomeUnlessAsked) {
  fs::path home = Fresh("fake-home");
  ScopedEnv h("HOME", home.string());
  ScopedEnv x("XDG_CACHE_HOME", (home / ".cache").string());
  ScopedEnv e("SHADOWPORT_SHADER_CACHE", std::nullopt);
  EXPECT_TRUE(hlsl::DefaultCacheDir().empty());

  std::string src = UniqueSource();
  hlsl::CacheStats s0 = hlsl::GetCacheStats();
  ShaderBytecode a = hlsl::CompileSource(src, "no-disk-cache.hlsl", Options());
  ShaderBytecode b = hlsl::CompileSource(src, "no-disk-cache.hlsl", Options());
  hlsl::CacheStats s1 = hlsl::GetCacheStats();
  EXPECT_EQ(s1.misses, s0.misses + 1);  // the second compile came from memory
  EXPECT_EQ(s1.hits, s0.hits + 1);
  EXPECT_EQ(a.spirv, b.spirv);
  EXPECT_EQ(FilesUnder(home), 0u);
}

// The memory cache checks #included files as the disk cache does.
TEST(ShaderCacheLocation, MemoryCacheSeesIncludedFilesChange) {
  ScopedEnv e("SHADOWPORT_SHADER_CACHE", std::nullopt);
  fs::path dir = Fresh("memory-includes");
  std::ofstream(dir / "value.hlsli") << "#define VALUE 0.25\n";
  std::ofstream(dir / "main.hlsl") << "#include \"value.hlsli\"\nfloat4 main() : SV_Target { return VALUE; }\n" << "// " << UniqueToken() << "\n";
  ShaderBytecode a = hlsl::CompileFile(dir / "main.hlsl", Options());
  EXPECT_NE(a.glsl.find("0.25"), std::string::npos) << a.glsl;
  hlsl::CacheStats s0 = hlsl::GetCacheStats();
  hlsl::CompileFile(dir / "main.hlsl", Options());
  EXPECT_EQ(hlsl::GetCacheStats().hits, s0.hits + 1);
  std::ofstream(dir / "value.hlsli", std::ios::trunc) << "#define VALUE 0.125\n";
  ShaderBytecode b = hlsl::CompileFile(dir / "main.hlsl", Options());
  EXPECT_NE(b.glsl.find("0.125"), std::string::npos) << b.glsl;
}

TEST(ShaderCacheLocation, EnvironmentVariableChoosesTheDiskCache) {
  fs::path home = Fresh("env-home");
  fs::path cache = Fresh("env-cache");
  ScopedEnv h("HOME", home.string());
  ScopedEnv e("SHADOWPORT_SHADER_CACHE", cache.string());
  EXPECT_EQ(hlsl::DefaultCacheDir(), cache);
  hlsl::CompileSource(UniqueSource(), "env-cache.hlsl", Options());
  EXPECT_EQ(FilesUnder(cache), 3u);  // <key>.json, .spv, .glsl
  EXPECT_EQ(FilesUnder(home), 0u);
}

TEST(ShaderCacheLocation, OptionWinsOverTheEnvironment) {
  fs::path fromEnv = Fresh("option-env");
  fs::path fromOption = Fresh("option-dir");
  ScopedEnv e("SHADOWPORT_SHADER_CACHE", fromEnv.string());
  hlsl::CompileOptions o = Options();
  o.cacheDir = fromOption;
  std::string src = UniqueSource();
  hlsl::CompileSource(src, "option-cache.hlsl", o);
  EXPECT_EQ(FilesUnder(fromOption), 3u);
  EXPECT_EQ(FilesUnder(fromEnv), 0u);
  hlsl::CacheStats s0 = hlsl::GetCacheStats();
  hlsl::CompileSource(src, "option-cache.hlsl", o);
  EXPECT_EQ(hlsl::GetCacheStats().hits, s0.hits + 1);
  // useCache = false writes nowhere.
  fs::remove_all(fromOption);
  o.useCache = false;
  hlsl::CompileSource(src, "option-cache.hlsl", o);
  EXPECT_FALSE(fs::exists(fromOption));
}

}  // namespace
}  // namespace sp::test
