// HLSL -> SPIR-V -> (legalised, validated) -> reflection -> GLSL. See sp/hlsl/compiler.h.
#include <glslang/Include/intermediate.h>
#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>
#include <glslang/build_info.h>

#include <fstream>
#include <mutex>
#include <regex>
#include <set>
#include <spirv-tools/libspirv.hpp>
#include <spirv-tools/optimizer.hpp>
#include <sstream>

#include "cache.h"
#include "spirv-edit.h"
#include "toolchain.h"

namespace sp::hlsl {
namespace fs = std::filesystem;

static std::string FormatDiagnostics(const std::vector<Diagnostic>& d, const std::string& fallback) {
  if (d.empty()) return fallback;
  std::string s;
  for (size_t i = 0; i < d.size(); ++i) {
    if (i) s += "\n";
    s += d[i].file;
    if (d[i].line) s += ":" + std::to_string(d[i].line);
    s += ": error: " + d[i].message;
  }
  return s;
}

CompileError::CompileError(std::string call, std::string object, std::vector<Diagnostic> diagnostics, std::string log)
    : Error(ErrorId::SHADER_COMPILE_FAILED, std::move(call), std::move(object), FormatDiagnostics(diagnostics, log)),
      diagnostics_(std::move(diagnostics)),
      log_(std::move(log)) {}

bool ParseTarget(std::string_view target, ShaderStage* stage) {
  if (target == "vs_5_0") *stage = ShaderStage::Vertex;
  else if (target == "ps_5_0") *stage = ShaderStage::Pixel;
  else if (target == "cs_5_0") *stage = ShaderStage::Compute;
  else if (target == "gs_5_0") *stage = ShaderStage::Geometry;
  else return false;
  return true;
}

namespace {

std::once_flag gInitOnce;
std::mutex gCompileMutex;  // glslang keeps process-wide state

EShLanguage LanguageOf(ShaderStage s) {
  switch (s) {
    case ShaderStage::Vertex: return EShLangVertex;
    case ShaderStage::Pixel: return EShLangFragment;
    case ShaderStage::Geometry: return EShLangGeometry;
    case ShaderStage::Compute: return EShLangCompute;
  }
  return EShLangVertex;
}

bool ReadFile(const fs::path& p, std::string* out) {
  std::ifstream f(p, std::ios::binary);
  if (!f) return false;
  std::stringstream ss;
  ss << f.rdbuf();
  *out = ss.str();
  return true;
}

// fxc's #include rules: "file" relative to the including file, then the -I folders; <file> in
// the -I folders. Every file read is remembered for the cache's dependency check.
class Includer : public glslang::TShader::Includer {
 public:
  Includer(fs::path mainDir, std::vector<fs::path> dirs) : mainDir_(std::move(mainDir)), dirs_(std::move(dirs)) {}

  IncludeResult* includeLocal(const char* header, const char* includer, size_t) override {
    fs::path base = includer && *includer ? fs::path(includer).parent_path() : mainDir_;
    if (IncludeResult* r = TryOpen(base / header)) return r;
    return includeSystem(header, includer, 0);
  }
  IncludeResult* includeSystem(const char* header, const char*, size_t) override {
    for (const fs::path& d : dirs_)
      if (IncludeResult* r = TryOpen(d / header)) return r;
    return nullptr;
  }
  void releaseInclude(IncludeResult* r) override {
    if (!r) return;
    delete static_cast<std::string*>(r->userData);
    delete r;
  }
  const std::vector<Dependency>& deps() const { return deps_; }

 private:
  IncludeResult* TryOpen(const fs::path& p) {
    std::string* content = new std::string;
    if (!ReadFile(p, content)) {
      delete content;
      return nullptr;
    }
    std::string name = p.lexically_normal().string();
    deps_.push_back({fs::absolute(p).lexically_normal().string(), Hash64(content->data(), content->size())});
    return new IncludeResult(name, content->data(), content->size(), content);
  }
  fs::path mainDir_;
  std::vector<fs::path> dirs_;
  std::vector<Dependency> deps_;
};

// "ERROR: path/file.hlsl:12: 'x' : undeclared identifier" -> {path/file.hlsl, 12, ...}
std::vector<Diagnostic> ParseGlslangLog(const std::string& log, const std::string& defaultFile) {
  std::vector<Diagnostic> out;
  static const std::regex withLine(R"(^(?:ERROR|error): (.+?):(\d+): (.*)$)");
  static const std::regex noLine(R"(^(?:ERROR|error): (.*)$)");
  std::istringstream in(log);
  std::string line;
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_match(line, m, withLine)) {
      out.push_back({m[1].str(), std::stoi(m[2].str()), m[3].str()});
    } else if (std::regex_match(line, m, noLine)) {
      std::string msg = m[1].str();
      if (msg.find("compilation errors") != std::string::npos || msg.find("No code generated") != std::string::npos) continue;
      out.push_back({defaultFile, 0, msg});
    }
  }
  return out;
}

// glslang's HLSL front end wraps the entry point in a function that copies the stage inputs into
// temporaries and passes them to the user's function. For some inputs it declares the input but
// never copies it (glslang 12: a scalar `uint c : SV_Coverage` parameter), so the shader reads an
// undefined value; this finds entry-point arguments that are read but never written.
class UnconnectedInputs : public glslang::TIntermTraverser {
 public:
  explicit UnconnectedInputs(std::string wrapper) : wrapper_(std::move(wrapper)) {}
  std::vector<std::string> names;

  bool visitAggregate(glslang::TVisit visit, glslang::TIntermAggregate* node) override {
    if (node->getOp() == glslang::EOpFunction) {
      inWrapper_ = visit == glslang::EvPreVisit && node->getName().compare(0, wrapper_.size(), wrapper_.c_str()) == 0;
      written_.clear();
    } else if (inWrapper_ && visit == glslang::EvPreVisit && node->getOp() == glslang::EOpFunctionCall) {
      const glslang::TQualifierList& qualifiers = node->getQualifierList();
      const glslang::TIntermSequence& args = node->getSequence();
      for (size_t i = 0; i < args.size() && i < qualifiers.size(); ++i) {
        const glslang::TIntermSymbol* sym = args[i]->getAsSymbolNode();
        bool input = qualifiers[i] == glslang::EvqIn || qualifiers[i] == glslang::EvqConstReadOnly || qualifiers[i] == glslang::EvqInOut;
        if (input && sym && sym->getQualifier().storage == glslang::EvqTemporary && !written_.count(sym->getId()))
          names.push_back(sym->getName().c_str());
      }
    }
    return true;
  }
  bool visitBinary(glslang::TVisit visit, glslang::TIntermBinary* node) override {
    if (inWrapper_ && visit == glslang::EvPreVisit && node->getOp() == glslang::EOpAssign) {
      glslang::TIntermTyped* target = node->getLeft();
      while (glslang::TIntermBinary* b = target->getAsBinaryNode()) target = b->getLeft();  // a.b[i] -> a
      if (glslang::TIntermSymbol* sym = target->getAsSymbolNode()) written_.insert(sym->getId());
    }
    return true;
  }

 private:
  std::string wrapper_;
  bool inWrapper_ = false;
  std::set<long long> written_;
};

std::vector<uint32_t> RunGlslang(const std::string& source, const std::string& fileName, const CompileOptions& opt, ShaderStage stage,
                                 const std::string& entry, Includer& includer) {
  std::call_once(gInitOnce, [] { glslang::InitializeProcess(); });
  EShLanguage lang = LanguageOf(stage);
  glslang::TShader shader(lang);
  const char* src = source.c_str();
  const char* name = fileName.c_str();
  int len = int(source.size());
  shader.setStringsWithLengthsAndNames(&src, &len, &name, 1);
  std::string preamble;
  for (const Define& d : opt.defines) preamble += "#define " + d.name + " " + (d.value.empty() ? std::string("1") : d.value) + "\n";
  shader.setPreamble(preamble.c_str());
  shader.setEntryPoint(entry.c_str());
  shader.setSourceEntryPoint(entry.c_str());
  shader.setEnvInput(glslang::EShSourceHlsl, lang, glslang::EShClientVulkan, 100);
  shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_1);
  shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_3);
  shader.setEnvTargetHlslFunctionality1();
  shader.setHlslIoMapping(true);
  shader.setShiftBinding(glslang::EResUbo, vkbind::kConstantBuffer);
  shader.setShiftBinding(glslang::EResTexture, vkbind::kShaderResource);
  shader.setShiftBinding(glslang::EResSsbo, vkbind::kShaderResource);
  shader.setShiftBinding(glslang::EResSampler, vkbind::kSampler);
  shader.setShiftBinding(glslang::EResImage, vkbind::kUnorderedAccess);
  shader.setShiftBinding(glslang::EResUav, vkbind::kUnorderedAccess);
  shader.setResourceSetBinding({std::to_string(vkbind::SetForStage(stage))});
  shader.setAutoMapBindings(true);
  shader.setNoStorageFormat(true);
  // D3D's +y is up in NDC and row 0 is the top; negating y in the last pre-rasterization stage
  // gives D3D's orientation on both APIs (see docs/porting.md, "Orientation").
  if (stage == ShaderStage::Vertex) shader.setInvertY(true);
  auto messages = EShMessages(EShMsgSpvRules | EShMsgVulkanRules | EShMsgReadHlsl | EShMsgHlslOffsets);

  if (!shader.parse(GetDefaultResources(), 100, ENoProfile, false, false, messages, includer)) {
    std::string log = std::string(shader.getInfoLog()) + shader.getInfoDebugLog();
    throw CompileError("glslang", fileName + ":" + entry, ParseGlslangLog(log, fileName), log);
  }
  glslang::TProgram program;
  program.addShader(&shader);
  if (!program.link(messages) || !program.mapIO()) {
    std::string log = program.getInfoLog();
    throw CompileError("glslang (link)", fileName + ":" + entry, ParseGlslangLog(log, fileName), log);
  }
  UnconnectedInputs unconnected(entry + "(");
  program.getIntermediate(lang)->getTreeRoot()->traverse(&unconnected);
  if (!unconnected.names.empty()) {
    std::string msg = "glslang does not connect the entry-point input '" + unconnected.names[0] +
                      "' (it would read an undefined value); declare it as a member of an input struct instead";
    throw CompileError("glslang", fileName + ":" + entry, {{fileName, 0, msg}}, msg);
  }
  std::vector<uint32_t> spirv;
  glslang::SpvOptions spvOptions;
  spvOptions.disableOptimizer = true;  // we run spirv-opt ourselves, with known passes
  spvOptions.validate = false;
  spv::SpvBuildLogger logger;
  glslang::GlslangToSpv(*program.getIntermediate(lang), spirv, &logger, &spvOptions);
  std::string msgs = logger.getAllMessages();
  if (msgs.find("error") != std::string::npos || msgs.find("Missing functionality") != std::string::npos) {
    // glslang exits 0 but writes invalid SPIR-V for HLSL features it cannot translate; report them.
    throw CompileError("glslang (SPIR-V)", fileName + ":" + entry, {{fileName, 0, msgs}}, msgs);
  }
  return spirv;
}

struct ToolMessages {
  std::string text;
  void operator()(spv_message_level_t, const char*, const spv_position_t& pos, const char* m) {
    text += m;
    text += "\n";
  }
};

std::vector<uint32_t> Legalize(const std::vector<uint32_t>& in, const std::string& name) {
  ToolMessages log;
  spvtools::Optimizer opt(SPV_ENV_VULKAN_1_1);
  opt.SetMessageConsumer([&log](spv_message_level_t l, const char* s, const spv_position_t& p, const char* m) { log(l, s, p, m); });
  // HLSL needs legalisation (resources in locals, inlining); it also fully unrolls [unroll]
  // loops and folds constants, so their texel offsets become constants.
  opt.RegisterLegalizationPasses();
  opt.RegisterPerformancePasses();
  spvtools::OptimizerOptions options;
  options.set_run_validator(false);
  std::vector<uint32_t> out;
  if (!opt.Run(in.data(), in.size(), &out, options)) throw CompileError("spirv-opt", name, {{name, 0, "spirv-opt failed: " + log.text}}, log.text);
  return out;
}

std::vector<uint32_t> StripHlslDecorations(const std::vector<uint32_t>& in, const std::string& name) {
  spvtools::Optimizer opt(SPV_ENV_VULKAN_1_1);
  opt.RegisterPass(spvtools::CreateStripNonSemanticInfoPass());
  spvtools::OptimizerOptions options;
  options.set_run_validator(false);
  std::vector<uint32_t> out;
  if (!opt.Run(in.data(), in.size(), &out, options)) throw CompileError("spirv-opt", name, {{name, 0, "stripping decorations failed"}}, "");
  return out;
}

void Validate(const std::vector<uint32_t>& spirv, const std::string& fileName, const std::string& name) {
  ToolMessages log;
  spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_1);
  tools.SetMessageConsumer([&log](spv_message_level_t l, const char* s, const spv_position_t& p, const char* m) { log(l, s, p, m); });
  spvtools::ValidatorOptions vo;
  vo.SetRelaxBlockLayout(true);  // HLSL packing (float3 after float) is legal under Vulkan 1.1's relaxed layout
  if (!tools.Validate(spirv.data(), spirv.size(), vo)) {
    std::string msg = "the generated SPIR-V is invalid (a glslang limitation with this HLSL construct): " + log.text;
    throw CompileError("spirv-val", name, {{fileName, 0, msg}}, log.text);
  }
}

std::string CacheKey(const std::string& source, const std::string& fileName, const CompileOptions& opt, const std::string& entry) {
  std::string k = std::string(kToolchainRevision) + "|glslang " + std::to_string(GLSLANG_VERSION_MAJOR) + "." +
                  std::to_string(GLSLANG_VERSION_MINOR) + "." + std::to_string(GLSLANG_VERSION_PATCH) + "|" + opt.target + "|" + entry + "|" +
                  fs::absolute(fileName).lexically_normal().string();
  for (const Define& d : opt.defines) k += "|D" + d.name + "=" + d.value;
  for (const fs::path& p : opt.includeDirs) k += "|I" + fs::absolute(p).lexically_normal().string();
  uint64_t h = Hash64(k.data(), k.size());
  h = Hash64(source.data(), source.size(), h);
  return HexHash(h);
}

}  // namespace

ShaderBytecode CompileSource(std::string_view sourceView, const std::string& fileName, const CompileOptions& opt) {
  ShaderStage stage;
  std::string entry = opt.entryPoint.empty() ? "main" : opt.entryPoint;
  std::string name = fileName + ":" + entry;
  if (!ParseTarget(opt.target, &stage))
    throw CompileError("Compile", name, {{fileName, 0, "unknown target '" + opt.target + "' (use vs_5_0, ps_5_0 or cs_5_0)"}}, "");
  std::string source(sourceView);

  fs::path cacheDir = opt.cacheDir.empty() ? DefaultCacheDir() : opt.cacheDir;
  std::string key = CacheKey(source, fileName, opt, entry);
  if (opt.useCache) {
    if (std::optional<ShaderBytecode> hit = CacheLoad(cacheDir, key)) return *hit;
  }

  std::lock_guard lock(gCompileMutex);
  Includer includer(fs::path(fileName).parent_path(), opt.includeDirs);
  std::vector<uint32_t> spirv = RunGlslang(source, fileName, opt, stage, entry, includer);
  DropBiasFromGathers(spirv);
  FixAtomicOperandTypes(spirv);
  // Before legalisation: a UAV used only through IncrementCounter/DecrementCounter is removed as
  // dead code there, and with it the decoration that ties its counter to its register.
  RemapCounterBindings(spirv, vkbind::kUnorderedAccess, vkbind::kUavCounter);
  spirv = Legalize(spirv, name);
  LowerDotAndMatrixProducts(spirv);
  ConstOffsetsFromConstants(spirv);
  ShiftUnshiftedTextureBindings(spirv, vkbind::kShaderResource);
  SetFormatOfReadImages(spirv);
  Validate(spirv, fileName, name);

  ShaderBytecode b;
  b.stage = stage;
  b.sourceName = name;
  b.reflection = Reflect(spirv, stage, entry, name);
  b.spirv = StripHlslDecorations(spirv, name);
  Validate(b.spirv, fileName, name);
  GlslOutput glsl = CrossCompileToGlsl(b.spirv, b.reflection, name);
  b.glsl = std::move(glsl.glsl);
  detail::SetGlBindings(b, std::move(glsl.bindings));
  CacheCountMiss();
  if (opt.useCache) CacheStore(cacheDir, key, b, includer.deps());
  return b;
}

ShaderBytecode CompileFile(const fs::path& file, const CompileOptions& opt) {
  std::string source;
  if (!ReadFile(file, &source)) {
    std::string msg = "cannot open the file";
    throw CompileError("CompileFile", file.string(), {{file.string(), 0, msg}}, msg);
  }
  return CompileSource(source, file.string(), opt);
}

}  // namespace sp::hlsl
