#include "pcf-params.h"

#include <cmath>
#include <stdexcept>

namespace sp::tech {

const std::vector<std::string>& PcfFilterNames() {
  static const std::vector<std::string> names = {"hw2x2", "box", "gauss", "gathercmp", "poisson", "pcss"};
  return names;
}

int PcfFilterIndex(const std::string& name) {
  const std::vector<std::string>& n = PcfFilterNames();
  for (size_t i = 0; i < n.size(); ++i)
    if (n[i] == name) return int(i);
  return -1;
}

ParamSpec PcfKernelParam(const std::string& filters) {
  std::vector<std::string> widths;
  for (int n = 3; n <= 31; n += 2) widths.push_back(std::to_string(n));
  return {ParamSpec::Choice, "kernel", "filter kernel width in texels (" + filters + "; at most 15, gathercmp 31)", "3", 0, 0, widths};
}

void CheckPcfKernel(const std::string& technique, int filter, int kernel) {
  // gathercmp reads (N+1)^2/4 texels per fetch group, which makes up to 31 affordable; the
  // SampleCmp kernels take N^2 taps.
  if (filter == 1 || filter == 2 || filter == 4) {
    if (kernel > 15)
      throw std::invalid_argument("technique '" + technique + "': kernel=" + std::to_string(kernel) + " is too wide for filter=" + PcfFilterNames()[filter] +
                                  " (at most 15; gathercmp takes up to 31)");
  }
}

std::vector<ParamSpec> PcssParamSpecs(PcssLight light) {
  std::vector<ParamSpec> specs;
  if (light == PcssLight::Directional)
    specs.push_back({ParamSpec::Float, "light_size", "filter=pcss: the sun's angular diameter in degrees (the real sun: 0.53)", "0.53", 0.01, 20, {}});
  else
    specs.push_back({ParamSpec::Float, "light_size", "filter=pcss: radius of the light's disc in world units", "0.05", 1e-4, 100, {}});
  specs.push_back({ParamSpec::Int, "pcss_search", "filter=pcss: blocker-search taps per axis (a grid of point loads over the region the light subtends)", "6", 2, 16, {}});
  specs.push_back({ParamSpec::Int, "pcss_max_kernel", "filter=pcss: widest penumbra filter in texels (wider penumbrae are clamped)", "15", 1, 31, {}});
  return specs;
}

PcssSettings PcssSettingsFrom(const ParamValues& p) {
  return {p.getFloat("light_size"), p.getInt("pcss_search"), p.getInt("pcss_max_kernel")};
}

PcssConstants OrthoPcssConstants(const PcssSettings& s, float nearZ, float farZ, glm::vec2 worldTexel) {
  PcssConstants c;
  c.depthRange = {nearZ, farZ};
  c.perspective = 0;
  c.penumbraScale = 2.0f * std::tan(0.5f * glm::radians(s.lightSize)) / worldTexel;
  c.searchTaps = float(s.searchTaps);
  c.maxKernel = float(s.maxKernel);
  return c;
}

glm::vec4 CascadePcssRow(const PcssSettings& s) {
  return glm::vec4(2.0f * std::tan(0.5f * glm::radians(s.lightSize)), float(s.searchTaps), float(s.maxKernel), 0.0f);
}

PcssConstants PerspectivePcssConstants(const PcssSettings& s, float nearZ, float farZ, float fovY, float mapSize) {
  PcssConstants c;
  c.depthRange = {nearZ, farZ};
  c.perspective = 1;
  // At depth d one texel is d * 2 tan(fov/2) / mapSize wide; the penumbra 2 r (dR - dB) / dB.
  c.penumbraScale = glm::vec2(2.0f * s.lightSize * mapSize / (2.0f * std::tan(0.5f * fovY)));
  c.searchTaps = float(s.searchTaps);
  c.maxKernel = float(s.maxKernel);
  return c;
}

}  // namespace sp::tech
