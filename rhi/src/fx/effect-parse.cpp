// The effect-file grammar (FX11's documented syntax) over preprocessed tokens: techniques and
// groups, passes, state objects, shader variables and annotations. Shader code between them is
// skipped by bracket matching; only statements at file scope are looked at.
#include <algorithm>
#include <cctype>

#include "effect-parse.h"

namespace sp::fx::detail {
namespace {

using hlsl::compat::Source;
using hlsl::compat::TokenKind;

std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

struct StageName {
  const char* type;     // VertexShader (shader variables)
  const char* setter;   // SetVertexShader
  ShaderStage stage;
  bool supported;
};
constexpr StageName kStages[] = {
    {"VertexShader", "SetVertexShader", ShaderStage::Vertex, true},
    {"PixelShader", "SetPixelShader", ShaderStage::Pixel, true},
    {"GeometryShader", "SetGeometryShader", ShaderStage::Geometry, true},
    {"ComputeShader", "SetComputeShader", ShaderStage::Compute, true},
    {"HullShader", "SetHullShader", ShaderStage::Vertex, false},
    {"DomainShader", "SetDomainShader", ShaderStage::Vertex, false},
};

const StageName* StageOfType(const std::string& t) {
  for (const StageName& s : kStages)
    if (t == s.type) return &s;
  return nullptr;
}

class Parser {
 public:
  explicit Parser(const Source& s) : s_(s) {}

  ParsedEffect Run() {
    size_t i = 0;
    bool statementStart = true;
    while (i < s_.size()) {
      const auto& t = s_[i];
      if (t.kind == TokenKind::Directive) {
        ++i;
        continue;
      }
      if (statementStart && t.IsIdentifier()) {
        std::string lower = Lower(t.text);
        if (lower == "technique" || lower == "technique10" || lower == "technique11") {
          i = Technique(i, "");
          continue;
        }
        if (lower == "fxgroup") {
          i = Group(i);
          continue;
        }
        if ((t.Is("RasterizerState") || t.Is("DepthStencilState") || t.Is("BlendState")) && !s_.Is(i + 2, "(")) {
          i = StateObject(i);
          continue;
        }
        if (t.Is("SamplerState") || t.Is("SamplerComparisonState")) {
          i = Sampler(i);
          continue;
        }
        if (StageOfType(t.text) && i + 1 < s_.size() && s_[i + 1].IsIdentifier() && !s_.Is(i + 2, "(")) {
          i = ShaderVariableDecl(i);
          continue;
        }
      }
      // Annotations on shader variables (`float4 g_v < string UIName = "x"; > = 1;`) stay:
      // glslang's HLSL grammar accepts and ignores them.
      if (t.Is("{") || t.Is("(") || t.Is("[")) {
        size_t m = s_.Matching(i);
        if (m >= s_.size()) s_.Fail(i, "unbalanced '" + t.text + "'");
        // A function body or a struct/cbuffer ends a statement; a parenthesis does not.
        statementStart = t.Is("{");
        i = m + 1;
        // `struct S { ... } s;` and cbuffers continue after the brace.
        continue;
      }
      statementStart = t.Is(";") || t.Is("}");
      ++i;
    }
    return std::move(out_);
  }

 private:
  SourceLocation Loc(size_t i) const { return {s_.FileOf(std::min(i, s_.size() - 1)), s_[std::min(i, s_.size() - 1)].line}; }

  void Expect(size_t i, const char* what, const std::string& context) const {
    if (!s_.Is(i, what)) {
      std::string found = i < s_.size() ? "'" + s_[i].text + "'" : "the end of the file";
      s_.Fail(i, std::string("expected '") + what + "' " + context + ", found " + found);
    }
  }

  // The '>' closing an annotation opened at `open`, or size() when `open` does not start one.
  // Annotations hold `type name = value;` declarations (or nothing); template arguments
  // (Texture2D<float4>) never hold a ';'.
  size_t AnnotationEnd(size_t open) const {
    for (size_t j = open + 1; j < s_.size(); ++j) {
      const auto& t = s_[j];
      if (t.kind == TokenKind::Directive || t.Is("}")) return s_.size();
      if (t.Is("(") || t.Is("{")) {  // float4(...) and {1, 2} initialisers inside
        j = s_.Matching(j);
        if (j >= s_.size()) return s_.size();
        continue;
      }
      // Each annotation ends with ';', so the '>' after one closes the block.
      if (t.Is(">")) return j == open + 1 || s_[j - 1].Is(";") ? j : s_.size();
    }
    return s_.size();
  }

  // Skips an annotation at i, if any; returns the index after it.
  size_t SkipAnnotation(size_t i) const {
    if (!s_.Is(i, "<")) return i;
    size_t e = AnnotationEnd(i);
    if (e >= s_.size()) s_.Fail(i, "malformed annotation: expected '< type name = value; ... >'");
    return e + 1;
  }

  size_t Group(size_t start) {
    size_t i = start + 1;
    std::string name;
    if (i < s_.size() && s_[i].IsIdentifier()) name = s_[i++].text;
    i = SkipAnnotation(i);
    Expect(i, "{", "after fxgroup " + name);
    size_t close = s_.Matching(i);
    if (close >= s_.size()) s_.Fail(i, "fxgroup " + name + " has no closing '}'");
    for (size_t j = i + 1; j < close;) {
      if (s_[j].kind == TokenKind::Directive) {
        ++j;
        continue;
      }
      std::string lower = Lower(s_[j].text);
      if (lower == "technique" || lower == "technique10" || lower == "technique11") j = Technique(j, name, false);
      else s_.Fail(j, "expected a technique11 in fxgroup " + name + ", found '" + s_[j].text + "'");
    }
    size_t end = s_.Is(close + 1, ";") ? close + 1 : close;
    out_.hidden.push_back({start, end});
    return end + 1;
  }

  size_t Technique(size_t start, const std::string& group, bool hide = true) {
    ParsedTechnique tech;
    tech.group = group;
    tech.location = Loc(start);
    size_t i = start + 1;
    if (i < s_.size() && s_[i].IsIdentifier()) tech.name = s_[i++].text;
    i = SkipAnnotation(i);
    Expect(i, "{", "after " + s_[start].text + " " + tech.name);
    size_t close = s_.Matching(i);
    if (close >= s_.size()) s_.Fail(i, "technique " + tech.name + " has no closing '}'");
    for (size_t j = i + 1; j < close;) {
      if (s_[j].kind == TokenKind::Directive) {
        ++j;
        continue;
      }
      if (!s_[j].Is("pass")) s_.Fail(j, "expected 'pass' in technique " + tech.name + ", found '" + s_[j].text + "'");
      j = Pass(j, tech);
    }
    size_t end = s_.Is(close + 1, ";") ? close + 1 : close;
    if (hide) out_.hidden.push_back({start, end});
    out_.techniques.push_back(std::move(tech));
    return end + 1;
  }

  size_t Pass(size_t start, ParsedTechnique& tech) {
    ParsedPass pass;
    pass.desc.location = Loc(start);
    size_t i = start + 1;
    if (i < s_.size() && s_[i].IsIdentifier()) pass.desc.name = s_[i++].text;
    i = SkipAnnotation(i);
    Expect(i, "{", "after pass " + pass.desc.name);
    size_t close = s_.Matching(i);
    if (close >= s_.size()) s_.Fail(i, "pass " + pass.desc.name + " has no closing '}'");
    for (size_t j = i + 1; j < close;) j = s_[j].kind == TokenKind::Directive ? j + 1 : PassStatement(j, close, pass);
    tech.passes.push_back(std::move(pass));
    return s_.Is(close + 1, ";") ? close + 2 : close + 1;
  }

  // Set*(args); inside a pass.
  size_t PassStatement(size_t i, size_t close, ParsedPass& pass) {
    const auto& t = s_[i];
    if (s_.Is(i + 1, "=")) {
      s_.Fail(i, "'" + t.text + " = ...' in a pass is Direct3D 9 effect syntax; FX11 passes call SetVertexShader(CompileShader(vs_5_0, VS())), "
                 "SetRasterizerState(rs), ...");
    }
    if (!t.IsIdentifier() || !s_.Is(i + 1, "("))
      s_.Fail(i, "expected a Set...(...) call in pass " + pass.desc.name + ", found '" + t.text + "'");
    size_t open = i + 1, end = s_.Matching(open);
    if (end >= close) s_.Fail(open, "unbalanced '(' in pass " + pass.desc.name);
    auto args = s_.SplitCommas(open + 1, end);
    auto argCount = [&](size_t n) {
      if (args.size() != n)
        s_.Fail(i, t.text + " takes " + std::to_string(n) + " argument" + (n == 1 ? "" : "s") + ", not " + std::to_string(args.size()));
    };
    bool handled = false;
    for (const StageName& st : kStages) {
      if (t.text != st.setter) continue;
      handled = true;
      argCount(1);
      ShaderExpr e = Shader(args[0].first, args[0].second, st);
      if (!st.supported && !e.isNull) s_.Fail(i, std::string(st.setter) + ": hull and domain shaders are not supported");
      if (!st.supported) break;
      ShaderDesc d;
      d.stage = st.stage;
      d.isNull = e.isNull;
      d.target = e.target;
      d.function = e.function;
      d.arguments = e.arguments;
      d.variable = e.variable;
      d.location = e.location;
      pass.desc.shaders[size_t(st.stage)] = d;
    }
    if (t.Is("SetRasterizerState")) {
      argCount(1);
      pass.desc.rasterizerState = StateName(args[0], StateType::Rasterizer);
    } else if (t.Is("SetDepthStencilState")) {
      argCount(2);
      pass.desc.depthStencilState = StateName(args[0], StateType::DepthStencil);
      pass.desc.stencilRef = uint32_t(Number(args[1], "the stencil reference"));
    } else if (t.Is("SetBlendState")) {
      argCount(3);
      pass.desc.blendState = StateName(args[0], StateType::Blend);
      auto [f0, f1] = args[1];
      if (!(s_.Is(f0, "float4") && s_.Is(f0 + 1, "(") && s_.Matching(f0 + 1) == f1 - 1))
        s_.Fail(f0, "SetBlendState's blend factor must be float4(r, g, b, a), not '" + s_.Text(f0, f1) + "'");
      auto comps = s_.SplitCommas(f0 + 2, f1 - 1);
      if (comps.size() != 4) s_.Fail(f0, "SetBlendState's blend factor takes 4 components");
      for (size_t k = 0; k < 4; ++k) pass.desc.blendFactor[k] = float(Number(comps[k], "a blend factor component"));
      pass.desc.sampleMask = uint32_t(int64_t(Number(args[2], "the sample mask")));
    } else if (!handled) {
      s_.Fail(i, "unknown pass statement '" + t.text +
                     "' (valid: SetVertexShader, SetPixelShader, SetGeometryShader, SetComputeShader, SetRasterizerState, "
                     "SetDepthStencilState, SetBlendState)");
    }
    Expect(end + 1, ";", "after " + t.text + "(...)");
    return end + 2;
  }

  double Number(std::pair<size_t, size_t> r, const std::string& what) const {
    double d;
    if (!ParseNumber(s_, r.first, r.second, &d)) s_.Fail(r.first, what + " must be a number, not '" + s_.Text(r.first, r.second) + "'");
    return d;
  }

  // A state variable name or NULL ("").
  std::string StateName(std::pair<size_t, size_t> r, StateType type) const {
    if (r.second - r.first == 1 && s_[r.first].Is("NULL")) return "";
    if (r.second - r.first != 1 || !s_[r.first].IsIdentifier())
      s_.Fail(r.first, std::string("expected the name of a ") + StateTypeName(type) + " (or NULL), found '" + s_.Text(r.first, r.second) + "'");
    const std::string& name = s_[r.first].text;
    for (const StateObjectDesc& st : out_.states)
      if (st.name == name) {
        if (st.type != type) s_.Fail(r.first, "'" + name + "' is a " + StateTypeName(st.type) + ", not a " + StateTypeName(type));
        return name;
      }
    s_.Fail(r.first, std::string("unknown ") + StateTypeName(type) + " '" + name + "' (declare it before the technique)");
  }

  // NULL | variable | CompileShader(target, Function(args)).
  ShaderExpr Shader(size_t first, size_t last, const StageName& st) const {
    ShaderExpr e;
    e.location = Loc(first);
    if (last - first == 1 && s_[first].Is("NULL")) {
      e.isNull = true;
      return e;
    }
    if (last - first == 1 && s_[first].IsIdentifier()) {
      for (const ShaderVariable& v : out_.shaderVariables)
        if (v.name == s_[first].text) {
          if (v.stage != st.stage || !StageOfType(st.type)->supported)
            s_.Fail(first, "'" + v.name + "' is a " + ShaderStageName(v.stage) + " shader variable, given to " + st.setter);
          e = v.shader;
          e.variable = v.name;
          return e;
        }
      s_.Fail(first, "unknown shader variable '" + s_[first].text + "' (declare it as " + st.type + " " + s_[first].text +
                         " = CompileShader(...); before the technique)");
    }
    if (s_[first].Is("ConstructGSWithSO") || s_[first].Is("ConstructGSWithSO5"))
      s_.Fail(first, "ConstructGSWithSO: stream output is not supported");
    if (s_[first].Is("compile")) s_.Fail(first, "'compile target Function()' is Direct3D 9 effect syntax: use CompileShader(target, Function())");
    if (!s_[first].Is("CompileShader") || !s_.Is(first + 1, "(") || s_.Matching(first + 1) != last - 1)
      s_.Fail(first, "expected NULL, a shader variable or CompileShader(target, Function(...)), found '" + s_.Text(first, last) + "'");
    auto args = s_.SplitCommas(first + 2, last - 1);
    if (args.size() != 2) s_.Fail(first, "CompileShader takes a target and a function call: CompileShader(vs_5_0, VS())");
    auto [t0, t1] = args[0];
    if (t1 - t0 != 1 || !s_[t0].IsIdentifier()) s_.Fail(t0, "CompileShader's first argument must be a target such as vs_5_0");
    e.target = s_[t0].text;
    ShaderStage stage;
    if (!hlsl::ParseTarget(e.target, &stage))
      s_.Fail(t0, "CompileShader: unknown target '" + e.target + "' (valid: " + hlsl::ValidTargets() + ")");
    if (stage != st.stage || !st.supported)
      s_.Fail(t0, "CompileShader: target " + e.target + " is not a " + std::string(st.type) + " target");
    auto [c0, c1] = args[1];
    if (!(s_[c0].IsIdentifier() && s_.Is(c0 + 1, "(") && s_.Matching(c0 + 1) == c1 - 1))
      s_.Fail(c0, "CompileShader's second argument must be a function call such as VS(), not '" + s_.Text(c0, c1) + "'");
    e.function = s_[c0].text;
    for (auto [a0, a1] : s_.SplitCommas(c0 + 2, c1 - 1)) {
      if (a0 >= a1) s_.Fail(c0, "CompileShader: empty argument in " + s_.Text(c0, c1));
      e.arguments.push_back(s_.Text(a0, a1));
    }
    return e;
  }

  size_t ShaderVariableDecl(size_t start) {
    const StageName* st = StageOfType(s_[start].text);
    ShaderVariable v;
    v.name = s_[start + 1].text;
    v.stage = st->stage;
    size_t i = start + 2;
    if (s_.Is(i, "[")) s_.Fail(i, std::string("arrays of ") + st->type + " variables are not supported");
    i = SkipAnnotation(i);
    size_t end = i;
    if (s_.Is(i, "=")) {
      end = i + 1;
      while (end < s_.size() && !s_[end].Is(";")) {
        if (s_[end].Is("(") || s_[end].Is("{")) end = s_.Matching(end);
        if (end >= s_.size()) break;
        ++end;
      }
      if (end >= s_.size()) s_.Fail(start, std::string(st->type) + " " + v.name + ": expected ';'");
      if (s_.Is(i + 1, "{")) s_.Fail(i + 1, std::string("arrays of ") + st->type + " variables are not supported");
      v.shader = Shader(i + 1, end, *st);
    } else {
      Expect(i, ";", std::string("after ") + st->type + " " + v.name);
      v.shader.isNull = true;
      v.shader.location = Loc(start);
    }
    out_.shaderVariables.push_back(v);
    out_.hidden.push_back({start, end});
    return end + 1;
  }

  // RasterizerState / DepthStencilState / BlendState name [< annotations >] [{ fields }];
  size_t StateObject(size_t start) {
    StateObjectDesc st;
    st.type = s_[start].Is("RasterizerState") ? StateType::Rasterizer : s_[start].Is("DepthStencilState") ? StateType::DepthStencil : StateType::Blend;
    size_t i = start + 1;
    if (i >= s_.size() || !s_[i].IsIdentifier()) s_.Fail(start, std::string("expected a name after ") + StateTypeName(st.type));
    st.name = s_[i++].text;
    st.location = Loc(start);
    if (s_.Is(i, "[")) s_.Fail(i, std::string("arrays of ") + StateTypeName(st.type) + " are not supported");
    i = SkipAnnotation(i);
    if (s_.Is(i, "{")) i = Fields(i, st) + 1;
    Expect(i, ";", std::string("after ") + StateTypeName(st.type) + " " + st.name);
    FinishState(st);
    AddState(std::move(st), start);
    out_.hidden.push_back({start, i});
    return i + 1;
  }

  // SamplerState name [: register(sN)] [< annotations >] [{ fields }] [, name ...]; keeps the
  // declarations (the shader code samples with them) without their blocks.
  size_t Sampler(size_t start) {
    StateType type = s_[start].Is("SamplerState") ? StateType::Sampler : StateType::SamplerComparison;
    // A function returning a sampler is shader code, not a declaration of ours.
    if (!s_.Is(start + 2, "(") && start + 1 < s_.size() && s_[start + 1].IsIdentifier()) {
      size_t i = start + 1;
      for (;;) {
        i = SamplerDeclarator(i, type, start);
        if (s_.Is(i, ",") && i + 1 < s_.size() && s_[i + 1].IsIdentifier()) {
          ++i;
          continue;
        }
        Expect(i, ";", std::string("after the ") + StateTypeName(type) + " declaration");
        return i + 1;
      }
    }
    return start + 1;  // not ours (or malformed): glslang reports what it makes of it
  }

  // One declarator at `i`; returns the index after it.
  size_t SamplerDeclarator(size_t i, StateType type, size_t typeToken) {
    StateObjectDesc st;
    st.type = type;
    st.name = s_[i].text;
    st.location = Loc(typeToken);
    size_t nameToken = i++;
    if (s_.Is(i, "[")) {
      // Arrays of samplers are plain HLSL without a block; with one they would need per-element state.
      size_t after = s_.Matching(i) + 1;
      while (after < s_.size() && !s_[after].Is(";") && !s_[after].Is("{") && !s_[after].Is(",")) ++after;
      if (s_.Is(after, "{")) s_.Fail(i, "arrays of sampler states with a state block are not supported");
      return after;
    }
    if (s_.Is(i, ":")) {
      // `: register(s0)`
      i += 1;
      if (s_.Is(i, "register") && s_.Is(i + 1, "(")) i = s_.Matching(i + 1) + 1;
      else s_.Fail(i, "expected register(sN) after ':' in " + std::string(StateTypeName(st.type)) + " " + st.name);
    }
    if (s_.Is(i, "<")) {
      size_t e = SkipAnnotation(i);
      out_.hidden.push_back({i, e - 1});
      i = e;
    }
    if (s_.Is(i, "=")) s_.Fail(i, "'" + st.name + " = sampler_state { ... }' is Direct3D 9 effect syntax: write SamplerState " + st.name + " { ... };");
    if (s_.Is(i, "{")) {
      size_t close = Fields(i, st);
      out_.hidden.push_back({i, close});
      i = close + 1;
    }
    AddState(std::move(st), nameToken);
    return i;
  }

  void AddState(StateObjectDesc st, size_t token) {
    for (const StateObjectDesc& o : out_.states)
      if (o.name == st.name) s_.Fail(token, "'" + st.name + "' is declared twice (first at " + o.location.ToString() + ")");
    out_.states.push_back(std::move(st));
  }

  // { Field = value; Field[N] = value; ... } starting at `open`; returns the closing brace.
  size_t Fields(size_t open, StateObjectDesc& st) {
    size_t close = s_.Matching(open);
    if (close >= s_.size()) s_.Fail(open, std::string(StateTypeName(st.type)) + " " + st.name + " has no closing '}'");
    for (size_t j = open + 1; j < close;) {
      if (s_[j].kind == TokenKind::Directive) {
        ++j;
        continue;
      }
      size_t field = j;
      if (!s_[j].IsIdentifier()) s_.Fail(j, "expected a field name in " + std::string(StateTypeName(st.type)) + " " + st.name + ", found '" + s_[j].text + "'");
      ++j;
      int index = -1;
      if (s_.Is(j, "[")) {
        size_t m = s_.Matching(j);
        double d;
        if (m >= close || !ParseNumber(s_, j + 1, m, &d) || d < 0)
          s_.Fail(j, "the index of '" + s_[field].text + "' must be a number");
        index = int(d);
        j = m + 1;
      }
      Expect(j, "=", "after the field '" + s_[field].text + "'");
      size_t v0 = j + 1, v1 = v0;
      while (v1 < close && !s_[v1].Is(";")) {
        if (s_[v1].Is("(")) v1 = s_.Matching(v1);
        ++v1;
      }
      if (v1 >= close) s_.Fail(field, "expected ';' after the value of '" + s_[field].text + "'");
      SetStateField(st, s_, field, index, v0, v1);
      j = v1 + 1;
    }
    return close;
  }

  const Source& s_;
  ParsedEffect out_;
};

}  // namespace

ParsedEffect ParseEffect(const Source& source) { return Parser(source).Run(); }

}  // namespace sp::fx::detail
