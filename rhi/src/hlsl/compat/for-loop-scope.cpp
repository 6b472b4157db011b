#include "compat.h"

namespace sp::hlsl::compat {

void RewriteForLoopScope(const Source&, Edits&) {}

}  // namespace sp::hlsl::compat
