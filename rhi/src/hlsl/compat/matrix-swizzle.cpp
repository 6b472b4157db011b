#include "compat.h"

namespace sp::hlsl::compat {

void RewriteMatrixSwizzles(const Source&, Edits&) {}

}  // namespace sp::hlsl::compat
