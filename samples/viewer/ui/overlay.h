// The viewer's overlays (docs/viewer.md): what replaces the frame in the window when one is on.
// Everything here is CPU-side and pure (no device), so tests check it without a window:
//  - layer colours: each pixel that read a shadow map tinted by the layer it read (the lab lit
//    pass's lookup.x: cascade, partition, cube face), LayerTint(k) mixed half and half with the
//    frame's sRGB bytes;
//  - the shadow-map view: a technique's map layers (first channel: depth, or a moment map's first
//    moment) as grey, tiled over the window.
// The density and error heat maps are eval/metrics' pictures (TexelDensityHeatMap, ErrorHeatMap).
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <sp/tech/renderer.h>

namespace sp::viewer {

enum class Overlay { Off, Layers, Density, Error, ShadowMap };
const char* OverlayName(Overlay o);  // "none", "layers", "density", "error", "shadowmap"
bool ParseOverlay(const std::string& name, Overlay* out);

// The tint of shadow layer k (k >= 0): kLayerTints[k % 8]; distinct hues in cascade order.
constexpr size_t kLayerTintCount = 8;
std::array<uint8_t, 3> LayerTint(int layer);
// The layer a lab pixel read: lookup.x rounded, -1 for none (sky, or no map read).
int LayerOf(const tech::LabBuffers& lab, size_t pixel);
// The frame (lab.color) with pixels that read layer k >= 0 as (colour + LayerTint(k)) / 2 per
// channel (integer division, on the sRGB bytes); others unchanged. RGBA8, alpha 255.
std::vector<uint8_t> ComposeLayerColours(const tech::LabBuffers& lab);

// A shadow map read back: `layers` slices of width x height values of its first channel.
struct MapImage {
  uint32_t width = 0, height = 0, layers = 0;
  std::vector<float> values;  // slice by slice, row by row from the top
  // A depth map, where 1 is the clear value (nothing drawn); false: moments (ESM's and EVSM's
  // exponentials exceed 1), where every finite value counts.
  bool depth = true;
};
// The slices tiled in a grid of columns = ceil(sqrt(layers)) over a width x height picture (each
// tile the largest square-texel fit, nearest texel, black around), as grey: per slice, values at
// or above "nothing drawn" (depth: 1; moments: the slice's largest value) are white and the range
// [min, max] of the others maps to [0, 255] (on a log scale for moments spanning more than 100x,
// ESM's and EVSM's exponentials), so a map of a small scene still shows contrast. Non-finite values
// are black. RGBA8 (sRGB bytes), alpha 255.
std::vector<uint8_t> TileShadowMap(const MapImage& map, uint32_t width, uint32_t height);

}  // namespace sp::viewer
