// Effect::Load: preprocess, read the effect blocks, compile each pass's shaders. A
// CompileShader(ps_5_0, PS(true)) passes literals to PS's `uniform` parameters; glslang has no
// such thing, so a generated entry point calls PS with them.
#include <fstream>
#include <map>
#include <sstream>

#include "effect-parse.h"
#include "hlsl/toolchain.h"

namespace sp::fx {
namespace {

using hlsl::CompileError;
using hlsl::compat::Source;

[[noreturn]] void FailAt(const SourceLocation& loc, const std::string& message) {
  throw CompileError("Effect::Load", loc.ToString(), {{loc.file, loc.line, message}}, message);
}

struct Param {
  std::string text, name;
  bool uniform = false;
};

struct Signature {
  std::string attributes, returnType, semantic;
  std::vector<Param> params;
};

// The definition of `function` in the preprocessed source (overloads are refused: which one
// CompileShader means would depend on argument types).
Signature FindSignature(const Source& s, const std::string& function, const SourceLocation& use) {
  std::vector<size_t> defs;
  for (size_t i = 0; i < s.size(); ++i) {
    if (!s[i].Is(function) || !s.Is(i + 1, "(")) continue;
    size_t close = s.Matching(i + 1);
    if (close >= s.size()) continue;
    size_t j = close + 1;
    if (s.Is(j, ":") && j + 1 < s.size() && s[j + 1].IsIdentifier()) j += 2;
    if (s.Is(j, "{")) defs.push_back(i);
  }
  if (defs.empty()) FailAt(use, "CompileShader: no function '" + function + "' is defined");
  if (defs.size() > 1)
    FailAt(use, "CompileShader: '" + function + "' is overloaded (defined at " + s.FileOf(defs[0]) + ":" + std::to_string(s[defs[0]].line) +
                    " and " + std::to_string(s[defs[1]].line) + "); give the uniform overload its own name");
  size_t i = defs[0];
  Signature sig;
  // The return type runs back to the previous statement or attribute.
  size_t r = i;
  while (r > 0) {
    const auto& t = s[r - 1];
    if (t.kind == hlsl::compat::TokenKind::Directive || t.Is(";") || t.Is("}") || t.Is("]") || t.Is("{")) break;
    --r;
  }
  sig.returnType = s.Text(r, i);
  size_t a = r;
  while (a > 0 && s[a - 1].Is("]")) {
    size_t open = s.MatchingOpen(a - 1);
    if (open >= s.size()) break;
    a = open;
  }
  sig.attributes = s.Text(a, r);
  size_t close = s.Matching(i + 1);
  if (s.Is(close + 1, ":")) sig.semantic = ": " + s[close + 2].text;
  for (auto [p0, p1] : s.SplitCommas(i + 2, close)) {
    Param p;
    p.text = s.Text(p0, p1);
    size_t nameEnd = p1;
    for (size_t k = p0; k < p1; ++k) {
      if (s[k].Is("uniform")) p.uniform = true;
      if ((s[k].Is(":") || s[k].Is("=") || s[k].Is("[")) && nameEnd == p1) nameEnd = k;
    }
    if (nameEnd > p0 && s[nameEnd - 1].IsIdentifier()) p.name = s[nameEnd - 1].text;
    if (p.name.empty() || p.text == "void") continue;
    sig.params.push_back(p);
  }
  return sig;
}

class Loader {
 public:
  Loader(std::string source, std::string fileName, const EffectOptions& opt)
      : source_(std::move(source)), fileName_(std::move(fileName)), opt_(opt) {}

  void Run(std::vector<StateObjectDesc>& states, std::vector<detail::ParsedTechnique>& techniques) {
    hlsl::CompileOptions pre;
    pre.defines = opt_.defines;
    pre.includeDirs = opt_.includeDirs;
    pre.flags1 = opt_.flags1;
    preprocessed_ = std::make_unique<Source>(hlsl::PreprocessOnly(source_, fileName_, pre), fileName_);
    detail::ParsedEffect parsed;
    try {
      parsed = detail::ParseEffect(*preprocessed_);
    } catch (const hlsl::compat::RewriteError& e) {
      throw CompileError("Effect::Load", fileName_, {{e.file, e.line, e.what()}}, e.what());
    }
    states = std::move(parsed.states);
    techniques = std::move(parsed.techniques);
    for (detail::ParsedTechnique& t : techniques)
      for (detail::ParsedPass& p : t.passes)
        for (std::optional<ShaderDesc>& sh : p.desc.shaders)
          if (sh && !sh->isNull) Compile(*sh);
  }

 private:
  void Compile(ShaderDesc& d) {
    std::string key = d.target + "|" + d.function + "(";
    for (const std::string& a : d.arguments) key += a + ",";
    auto hit = done_.find(key);
    if (hit != done_.end()) {
      d.entryPoint = hit->second.entryPoint;
      d.bytecode = hit->second.bytecode;
      d.error = hit->second.error;
      return;
    }
    std::string source = source_;
    d.entryPoint = d.function;
    if (!d.arguments.empty()) {
      Signature sig = FindSignature(*preprocessed_, d.function, d.location);
      size_t uniforms = 0;
      for (const Param& p : sig.params) uniforms += p.uniform;
      if (uniforms != d.arguments.size())
        FailAt(d.location, "CompileShader: " + d.function + " has " + std::to_string(uniforms) + " uniform parameter" +
                               (uniforms == 1 ? "" : "s") + ", given " + std::to_string(d.arguments.size()) + " argument" +
                               (d.arguments.size() == 1 ? "" : "s"));
      d.entryPoint = "sp_fx_" + d.function + "_" + std::to_string(wrappers_++);
      std::string params, call;
      size_t arg = 0;
      for (const Param& p : sig.params) {
        if (p.uniform) {
          call += (call.empty() ? "" : ", ") + std::string("(") + d.arguments[arg++] + ")";
        } else {
          params += (params.empty() ? "" : ", ") + p.text;
          call += (call.empty() ? "" : ", ") + p.name;
        }
      }
      bool isVoid = sig.returnType.find("void") != std::string::npos;
      // The wrapper is reported at the CompileShader that asked for it.
      source += "\n#line " + std::to_string(d.location.line) + " \"" + d.location.file + "\"\n" + sig.attributes + " " + sig.returnType +
                " " + d.entryPoint + "(" + params + ") " + sig.semantic + " { " + (isVoid ? "" : "return ") + d.function + "(" + call +
                "); }\n";
    }
    hlsl::CompileOptions co;
    co.target = d.target;
    co.entryPoint = d.entryPoint;
    co.defines = opt_.defines;
    co.includeDirs = opt_.includeDirs;
    co.flags1 = opt_.flags1;
    co.cacheDir = opt_.cacheDir;
    try {
      d.bytecode = hlsl::CompileSource(source, fileName_, co);
    } catch (const CompileError& e) {
      if (opt_.failOnCompileError) throw;
      d.error = e.what();
    }
    done_[key] = d;
  }

  std::string source_, fileName_;
  EffectOptions opt_;
  std::unique_ptr<Source> preprocessed_;
  std::map<std::string, ShaderDesc> done_;
  int wrappers_ = 0;
};

}  // namespace

std::unique_ptr<Effect> Effect::LoadFromSource(std::string_view source, const std::string& fileName, const EffectOptions& options) {
  std::unique_ptr<Effect> fx(new Effect);
  fx->fileName_ = fileName;
  std::vector<detail::ParsedTechnique> techniques;
  Loader(std::string(source), fileName, options).Run(fx->states_, techniques);
  for (detail::ParsedTechnique& t : techniques) {
    auto tech = std::make_unique<EffectTechnique>();
    tech->name_ = t.name;
    tech->group_ = t.group;
    tech->location_ = t.location;
    for (detail::ParsedPass& p : t.passes) {
      auto pass = std::make_unique<EffectPass>();
      pass->effect_ = fx.get();
      pass->desc_ = std::move(p.desc);
      // The effect's samplers at the registers each stage's shader uses them.
      for (const std::optional<ShaderDesc>& sh : pass->desc_.shaders) {
        if (!sh || sh->isNull || sh->bytecode.empty()) continue;
        for (const ShaderResourceBinding& r : sh->bytecode.reflection.resources) {
          if (r.registerClass != RegisterClass::Sampler) continue;
          for (size_t k = 0; k < fx->states_.size(); ++k) {
            const StateObjectDesc& st = fx->states_[k];
            if ((st.type == StateType::Sampler || st.type == StateType::SamplerComparison) && st.name == r.name) {
              pass->desc_.samplers.push_back({sh->stage, r.registerIndex, st.name});
              pass->samplerStates_.push_back(k);
            }
          }
        }
      }
      tech->passes_.push_back(std::move(pass));
    }
    fx->techniques_.push_back(std::move(tech));
  }
  return fx;
}

std::unique_ptr<Effect> Effect::Load(const std::filesystem::path& file, const EffectOptions& options) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    std::string msg = "cannot open the file";
    throw CompileError("Effect::Load", file.string(), {{file.string(), 0, msg}}, msg);
  }
  std::stringstream ss;
  ss << in.rdbuf();
  return LoadFromSource(ss.str(), file.string(), options);
}

}  // namespace sp::fx
