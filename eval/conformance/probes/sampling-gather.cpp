// Gather4 (Gather, GatherRed/Green/Blue/Alpha) and comparison gather (GatherCmp, GatherCmpRed).
// D3D11 (functional spec, 7.18.5 "gather4") returns the four texels bilinear filtering would use,
// unfiltered, in the order
//   x = (i0, j1), y = (i1, j1), z = (i1, j0), w = (i0, j0)
// with i0 = floor(u * W - 0.5), j0 = floor(v * H - 0.5), i1 = i0 + 1, j1 = j0 + 1 (j counts memory
// rows, so j1 is the row below j0), each texel addressed on its own (CLAMP, WRAP, ...). A constant
// offset (int2 in [-8, 7]) moves i0 and j0 in texel space before addressing. Gather returns texel
// values unchanged and GatherCmp returns 0/1, so every component must match exactly.
//
// The texture holds a distinct value per texel and channel (1000 * channel + 16 * y + x + 1), so a
// wrong order, row, channel or addressing shows up as a different number.
#include "sampling-util.h"

namespace sp::conformance::sampling {
namespace {

constexpr uint32_t W = 8, H = 4;

float TexelValue(uint32_t c, uint32_t x, uint32_t y) { return float(1000 * c + 16 * y + x + 1); }

// Texel-space positions (s = u * W - 0.5, t = v * H - 0.5): 1/64 texel either side of texel
// boundaries (far more than D3D11's 1/256 subtexel precision, so the side is unambiguous), exactly
// on them (fraction 0 selects i0 = s), and past every edge.
const std::array<double, 2> kPositions[] = {
    {1.0 + 1.0 / 64, 2.0 - 1.0 / 64}, {2.0 - 1.0 / 64, 1.0 + 1.0 / 64}, {3.0, 1.0}, {0.5, 0.5}, {-0.4, 1.2}, {7.3, 2.6},
    {-1.0 / 64, -1.0 / 64}, {7.0 + 1.0 / 64, 3.0 + 1.0 / 64}, {-0.9, 2.9}, {4.75, -0.75}};

struct Variant {
  std::string method;  // "Gather", "GatherGreen", "GatherCmp", ...
  int channel = 0;     // what it reads (comparison: 0)
  bool offset = false;
  int ox = 0, oy = 0;
  int sampler = 0;  // index into kModes
};

const std::array<TEXTURE_ADDRESS_MODE, 2> kModes[] = {
    {TEXTURE_ADDRESS_CLAMP, TEXTURE_ADDRESS_CLAMP}, {TEXTURE_ADDRESS_WRAP, TEXTURE_ADDRESS_WRAP}, {TEXTURE_ADDRESS_WRAP, TEXTURE_ADDRESS_CLAMP}};
// Variants per shader: llvmpipe's GL compiler (Mesa 22.3) sends switch cases beyond about the
// 79th to the wrong label, so one large switch would test that instead of Gather.
constexpr size_t kChunk = 32;

const std::array<int, 2> kOffsets[] = {{0, 0}, {-8, 7}, {7, -8}, {1, -1}, {-3, 2}, {5, 5}};

bool IsCmp(const Variant& v) { return v.method.rfind("GatherCmp", 0) == 0; }

std::string Describe(const Variant& v) {
  std::string s = v.method + " " + AddressName(kModes[v.sampler][0]) + "/" + AddressName(kModes[v.sampler][1]);
  if (v.offset) s += " offset (" + std::to_string(v.ox) + "," + std::to_string(v.oy) + ")";
  return s;
}

// HLSL: one switch over the variants, each a Gather call with its literal offset.
std::string Body(const std::vector<Variant>& variants, bool cmp) {
  std::string s = cmp ? "Texture2D<float> tex : register(t0);\n" : "Texture2D<float4> tex : register(t0);\n";
  for (size_t i = 0; i < std::size(kModes); ++i)
    s += std::string(cmp ? "SamplerComparisonState" : "SamplerState") + " s" + std::to_string(i) + " : register(s" + std::to_string(i) + ");\n";
  s += "float4 Probe(Case k, uint index) {\n  switch (uint(k.b.x)) {\n";
  for (size_t i = 0; i < variants.size(); ++i) {
    const Variant& v = variants[i];
    s += "    case " + std::to_string(i) + ": return tex." + v.method + "(s" + std::to_string(v.sampler) + ", k.a.xy" + (cmp ? ", k.a.z" : "");
    if (v.offset) s += ", int2(" + std::to_string(v.ox) + ", " + std::to_string(v.oy) + ")";
    s += ");\n";
  }
  s += "  }\n  return float4(-1, -1, -1, -1);\n}\n";
  return s;
}

Result Run(Device& device, const std::vector<Variant>& variants, const std::string& name) {
  const bool cmp = IsCmp(variants.front());
  const uint32_t need = cmp ? FORMAT_SUPPORT_SHADER_GATHER_COMPARISON : FORMAT_SUPPORT_SHADER_GATHER;
  const FORMAT fmt = cmp ? FORMAT_R32_FLOAT : FORMAT_R32G32B32A32_FLOAT;
  if (!(device.CheckFormatSupport(fmt) & need)) return Unsupported(std::string(FormatName(fmt)) + " does not support " + (cmp ? "GatherCmp" : "Gather"));

  // Comparison: depths k/64 and LESS_EQUAL, references on a texel value and between values.
  std::vector<float> depths(W * H);
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) depths[y * W + x] = float(1 + (x * 37 + y * 11) % 62) / 64.0f;
  std::vector<float> texels(W * H * 4);
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x)
      for (uint32_t c = 0; c < 4; ++c) texels[(y * W + x) * 4 + c] = TexelValue(c, x, y);

  std::vector<Ref<SamplerState>> keep;
  std::vector<SamplerState*> samplers;
  for (auto& m : kModes) {
    SAMPLER_DESC d;
    d.Filter = cmp ? FILTER_COMPARISON_MIN_MAG_LINEAR_MIP_POINT : FILTER_MIN_MAG_MIP_LINEAR;
    d.ComparisonFunc = COMPARISON_LESS_EQUAL;
    d.AddressU = m[0];
    d.AddressV = m[1];
    keep.push_back(MakeSampler(device, d));
    samplers.push_back(keep.back().get());
  }
  const std::vector<float> refs = cmp ? std::vector<float>{depths[W + 2], 0.5f + 1.0f / 128, depths[2 * W + 5]} : std::vector<float>{0.0f};

  std::vector<Case> cases;
  for (size_t vi = 0; vi < variants.size(); ++vi)
    for (auto [sx, sy] : kPositions)
      for (float r : refs) cases.push_back({{float((sx + 0.5) / W), float((sy + 0.5) / H), r, 0}, {float(vi % kChunk), float(vi), 0, 0}});

  Ref<Texture2D> colour;
  Ref<ShaderResourceView> srv;
  DepthTexture depth;
  if (cmp) {
    depth = MakeDepthTexture(device, W, H, depths, false);
    srv = depth.srv;
  } else {
    colour = MakeFloatTexture(device, W, H, 4, {texels});
    srv = device.CreateShaderResourceView(colour.get());
  }
  std::vector<Float4> got;
  for (size_t first = 0; first < variants.size(); first += kChunk) {
    std::vector<Variant> chunk(variants.begin() + first, variants.begin() + std::min(variants.size(), first + kChunk));
    std::vector<Case> chunkCases;
    for (const Case& c : cases)
      if (size_t(c.b[1]) >= first && size_t(c.b[1]) < first + kChunk) chunkCases.push_back(c);
    std::vector<Float4> part = RunCompute(device, Body(chunk, cmp), name, chunkCases, {srv.get()}, samplers);
    got.insert(got.end(), part.begin(), part.end());
  }

  Worst worst;
  static const char* kComp = "xyzw";
  for (size_t i = 0; i < cases.size(); ++i) {
    const Variant& v = variants[size_t(cases[i].b[1])];
    const double u = cases[i].a[0], vv = cases[i].a[1], ref = cases[i].a[2];
    const int i0 = int(std::floor(u * W - 0.5)) + (v.offset ? v.ox : 0), j0 = int(std::floor(vv * H - 0.5)) + (v.offset ? v.oy : 0);
    const int pos[4][2] = {{i0, j0 + 1}, {i0 + 1, j0 + 1}, {i0 + 1, j0}, {i0, j0}};
    for (int c = 0; c < 4; ++c) {
      int x = AddressTexel(kModes[v.sampler][0], pos[c][0], W), y = AddressTexel(kModes[v.sampler][1], pos[c][1], H);
      double expected = cmp ? (ref <= depths[y * W + x] ? 1.0 : 0.0) : TexelValue(uint32_t(v.channel), uint32_t(x), uint32_t(y));
      worst.Add(got[i][c], {expected, 0.0},
                Describe(v) + " uv (" + Fmt(u) + ", " + Fmt(vv) + ")" + (cmp ? " ref " + Fmt(ref) : "") + " ." + kComp[c] + " = texel (" +
                    std::to_string(x) + "," + std::to_string(y) + ")");
    }
  }
  return worst.Finish("abs");
}

std::vector<Variant> Variants(const std::vector<std::pair<std::string, int>>& methods, bool withOffsets, bool withoutOffset) {
  std::vector<Variant> out;
  for (auto& [method, channel] : methods)
    for (int s = 0; s < int(std::size(kModes)); ++s) {
      if (withoutOffset) out.push_back({method, channel, false, 0, 0, s});
      if (withOffsets)
        for (auto& o : kOffsets) out.push_back({method, channel, true, o[0], o[1], s});
    }
  return out;
}

}  // namespace

SP_PROBE(kGroup, "Gather component order and texel selection (CLAMP, WRAP)",
         "Gather returns (i0,j1), (i1,j1), (i1,j0), (i0,j0) of the red channel, i0 = floor(u*W - 0.5), each texel addressed") {
  return Run(device, Variants({{"Gather", 0}}, false, true), "sampling-gather");
}
SP_PROBE(kGroup, "GatherRed/Green/Blue/Alpha channel and order", "GatherRed/Green/Blue/Alpha return one channel of the four footprint texels in Gather's order") {
  return Run(device, Variants({{"GatherRed", 0}, {"GatherGreen", 1}, {"GatherBlue", 2}, {"GatherAlpha", 3}}, false, true), "sampling-gather-channels");
}
SP_PROBE(kGroup, "Gather* with constant offsets in [-8, 7]", "an immediate offset moves i0, j0 in texel space before addressing (CLAMP, WRAP)") {
  return Run(device, Variants({{"Gather", 0}, {"GatherRed", 0}, {"GatherGreen", 1}, {"GatherBlue", 2}, {"GatherAlpha", 3}}, true, false),
             "sampling-gather-offsets");
}
SP_PROBE(kGroup, "GatherCmp component order, LESS_EQUAL", "GatherCmp returns the four 0/1 results of ref <= texel in Gather's order") {
  return Run(device, Variants({{"GatherCmp", 0}}, false, true), "sampling-gathercmp");
}
SP_PROBE(kGroup, "GatherCmpRed without offset", "GatherCmpRed equals GatherCmp: the four 0/1 comparison results in Gather's order") {
  return Run(device, Variants({{"GatherCmpRed", 0}}, false, true), "sampling-gathercmpred");
}
SP_PROBE(kGroup, "GatherCmp/GatherCmpRed with constant offsets", "an immediate offset moves the comparison footprint before addressing") {
  return Run(device, Variants({{"GatherCmp", 0}, {"GatherCmpRed", 0}}, true, false), "sampling-gathercmp-offsets");
}

}  // namespace sp::conformance::sampling
