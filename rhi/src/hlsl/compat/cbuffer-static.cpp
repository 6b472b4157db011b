// A static declared inside a cbuffer block: fxc treats it as an ordinary static global (it takes
// no room in the buffer), the classic home of `static float s[8] = (float[8])packed;` next to the
// packed member it reads. glslang takes it for a member ("struct-member initializers ignored",
// then "unknown variable"), so it moves to just after the block, where it means the same.
#include "compat.h"

namespace sp::hlsl::compat {

void RewriteCbufferStatics(const Source& s, Edits& edits) {
  for (size_t i = 0; i + 1 < s.size(); ++i) {
    if (!s[i].Is("cbuffer") && !s[i].Is("tbuffer")) continue;
    size_t open = i + 1;
    while (open < s.size() && !s[open].Is("{") && !s[open].Is(";")) ++open;
    if (open >= s.size() || !s[open].Is("{")) continue;
    size_t close = s.Matching(open);
    if (close >= s.size()) s.Fail(i, "unbalanced braces in cbuffer block");
    std::string moved;
    for (size_t j = open + 1; j < close; ++j) {
      if (s[j].Is("{") || s[j].Is("(")) {  // a nested struct or an initialiser
        j = s.Matching(j);
        continue;
      }
      if (!s[j].Is("static")) continue;
      size_t end = j;
      while (end < close && !s[end].Is(";")) {
        if (s[end].Is("{") || s[end].Is("(")) end = s.Matching(end);
        ++end;
      }
      if (end >= close) s.Fail(j, "a static in a cbuffer block must end with ';'");
      moved += " " + s.Text(j, end + 1);
      edits.Replace(s[j].begin, s[end].end, "");
      j = end;
    }
    if (moved.empty()) continue;
    size_t after = s.Is(close + 1, ";") ? close + 1 : close;
    edits.Insert(s[after].end, moved);
    i = close;
  }
}

}  // namespace sp::hlsl::compat
