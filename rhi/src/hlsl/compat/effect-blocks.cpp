#include "compat.h"

namespace sp::hlsl::compat {

void RewriteEffectBlocks(const Source&, Edits&) {}

}  // namespace sp::hlsl::compat
