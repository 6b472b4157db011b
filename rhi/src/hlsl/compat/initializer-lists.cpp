#include "compat.h"

namespace sp::hlsl::compat {

void RewriteInitializerLists(const Source&, Edits&) {}

}  // namespace sp::hlsl::compat
