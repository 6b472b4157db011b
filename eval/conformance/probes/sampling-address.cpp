// Texture address modes at coordinates outside [0, 1], each mode on U and V independently, with
// point and bilinear filtering. D3D11 (functional spec, 7.18.6 "Texture Addressing") addresses
// every integer texel of the footprint on its own (n = the level's size):
//   WRAP          i mod n
//   MIRROR        i mod 2n, reflected into [0, n)
//   CLAMP         clamp(i, 0, n - 1)
//   BORDER        the sampler's BorderColor when i is outside [0, n)
//   MIRROR_ONCE   mirror once about 0 (i < 0 -> -i - 1), then CLAMP
// and then filters those texels. BorderColor is returned exactly as given for a float format.
//
// The texture is R32G32B32A32_FLOAT, 4 x 8 (unequal sides catch swapped axes), channel c of texel
// (x, y) = 0.25 c + (1 + 4 y + x) / 128, so no texel equals a border colour component.
// Tolerance: point filtering is exact; bilinear as in sampling-util.h.
#include "sampling-util.h"

namespace sp::conformance::sampling {
namespace {

constexpr uint32_t W = 4, H = 8;

// Away from texel boundaries (u * 4 and v * 8 never within 0.2 of an integer), so the point
// sampled texel is unambiguous; far enough out to reach the second repetition on both sides.
const float kU[] = {-2.2f, -1.3f, -0.6f, -0.1f, 0.3f, 0.95f, 1.1f, 1.6f, 2.35f};
const float kV[] = {-1.45f, -0.3f, 0.6f, 1.2f, 1.85f, 3.1f};

std::vector<MipChain> Channels() {
  std::vector<MipChain> ch(4, MipChain{W, H, {std::vector<float>(W * H)}});
  for (uint32_t c = 0; c < 4; ++c)
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x) ch[c].levels[0][y * W + x] = 0.25f * float(c) + float(1 + 4 * y + x) / 128.0f;
  return ch;
}

// Runs one sampler per (U, V) mode pair on every position; the case picks the sampler.
Result Run(Device& device, const std::vector<std::array<TEXTURE_ADDRESS_MODE, 2>>& pairs, const std::array<float, 4>& border,
           const std::string& name) {
  std::vector<MipChain> ch = Channels();
  std::vector<float> texels(W * H * 4);
  for (uint32_t t = 0; t < W * H; ++t)
    for (uint32_t c = 0; c < 4; ++c) texels[t * 4 + c] = ch[c].levels[0][t];
  Ref<Texture2D> tex = MakeFloatTexture(device, W, H, 4, {texels});
  Ref<ShaderResourceView> srv = device.CreateShaderResourceView(tex.get());

  std::string body = "Texture2D<float4> tex : register(t0);\n";
  for (size_t i = 0; i < pairs.size(); ++i) body += "SamplerState s" + std::to_string(i) + " : register(s" + std::to_string(i) + ");\n";
  body += "float4 Probe(Case k, uint index) {\n  switch (uint(k.b.x)) {\n";
  for (size_t i = 0; i < pairs.size(); ++i) body += "    case " + std::to_string(i) + ": return tex.SampleLevel(s" + std::to_string(i) + ", k.a.xy, 0);\n";
  body += "  }\n  return float4(-1, -1, -1, -1);\n}\n";

  std::vector<Case> cases;
  for (size_t p = 0; p < pairs.size(); ++p)
    for (float u : kU)
      for (float v : kV) cases.push_back({{u, v, 0, 0}, {float(p), 0, 0, 0}});

  Worst worst;
  for (bool linear : {false, true}) {
    std::vector<Ref<SamplerState>> keep;
    std::vector<SamplerState*> samplers;
    for (auto& pr : pairs) {
      SAMPLER_DESC d;
      d.Filter = linear ? FILTER_MIN_MAG_MIP_LINEAR : FILTER_MIN_MAG_MIP_POINT;
      d.AddressU = pr[0];
      d.AddressV = pr[1];
      for (int c = 0; c < 4; ++c) d.BorderColor[c] = border[c];
      try {
        keep.push_back(MakeSampler(device, d));
      } catch (const Error& e) {
        if (e.id() == ErrorId::NOT_SUPPORTED) return Unsupported(e.detail());
        throw;
      }
      samplers.push_back(keep.back().get());
    }
    std::vector<Float4> got = RunCompute(device, body, name, cases, {srv.get()}, samplers);
    for (size_t i = 0; i < cases.size(); ++i) {
      auto& pr = pairs[size_t(cases[i].b[0])];
      for (int c = 0; c < 4; ++c) {
        SamplerModel m;
        m.linear = linear;
        m.u = pr[0];
        m.v = pr[1];
        m.border = border[c];
        Expected e = SampleLevelCpu(ch[c], 0, cases[i].a[0], cases[i].a[1], m);
        worst.Add(got[i][c], e,
                  std::string(linear ? "linear" : "point") + " U " + AddressName(pr[0]) + " V " + AddressName(pr[1]) + " uv (" + Fmt(cases[i].a[0]) +
                      ", " + Fmt(cases[i].a[1]) + ") ." + "xyzw"[c]);
      }
    }
  }
  return worst.Finish("abs");
}

const TEXTURE_ADDRESS_MODE kNonBorder[] = {TEXTURE_ADDRESS_WRAP, TEXTURE_ADDRESS_MIRROR, TEXTURE_ADDRESS_CLAMP, TEXTURE_ADDRESS_MIRROR_ONCE};

// BORDER on U, on V and on both, the other axis taking every other mode.
std::vector<std::array<TEXTURE_ADDRESS_MODE, 2>> BorderPairs() {
  std::vector<std::array<TEXTURE_ADDRESS_MODE, 2>> p = {{TEXTURE_ADDRESS_BORDER, TEXTURE_ADDRESS_BORDER}};
  for (TEXTURE_ADDRESS_MODE m : kNonBorder) {
    p.push_back({TEXTURE_ADDRESS_BORDER, m});
    p.push_back({m, TEXTURE_ADDRESS_BORDER});
  }
  return p;
}

}  // namespace

SP_PROBE(kGroup, "WRAP, MIRROR, CLAMP, MIRROR_ONCE on U and V independently", "every pair of the four modes, point and bilinear, at u, v outside [0, 1]") {
  std::vector<std::array<TEXTURE_ADDRESS_MODE, 2>> pairs;
  for (TEXTURE_ADDRESS_MODE u : kNonBorder)
    for (TEXTURE_ADDRESS_MODE v : kNonBorder) pairs.push_back({u, v});
  return Run(device, pairs, {1, 1, 1, 1}, "sampling-address");
}
SP_PROBE(kGroup, "BORDER with transparent black (0,0,0,0)", "outside texels read (0,0,0,0); BORDER on U, V or both, the other axis any mode") {
  return Run(device, BorderPairs(), {0, 0, 0, 0}, "sampling-border");
}
SP_PROBE(kGroup, "BORDER with opaque white (1,1,1,1)", "outside texels read (1,1,1,1); BORDER on U, V or both, the other axis any mode") {
  return Run(device, BorderPairs(), {1, 1, 1, 1}, "sampling-border");
}
SP_PROBE(kGroup, "BORDER with an arbitrary colour (0.25, 0.5, 0.75, 0.125)", "outside texels read the sampler's BorderColor exactly, per channel") {
  return Run(device, BorderPairs(), {0.25f, 0.5f, 0.75f, 0.125f}, "sampling-border");
}

}  // namespace sp::conformance::sampling
