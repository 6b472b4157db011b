#include "compat.h"

namespace sp::hlsl::compat {

void RewriteCbufferStatics(const Source&, Edits&) {}

}  // namespace sp::hlsl::compat
