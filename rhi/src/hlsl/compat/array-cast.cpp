#include "compat.h"

namespace sp::hlsl::compat {

void RewriteArrayCasts(const Source&, Edits&) {}

}  // namespace sp::hlsl::compat
