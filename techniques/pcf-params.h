// Parameters of the PCF library (shaders-hlsl/common/shadow-filter.hlsli, shadow-pcss.hlsli)
// shared by every technique that offers its filters: one kernel list, one width rule, one set of
// PCSS parameters and its constants, so the techniques cannot drift apart.
#pragma once
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include <sp/tech/technique.h>

namespace sp::tech {

// SHADOW_FILTER's names by index; pcss (5) is offered only by techniques that wire it.
const std::vector<std::string>& PcfFilterNames();
constexpr int kPcssFilter = 5;
// Index of `name` in PcfFilterNames(), -1 if it is not one.
int PcfFilterIndex(const std::string& name);

// The `kernel` choice: odd widths 3..31 (31 for gathercmp only, CheckPcfKernel).
ParamSpec PcfKernelParam(const std::string& filters);
// Throws std::invalid_argument naming `kernel` when the width is more than `filter` allows.
void CheckPcfKernel(const std::string& technique, int filter, int kernel);

// light_size, pcss_search, pcss_max_kernel. Directional: light_size is the sun's angular diameter
// in degrees; local lights: the radius of the light's disc in world units.
enum class PcssLight { Directional, Local };
std::vector<ParamSpec> PcssParamSpecs(PcssLight light);

struct PcssSettings {
  float lightSize = 0.53f;
  int searchTaps = 6;
  int maxKernel = 15;
};
PcssSettings PcssSettingsFrom(const ParamValues& p);

// ShadowPcssInput of shadow-pcss.hlsli, as a technique's cbuffer holds it.
struct PcssConstants {
  glm::vec2 depthRange{0.0f, 1.0f};
  glm::vec2 penumbraScale{0.0f};
  float perspective = 0;
  float searchTaps = 6;
  float maxKernel = 15;
  float pad = 0;
};
static_assert(sizeof(PcssConstants) == 32);

// An orthographic map: light size in degrees, one texel's width and height in world units.
PcssConstants OrthoPcssConstants(const PcssSettings& s, float nearZ, float farZ, glm::vec2 worldTexel);
// csm/shadow.hlsli's csmPcss (csm and sdsm): 2 tan(angle / 2), search taps, max kernel, 0. The
// cascades' depth ranges and texel sizes differ, so the shader derives the rest per cascade.
glm::vec4 CascadePcssRow(const PcssSettings& s);
// A perspective map: light radius in world units, vertical field of view in radians, map size.
PcssConstants PerspectivePcssConstants(const PcssSettings& s, float nearZ, float farZ, float fovY, float mapSize);

}  // namespace sp::tech
