// `uniform` on a parameter: fxc reads it only on the entry point (its $Params constants, set by
// FX11's CompileShader(ps_5_0, PS(true)) or the application); on any other function it changes
// nothing. glslang keeps it on called functions and then emits invalid SPIR-V for an argument
// that needs a conversion (an int literal for a `uniform float k`: "OpStore Pointer's type does
// not match Object's type", which spirv-opt crashes on). Outside the entry point it is removed.
#include "compat.h"

namespace sp::hlsl::compat {

void RewriteUniformParameters(const Source& s, Edits& edits) {
  int depth = 0;  // of braces: parameter lists are at file scope
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i].Is("{")) ++depth;
    else if (s[i].Is("}")) --depth;
    if (depth != 0 || !s[i].Is("(") || i == 0 || !s[i - 1].IsIdentifier()) continue;
    size_t close = s.Matching(i);
    if (close >= s.size()) return;
    // A definition or declaration: the list is followed by `{`, `;` or a `: SEMANTIC`.
    bool function = s.Is(close + 1, "{") || s.Is(close + 1, ";") || s.Is(close + 1, ":");
    if (function && s[i - 1].text != s.entryPoint())
      for (size_t k = i + 1; k < close; ++k)
        if (s[k].Is("uniform")) edits.Replace(s[k].begin, s[k].end, "");
    i = close;
  }
}

}  // namespace sp::hlsl::compat
