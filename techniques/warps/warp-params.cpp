// The parameters of psm, lispsm and tsm: the shared ones (resolution, cascades and their splits,
// depth mode and bias) and each warp's own knob, with WarpParams' defaults.
#include <cstdio>

#include "pcf-params.h"
#include "warp-technique.h"

namespace sp::tech::warps {

const char* WarpName(Warp warp) {
  switch (warp) {
    case Warp::Psm: return "psm";
    case Warp::Lispsm: return "lispsm";
    case Warp::Tsm: return "tsm";
    case Warp::None: break;
  }
  return "uniform";
}

namespace {
// A default as the user would type it (0.3, not 0.300000).
std::string Text(float v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", double(v));
  return b;
}
}  // namespace

std::vector<ParamSpec> WarpTechniqueParams(Warp warp) {
  using P = ParamSpec;
  const WarpParams d;
  // TSM's paper keeps depth linear in light space (WarpFit::preferLinearDepth); the others
  // default to the plain warped depth buffer.
  const char* depth = warp == Warp::Tsm ? "linear" : "warped";
  std::vector<ParamSpec> specs = {
      {P::Int, "resolution", "width and height of each cascade's map in texels", "2048", 16, 8192, {}},
      {P::Int, "cascades", "number of cascades, each warped separately (1 = one warped map of the whole view)", "1", 1, kMaxWarpCascades, {}},
      {P::Choice, "split", "how the view range is split (as csm)", "pssm", 0, 0, {"uniform", "log", "pssm"}},
      {P::Float, "lambda", "pssm: weight of the logarithmic split against the uniform one", "0.75", 0, 1, {}},
      {P::Choice, "depth", "warped: post-projective depth with rasterizer bias; linear: light-space linear depth written by the pixel shader",
       depth, 0, 0, {"warped", "linear"}},
      {P::Int, "depth_bias", "depth=warped: D3D11 DepthBias (units of the D32 format)", "100", -1e7, 1e7, {}},
      {P::Float, "slope_bias", "depth=warped: D3D11 SlopeScaledDepthBias", "2.0", -100, 100, {}},
      {P::Float, "linear_bias", "depth=linear: constant bias in linear depth units (the cascade's light-space depth range is 1)", "0.0002", -1, 1, {}},
      // 1, not slope_bias's 2: on distant-occluder 2 turned psm's and tsm's misclassified pixels
      // from 0.36 / 0.34 % into 0.47 / 0.44 % (false lit), and 0.5 left acne on the grazing
      // lights of the singular-configuration tests (docs/techniques.md).
      {P::Float, "linear_slope_bias", "depth=linear: slope-scaled bias, times the linear depth's largest change per map texel (D3D11's slope term, applied in the depth shader)",
       "1.0", -100, 100, {}},
      {P::Choice, "filter", "comparison filter (common/shadow-filter.hlsli; pcss is refused: the warped texel size is not uniform)", "hw2x2", 0, 0,
       {"hw2x2", "box", "gauss", "gathercmp", "poisson", "pcss"}},
      PcfKernelParam("box, gauss, gathercmp, poisson"),
      {P::Int, "receiver_plane", "1: receiver-plane depth bias per filter tap, from the derivatives of the warped map coordinates", "0", 0, 1, {}},
  };
  switch (warp) {
    case Warp::Psm:
      specs.push_back({P::Float, "slide_back", "extra virtual slide-back in multiples of the view-depth range (more = milder warp)",
                       Text(d.psmSlideBack), 0, 1e6, {}});
      break;
    case Warp::Lispsm:
      specs.push_back({P::Float, "n_scale", "n = n_scale * n_opt (< 1 warps more, > 1 less)", Text(d.lispsmScale), 1e-3, 1e6, {}});
      break;
    case Warp::Tsm:
      specs.push_back({P::Float, "focus", "fraction of the map the focus line maps to (the 80 % rule; 0 = uniform)", Text(d.tsmFocus), 0, 0.99, {}});
      specs.push_back({P::Float, "focus_depth", "where the focus line is, as a fraction of the view-depth range", Text(d.tsmFocusDepth), 0, 1, {}});
      break;
    case Warp::None: break;
  }
  return specs;
}

WarpSettings WarpSettingsFrom(Warp warp, const ParamValues& p) {
  WarpSettings s;
  s.warp = warp;
  s.resolution = uint32_t(p.getInt("resolution"));
  s.cascades = p.getInt("cascades");
  s.split = csm::ParseSplitScheme(p.getChoice("split"));
  s.lambda = p.getFloat("lambda");
  s.linearDepth = p.getChoice("depth") == "linear";
  s.depthBias = p.getInt("depth_bias");
  s.slopeBias = p.getFloat("slope_bias");
  s.linearBias = p.getFloat("linear_bias");
  s.linearSlopeBias = p.getFloat("linear_slope_bias");
  const std::string& filter = p.getChoice("filter");
  // PCSS turns a penumbra in world units into texels with one scale per map (or per cascade); the
  // perspective warp's texels grow and shrink across the map, so no such scale exists.
  if (filter == "pcss")
    throw std::invalid_argument(std::string(WarpName(warp)) + ": filter=pcss is not offered: the warped map's texel size is not uniform (it changes across the map with "
                                "the perspective warp), so PCSS's penumbra has no single width in texels (use basic, csm or sdsm)");
  const char* const filters[] = {"hw2x2", "box", "gauss", "gathercmp", "poisson"};
  for (int i = 0; i < 5; ++i)
    if (filter == filters[i]) s.filter = i;
  s.kernel = std::stoi(p.getChoice("kernel"));
  CheckPcfKernel("warps", s.filter, s.kernel);
  s.receiverPlane = p.getInt("receiver_plane") == 1;
  if (warp == Warp::Psm) s.params.psmSlideBack = p.getFloat("slide_back");
  if (warp == Warp::Lispsm) s.params.lispsmScale = p.getFloat("n_scale");
  if (warp == Warp::Tsm) {
    s.params.tsmFocus = p.getFloat("focus");
    s.params.tsmFocusDepth = p.getFloat("focus_depth");
  }
  return s;
}

}  // namespace sp::tech::warps
