// The csm technique's parameters: declarations for ParamValues::Parse and their translation into
// CsmSettings.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "csm-technique.h"
#include "pcf-params.h"

namespace sp::tech::csm {

std::vector<ParamSpec> CsmParams() {
  using P = ParamSpec;
  std::vector<std::string> filters = PcfFilterNames();
  for (const std::string& m : MomentFilterNames()) filters.push_back(m);
  std::vector<ParamSpec> specs = {
      {P::Int, "cascades", "number of cascades (1 = one map focused on the view)", "4", 1, 8, {}},
      {P::Choice, "split", "how the view range is split", "pssm", 0, 0, {"uniform", "log", "pssm", "manual"}},
      {P::Float, "lambda", "pssm: weight of the logarithmic split against the uniform one", "0.75", 0, 1, {}},
      {P::Text, "splits", "split=manual: cascades-1 increasing fractions of the view range, separated by commas or colons (e.g. 0.05,0.15,0.4)", "", 0, 0, {}},
      {P::Choice, "fit", "cascade: each cascade fits its own slice; scene: each fits from the camera's near plane", "cascade", 0, 0, {"scene", "cascade"}},
      {P::Choice, "select", "interval: cascade by view depth; map: first cascade whose map holds the point", "interval", 0, 0, {"interval", "map"}},
      {P::Float, "blend", "fraction of each cascade mixed with the next towards its end", "0", 0, 0.5, {}},
      {P::Int, "stabilize", "1: constant cascade size and whole-texel snapping (no shimmer); 0: tight fit", "1", 0, 1, {}},
      {P::Choice, "storage", "array: one slice per cascade; atlas: one texture, cascades in a grid", "array", 0, 0, {"array", "atlas"}},
      {P::Choice, "focus", "receivers: fit to the slice within the scene and its casters; scene: slice and whole scene depth", "receivers", 0, 0, {"scene", "receivers"}},
      {P::Choice, "filter", "shadow filter: PCF (common/shadow-filter.hlsli) or moments (moments/moments.hlsli; storage=array only)", "hw2x2", 0,
       0, filters},
      PcfKernelParam("box, gauss, gathercmp, poisson"),
      {P::Choice, "bias",
       "const: DepthBias; slope: + SlopeScaledDepthBias; normal: normal offset + DepthBias; receiver-plane: depth gradient + DepthBias "
       "(moment filters: no depth bias; bias=normal applies its normal offset)",
       "slope", 0, 0, {"const", "slope", "normal", "receiver-plane"}},
      {P::Int, "depth_bias", "D3D11 DepthBias (units of the D32 format)", "100", -1e7, 1e7, {}},
      {P::Float, "slope_bias", "D3D11 SlopeScaledDepthBias (bias=slope)", "2.0", -100, 100, {}},
      {P::Float, "normal_offset", "bias=normal: offset along the normal in texels of the cascade", "1.0", 0, 16, {}},
      {P::Int, "resolution", "width and height of each cascade's region in texels", "1024", 16, 8192, {}},
  };
  for (const ParamSpec& p : PcssParamSpecs(PcssLight::Directional)) specs.push_back(p);
  // msaa, blur, bleed, exponents, precision: used by the moment filters only.
  for (ParamSpec m : MomentParamSpecs()) {
    m.help += " (moment filters only)";
    specs.push_back(m);
  }
  for (ParamSpec h : HpsmParams()) {
    h.help += " (comparison filters only)";
    specs.push_back(h);
  }
  specs.push_back({P::Choice, "anisotropy", "maximum anisotropy of the moment lookups, 1 = trilinear (moment filters only)", "1", 0, 0,
                   {"1", "2", "4", "8", "16"}});
  return specs;
}

CsmSettings SettingsFrom(const ParamValues& p, const std::string& technique) {
  const std::string prefix = "technique '" + technique + "': ";
  CsmSettings s;
  FitSettings& f = s.fit;
  f.cascades = p.getInt("cascades");
  f.split = ParseSplitScheme(p.getChoice("split"));
  f.lambda = p.getFloat("lambda");
  const std::string& splits = p.getChoice("splits");
  if (f.split == SplitScheme::Manual) {
    try {
      f.manualFractions = ParseManualSplits(splits, f.cascades);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(prefix + e.what());
    }
  } else if (!splits.empty()) {
    throw std::invalid_argument(prefix + "splits=" + splits + " is only used with split=manual (split is " + p.getChoice("split") + ")");
  }
  f.fitToScene = p.getChoice("fit") == "scene";
  f.focusReceivers = p.getChoice("focus") == "receivers";
  f.stabilize = p.getInt("stabilize") != 0;
  f.blend = p.getFloat("blend");
  f.resolution = uint32_t(p.getInt("resolution"));

  s.select = p.getChoice("select") == "map" ? Select::Map : Select::Interval;
  s.storage = p.getChoice("storage") == "atlas" ? Storage::Atlas : Storage::Array;
  const std::string& filter = p.getChoice("filter");
  s.filter = std::max(PcfFilterIndex(filter), 0);
  s.pcss = PcssSettingsFrom(p);
  s.kernel = p.getInt("kernel");
  CheckPcfKernel("csm", s.filter, s.kernel);
  s.moments = IsMomentFilter(filter);
  s.anisotropy = std::stoi(p.getChoice("anisotropy"));
  {
    // Parsed whatever the filter, so a bad value is an error even where it would be ignored (a
    // comparison filter's values are checked as evsm4's, the kind that accepts every form).
    std::map<std::string, std::string> values = p.all();
    if (!s.moments) values["filter"] = "evsm4";
    try {
      s.moment = ParseMomentOptions(values);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(prefix + e.what());
    }
  }
  if (s.moments && s.storage == Storage::Atlas)
    throw std::invalid_argument(prefix + "filter=" + filter +
                                " needs storage=array: the moment blur and mip chain of an atlas would mix neighbouring cascades' regions");
  const std::string& bias = p.getChoice("bias");
  s.bias = bias == "const" ? Bias::Const : bias == "normal" ? Bias::Normal : bias == "receiver-plane" ? Bias::ReceiverPlane : Bias::Slope;
  s.depthBias = p.getInt("depth_bias");
  s.slopeBias = p.getFloat("slope_bias");
  s.normalOffset = p.getFloat("normal_offset");

  // Texels between the fitted area and the region's edge: the filter's reach (the 2x2 hardware
  // filter, and the bilinear moment lookup at mip 0, read one texel beyond their centre; a k-wide
  // kernel k/2 plus that one), and the normal offset, which moves the lookup away from the point
  // the cascade was chosen for.
  // pcss: its box reaches half the widest kernel, rounded up, plus the texel it ends in.
  uint32_t reach = s.filter == 0 || s.moments ? 1u : s.filter == kPcssFilter ? uint32_t((s.pcss.maxKernel + 1) / 2 + 1) : uint32_t(s.kernel / 2 + 1);
  if (s.bias == Bias::Normal) reach += uint32_t(std::ceil(s.normalOffset));
  f.padTexels = reach;
  if (f.resolution < 8 * f.padTexels)
    throw std::invalid_argument(prefix + "resolution=" + std::to_string(f.resolution) + " is too small for the filter's padding of " +
                                std::to_string(f.padTexels) + " texels; use at least " + std::to_string(8 * f.padTexels));
  // Techniques sharing these parameters without accel (sdsm) keep it at none.
  if (p.all().count("accel")) {
    if (s.moments && p.getChoice("accel") != "none")
      throw std::invalid_argument(prefix + "accel=" + p.getChoice("accel") + " needs a comparison filter (filter is " + filter + ")");
    try {
      if (!s.moments) s.hpsm = ReadHpsmSettings(p, s.filter, s.filter == 0 ? 3 : s.filter == kPcssFilter ? s.pcss.maxKernel : s.kernel, f.resolution);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(prefix + e.what());
    }
  }
  if (s.moments) {
    // The moment blur reaches `blur` world units, a different number of texels per cascade: the
    // fit pads each cascade by its own share, within the same 1/8 of the region the fixed padding
    // may take (the technique clamps the blur to what was padded).
    f.padWorld = s.moment.blur;
    f.farToRegion = true;
    f.padWorldMaxTexels = std::min(uint32_t(kMaxBlurRadiusTexels), f.resolution / 8 - f.padTexels);
  }
  return s;
}

}  // namespace sp::tech::csm
