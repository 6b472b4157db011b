// `uint coverage : SV_Coverage` as a parameter of the entry point (fxc accepts it; MSAA resolves
// and custom-resolve shadow filters use it). glslang declares the input but never copies it into
// the parameter, so the shader would read an undefined value (the toolchain refuses that). As a
// member of an input struct glslang connects it: the parameter becomes such a struct, and a local
// of the original name is initialised from it at the top of the body.
#include <algorithm>
#include <cctype>

#include "compat.h"

namespace sp::hlsl::compat {
namespace {

bool IsCoverage(const std::string& semantic) {
  std::string s = semantic;
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::toupper(c)); });
  return s == "SV_COVERAGE";
}

}  // namespace

void RewriteCoverageParameter(const Source& s, Edits& edits) {
  if (s.entryPoint().empty()) return;
  int depth = 0;
  for (size_t i = 0; i + 1 < s.size(); ++i) {
    if (s[i].Is("{")) ++depth;
    else if (s[i].Is("}")) --depth;
    if (depth != 0 || !s[i].Is(s.entryPoint()) || !s.Is(i + 1, "(")) continue;
    size_t close = s.Matching(i + 1);
    if (close >= s.size()) return;
    size_t body = close + 1;
    if (s.Is(body, ":")) body += 2;
    if (!s.Is(body, "{")) continue;  // a declaration or a call
    for (auto [a, b] : s.SplitCommas(i + 2, close)) {
      // [in] TYPE NAME : SV_Coverage
      if (b < a + 4 || !s[b - 2].Is(":") || !IsCoverage(s[b - 1].text) || !s[b - 3].IsIdentifier()) continue;
      size_t typeFirst = s.Is(a, "in") ? a + 1 : a;
      if (typeFirst + 1 != b - 3) s.Fail(a, "an SV_Coverage parameter must be `uint name : SV_Coverage`");
      edits.AddPrelude("coverage-parameter", "struct SpCompatCoverage { uint value : SV_Coverage; };");
      edits.Replace(s[a].begin, s[b - 1].end, "SpCompatCoverage spcompat_coverage");
      edits.Insert(s[body].end, " " + s[typeFirst].text + " " + s[b - 3].text + " = spcompat_coverage.value;");
    }
    return;
  }
}

}  // namespace sp::hlsl::compat
