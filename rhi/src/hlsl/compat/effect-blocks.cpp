// FX11 effect blocks (technique/pass, fxgroup, state objects, shader variables, annotations) are
// read by sp::fx::Effect from the same preprocessed text; the shader compiler must not see them.
// The parser is shared (fx/effect-parse.h), so a block it does not understand fails here too,
// at the user's line, instead of being dropped silently. Sampler states keep their declaration
// (the shader code samples with them) without the state block.
#include "compat.h"
#include "fx/effect-parse.h"

namespace sp::hlsl::compat {

void RewriteEffectBlocks(const Source& source, Edits& edits) {
  fx::detail::ParsedEffect effect = fx::detail::ParseEffect(source);
  // #line directives inside a block (an #include in a technique) stay, or glslang's later line
  // numbers would be wrong.
  for (auto [first, last] : effect.hidden) {
    size_t run = first;
    for (size_t i = first; i <= last + 1; ++i) {
      if (i <= last && source[i].kind != TokenKind::Directive) continue;
      if (run < i) edits.Replace(source[run].begin, source[i - 1].end, "");
      run = i + 1;
    }
  }
}

}  // namespace sp::hlsl::compat
