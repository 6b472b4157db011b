#include "compat.h"

#include <regex>

namespace sp::hlsl::compat {

bool ParseNumericTypeName(const std::string& name, NumericTypeName* type) {
  static const std::regex re(R"((float|int|uint|half|double|bool|dword|min16float|min10float|min16int|min12int|min16uint)([1-4])?(?:x([1-4]))?)");
  std::smatch m;
  if (!std::regex_match(name, m, re)) return false;
  type->components = (m[2].matched ? std::stoi(m[2].str()) : 1) * (m[3].matched ? std::stoi(m[3].str()) : 1);
  type->matrix = m[3].matched;
  return true;
}

const std::vector<Rewrite>& Rewrites() {
  static const std::vector<Rewrite> kRewrites = {
      {"effect-blocks", "FX11 technique/pass blocks and state-object initialisers (kept for sp::fx::Effect, hidden from the shader)",
       RewriteEffectBlocks},
      {"for-loop-scope", "a variable declared in a for initialiser, used after the loop (fxc's old scoping)", RewriteForLoopScope},
      {"cbuffer-static", "a static declared inside a cbuffer block", RewriteCbufferStatics},
      {"array-cast", "an array reinterpreted by a cast, (float[8])packedFloat4s", RewriteArrayCasts},
      {"initializer-list", "brace-elided and flat initializer lists for structs, vectors and arrays", RewriteInitializerLists},
      {"matrix-swizzle", "matrix swizzles (m._11_21_31, m._m00_m10), read and written", RewriteMatrixSwizzles},
      {"uniform-parameter", "`uniform` on the parameters of functions other than the entry point", RewriteUniformParameters},
      {"object-array", "arrays of textures and samplers (Texture2D maps[4] : register(t0)), one register per element",
       RewriteObjectArrays},
      {"coverage-parameter", "`uint c : SV_Coverage` as a parameter of the entry point", RewriteCoverageParameter},
  };
  return kRewrites;
}

// glslang's parser (and fxc's) is recursive: ten thousand nested parentheses overflow its stack.
// A limit far above what real shaders nest turns that crash into a message.
constexpr int kMaxNesting = 512;

// Also refuses unbalanced brackets, with the line of the first one that has no partner: such a
// source is not HLSL, and every rewrite relies on Source::Matching finding a partner (an
// unmatched ']' before a for loop once sent the for-loop rewrite past the end of the tokens:
// found by fuzz/hlsl-preprocess-fuzz.cpp).
void CheckNesting(const Source& s) {
  std::vector<size_t> open;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i].Is("(") || s[i].Is("[") || s[i].Is("{")) {
      open.push_back(i);
      if (open.size() > size_t(kMaxNesting))
        s.Fail(i, "brackets nested more than " + std::to_string(kMaxNesting) + " levels deep (the parser is recursive); simplify the expression");
    } else if (s[i].Is(")") || s[i].Is("]") || s[i].Is("}")) {
      const char* want = s[i].Is(")") ? "(" : s[i].Is("]") ? "[" : "{";
      bool anyOpen = false;
      for (size_t o : open) anyOpen = anyOpen || s[o].Is(want);
      if (!anyOpen) s.Fail(i, "'" + s[i].text + "' without a matching '" + want + "'");
      if (!s[open.back()].Is(want))
        s.Fail(open.back(), "'" + s[open.back()].text + "' closed by '" + s[i].text + "' (line " + std::to_string(s[i].line) + ")");
      open.pop_back();
    }
  }
  if (!open.empty()) s.Fail(open.back(), "'" + s[open.back()].text + "' is never closed");
}

Result Apply(const std::string& preprocessed, const std::string& mainFile, const std::string& entryPoint) {
  Result r;
  r.source = preprocessed;
  CheckNesting(Source(preprocessed, mainFile));
  for (const Rewrite& rw : Rewrites()) {
    // A rewrite skips a construct nested in one it is rewriting; the next round gets it.
    for (int round = 0; round < 8; ++round) {
      Source src(r.source, mainFile, entryPoint);
      Edits edits;
      rw.run(src, edits);
      if (edits.empty()) break;
      r.source = edits.Apply(src);
      if (round == 0) r.applied.push_back(rw.name);
    }
  }
  return r;
}

}  // namespace sp::hlsl::compat
