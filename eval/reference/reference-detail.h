// Shared between the tracer and the cache, so both reject the same inputs with the same words.
#pragma once
#include <cstddef>
#include <cstdint>

#include "reference.h"

namespace sp::eval::detail {

// Throws std::runtime_error prefixed with `who` for a null buffer, an ill-formed light, or a
// valid pixel with a non-finite position or a zero or non-finite normal (naming the pixel).
void ValidateVisibilityInputs(const char* who, const glm::vec3* positions, const glm::vec3* normals, const uint8_t* valid,
                              size_t count, const ReferenceLight& light, const void* out);

}  // namespace sp::eval::detail
