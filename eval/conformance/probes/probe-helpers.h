// Shared pieces of the conformance probes: a depth-only draw with per-vertex depth into a given
// depth format and its readback in the format's own units, and D3D11's rasterization rules on the
// CPU.
#pragma once
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "../conformance.h"
#include "../gpu-util.h"

namespace sp::conformance {

struct DepthVertex {
  float x, y, z;  // NDC (D3D: +y up), depth
};

// Draws `vertices` (triangle list, line list or point list) with `rasterizer` into a W x H depth
// target of `format` cleared to `clear`, depth test ALWAYS; returns the stored values per pixel:
// UNORM formats as integers (LSB units), D32_FLOAT as floats.
std::vector<double> DrawDepth(Device& device, FORMAT format, uint32_t w, uint32_t h, const std::vector<DepthVertex>& vertices,
                              PRIMITIVE_TOPOLOGY topology, const RASTERIZER_DESC& rasterizer, float clear = 1.0f,
                              const VIEWPORT* viewport = nullptr);

// Bits of a UNORM depth format (16 or 24), 0 for D32_FLOAT.
uint32_t UnormBits(FORMAT depthFormat);

// D3D11 float -> UNORM conversion of a depth value (round to nearest).
double QuantizeUnorm(double z, uint32_t bits);

// Unit in the last place of a float in [0, 1] (for D32_FLOAT error reports).
double FloatUlp(double z);

// D3D11 coverage of pixel centres (top-left rule); triangle in pixel coordinates, y down.
bool D3DCovers(std::array<double, 2> a, std::array<double, 2> b, std::array<double, 2> c, double px, double py);

}  // namespace sp::conformance
