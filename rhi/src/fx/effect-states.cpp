// State-object fields of effect files, with FX11's names and value spellings (case-insensitive,
// or numbers: the D3D11 enum values), into sp::*_DESC fields.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>

#include "effect-parse.h"

namespace sp::fx {

const char* StateTypeName(StateType t) {
  switch (t) {
    case StateType::Rasterizer: return "RasterizerState";
    case StateType::DepthStencil: return "DepthStencilState";
    case StateType::Blend: return "BlendState";
    case StateType::Sampler: return "SamplerState";
    case StateType::SamplerComparison: return "SamplerComparisonState";
  }
  return "?";
}

namespace detail {
namespace {

using hlsl::compat::Source;
using hlsl::compat::TokenKind;

std::string Upper(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::toupper(c)); });
  return s;
}

struct Named {
  const char* name;
  uint32_t value;
};

constexpr Named kBools[] = {{"FALSE", 0}, {"TRUE", 1}};
constexpr Named kFill[] = {{"WIREFRAME", FILL_WIREFRAME}, {"SOLID", FILL_SOLID}};
constexpr Named kCull[] = {{"NONE", CULL_NONE}, {"FRONT", CULL_FRONT}, {"BACK", CULL_BACK}};
constexpr Named kCompare[] = {{"NEVER", COMPARISON_NEVER},       {"LESS", COMPARISON_LESS},
                              {"EQUAL", COMPARISON_EQUAL},       {"LESS_EQUAL", COMPARISON_LESS_EQUAL},
                              {"GREATER", COMPARISON_GREATER},   {"NOT_EQUAL", COMPARISON_NOT_EQUAL},
                              {"GREATER_EQUAL", COMPARISON_GREATER_EQUAL}, {"ALWAYS", COMPARISON_ALWAYS}};
constexpr Named kWriteMask[] = {{"ZERO", DEPTH_WRITE_MASK_ZERO}, {"ALL", DEPTH_WRITE_MASK_ALL}};
constexpr Named kStencilOp[] = {{"KEEP", STENCIL_OP_KEEP},         {"ZERO", STENCIL_OP_ZERO},
                                {"REPLACE", STENCIL_OP_REPLACE},   {"INCR_SAT", STENCIL_OP_INCR_SAT},
                                {"DECR_SAT", STENCIL_OP_DECR_SAT}, {"INVERT", STENCIL_OP_INVERT},
                                {"INCR", STENCIL_OP_INCR},         {"DECR", STENCIL_OP_DECR}};
constexpr Named kBlend[] = {{"ZERO", BLEND_ZERO},
                            {"ONE", BLEND_ONE},
                            {"SRC_COLOR", BLEND_SRC_COLOR},
                            {"INV_SRC_COLOR", BLEND_INV_SRC_COLOR},
                            {"SRC_ALPHA", BLEND_SRC_ALPHA},
                            {"INV_SRC_ALPHA", BLEND_INV_SRC_ALPHA},
                            {"DEST_ALPHA", BLEND_DEST_ALPHA},
                            {"INV_DEST_ALPHA", BLEND_INV_DEST_ALPHA},
                            {"DEST_COLOR", BLEND_DEST_COLOR},
                            {"INV_DEST_COLOR", BLEND_INV_DEST_COLOR},
                            {"SRC_ALPHA_SAT", BLEND_SRC_ALPHA_SAT},
                            {"BLEND_FACTOR", BLEND_BLEND_FACTOR},
                            {"INV_BLEND_FACTOR", BLEND_INV_BLEND_FACTOR},
                            {"SRC1_COLOR", BLEND_SRC1_COLOR},
                            {"INV_SRC1_COLOR", BLEND_INV_SRC1_COLOR},
                            {"SRC1_ALPHA", BLEND_SRC1_ALPHA},
                            {"INV_SRC1_ALPHA", BLEND_INV_SRC1_ALPHA}};
constexpr Named kBlendOp[] = {{"ADD", BLEND_OP_ADD},
                              {"SUBTRACT", BLEND_OP_SUBTRACT},
                              {"REV_SUBTRACT", BLEND_OP_REV_SUBTRACT},
                              {"MIN", BLEND_OP_MIN},
                              {"MAX", BLEND_OP_MAX}};
constexpr Named kAddress[] = {{"WRAP", TEXTURE_ADDRESS_WRAP},
                              {"MIRROR", TEXTURE_ADDRESS_MIRROR},
                              {"CLAMP", TEXTURE_ADDRESS_CLAMP},
                              {"BORDER", TEXTURE_ADDRESS_BORDER},
                              {"MIRROR_ONCE", TEXTURE_ADDRESS_MIRROR_ONCE}};
// The filter names are the D3D11_FILTER_ names without the prefix; the reduction prefixes
// (COMPARISON_, MINIMUM_, MAXIMUM_) go with each min/mag/mip combination.
constexpr Named kFilterBase[] = {{"MIN_MAG_MIP_POINT", 0x0},
                                 {"MIN_MAG_POINT_MIP_LINEAR", 0x1},
                                 {"MIN_POINT_MAG_LINEAR_MIP_POINT", 0x4},
                                 {"MIN_POINT_MAG_MIP_LINEAR", 0x5},
                                 {"MIN_LINEAR_MAG_MIP_POINT", 0x10},
                                 {"MIN_LINEAR_MAG_POINT_MIP_LINEAR", 0x11},
                                 {"MIN_MAG_LINEAR_MIP_POINT", 0x14},
                                 {"MIN_MAG_MIP_LINEAR", 0x15},
                                 {"ANISOTROPIC", 0x55}};
constexpr Named kFilterReduction[] = {{"", 0}, {"COMPARISON_", 0x80}, {"MINIMUM_", 0x100}, {"MAXIMUM_", 0x180}};

std::vector<Named> FilterNames() {
  std::vector<Named> v;
  static std::vector<std::string> storage;  // names live for the process
  if (storage.empty())
    for (const Named& r : kFilterReduction)
      for (const Named& b : kFilterBase) storage.push_back(std::string(r.name) + b.name);
  size_t k = 0;
  for (const Named& r : kFilterReduction)
    for (const Named& b : kFilterBase) v.push_back({storage[k++].c_str(), r.value | b.value});
  return v;
}

template <size_t N>
std::vector<Named> Vec(const Named (&a)[N]) {
  return std::vector<Named>(a, a + N);
}

std::string Spellings(const std::vector<Named>& names) {
  std::string s;
  for (const Named& n : names) s += (s.empty() ? "" : ", ") + std::string(n.name);
  return s;
}

// What a field's value may be.
enum class ValueKind { Enum, Bool, Int, Uint8, Float, Float4 };

struct Value {
  uint32_t u = 0;
  double f = 0;
  float f4[4] = {0, 0, 0, 0};
  std::string spelling;  // normalised, for setFields
};

Value ReadValue(const Source& src, size_t fieldToken, size_t first, size_t last, ValueKind kind, const std::vector<Named>& names) {
  const std::string& field = src[fieldToken].text;
  Value v;
  if (first >= last) src.Fail(fieldToken, "effect state field '" + field + "' has no value");
  if (kind == ValueKind::Float4) {
    // float4(r, g, b, a)
    if (!(src[first].Is("float4") && src.Is(first + 1, "(") && src.Matching(first + 1) == last - 1))
      src.Fail(first, "effect state field '" + field + "' takes float4(r, g, b, a), not '" + src.Text(first, last) + "'");
    auto parts = src.SplitCommas(first + 2, last - 1);
    if (parts.size() != 4) src.Fail(first, "effect state field '" + field + "' takes float4 with 4 components");
    v.spelling = "float4(";
    for (size_t i = 0; i < 4; ++i) {
      double d;
      if (!ParseNumber(src, parts[i].first, parts[i].second, &d))
        src.Fail(parts[i].first, "effect state field '" + field + "': '" + src.Text(parts[i].first, parts[i].second) + "' is not a number");
      v.f4[i] = float(d);
      char buf[32];
      std::snprintf(buf, sizeof buf, "%g", d);
      v.spelling += (i ? ", " : "") + std::string(buf);
    }
    v.spelling += ")";
    return v;
  }
  if (last - first == 1 && src[first].IsIdentifier()) {
    std::string u = Upper(src[first].text);
    const std::vector<Named>& table = kind == ValueKind::Bool ? Vec(kBools) : names;
    for (const Named& n : table)
      if (u == n.name) {
        v.u = n.value;
        v.f = n.value;
        v.spelling = n.name;
        return v;
      }
    if (kind == ValueKind::Enum || kind == ValueKind::Bool)
      src.Fail(first, "unknown value '" + src[first].text + "' for effect state field '" + field + "' (valid: " +
                          Spellings(kind == ValueKind::Bool ? Vec(kBools) : names) + ", or a number)");
  }
  double d;
  if (!ParseNumber(src, first, last, &d))
    src.Fail(first, "effect state field '" + field + "': '" + src.Text(first, last) + "' is not a value this field takes" +
                        (names.empty() ? std::string() : " (valid: " + Spellings(names) + ", or a number)"));
  v.f = d;
  if (kind != ValueKind::Float) {
    if (d != std::floor(d)) src.Fail(first, "effect state field '" + field + "' takes an integer, not '" + src.Text(first, last) + "'");
    if (kind == ValueKind::Uint8 && (d < 0 || d > 255)) src.Fail(first, "effect state field '" + field + "' takes 0 to 255");
    v.u = uint32_t(int64_t(d));
  }
  if (kind == ValueKind::Enum) {
    bool known = false;
    for (const Named& n : names)
      if (n.value == v.u) {
        known = true;
        v.spelling = n.name;
      }
    if (!known) src.Fail(first, "effect state field '" + field + "': " + src.Text(first, last) + " is not a valid value (valid: " + Spellings(names) + ")");
  } else if (kind == ValueKind::Bool) {
    v.spelling = v.u ? "TRUE" : "FALSE";
  } else if (kind == ValueKind::Uint8) {
    v.spelling = src.Text(first, last);  // masks read best as written (0x0F)
  } else {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", d);
    v.spelling = buf;
  }
  return v;
}

// One settable field: its name, value kind and where it goes. `index` is the [N] (render target
// for blend fields), -1 when absent.
struct Field {
  const char* name;
  ValueKind kind;
  std::vector<Named> names;
  bool indexed;  // takes [N] (blend render-target fields)
  std::function<void(StateObjectDesc&, int index, const Value&)> set;
};

#define SP_FIELD(desc, member, cast) [](StateObjectDesc& s, int, const Value& v) { s.desc.member = cast; }

const std::vector<Field>& RasterizerFields() {
  static const std::vector<Field> f = {
      {"FillMode", ValueKind::Enum, Vec(kFill), false, SP_FIELD(rasterizer, FillMode, FILL_MODE(v.u))},
      {"CullMode", ValueKind::Enum, Vec(kCull), false, SP_FIELD(rasterizer, CullMode, CULL_MODE(v.u))},
      {"FrontCounterClockwise", ValueKind::Bool, {}, false, SP_FIELD(rasterizer, FrontCounterClockwise, v.u != 0)},
      {"DepthBias", ValueKind::Int, {}, false, SP_FIELD(rasterizer, DepthBias, int32_t(int64_t(v.f)))},
      {"DepthBiasClamp", ValueKind::Float, {}, false, SP_FIELD(rasterizer, DepthBiasClamp, float(v.f))},
      {"SlopeScaledDepthBias", ValueKind::Float, {}, false, SP_FIELD(rasterizer, SlopeScaledDepthBias, float(v.f))},
      {"DepthClipEnable", ValueKind::Bool, {}, false, SP_FIELD(rasterizer, DepthClipEnable, v.u != 0)},
      {"ScissorEnable", ValueKind::Bool, {}, false, SP_FIELD(rasterizer, ScissorEnable, v.u != 0)},
      {"MultisampleEnable", ValueKind::Bool, {}, false, SP_FIELD(rasterizer, MultisampleEnable, v.u != 0)},
      {"AntialiasedLineEnable", ValueKind::Bool, {}, false, SP_FIELD(rasterizer, AntialiasedLineEnable, v.u != 0)},
  };
  return f;
}

const std::vector<Field>& DepthStencilFields() {
  static const std::vector<Field> f = {
      {"DepthEnable", ValueKind::Bool, {}, false, SP_FIELD(depthStencil, DepthEnable, v.u != 0)},
      {"DepthWriteMask", ValueKind::Enum, Vec(kWriteMask), false, SP_FIELD(depthStencil, DepthWriteMask, DEPTH_WRITE_MASK(v.u))},
      {"DepthFunc", ValueKind::Enum, Vec(kCompare), false, SP_FIELD(depthStencil, DepthFunc, COMPARISON_FUNC(v.u))},
      {"StencilEnable", ValueKind::Bool, {}, false, SP_FIELD(depthStencil, StencilEnable, v.u != 0)},
      {"StencilReadMask", ValueKind::Uint8, {}, false, SP_FIELD(depthStencil, StencilReadMask, uint8_t(v.u))},
      {"StencilWriteMask", ValueKind::Uint8, {}, false, SP_FIELD(depthStencil, StencilWriteMask, uint8_t(v.u))},
      {"FrontFaceStencilFail", ValueKind::Enum, Vec(kStencilOp), false, SP_FIELD(depthStencil, FrontFace.StencilFailOp, STENCIL_OP(v.u))},
      {"FrontFaceStencilDepthFail", ValueKind::Enum, Vec(kStencilOp), false, SP_FIELD(depthStencil, FrontFace.StencilDepthFailOp, STENCIL_OP(v.u))},
      {"FrontFaceStencilPass", ValueKind::Enum, Vec(kStencilOp), false, SP_FIELD(depthStencil, FrontFace.StencilPassOp, STENCIL_OP(v.u))},
      {"FrontFaceStencilFunc", ValueKind::Enum, Vec(kCompare), false, SP_FIELD(depthStencil, FrontFace.StencilFunc, COMPARISON_FUNC(v.u))},
      {"BackFaceStencilFail", ValueKind::Enum, Vec(kStencilOp), false, SP_FIELD(depthStencil, BackFace.StencilFailOp, STENCIL_OP(v.u))},
      {"BackFaceStencilDepthFail", ValueKind::Enum, Vec(kStencilOp), false, SP_FIELD(depthStencil, BackFace.StencilDepthFailOp, STENCIL_OP(v.u))},
      {"BackFaceStencilPass", ValueKind::Enum, Vec(kStencilOp), false, SP_FIELD(depthStencil, BackFace.StencilPassOp, STENCIL_OP(v.u))},
      {"BackFaceStencilFunc", ValueKind::Enum, Vec(kCompare), false, SP_FIELD(depthStencil, BackFace.StencilFunc, COMPARISON_FUNC(v.u))},
  };
  return f;
}

// A render-target field without [N] sets every render target (D3D10's shared blend factors);
// with [N] only that one. FinishState turns differences into IndependentBlendEnable.
#define SP_RT_FIELD(member, cast)                                                     \
  [](StateObjectDesc& s, int index, const Value& v) {                                 \
    for (int i = 0; i < int(SIMULTANEOUS_RENDER_TARGET_COUNT); ++i)                   \
      if (index < 0 || index == i) s.blend.RenderTarget[i].member = cast;             \
  }

const std::vector<Field>& BlendFields() {
  static const std::vector<Field> f = {
      {"AlphaToCoverageEnable", ValueKind::Bool, {}, false, SP_FIELD(blend, AlphaToCoverageEnable, v.u != 0)},
      {"IndependentBlendEnable", ValueKind::Bool, {}, false, SP_FIELD(blend, IndependentBlendEnable, v.u != 0)},
      {"BlendEnable", ValueKind::Bool, {}, true, SP_RT_FIELD(BlendEnable, v.u != 0)},
      {"SrcBlend", ValueKind::Enum, Vec(kBlend), true, SP_RT_FIELD(SrcBlend, BLEND(v.u))},
      {"DestBlend", ValueKind::Enum, Vec(kBlend), true, SP_RT_FIELD(DestBlend, BLEND(v.u))},
      {"BlendOp", ValueKind::Enum, Vec(kBlendOp), true, SP_RT_FIELD(BlendOp, BLEND_OP(v.u))},
      {"SrcBlendAlpha", ValueKind::Enum, Vec(kBlend), true, SP_RT_FIELD(SrcBlendAlpha, BLEND(v.u))},
      {"DestBlendAlpha", ValueKind::Enum, Vec(kBlend), true, SP_RT_FIELD(DestBlendAlpha, BLEND(v.u))},
      {"BlendOpAlpha", ValueKind::Enum, Vec(kBlendOp), true, SP_RT_FIELD(BlendOpAlpha, BLEND_OP(v.u))},
      {"RenderTargetWriteMask", ValueKind::Uint8, {}, true, SP_RT_FIELD(RenderTargetWriteMask, uint8_t(v.u & 15))},
  };
  return f;
}

const std::vector<Field>& SamplerFields() {
  static const std::vector<Field> f = {
      {"Filter", ValueKind::Enum, FilterNames(), false, SP_FIELD(sampler, Filter, FILTER(v.u))},
      {"AddressU", ValueKind::Enum, Vec(kAddress), false, SP_FIELD(sampler, AddressU, TEXTURE_ADDRESS_MODE(v.u))},
      {"AddressV", ValueKind::Enum, Vec(kAddress), false, SP_FIELD(sampler, AddressV, TEXTURE_ADDRESS_MODE(v.u))},
      {"AddressW", ValueKind::Enum, Vec(kAddress), false, SP_FIELD(sampler, AddressW, TEXTURE_ADDRESS_MODE(v.u))},
      {"MipLODBias", ValueKind::Float, {}, false, SP_FIELD(sampler, MipLODBias, float(v.f))},
      {"MaxAnisotropy", ValueKind::Int, {}, false, SP_FIELD(sampler, MaxAnisotropy, v.u)},
      {"ComparisonFunc", ValueKind::Enum, Vec(kCompare), false, SP_FIELD(sampler, ComparisonFunc, COMPARISON_FUNC(v.u))},
      {"BorderColor", ValueKind::Float4, {}, false,
       [](StateObjectDesc& s, int, const Value& v) { std::copy(v.f4, v.f4 + 4, s.sampler.BorderColor); }},
      {"MinLOD", ValueKind::Float, {}, false, SP_FIELD(sampler, MinLOD, float(v.f))},
      {"MaxLOD", ValueKind::Float, {}, false, SP_FIELD(sampler, MaxLOD, float(v.f))},
  };
  return f;
}

const std::vector<Field>& FieldsOf(StateType t) {
  switch (t) {
    case StateType::Rasterizer: return RasterizerFields();
    case StateType::DepthStencil: return DepthStencilFields();
    case StateType::Blend: return BlendFields();
    default: return SamplerFields();
  }
}

}  // namespace

bool ParseNumber(const Source& src, size_t first, size_t last, double* value) {
  bool negative = false;
  if (first < last && (src[first].Is("-") || src[first].Is("+"))) {
    negative = src[first].Is("-");
    ++first;
  }
  if (last - first != 1) return false;
  const auto& t = src[first];
  if (t.IsIdentifier()) {
    std::string u = Upper(t.text);
    if (u == "TRUE" || u == "FALSE") {
      *value = u == "TRUE" ? 1 : 0;
      return !negative;
    }
    return false;
  }
  if (t.kind != TokenKind::Number) return false;
  std::string s = t.text;
  char* end = nullptr;
  double d;
  if (s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) {
    while (!s.empty() && (s.back() == 'u' || s.back() == 'U' || s.back() == 'l' || s.back() == 'L')) s.pop_back();
    d = double(std::strtoull(s.c_str(), &end, 16));
  } else {
    while (!s.empty() && std::strchr("fFhHuUlL", s.back())) s.pop_back();
    d = std::strtod(s.c_str(), &end);
  }
  if (!end || *end) return false;
  *value = negative ? -d : d;
  return true;
}

void SetStateField(StateObjectDesc& state, const Source& src, size_t fieldToken, int index, size_t first, size_t last) {
  const std::string& name = src[fieldToken].text;
  const std::vector<Field>& fields = FieldsOf(state.type);
  for (const Field& f : fields) {
    if (Upper(name) != Upper(f.name)) continue;
    if (index >= 0 && !f.indexed)
      src.Fail(fieldToken, std::string("effect state field '") + f.name + "' of " + StateTypeName(state.type) + " takes no [index]");
    if (index >= int(SIMULTANEOUS_RENDER_TARGET_COUNT))
      src.Fail(fieldToken, std::string("effect state field '") + f.name + "[" + std::to_string(index) + "]': render targets are 0 to 7");
    Value v = ReadValue(src, fieldToken, first, last, f.kind, f.names);
    f.set(state, index, v);
    state.setFields.push_back(std::string(f.name) + (index >= 0 ? "[" + std::to_string(index) + "]" : "") + " = " + v.spelling);
    return;
  }
  std::string valid;
  for (const Field& f : fields) valid += (valid.empty() ? "" : ", ") + std::string(f.name);
  if (Upper(name) == "TEXTURE")
    src.Fail(fieldToken, "'Texture' in a sampler state is Direct3D 9 effect syntax: bind the texture in the shader code instead");
  src.Fail(fieldToken, "unknown field '" + name + "' in " + StateTypeName(state.type) + " '" + state.name + "' (valid: " + valid + ")");
}

void FinishState(StateObjectDesc& state) {
  if (state.type != StateType::Blend) return;
  auto same = [](const RENDER_TARGET_BLEND_DESC& a, const RENDER_TARGET_BLEND_DESC& b) {
    return a.BlendEnable == b.BlendEnable && a.SrcBlend == b.SrcBlend && a.DestBlend == b.DestBlend && a.BlendOp == b.BlendOp &&
           a.SrcBlendAlpha == b.SrcBlendAlpha && a.DestBlendAlpha == b.DestBlendAlpha && a.BlendOpAlpha == b.BlendOpAlpha &&
           a.RenderTargetWriteMask == b.RenderTargetWriteMask;
  };
  for (uint32_t i = 1; i < SIMULTANEOUS_RENDER_TARGET_COUNT; ++i)
    if (!same(state.blend.RenderTarget[i], state.blend.RenderTarget[0])) state.blend.IndependentBlendEnable = true;
}

}  // namespace detail
}  // namespace sp::fx
