// The HLSL toolchain: D3DCompile's job for both backends.
//
//   HLSL (SM 5.0) --glslang--> SPIR-V --spirv-opt legalisation--> --spirv-val--> Vulkan
//                                      \--SPIRV-Cross--> GLSL 4.50 + GL binding table --> OpenGL
//
// Reflection is read from the SPIR-V. Results are cached on disk, keyed by a hash of the sources
// (including every #included file), defines, target and toolchain options.
#pragma once
#include <filesystem>
#include <string>
#include <vector>
#include <sp/rhi/shader.h>

namespace sp::hlsl {

struct Define {
  std::string name;
  std::string value;  // empty: defined as 1, as fxc's -D NAME
};

struct CompileOptions {
  std::string target;      // "vs_5_0", "ps_5_0", "cs_5_0" (gs_5_0 parses but is not supported by the RHI yet)
  std::string entryPoint;  // "main" when empty
  std::vector<Define> defines;
  std::vector<std::filesystem::path> includeDirs;  // searched after the including file's folder
  bool useCache = true;
  // Where compiled shaders are cached. Empty: $SHADOWPORT_SHADER_CACHE, else
  // $XDG_CACHE_HOME/shadowport/shaders, else ~/.cache/shadowport/shaders.
  std::filesystem::path cacheDir;
};

// One compiler message, with the position in the user's file (not in a preprocessed buffer).
struct Diagnostic {
  std::string file;
  int line = 0;  // 0 when the tool gave no line (linker, validator)
  std::string message;
};

// Thrown for any failure (sp::ErrorId::SHADER_COMPILE_FAILED). what() begins with the first
// "file:line: error: message" so that it is useful printed as is.
class CompileError : public Error {
 public:
  CompileError(std::string call, std::string object, std::vector<Diagnostic> diagnostics, std::string log);
  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }
  const std::string& log() const { return log_; }

 private:
  std::vector<Diagnostic> diagnostics_;
  std::string log_;
};

ShaderBytecode CompileFile(const std::filesystem::path& file, const CompileOptions& options);
// `fileName` is used in messages and as the base for relative #includes.
ShaderBytecode CompileSource(std::string_view source, const std::string& fileName, const CompileOptions& options);

// Writes base.spv (SPIR-V), base.glsl (GLSL 4.50) and base.json (reflection, GL binding table):
// what `shadowport hlslc -Fo base` produces.
void WriteCompiledFiles(const std::filesystem::path& base, const ShaderBytecode& bytecode);

// Parses an fxc-style target ("ps_5_0"); returns false for unknown targets.
bool ParseTarget(std::string_view target, ShaderStage* stage);

struct CacheStats {
  uint64_t hits = 0;
  uint64_t misses = 0;  // compilations actually run
};
CacheStats GetCacheStats();
std::filesystem::path DefaultCacheDir();

}  // namespace sp::hlsl
