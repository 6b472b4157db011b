// Pieces shared by the rasterization and resource probes: triangles given in pixel coordinates of
// a render target (y down, as D3D's window), hit counting with additive blending, a compute pass
// that writes float4 results, depth upload through staging, and D3D11's standard sample
// positions and conversion rules on the CPU.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "probe-helpers.h"

namespace sp::conformance {

// Mesa 22.3 (llvmpipe and lavapipe) converts UNORM texels to float by multiplying the code by the
// float reciprocal of 2^n - 1, which is 1 ulp away from the correctly rounded code / (2^n - 1)
// that D3D11 requires (functional spec 3.2.3.2) for part of the codes. The conversion happens in
// the driver's texture unit; correcting it in shaders would need a variant per bound view format.
inline constexpr const char* kUnormReadDeviation =
    "Mesa reads UNORM texels as code * (1/(2^n-1)) in float, 1 ulp from the correctly rounded code / (2^n-1) of D3D11 3.2.3.2";


// A vertex in pixel coordinates of the viewport (y down) with NDC depth. Probes keep x and y on
// the 1/256 grid: D3D11 snaps vertices to 8 sub-pixel bits, so such vertices reach the rasterizer
// exactly and the CPU expectation cannot depend on snapping.
struct PixelVertex {
  double x, y;
  float z = 0.5f;
};

// Vertex shader + input layout drawing PixelVertex lists: the CPU converts to NDC (exact for
// power-of-two viewport sizes) and the shader passes the position through with w = 1.
class PixelDrawer {
 public:
  explicit PixelDrawer(Device& device);
  // Draws with whatever pixel shader and output-merger state is bound. `vpW` x `vpH` is the size of
  // the viewport the pixel coordinates refer to (the caller sets the viewport).
  void Draw(DeviceContext& ctx, const std::vector<PixelVertex>& vertices, double vpW, double vpH,
            PRIMITIVE_TOPOLOGY topology = PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  VertexShader* vs() const { return vs_.get(); }

 private:
  Device& device_;
  Ref<VertexShader> vs_;
  Ref<InputLayout> layout_;
};

// Draws a triangle list (pixel coordinates, CULL_NONE) into a w x h R32_FLOAT target with additive
// blending of 1 per pixel-shader invocation; returns the hit count of every pixel.
std::vector<float> CountHits(Device& device, uint32_t w, uint32_t h, const std::vector<PixelVertex>& triangles);

// Pixels (row-major) where `got` differs from `expected`; the first few are described in *detail.
int CountMismatches(const std::vector<float>& got, const std::vector<float>& expected, uint32_t w, std::string* detail,
                    const char* what = "value");

// Runs `source` (entry `main`, cs_5_0) once with `groups` thread groups after binding `srvs` to
// t0.. and `samplers` to s0..; u0 is a RWStructuredBuffer<float4> of `count` elements, returned.
std::vector<std::array<float, 4>> RunCompute(Device& device, const std::string& source, const std::string& name, uint32_t count,
                                             const std::vector<ShaderResourceView*>& srvs,
                                             const std::vector<SamplerState*>& samplers = {}, uint32_t groups = 1);

// Writes `texels` (tightly packed rows of the subresource's format) into subresource `sub` of a
// texture that D3D11 cannot update directly (depth-stencil, multisampled excluded): through a
// staging texture and CopySubresourceRegion, as D3D11 applications do.
void UploadThroughStaging(Device& device, Texture2D* texture, uint32_t sub, const void* texels);

Ref<SamplerState> MakeSampler(Device& device, FILTER filter, TEXTURE_ADDRESS_MODE address = TEXTURE_ADDRESS_CLAMP,
                              COMPARISON_FUNC cmp = COMPARISON_NEVER);
Ref<ShaderResourceView> MakeSrv(Device& device, Resource* resource, FORMAT format, SRV_DIMENSION dim, uint32_t firstSlice = 0,
                                uint32_t slices = 1);

// D3D11's standard 4x sample positions in 1/16 pixel, relative to the pixel centre, y down.
inline constexpr int kStandard4x[4][2] = {{-2, -6}, {6, -2}, {-6, 2}, {2, 6}};

// D3D11 3.2.3.6 FLOAT -> UNORM before rounding: the value on the integer scale. The spec allows
// any integer within 0.6 of it.
double UnormScaled(double c, uint32_t bits);
// D3D11 3.2.3.5 UNORM -> FLOAT: the correctly rounded float of code / (2^n - 1).
float UnormToFloat(uint32_t code, uint32_t bits);
// D3D11 3.2.3.8 ideal FLOAT -> SRGB without the rounding, on the 8-bit integer scale.
double SrgbEncodeScaled(double linear);
// D3D11 3.2.3.7 ideal SRGB -> FLOAT.
double SrgbDecode(uint32_t code);
// float32 -> float16 bits with D3D11's round-to-zero rule (3.2.2): values beyond the range give
// the largest finite value, never infinity.
uint16_t FloatToHalfRtz(float f);
float HalfToFloat(uint16_t h);

}  // namespace sp::conformance
