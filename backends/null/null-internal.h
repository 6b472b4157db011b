// Private interface of the null backend: a device that accepts every call the core has validated
// and does no GPU work, so that validation and misuse can be tested without a driver.
//
// What is real: object creation (with the format support and sample counts a Direct3D 11 feature
// level 11_0 device guarantees) and the CPU side of Map. What is not: draws, dispatches, clears,
// copies, UpdateSubresource, mip generation and resolves do nothing. A null device is for
// validation, never for pictures: a staging resource read back holds only what the CPU put there
// (its initial data, earlier Map writes), zeros otherwise, never what a GPU would have produced.
#pragma once
#include <vector>

#include "backend.h"

namespace sp::null {

// The CPU memory behind Map, for the resources the core lets the CPU map (USAGE_DYNAMIC and
// USAGE_STAGING); other resources carry none. One block per subresource (buffers: one), D3D's
// tight layout, allocated on first use so large never-mapped resources cost nothing.
struct NullResource : detail::BackendObject {
  std::vector<std::vector<uint8_t>> subresources;
};

std::unique_ptr<detail::ContextBackend> CreateNullContext();

}  // namespace sp::null
