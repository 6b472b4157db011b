// HLSL -> SPIR-V -> (legalised, validated) -> reflection -> GLSL. See sp/hlsl/compiler.h.
#include <glslang/Include/intermediate.h>
#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>
#include <glslang/build_info.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <fstream>
#include <mutex>
#include <regex>
#include <set>
#include <spirv-tools/libspirv.hpp>
#include <spirv-tools/optimizer.hpp>
#include <sstream>

#include "cache.h"
#include "compat/compat.h"
#include "isolated-run.h"
#include "spirv-edit.h"
#include "toolchain.h"

namespace sp::hlsl {
namespace fs = std::filesystem;

std::string FormatDiagnostics(const std::vector<Diagnostic>& d, const char* severity) {
  std::string s;
  for (size_t i = 0; i < d.size(); ++i) {
    if (i) s += "\n";
    s += d[i].file;
    if (d[i].line) s += ":" + std::to_string(d[i].line);
    s += std::string(": ") + severity + ": " + d[i].message;
  }
  return s;
}

CompileError::CompileError(std::string call, std::string object, std::vector<Diagnostic> diagnostics, std::string log)
    : Error(ErrorId::SHADER_COMPILE_FAILED, std::move(call), std::move(object),
            diagnostics.empty() ? log : FormatDiagnostics(diagnostics, "error")),
      diagnostics_(std::move(diagnostics)),
      log_(std::move(log)) {}

namespace {
struct TargetName {
  const char* name;
  ShaderStage stage;
};
// Shader Model 4 targets compile as their 5.0 twin: SPIR-V has no lower feature level to map to.
constexpr TargetName kTargets[] = {
    {"vs_4_0", ShaderStage::Vertex},  {"vs_4_1", ShaderStage::Vertex},   {"vs_5_0", ShaderStage::Vertex},
    {"ps_4_0", ShaderStage::Pixel},   {"ps_4_1", ShaderStage::Pixel},    {"ps_5_0", ShaderStage::Pixel},
    {"cs_4_0", ShaderStage::Compute}, {"cs_4_1", ShaderStage::Compute},  {"cs_5_0", ShaderStage::Compute},
    {"gs_4_0", ShaderStage::Geometry}, {"gs_4_1", ShaderStage::Geometry}, {"gs_5_0", ShaderStage::Geometry},
};
}  // namespace

bool ParseTarget(std::string_view target, ShaderStage* stage) {
  for (const TargetName& t : kTargets)
    if (target == t.name) {
      *stage = t.stage;
      return true;
    }
  return false;
}

const char* ValidTargets() {
  return "vs_4_0, vs_4_1, vs_5_0, ps_4_0, ps_4_1, ps_5_0, cs_4_0, cs_4_1, cs_5_0, gs_4_0, gs_4_1, gs_5_0";
}

static std::string UnknownTargetMessage(const std::string& target) {
  std::string msg = "unknown target '" + target + "' (valid: " + ValidTargets() + ")";
  if (target.size() > 3 && target[2] == '_' && target[3] >= '1' && target[3] <= '3')
    msg += "; Shader Model 3 and older are Direct3D 9 targets";
  else if (target.size() > 3 && target[2] == '_' && target[3] == '6')
    msg += "; Shader Model 6 (DXIL) is not supported";
  else if (target.rfind("hs_", 0) == 0 || target.rfind("ds_", 0) == 0)
    msg += "; hull and domain shaders are not supported";
  else if (target.rfind("lib_", 0) == 0 || target.rfind("fx_", 0) == 0 || target.rfind("tx_", 0) == 0)
    msg += "; libraries, effects and texture shaders are not supported";
  return msg;
}

// "" when `flags` is a valid combination of COMPILE_* bits, else why not.
std::string CheckCompileFlags(uint32_t flags) {
  if (flags & ~kKnownCompileFlags) {
    char hex[16];
    std::snprintf(hex, sizeof hex, "0x%x", flags & ~kKnownCompileFlags);
    return std::string("unknown compile flags ") + hex + " (flags1 takes the COMPILE_* values, D3DCOMPILE_* of fxc)";
  }
  if ((flags & COMPILE_PACK_MATRIX_ROW_MAJOR) && (flags & COMPILE_PACK_MATRIX_COLUMN_MAJOR))
    return "COMPILE_PACK_MATRIX_ROW_MAJOR (-Zpr) and COMPILE_PACK_MATRIX_COLUMN_MAJOR (-Zpc) exclude each other";
  if ((flags & COMPILE_AVOID_FLOW_CONTROL) && (flags & COMPILE_PREFER_FLOW_CONTROL))
    return "COMPILE_AVOID_FLOW_CONTROL (-Gfa) and COMPILE_PREFER_FLOW_CONTROL (-Gfp) exclude each other";
  return {};
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

// D3D shaders come from Windows: `#include "..\Shared\Common.hlsl"` with backslashes, and names
// whose case differs from the file's. A path that does not exist as written is looked up again
// with '/' separators and, component by component, ignoring case (the first match in directory
// order when several names differ only in case).
fs::path WindowsPath(const fs::path& written) {
  std::error_code ec;
  if (fs::exists(written, ec)) return written;
  std::string s = written.string();
  std::replace(s.begin(), s.end(), '\\', '/');
  fs::path p(s);
  if (fs::exists(p, ec)) return p;
  fs::path resolved = p.is_absolute() ? p.root_path() : fs::path();
  for (const fs::path& part : p.relative_path()) {
    fs::path next = resolved / part;
    if (part == "." || part == ".." || fs::exists(next, ec)) {
      resolved = next;
      continue;
    }
    std::string want = part.string();
    bool found = false;
    for (const fs::directory_entry& e : fs::directory_iterator(resolved.empty() ? fs::path(".") : resolved, ec)) {
      std::string name = e.path().filename().string();
      if (name.size() == want.size() &&
          std::equal(name.begin(), name.end(), want.begin(), [](char a, char b) { return std::tolower(a) == std::tolower(b); })) {
        resolved /= name;
        found = true;
        break;
      }
    }
    if (!found) return written;
  }
  return resolved;
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
  IncludeResult* TryOpen(const fs::path& asWritten) {
    fs::path p = WindowsPath(asWritten);
    std::string* content = new std::string;
    if (!ReadFile(p, content)) {
      delete content;
      return nullptr;
    }
    std::string name = p.lexically_normal().string();
    std::string absolute = fs::absolute(p).lexically_normal().string();
    deps_.push_back({absolute, Hash64(content->data(), content->size())});
    // fxc honours `#pragma once`; glslang's preprocessor passes it through and includes the file
    // again ("function already has a body"). A second include of such a file is empty.
    static const std::regex once(R"((^|\n)[ \t]*#[ \t]*pragma[ \t]+once\b)");
    if (std::regex_search(*content, once) && !onceFiles_.insert(absolute).second) content->clear();
    return new IncludeResult(name, content->data(), content->size(), content);
  }
  fs::path mainDir_;
  std::vector<fs::path> dirs_;
  std::vector<Dependency> deps_;
  std::set<std::string> onceFiles_;
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

// "WARNING: path/file.hlsl:12: 'foobar' : unrecognized attribute" -> {path/file.hlsl, 12, ...}.
// glslang also warns that fxc's hint attributes [fastopt] and [allow_uav_condition] (loops) and
// [forcecase] and [call] (switches) "do not apply"; fxc accepts them, so those are dropped
// rather than failing valid D3D code under -WX.
std::vector<Diagnostic> ParseGlslangWarnings(const std::string& log, const std::string& defaultFile) {
  std::vector<Diagnostic> out;
  static const std::regex withLine(R"(^WARNING: (.+?):(\d+): (.*?)\s*$)");
  static const std::regex noLine(R"(^WARNING: (.*?)\s*$)");
  std::istringstream in(log);
  std::string line;
  while (std::getline(in, line)) {
    std::smatch m;
    Diagnostic d;
    if (std::regex_match(line, m, withLine)) d = {m[1].str(), std::stoi(m[2].str()), m[3].str()};
    else if (std::regex_match(line, m, noLine)) d = {defaultFile, 0, m[1].str()};
    else continue;
    if (d.message.find("attribute does not apply to a loop") != std::string::npos ||
        d.message.find("attribute does not apply to a switch") != std::string::npos ||
        // glslang's own words for the pragma, which the Includer honours
        d.message.find("'#pragma once' : not implemented") != std::string::npos)
      continue;
    out.push_back(std::move(d));
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

// Settings shared by the preprocessing and the parsing run of glslang.
void ConfigureShader(glslang::TShader& shader, ShaderStage stage, const std::string& entry) {
  EShLanguage lang = LanguageOf(stage);
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
}

constexpr auto kMessages = EShMessages(EShMsgSpvRules | EShMsgVulkanRules | EShMsgReadHlsl | EShMsgHlslOffsets);

}  // namespace

// glslang's preprocessor alone (defines, includes), with #line directives naming the user's files.
static std::string RunPreprocessor(const std::string& source, const std::string& fileName, const CompileOptions& opt,
                                   ShaderStage stage, const std::string& entry, glslang::TShader::Includer& includer) {
  std::call_once(gInitOnce, [] { glslang::InitializeProcess(); });
  glslang::TShader shader(LanguageOf(stage));
  const char* src = source.c_str();
  const char* name = fileName.c_str();
  int len = int(source.size());
  shader.setStringsWithLengthsAndNames(&src, &len, &name, 1);
  std::string preamble;
  for (const Define& d : opt.defines) preamble += "#define " + d.name + " " + (d.value.empty() ? std::string("1") : d.value) + "\n";
  shader.setPreamble(preamble.c_str());
  ConfigureShader(shader, stage, entry);
  std::string out;
  if (!shader.preprocess(GetDefaultResources(), 100, ENoProfile, false, false, kMessages, &out, includer)) {
    std::string log = std::string(shader.getInfoLog()) + shader.getInfoDebugLog();
    throw CompileError("glslang (preprocessor)", fileName + ":" + entry, ParseGlslangLog(log, fileName), log);
  }
  return out;
}

// glslang's preprocessor (defines, includes, -Zpr/-Zpc), then the D3D11 compatibility rewrites:
// the text glslang's parser is given, with #line directives naming the user's files.
static compat::Result PreprocessWithRewrites(const std::string& source, const std::string& fileName, const CompileOptions& opt,
                                      ShaderStage stage, const std::string& entry, glslang::TShader::Includer& includer) {
  std::string out = RunPreprocessor(source, fileName, opt, stage, entry, includer);
  // fxc's -Zpr/-Zpc set the packing of matrices declared without row_major/column_major; the
  // pragma does the same in glslang (and a pack_matrix pragma in the source still wins after it).
  // It goes before the preprocessed text, not into the preamble, whose pragmas the preprocessor
  // prints without a line break before the source's first line.
  std::string pragmas;
  if (opt.flags1 & COMPILE_PACK_MATRIX_ROW_MAJOR) pragmas = "#pragma pack_matrix(row_major)\n";
  if (opt.flags1 & COMPILE_PACK_MATRIX_COLUMN_MAJOR) pragmas = "#pragma pack_matrix(column_major)\n";
  try {
    compat::Result r = compat::Apply(out, fileName, entry);
    if (!pragmas.empty()) r.source = pragmas + "#line 1 \"" + fileName + "\"\n" + r.source;
    return r;
  } catch (const compat::RewriteError& e) {
    throw CompileError("D3D11 compatibility pass", fileName + ":" + entry, {{e.file, e.line, e.what()}}, e.what());
  }
}

namespace {

// What glslang's parser, linker and SPIR-V generator make of a preprocessed source.
struct ParseOutcome {
  std::string failedCall;               // empty on success, else the step that failed ("glslang (link)")
  std::vector<Diagnostic> diagnostics;  // the errors, or on success the warnings
  std::string log;
  std::vector<uint32_t> spirv;
};

ParseOutcome ParseToSpirv(const std::string& source, const std::string& fileName, ShaderStage stage, const std::string& entry,
                          Includer& includer) {
  ParseOutcome o;
  EShLanguage lang = LanguageOf(stage);
  glslang::TShader shader(lang);
  const char* src = source.c_str();
  const char* name = fileName.c_str();
  int len = int(source.size());
  shader.setStringsWithLengthsAndNames(&src, &len, &name, 1);
  ConfigureShader(shader, stage, entry);
  auto messages = kMessages;

  if (!shader.parse(GetDefaultResources(), 100, ENoProfile, false, false, messages, includer)) {
    o.log = std::string(shader.getInfoLog()) + shader.getInfoDebugLog();
    o.failedCall = "glslang", o.diagnostics = ParseGlslangLog(o.log, fileName);
    return o;
  }
  o.diagnostics = ParseGlslangWarnings(std::string(shader.getInfoLog()), fileName);
  glslang::TProgram program;
  program.addShader(&shader);
  if (!program.link(messages) || !program.mapIO()) {
    o.log = program.getInfoLog();
    o.failedCall = "glslang (link)", o.diagnostics = ParseGlslangLog(o.log, fileName);
    return o;
  }
  UnconnectedInputs unconnected(entry + "(");
  program.getIntermediate(lang)->getTreeRoot()->traverse(&unconnected);
  if (!unconnected.names.empty()) {
    o.log = "glslang does not connect the entry-point input '" + unconnected.names[0] +
            "' (it would read an undefined value); declare it as a member of an input struct instead";
    o.failedCall = "glslang", o.diagnostics = {{fileName, 0, o.log}};
    return o;
  }
  glslang::SpvOptions spvOptions;
  spvOptions.disableOptimizer = true;  // we run spirv-opt ourselves, with known passes
  spvOptions.validate = false;
  spv::SpvBuildLogger logger;
  glslang::GlslangToSpv(*program.getIntermediate(lang), o.spirv, &logger, &spvOptions);
  std::string msgs = logger.getAllMessages();
  if (msgs.find("error") != std::string::npos || msgs.find("Missing functionality") != std::string::npos) {
    // glslang exits 0 but writes invalid SPIR-V for HLSL features it cannot translate; report them.
    o.log = msgs;
    o.failedCall = "glslang (SPIR-V)", o.diagnostics = {{fileName, 0, msgs}};
  }
  return o;
}

std::string Serialize(const ParseOutcome& o) {
  std::string out;
  isolation::PutString(out, o.failedCall);
  isolation::PutString(out, o.log);
  isolation::PutU32(out, uint32_t(o.diagnostics.size()));
  for (const Diagnostic& d : o.diagnostics) {
    isolation::PutString(out, d.file);
    isolation::PutU32(out, uint32_t(d.line));
    isolation::PutString(out, d.message);
  }
  isolation::PutString(out, o.spirv.empty() ? std::string() : std::string(reinterpret_cast<const char*>(o.spirv.data()), o.spirv.size() * 4));
  return out;
}

bool Deserialize(const std::string& bytes, ParseOutcome* o) {
  isolation::ByteReader r(bytes);
  o->failedCall = r.String();
  o->log = r.String();
  uint32_t n = r.U32();
  for (uint32_t i = 0; i < n && r.ok(); ++i) {
    Diagnostic d;
    d.file = r.String();
    d.line = int(r.U32());
    d.message = r.String();
    o->diagnostics.push_back(std::move(d));
  }
  std::string words = r.String();
  if (!r.ok() || words.size() % 4) return false;
  o->spirv.resize(words.size() / 4);
  if (!words.empty()) std::memcpy(o->spirv.data(), words.data(), words.size());  // data() of an empty vector may be null
  return true;
}

// A source takes glslang well under a second; a sanitizer build a few. More is a hang.
constexpr unsigned kParserTimeoutSeconds = 120;

// Where glslang crashed: the crash happens while it parses one line, and any prefix of the text
// that includes that line ends in a crash too (a prefix cut after it only adds an error at its
// end, after the crash). So the shortest crashing prefix of whole lines, found by bisection (a
// dozen parses for a thousand lines), ends at that line; the #line directives of the
// preprocessed text give it back in the user's file. {"", 0} when it cannot be found.
Diagnostic LocateParserCrash(const std::string& text, const std::string& fileName, ShaderStage stage, const std::string& entry,
                             Includer& includer) {
  std::vector<size_t> lineEnds;  // byte offset one past each line
  for (size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n') lineEnds.push_back(i + 1);
  if (lineEnds.empty() || lineEnds.back() != text.size()) lineEnds.push_back(text.size());
  auto crashes = [&](size_t lines) {
    std::string prefix = text.substr(0, lineEnds[lines - 1]);
    isolation::IsolatedResult r =
        isolation::RunIsolated([&] { return Serialize(ParseToSpirv(prefix, fileName, stage, entry, includer)); }, kParserTimeoutSeconds);
    return r.signal != 0 && !r.timedOut;
  };
  size_t lo = 0, hi = lineEnds.size();  // the first lo lines do not crash it; the first hi do
  if (!crashes(hi)) return {"", 0, ""};
  while (hi - lo > 1) {
    size_t mid = (lo + hi) / 2;
    (crashes(mid) ? hi : lo) = mid;
  }
  // Line hi of the text, in the user's terms: `#line N "file"` makes the next line N of file.
  Diagnostic d{fileName, 0, ""};
  int line = 0;
  size_t start = 0;
  for (size_t k = 0; k < hi; ++k) {
    std::string l = text.substr(start, lineEnds[k] - start);
    start = lineEnds[k];
    ++line;
    std::smatch m;
    static const std::regex kLine(R"re(^\s*#\s*line\s+(\d+)(?:\s+"([^"]*)")?)re");
    if (k + 1 < hi && std::regex_search(l, m, kLine)) {
      line = std::stoi(m[1]) - 1;
      if (m[2].matched) d.file = m[2];
    }
  }
  d.line = line;
  return d;
}

std::vector<uint32_t> RunGlslang(const std::string& source, const std::string& fileName, const CompileOptions& opt, ShaderStage stage,
                                 const std::string& entry, Includer& includer, std::vector<Diagnostic>* warnings) {
  // The preprocessor and the rewrites run here: the includer records the files read (the cache's
  // dependencies), which a child could not hand back.
  compat::Result pre = PreprocessWithRewrites(source, fileName, opt, stage, entry, includer);
  // glslang's parser crashes on some invalid HLSL (a global declaration list that goes on with a
  // struct type, `float4 a, S b;`, segfaults glslang 11 in growGlobalUniformBlock: found by
  // fuzz/fx-effect-fuzz.cpp), so it runs in a child process; see isolated-run.h.
  const std::string object = fileName + ":" + entry;
  isolation::IsolatedResult r =
      isolation::RunIsolated([&] { return Serialize(ParseToSpirv(pre.source, fileName, stage, entry, includer)); }, kParserTimeoutSeconds);
  ParseOutcome o;
  if (!r.completed || !Deserialize(r.bytes, &o)) {
    Diagnostic where{fileName, 0, ""};
    if (r.signal != 0 && !r.timedOut) where = LocateParserCrash(pre.source, fileName, stage, entry, includer);
    if (where.file.empty()) where.file = fileName;
    where.message = "the HLSL parser (glslang) " + (r.failure.empty() ? std::string("sent back a malformed result") : r.failure) +
                    (where.line ? " on this line" : " on this source") +
                    " instead of reporting an error. glslang does not validate HLSL, so this is most likely a syntax error it "
                    "does not catch: check the line, or compile it with fxc to have it named";
    throw CompileError("glslang", object, {where}, r.failure);
  }
  if (!o.failedCall.empty()) throw CompileError(o.failedCall, object, std::move(o.diagnostics), o.log);
  *warnings = std::move(o.diagnostics);
  return std::move(o.spirv);
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

// `beforeLegalization`: glslang's raw output, which may still keep resources in locals and the
// like (spirv-val's --before-hlsl-legalization). spirv-opt assumes valid input and can crash on
// what glslang sometimes emits, so its input is checked too, against SPIR-V's core rules only:
// Vulkan's rules (image formats for atomics, ...) are met by the edits after legalisation.
void Validate(const std::vector<uint32_t>& spirv, const std::string& fileName, const std::string& name,
              bool beforeLegalization = false) {
  ToolMessages log;
  spvtools::SpirvTools tools(beforeLegalization ? SPV_ENV_UNIVERSAL_1_3 : SPV_ENV_VULKAN_1_1);
  tools.SetMessageConsumer([&log](spv_message_level_t l, const char* s, const spv_position_t& p, const char* m) { log(l, s, p, m); });
  spvtools::ValidatorOptions vo;
  vo.SetBeforeHlslLegalization(beforeLegalization);
  vo.SetRelaxBlockLayout(true);  // HLSL packing (float3 after float) is legal under Vulkan 1.1's relaxed layout
  if (!tools.Validate(spirv.data(), spirv.size(), vo)) {
    std::string msg = "the generated SPIR-V is invalid (a glslang limitation with this HLSL construct): " + log.text;
    throw CompileError("spirv-val", name, {{fileName, 0, msg}}, log.text);
  }
}

// SM4 targets share their SM5 twin's entries (same compilation); only the flags that change
// the output are part of the key (-WX does not: warnings are stored with each entry).
std::string CacheKey(const std::string& source, const std::string& fileName, const CompileOptions& opt, ShaderStage stage,
                     const std::string& entry) {
  std::string k = std::string(kToolchainRevision) + "|glslang " + std::to_string(GLSLANG_VERSION_MAJOR) + "." +
                  std::to_string(GLSLANG_VERSION_MINOR) + "." + std::to_string(GLSLANG_VERSION_PATCH) + "|" +
                  ShaderStagePrefix(stage) + "|" + entry + "|" + fs::absolute(fileName).lexically_normal().string();
  k += "|F" + std::to_string(opt.flags1 & kSemanticCompileFlags);
  for (const Define& d : opt.defines) k += "|D" + d.name + "=" + d.value;
  for (const fs::path& p : opt.includeDirs) k += "|I" + fs::absolute(p).lexically_normal().string();
  uint64_t h = Hash64(k.data(), k.size());
  h = Hash64(source.data(), source.size(), h);
  return HexHash(h);
}

// Hands the warnings to the caller, or fails the compile with them under -WX.
void DeliverWarnings(const std::vector<Diagnostic>& found, const CompileOptions& opt, const std::string& name,
                     std::vector<Diagnostic>* out) {
  if (!found.empty() && (opt.flags1 & COMPILE_WARNINGS_ARE_ERRORS)) {
    std::vector<Diagnostic> errors = found;
    for (Diagnostic& d : errors) d.message += " (a warning, treated as an error: COMPILE_WARNINGS_ARE_ERRORS / -WX)";
    throw CompileError("glslang", name, errors, FormatDiagnostics(found, "warning"));
  }
  if (out) *out = found;
}

}  // namespace

ShaderBytecode CompileSource(std::string_view sourceView, const std::string& fileName, const CompileOptions& opt,
                             std::vector<Diagnostic>* warnings) {
  ShaderStage stage;
  std::string entry = opt.entryPoint.empty() ? "main" : opt.entryPoint;
  std::string name = fileName + ":" + entry;
  if (warnings) warnings->clear();
  if (!ParseTarget(opt.target, &stage)) throw CompileError("Compile", name, {{fileName, 0, UnknownTargetMessage(opt.target)}}, "");
  if (std::string bad = CheckCompileFlags(opt.flags1); !bad.empty()) throw CompileError("Compile", name, {{fileName, 0, bad}}, "");
  std::string source(sourceView);

  fs::path cacheDir = opt.cacheDir.empty() ? DefaultCacheDir() : opt.cacheDir;
  std::string key = CacheKey(source, fileName, opt, stage, entry);
  if (opt.useCache) {
    std::optional<CachedShader> hit = cacheDir.empty() ? MemoryCacheLoad(key) : CacheLoad(cacheDir, key);
    if (hit) {
      DeliverWarnings(hit->warnings, opt, name, warnings);
      return std::move(hit->bytecode);
    }
  }

  std::lock_guard lock(gCompileMutex);
  Includer includer(fs::path(fileName).parent_path(), opt.includeDirs);
  CachedShader result;
  std::vector<uint32_t> spirv = RunGlslang(source, fileName, opt, stage, entry, includer, &result.warnings);
  DeliverWarnings(result.warnings, opt, name, nullptr);
  DropBiasFromGathers(spirv);
  FixAtomicOperandTypes(spirv);
  // Before legalisation: a UAV used only through IncrementCounter/DecrementCounter is removed as
  // dead code there, and with it the decoration that ties its counter to its register.
  RemapCounterBindings(spirv, vkbind::kUnorderedAccess, vkbind::kUavCounter);
  SplitMatrixIntrinsics(spirv);
  Validate(spirv, fileName, name, true);
  spirv = Legalize(spirv, name);
  LowerDotAndMatrixProducts(spirv);
  ConstOffsetsFromConstants(spirv);
  ShiftUnshiftedTextureBindings(spirv, vkbind::kShaderResource);
  SetFormatOfReadImages(spirv);
  Validate(spirv, fileName, name);

  ShaderBytecode& b = result.bytecode;
  b.stage = stage;
  b.sourceName = name;
  b.reflection = Reflect(spirv, stage, entry, name);
  b.spirv = StripHlslDecorations(spirv, name);
  Validate(b.spirv, fileName, name);
  // Everything backend-specific, once per target (target-glsl.cpp, target-spirv.cpp).
  GlslOutput glsl = CrossCompileToGlsl(b.spirv, b.reflection, name);
  b.glsl = std::move(glsl.glsl);
  detail::TargetProducts targets;
  targets.gl = std::move(glsl.products);
  targets.spirv = MakeSpirvProducts(b.spirv, b.reflection, name);
  detail::SetTargets(b, std::move(targets));
  CacheCountMiss();
  if (opt.useCache) {
    if (cacheDir.empty()) MemoryCacheStore(key, result, includer.deps());
    else CacheStore(cacheDir, key, result, includer.deps());
  }
  if (warnings) *warnings = result.warnings;
  return std::move(result.bytecode);
}

std::string Preprocess(std::string_view source, const std::string& fileName, const CompileOptions& opt,
                       std::vector<std::string>* rewritesApplied) {
  ShaderStage stage = ShaderStage::Pixel;
  if (!opt.target.empty() && !ParseTarget(opt.target, &stage))
    throw CompileError("Preprocess", fileName, {{fileName, 0, UnknownTargetMessage(opt.target)}}, "");
  std::lock_guard lock(gCompileMutex);
  Includer includer(fs::path(fileName).parent_path(), opt.includeDirs);
  compat::Result r = PreprocessWithRewrites(std::string(source), fileName, opt, stage, opt.entryPoint.empty() ? "main" : opt.entryPoint, includer);
  if (rewritesApplied) *rewritesApplied = r.applied;
  return r.source;
}

std::string PreprocessOnly(std::string_view source, const std::string& fileName, const CompileOptions& opt) {
  std::lock_guard lock(gCompileMutex);
  Includer includer(fs::path(fileName).parent_path(), opt.includeDirs);
  return RunPreprocessor(std::string(source), fileName, opt, ShaderStage::Pixel, "main", includer);
}

ShaderBytecode CompileFile(const fs::path& file, const CompileOptions& opt, std::vector<Diagnostic>* warnings) {
  std::string source;
  if (!ReadFile(file, &source)) {
    std::string msg = "cannot open the file";
    throw CompileError("CompileFile", file.string(), {{file.string(), 0, msg}}, msg);
  }
  return CompileSource(source, file.string(), opt, warnings);
}

// ---- D3DCompile's shape ----------------------------------------------------------------------

Blob::Blob(size_t size) : data_(new uint8_t[size ? size : 1]()), size_(size) {}

Blob* Blob::Create(const void* data, size_t size) {
  Blob* b = new Blob(size);
  if (data && size) std::memcpy(b->data_.get(), data, size);
  return b;
}

uint32_t Blob::AddRef() { return ++refs_; }

uint32_t Blob::Release() {
  uint32_t left = --refs_;
  if (left == 0) delete this;
  return left;
}

HRESULT CreateBlob(size_t size, Blob** blob) {
  if (!blob) return E_INVALIDARG;
  *blob = Blob::Create(nullptr, size);
  return S_OK;
}

namespace {

// fxc's error blobs are C strings whose size counts the terminator.
Blob* TextBlob(const std::string& text) { return Blob::Create(text.c_str(), text.size() + 1); }

HRESULT Refuse(HRESULT hr, const std::string& why, Blob** errors) {
  if (errors) *errors = TextBlob(why);
  return hr;
}

// The common part of Compile and CompileFromFile once the source is in memory.
HRESULT CompileToBlobs(std::string_view source, const std::string& fileName, const SHADER_MACRO* defines, Include* include,
                       const char* entry, const char* target, uint32_t flags1, Blob** code, Blob** errors) {
  if (include && include != COMPILE_STANDARD_FILE_INCLUDE)
    return Refuse(E_INVALIDARG,
                  fileName + ": error: include handlers (ID3DInclude) are not supported; pass nullptr or "
                             "COMPILE_STANDARD_FILE_INCLUDE, or CompileOptions::includeDirs to CompileSource",
                  errors);
  if (std::string bad = CheckCompileFlags(flags1); !bad.empty()) return Refuse(E_INVALIDARG, fileName + ": error: " + bad, errors);
  CompileOptions opt;
  opt.target = target;
  opt.entryPoint = entry ? entry : "";
  opt.flags1 = flags1;
  for (const SHADER_MACRO* m = defines; m && m->Name; ++m)
    // A lone space keeps `#define NAME` empty: Define's empty value would mean 1.
    opt.defines.push_back({m->Name, m->Definition && *m->Definition ? m->Definition : " "});
  std::vector<Diagnostic> warnings;
  try {
    ShaderBytecode b = CompileSource(source, fileName, opt, &warnings);
    std::vector<uint8_t> bytes = b.Serialize();
    *code = Blob::Create(bytes.data(), bytes.size());
    if (errors && !warnings.empty()) *errors = TextBlob(FormatDiagnostics(warnings, "warning"));
    return S_OK;
  } catch (const CompileError& e) {
    return Refuse(E_FAIL, e.diagnostics().empty() ? e.what() : FormatDiagnostics(e.diagnostics(), "error"), errors);
  } catch (const std::exception& e) {
    return Refuse(E_FAIL, fileName + ": error: " + e.what(), errors);
  }
}

}  // namespace

HRESULT Compile(const void* srcData, size_t srcDataSize, const char* sourceName, const SHADER_MACRO* defines, Include* include,
                const char* entrypoint, const char* target, uint32_t flags1, uint32_t /*flags2*/, Blob** code, Blob** errors) {
  if (code) *code = nullptr;
  if (errors) *errors = nullptr;
  std::string name = sourceName && *sourceName ? sourceName : "memory";
  if (!code) return Refuse(E_INVALIDARG, name + ": error: Compile: ppCode is null", errors);
  if (!srcData) return Refuse(E_INVALIDARG, name + ": error: Compile: pSrcData is null", errors);
  if (!target) return Refuse(E_INVALIDARG, name + ": error: Compile: pTarget is null", errors);
  return CompileToBlobs(std::string_view(static_cast<const char*>(srcData), srcDataSize), name, defines, include, entrypoint,
                        target, flags1, code, errors);
}

HRESULT CompileFromFile(const fs::path& fileName, const SHADER_MACRO* defines, Include* include, const char* entrypoint,
                        const char* target, uint32_t flags1, uint32_t /*flags2*/, Blob** code, Blob** errors) {
  if (code) *code = nullptr;
  if (errors) *errors = nullptr;
  std::string name = fileName.string();
  if (!code) return Refuse(E_INVALIDARG, name + ": error: CompileFromFile: ppCode is null", errors);
  if (!target) return Refuse(E_INVALIDARG, name + ": error: CompileFromFile: pTarget is null", errors);
  std::string source;
  if (!ReadFile(fileName, &source)) return Refuse(E_FAIL, name + ": error: cannot open the file", errors);
  return CompileToBlobs(source, name, defines, include, entrypoint, target, flags1, code, errors);
}

HRESULT X11CompileFromFile(const fs::path& srcFile, const SHADER_MACRO* defines, Include* include, const char* functionName,
                           const char* profile, uint32_t flags1, uint32_t flags2, X11ThreadPump* pump, Blob** shader,
                           Blob** errorMsgs, HRESULT* hresult) {
  HRESULT hr;
  if (pump) {
    if (shader) *shader = nullptr;
    hr = Refuse(E_INVALIDARG, srcFile.string() + ": error: X11CompileFromFile: pPump must be null (compilation is synchronous)",
                errorMsgs);
  } else {
    hr = CompileFromFile(srcFile, defines, include, functionName, profile, flags1, flags2, shader, errorMsgs);
  }
  if (hresult) *hresult = hr;
  return hr;
}

}  // namespace sp::hlsl
