// Parameters of moment filtering: parsing, defaults per kind and precision, exponent clamps and
// the HLSL defines. The clamps are the ones derived in shaders-hlsl/moments/moments.hlsli.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "moment-maps.h"

namespace sp::tech {

glm::vec2 ClampEvsmExponents(glm::vec2 requested, bool fp16) {
  float limit = fp16 ? kEvsmMaxExponentFp16 : kEvsmMaxExponentFp32;
  return glm::clamp(requested, glm::vec2(kMomentMinExponent), glm::vec2(limit));
}

float ClampEsmExponent(float requested, bool fp16) {
  return std::clamp(requested, kMomentMinExponent, fp16 ? kEsmMaxExponentFp16 : kEsmMaxExponentFp32);
}

const std::vector<std::string>& MomentFilterNames() {
  static const std::vector<std::string> names = {"vsm", "esm", "evsm2", "evsm4", "msm"};
  return names;
}

bool IsMomentFilter(const std::string& name) {
  const auto& n = MomentFilterNames();
  return std::find(n.begin(), n.end(), name) != n.end();
}

std::string MomentKindName(MomentKind kind) { return MomentFilterNames().at(size_t(kind)); }

namespace {

[[noreturn]] void Invalid(const std::string& name, const std::string& value, const std::string& valid) {
  throw std::invalid_argument("moment filtering: " + name + "=" + value + " is not valid; " + name + " takes " + valid);
}

// `whole` is the parameter's full value (for the message) when `text` is a part of it.
float ParseNumber(const std::string& name, const std::string& text, const std::string& valid, const std::string& whole = "") {
  const std::string& shown = whole.empty() ? text : whole;
  size_t used = 0;
  float v = 0;
  try {
    v = std::stof(text, &used);
  } catch (const std::exception&) {
    Invalid(name, shown, valid);
  }
  if (used != text.size() || !std::isfinite(v)) Invalid(name, shown, valid);
  return v;
}

std::string Get(const std::map<std::string, std::string>& params, const std::string& key) {
  auto it = params.find(key);
  return it == params.end() ? "auto" : it->second;
}

// Light-bleeding defaults: the fraction of visibility the kind typically leaks where two
// occluders overlap (VSM leaks most, MSM least); larger values also darken penumbrae.
float DefaultBleed(MomentKind k) {
  switch (k) {
    case MomentKind::Vsm: return 0.2f;
    case MomentKind::Esm: return 0.0f;
    case MomentKind::Evsm2: return 0.1f;
    case MomentKind::Evsm4: return 0.05f;
    case MomentKind::Msm: return 0.03f;
  }
  return 0.0f;
}

}  // namespace

MomentOptions ParseMomentOptions(const std::map<std::string, std::string>& params) {
  MomentOptions o;
  std::string filter = Get(params, "filter");
  if (filter == "auto") filter = "evsm4";
  if (!IsMomentFilter(filter)) Invalid("filter", filter, "vsm|evsm2|evsm4|esm|msm");
  o.kind = MomentKind(std::find(MomentFilterNames().begin(), MomentFilterNames().end(), filter) - MomentFilterNames().begin());

  std::string precision = Get(params, "precision");
  if (precision == "auto" || precision == "fp32") {
    o.precision = MomentPrecision::Fp32;
  } else if (precision == "fp16") {
    o.precision = MomentPrecision::Fp16;
  } else {
    Invalid("precision", precision, "fp16|fp32");
  }
  const bool fp16 = o.precision == MomentPrecision::Fp16;

  std::string msaa = Get(params, "msaa");
  if (msaa == "auto" || msaa == "1") {
    o.msaa = 1;
  } else if (msaa == "4") {
    o.msaa = 4;
  } else {
    Invalid("msaa", msaa, "1|4");
  }

  std::string blur = Get(params, "blur");
  if (blur != "auto") {
    o.blur = ParseNumber("blur", blur, "a radius in world units >= 0");
    if (o.blur < 0) Invalid("blur", blur, "a radius in world units >= 0");
  }

  std::string bleed = Get(params, "bleed");
  o.bleed = DefaultBleed(o.kind);
  if (bleed != "auto") {
    o.bleed = ParseNumber("bleed", bleed, "a number in [0, 1)");
    if (o.bleed < 0 || o.bleed >= 1) Invalid("bleed", bleed, "a number in [0, 1)");
  }

  std::string exps = Get(params, "exponents");
  const std::string validExps = "X (esm) or X,Y or X:Y (evsm: positive and negative exponent), numbers > 0, or auto";
  glm::vec2 e = o.kind == MomentKind::Esm ? glm::vec2(80.0f, 0.0f) : glm::vec2(40.0f, 5.0f);
  if (exps != "auto") {
    // A colon too: `shadowport bench` reads commas in --param values as a sweep.
    size_t comma = exps.find_first_of(",:");
    e.x = ParseNumber("exponents", exps.substr(0, comma), validExps, exps);
    if (comma != std::string::npos) e.y = ParseNumber("exponents", exps.substr(comma + 1), validExps, exps);
    if (e.x <= 0 || (comma != std::string::npos && e.y <= 0)) Invalid("exponents", exps, validExps);
    if (o.kind == MomentKind::Esm && comma != std::string::npos) Invalid("exponents", exps, "one number for esm");
  }
  if (o.kind == MomentKind::Esm) {
    o.exponents = {ClampEsmExponent(e.x, fp16), 0.0f};
  } else if (o.kind == MomentKind::Evsm2 || o.kind == MomentKind::Evsm4) {
    o.exponents = ClampEvsmExponents(e, fp16);
  }

  // Variance floor: a receiver on the occluder differs from the filtered mean by the storage's
  // rounding (half an ulp at depth 1: 3e-8 fp32, 2.4e-4 fp16); the floor must dwarf that
  // distance squared (1e-15, 6e-8) so flat receivers stay lit, and stay small enough not to
  // blur contact shadows. 100x the squared rounding distance for fp16, and the same 1e-6 floor
  // for fp32 where filtering noise (1e-7 at depth 1) is the larger term.
  o.minVariance = fp16 ? 1e-5f : 1e-6f;
  // MSM moment bias alpha. 16-bit UNORM rounds each quantised moment by up to 7.6e-6 (half of
  // 1/65535), which the dequantisation amplifies by its row sums (up to ~2.5): 6e-5 (Peters &
  // Klein's value for 64-bit maps) keeps the Hankel matrix positive definite after that. In fp32
  // the storage is exact enough, but the reconstruction also runs in fp32 and the Hankel matrix of
  // a single depth is singular without bias: 3e-5 keeps d3 far above fp32 cancellation.
  o.msmBias = fp16 ? 6e-5f : 3e-5f;
  return o;
}

std::vector<ParamSpec> MomentParamSpecs() {
  return {
      {ParamSpec::Choice, "msaa", "samples of the moment filters' depth pass (resolved into moments)", "1", 0, 0, {"1", "4"}},
      {ParamSpec::Text, "blur", "moment blur radius in world units (0 = none)", "0", 0, 0, {}},
      {ParamSpec::Text, "bleed", "light-bleeding reduction in [0, 1), or auto (per filter)", "auto", 0, 0, {}},
      {ParamSpec::Text, "exponents", "esm: c; evsm: c+,c- or c+:c- (the colon form for bench sweeps); or auto (clamped to the format)", "auto", 0, 0, {}},
      {ParamSpec::Choice, "precision", "moment storage: 16 or 32 bits per channel", "fp32", 0, 0, {"fp16", "fp32"}},
  };
}

std::vector<hlsl::Define> MomentDefines(const MomentOptions& o) {
  auto num = [](double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    std::string s = buf;
    // HLSL literals: keep them floats ("40" would be an int in a float2 constructor anyway, but
    // "1e-06" and "0" are clearer with a point where there is none).
    if (s.find_first_of(".e") == std::string::npos) s += ".0";
    return s;
  };
  return {
      {"MOMENT_KIND", std::to_string(int(o.kind))},
      {"MOMENT_FP16", o.precision == MomentPrecision::Fp16 ? "1" : "0"},
      {"MOMENT_EXP_POS", num(o.exponents.x)},
      {"MOMENT_EXP_NEG", num(o.exponents.y)},
      {"MOMENT_BLEED", num(o.bleed)},
      {"MOMENT_MIN_VARIANCE", num(o.minVariance)},
      {"MOMENT_MSM_BIAS", num(o.msmBias)},
  };
}

FORMAT MomentFormat(MomentKind kind, MomentPrecision precision) {
  const bool h = precision == MomentPrecision::Fp16;
  switch (kind) {
    case MomentKind::Esm: return h ? FORMAT_R16_FLOAT : FORMAT_R32_FLOAT;
    case MomentKind::Vsm:
    case MomentKind::Evsm2: return h ? FORMAT_R16G16_FLOAT : FORMAT_R32G32_FLOAT;
    case MomentKind::Evsm4: return h ? FORMAT_R16G16B16A16_FLOAT : FORMAT_R32G32B32A32_FLOAT;
    case MomentKind::Msm: return h ? FORMAT_R16G16B16A16_UNORM : FORMAT_R32G32B32A32_FLOAT;
  }
  return FORMAT_UNKNOWN;
}

float BlurRadiusTexels(float worldRadius, float layerWorldWidth, uint32_t layerTexels) {
  if (!(layerWorldWidth > 0) || !(worldRadius > 0)) return 0.0f;
  return std::min(worldRadius * float(layerTexels) / layerWorldWidth, kMaxBlurRadiusTexels);
}

}  // namespace sp::tech
