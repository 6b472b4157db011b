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
  for (auto [first, last] : effect.hidden) edits.Replace(source[first].begin, source[last].end, "");
}

}  // namespace sp::hlsl::compat
