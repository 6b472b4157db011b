// The HLSL toolchain: D3DCompile's job for both backends.
//
//   HLSL (SM 4.0-5.0) --glslang--> SPIR-V --spirv-opt legalisation--> --spirv-val--> Vulkan
//                                          \--SPIRV-Cross--> GLSL 4.50 + GL binding table --> OpenGL
//
// Reflection is read from the SPIR-V. Results are cached, keyed by a hash of the sources
// (including every #included file), defines, target, the flags that change the output and the
// toolchain's own revision. Where the cache lives:
//   1. CompileOptions::cacheDir, if set;
//   2. else $SHADOWPORT_SHADER_CACHE, if set (`./shadowport` sets it to build/shader-cache);
//   3. else nowhere on disk: compiled shaders are kept in memory for the life of the process.
// The toolchain never writes under $HOME or $XDG_CACHE_HOME on its own.
//
// Two interfaces: CompileFile/CompileSource (throw CompileError), and Compile/CompileFromFile,
// D3DCompile's and D3DCompileFromFile's shape (HRESULT, Blob out-pointers), for ports.
// Naming: the `D3D` prefix becomes the sp::hlsl namespace: D3DCompile -> sp::hlsl::Compile,
// D3DCOMPILE_DEBUG -> sp::hlsl::COMPILE_DEBUG, D3D_SHADER_MACRO -> sp::hlsl::SHADER_MACRO,
// ID3DBlob -> sp::hlsl::Blob, D3D_COMPILE_STANDARD_FILE_INCLUDE -> sp::hlsl::COMPILE_STANDARD_FILE_INCLUDE.
#pragma once
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>
#include <sp/rhi/shader.h>

namespace sp::hlsl {

// fxc's compile flags (D3DCOMPILE_*, fxc's command-line switch in brackets), with fxc's values.
// Flags that change what a shader means are honoured; the rest ask fxc for code-generation
// choices that SPIR-V and GLSL drivers make themselves, and are accepted without effect.
inline constexpr uint32_t COMPILE_DEBUG = 1u << 0;                      // -Zi: no effect (no debug info is emitted)
inline constexpr uint32_t COMPILE_SKIP_VALIDATION = 1u << 1;            // -Vd: no effect (spirv-val always runs: glslang can emit invalid SPIR-V)
inline constexpr uint32_t COMPILE_SKIP_OPTIMIZATION = 1u << 2;          // -Od: no effect (legalisation needs the optimiser)
inline constexpr uint32_t COMPILE_PACK_MATRIX_ROW_MAJOR = 1u << 3;      // -Zpr: matrices without a qualifier are row_major
inline constexpr uint32_t COMPILE_PACK_MATRIX_COLUMN_MAJOR = 1u << 4;   // -Zpc: ... column_major (HLSL's default)
inline constexpr uint32_t COMPILE_PARTIAL_PRECISION = 1u << 5;          // -Gpp: no effect (full precision)
inline constexpr uint32_t COMPILE_FORCE_VS_SOFTWARE_NO_OPT = 1u << 6;   // no effect
inline constexpr uint32_t COMPILE_FORCE_PS_SOFTWARE_NO_OPT = 1u << 7;   // no effect
inline constexpr uint32_t COMPILE_NO_PRESHADER = 1u << 8;               // -Op: no effect (no preshaders)
inline constexpr uint32_t COMPILE_AVOID_FLOW_CONTROL = 1u << 9;         // -Gfa: no effect
inline constexpr uint32_t COMPILE_PREFER_FLOW_CONTROL = 1u << 10;       // -Gfp: no effect
inline constexpr uint32_t COMPILE_ENABLE_STRICTNESS = 1u << 11;         // -Ges: no effect (glslang has one dialect)
inline constexpr uint32_t COMPILE_ENABLE_BACKWARDS_COMPATIBILITY = 1u << 12;  // -Gec: no effect
inline constexpr uint32_t COMPILE_IEEE_STRICTNESS = 1u << 13;           // -Gis: no effect (arithmetic order is fixed anyway)
inline constexpr uint32_t COMPILE_OPTIMIZATION_LEVEL0 = 1u << 14;       // -O0: no effect
inline constexpr uint32_t COMPILE_OPTIMIZATION_LEVEL1 = 0;              // -O1: fxc's default
inline constexpr uint32_t COMPILE_OPTIMIZATION_LEVEL2 = (1u << 14) | (1u << 15);  // -O2: no effect
inline constexpr uint32_t COMPILE_OPTIMIZATION_LEVEL3 = 1u << 15;       // -O3: no effect
inline constexpr uint32_t COMPILE_WARNINGS_ARE_ERRORS = 1u << 18;       // -WX: a warning fails the compile
inline constexpr uint32_t COMPILE_RESOURCES_MAY_ALIAS = 1u << 19;       // -res_may_alias: no effect
inline constexpr uint32_t COMPILE_ENABLE_UNBOUNDED_DESCRIPTOR_TABLES = 1u << 20;  // no effect
inline constexpr uint32_t COMPILE_ALL_RESOURCES_BOUND = 1u << 21;       // -all_resources_bound: no effect
inline constexpr uint32_t COMPILE_DEBUG_NAME_FOR_SOURCE = 1u << 22;     // no effect
inline constexpr uint32_t COMPILE_DEBUG_NAME_FOR_BINARY = 1u << 23;     // no effect
// Every bit above; others are refused.
inline constexpr uint32_t kKnownCompileFlags = 0x00FCFFFFu;
// The flags that change the compiled shader (part of the cache key). -WX changes only whether a
// compile succeeds: cache entries keep their warnings, so it is checked on every hit.
inline constexpr uint32_t kSemanticCompileFlags = COMPILE_PACK_MATRIX_ROW_MAJOR | COMPILE_PACK_MATRIX_COLUMN_MAJOR;

struct Define {
  std::string name;
  std::string value;  // empty: defined as 1, as fxc's -D NAME
};

struct CompileOptions {
  // vs_4_0, vs_4_1, vs_5_0, ps_4_0, ps_4_1, ps_5_0, cs_4_0, cs_4_1, cs_5_0: Shader Model 4
  // targets compile exactly like their 5.0 twin (fxc's extra SM4 restrictions are not checked).
  // gs_4_0, gs_4_1, gs_5_0 compile, but the RHI does not create geometry shaders yet.
  std::string target;
  std::string entryPoint;  // "main" when empty
  std::vector<Define> defines;
  std::vector<std::filesystem::path> includeDirs;  // searched after the including file's folder
  uint32_t flags1 = 0;  // COMPILE_* (D3DCompile's Flags1)
  bool useCache = true;
  // Where compiled shaders are cached on disk; see the top of this file for the rule when empty.
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

// `warnings`, when given, receives the front end's warnings (also for cache hits); with
// COMPILE_WARNINGS_ARE_ERRORS any warning throws instead.
ShaderBytecode CompileFile(const std::filesystem::path& file, const CompileOptions& options,
                           std::vector<Diagnostic>* warnings = nullptr);
// `fileName` is used in messages and as the base for relative #includes.
ShaderBytecode CompileSource(std::string_view source, const std::string& fileName, const CompileOptions& options,
                             std::vector<Diagnostic>* warnings = nullptr);

// D3DPreprocess, and more: the text glslang's parser is given for this source. That is the
// preprocessor's output (defines expanded, includes inlined, #line directives naming the user's
// files) after the D3D11 compatibility rewrites, which turn constructs fxc accepts and glslang
// does not (brace-elided initializer lists, matrix swizzles, fxc's for-loop scoping, statics in
// cbuffers, array casts, effect-file blocks) into equivalent HLSL; `rewritesApplied` receives
// the names of those that changed something. What `shadowport hlslc -P out.hlsl` writes.
// Throws CompileError (preprocessor errors, and constructs the rewrites refuse).
std::string Preprocess(std::string_view source, const std::string& fileName, const CompileOptions& options,
                       std::vector<std::string>* rewritesApplied = nullptr);

// Writes base.spv (SPIR-V), base.glsl (GLSL 4.50) and base.json (reflection, GL binding table):
// what `shadowport hlslc -Fo base` produces.
void WriteCompiledFiles(const std::filesystem::path& base, const ShaderBytecode& bytecode);

// Parses an fxc-style target ("ps_5_0", "vs_4_0"); returns false for unknown targets.
bool ParseTarget(std::string_view target, ShaderStage* stage);
// "vs_4_0, vs_4_1, vs_5_0, ps_4_0, ..." for messages.
const char* ValidTargets();

// "file:line: warning: message" / "file:line: error: message", one per line.
std::string FormatDiagnostics(const std::vector<Diagnostic>& diagnostics, const char* severity);

struct CacheStats {
  uint64_t hits = 0;    // disk and memory
  uint64_t misses = 0;  // compilations actually run
};
CacheStats GetCacheStats();
// The disk cache used when CompileOptions::cacheDir is empty: $SHADOWPORT_SHADER_CACHE, or an
// empty path (no disk cache) when that is not set.
std::filesystem::path DefaultCacheDir();

// ---- D3DCompile's shape ----------------------------------------------------------------------

// ID3DBlob: bytes with a COM-style reference count. Created with a count of 1; Release() at 0
// deletes it, so SAFE_RELEASE(blob) works as in D3D code.
class Blob {
 public:
  void* GetBufferPointer() { return data_.get(); }
  const void* GetBufferPointer() const { return data_.get(); }
  size_t GetBufferSize() const { return size_; }
  uint32_t AddRef();
  uint32_t Release();

  static Blob* Create(const void* data, size_t size);  // a copy of `data` (zeros when null)
  Blob(const Blob&) = delete;
  Blob& operator=(const Blob&) = delete;

 private:
  explicit Blob(size_t size);
  ~Blob() = default;
  std::unique_ptr<uint8_t[]> data_;
  size_t size_;
  std::atomic<uint32_t> refs_{1};
};

// D3DCreateBlob.
HRESULT CreateBlob(size_t size, Blob** blob);

// D3D_SHADER_MACRO: arrays end with {nullptr, nullptr}. The macro is `#define Name Definition`,
// so a null or empty Definition defines Name as empty (fxc's -D NAME, CompileOptions' Define
// with an empty value, means 1 instead).
struct SHADER_MACRO {
  const char* Name;
  const char* Definition;
};

// ID3DInclude. Only the two values D3D code passes without writing its own include handler are
// accepted: nullptr and COMPILE_STANDARD_FILE_INCLUDE, both of which resolve #include "file"
// relative to the including file, as D3D_COMPILE_STANDARD_FILE_INCLUDE does. Include handlers of
// one's own (ID3DInclude subclasses) are not supported: pass the folders as
// CompileOptions::includeDirs to CompileSource instead.
struct Include;
inline Include* const COMPILE_STANDARD_FILE_INCLUDE = reinterpret_cast<Include*>(uintptr_t(1));

// D3DCompile: returns S_OK with *code = the serialized ShaderBytecode (what
// Device::CreateVertexShader(ptr, size) takes) and *errors = the warnings (or null when there
// are none); or E_FAIL with *code = null and *errors = "file:line: error: message" lines, as a
// null-terminated string (GetBufferSize() counts the terminator); or E_INVALIDARG for bad
// arguments (null source or target, unknown flags, an include handler), with the reason in
// *errors. `errors` may be null. `sourceName` (may be null) is used in messages and as the
// base of relative #includes; a null `entrypoint` means "main"; `flags2` (effect flags) is
// ignored as D3DCompile does for shaders. Compiled shaders are cached as CompileSource's are.
HRESULT Compile(const void* srcData, size_t srcDataSize, const char* sourceName, const SHADER_MACRO* defines,
                Include* include, const char* entrypoint, const char* target, uint32_t flags1, uint32_t flags2,
                Blob** code, Blob** errors);
// D3DCompileFromFile (which takes a wide-character path: L"file.hlsl" converts as well).
HRESULT CompileFromFile(const std::filesystem::path& fileName, const SHADER_MACRO* defines, Include* include,
                        const char* entrypoint, const char* target, uint32_t flags1, uint32_t flags2, Blob** code,
                        Blob** errors);

// D3DX11CompileFromFile, which the DirectX SDK's samples call (D3DX11 -> sp::hlsl::X11, and
// ID3D10Blob / D3D10_SHADER_MACRO are Blob / SHADER_MACRO): CompileFromFile with a thread pump,
// which must be null (compilation is synchronous; anything else is E_INVALIDARG, said in
// *errorMsgs), and the result also stored in *hresult when that is not null.
struct X11ThreadPump;
HRESULT X11CompileFromFile(const std::filesystem::path& srcFile, const SHADER_MACRO* defines, Include* include,
                           const char* functionName, const char* profile, uint32_t flags1, uint32_t flags2,
                           X11ThreadPump* pump, Blob** shader, Blob** errorMsgs, HRESULT* hresult);

}  // namespace sp::hlsl
