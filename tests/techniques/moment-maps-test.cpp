// MomentMaps end to end on small arrays: depth -> moments (1x and 4x), blur, mips and lookups
// through moments.hlsli with the map's own defines and sampler. CPU expectations are computed
// here (double precision moments, separable blur) and compared with the stated tolerances.
#include <algorithm>
#include <cmath>
#include <limits>

#include "backend-test.h"
#include <sp/tech/gpu-timer.h>
#include "moments/moment-maps.h"

namespace sp::test {
namespace {

using tech::MomentKind;
using tech::MomentMapDesc;
using tech::MomentMaps;
using tech::MomentOptions;
using tech::MomentPrecision;
using Texels = std::vector<glm::vec4>;

const float kInf = std::numeric_limits<float>::infinity(), kNaN = std::numeric_limits<float>::quiet_NaN();

float HalfToFloat(uint16_t h) {
  int e = (h >> 10) & 31, m = h & 1023;
  float v = e == 0 ? std::ldexp(float(m), -24) : e == 31 ? (m ? kNaN : kInf) : std::ldexp(float(m | 1024), e - 25);
  return h & 0x8000 ? -v : v;
}

// Stored moments of one depth (what resolve.hlsl writes for one sample), in double.
glm::dvec4 StoredMoments(const MomentOptions& o, double z) {
  z = std::isnan(z) ? 1.0 : std::clamp(z, 0.0, 1.0);
  double zs = 2 * z - 1, wp = std::exp(o.exponents.x * zs), wn = -std::exp(-o.exponents.y * zs);
  switch (o.kind) {
    case MomentKind::Vsm: return {z, z * z, 0, 0};
    case MomentKind::Esm: return {std::exp(o.exponents.x * z), 0, 0, 0};
    case MomentKind::Evsm2: return {wp, wp * wp, 0, 0};
    case MomentKind::Evsm4: return {wp, wp * wp, wn, wn * wn};
    case MomentKind::Msm: break;
  }
  glm::dvec4 b(z, z * z, z * z * z, z * z * z * z);
  if (o.precision == MomentPrecision::Fp32) return b;
  const double m[4][4] = {{-2.07224649, 13.7948857237, 0.105877704, 9.7924062118},
                          {32.23703778, -59.4683975703, -1.9077466311, -33.7652110555},
                          {-68.571074599, 82.0359750338, 9.3496555107, 47.9456096605},
                          {39.3703274134, -35.364903257, -6.6543490743, -23.9728048165}};
  glm::dvec4 q(0.035955884801, 0, 0, 0);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) q[j] += b[i] * m[i][j];
  return q;
}

MomentOptions Options(const std::string& filter, const std::map<std::string, std::string>& extra = {}) {
  std::map<std::string, std::string> p = extra;
  p["filter"] = filter;
  return tech::ParseMomentOptions(p);
}

class MomentMapsTest : public BackendTest {
 protected:
  // An R32_FLOAT array holding arbitrary "depth" (values a depth buffer could not hold included).
  Ref<Texture2D> Source(uint32_t w, uint32_t h, uint32_t layers, const std::vector<float>& data) {
    TEXTURE2D_DESC d;
    d.Width = w, d.Height = h, d.ArraySize = layers, d.Format = FORMAT_R32_FLOAT, d.BindFlags = BIND_SHADER_RESOURCE;
    std::vector<SUBRESOURCE_DATA> init(layers);
    for (uint32_t l = 0; l < layers; ++l) init[l] = {data.data() + size_t(l) * w * h, w * 4, w * h * 4};
    return device().CreateTexture2D(d, init.data());
  }

  std::unique_ptr<MomentMaps> Make(const MomentOptions& o, uint32_t w, uint32_t h, uint32_t layers, bool mips = true) {
    MomentMapDesc d;
    d.options = o;
    d.width = w, d.height = h, d.layers = layers, d.mips = mips;
    return std::make_unique<MomentMaps>(device(), d);
  }

  std::unique_ptr<MomentMaps> Convert(const MomentOptions& o, Texture2D* source, const std::vector<float>& radii, bool mips = true) {
    TEXTURE2D_DESC sd = source->GetDesc();
    auto maps = Make(o, sd.Width, sd.Height, sd.ArraySize, mips);
    maps->Convert(ctx(), MomentMaps::MakeDepthSrv(device(), source).get(), radii);
    return maps;
  }

  // One layer and mip of the map as float4 per texel, whatever its format.
  Texels Read(const MomentMaps& maps, uint32_t layer, uint32_t mip = 0) {
    Texture2D* t = maps.Texture();
    TEXTURE2D_DESC d = t->GetDesc();
    std::vector<uint8_t> raw = ReadTexture(device(), ctx(), t, mip + layer * d.MipLevels);
    const FormatInfo& fi = GetFormatInfo(d.Format);
    const bool half = d.Format == FORMAT_R16_FLOAT || d.Format == FORMAT_R16G16_FLOAT || d.Format == FORMAT_R16G16B16A16_FLOAT;
    const bool unorm = d.Format == FORMAT_R16G16B16A16_UNORM;
    const uint32_t channels = fi.bytesPerElement / (half || unorm ? 2 : 4);
    Texels out(raw.size() / fi.bytesPerElement, glm::vec4(0.0f));
    for (size_t i = 0; i < out.size(); ++i)
      for (uint32_t c = 0; c < channels; ++c) {
        if (half || unorm) {
          uint16_t v;
          std::memcpy(&v, raw.data() + i * fi.bytesPerElement + c * 2, 2);
          out[i][c] = unorm ? v / 65535.0f : HalfToFloat(v);
        } else {
          std::memcpy(&out[i][c], raw.data() + i * fi.bytesPerElement + c * 4, 4);
        }
      }
    return out;
  }

  // Visibility of receivers (u, v, layer, depth) through MomentSampleLevelVisibility at lod 0.
  std::vector<float> Lookup(const MomentMaps& maps, const std::vector<glm::vec4>& queries) {
    static const char* kLookupCS = R"(
#include "moments/moments.hlsli"
Texture2DArray<float4> momentMap : register(t0);
SamplerState momentSampler : register(s0);
StructuredBuffer<float4> queries : register(t1);  // u, v, layer, receiver depth
RWStructuredBuffer<float4> results : register(u0);
cbuffer Count : register(b0) { uint queryCount; uint3 padCount; };
[numthreads(64, 1, 1)] void main(uint3 id : SV_DispatchThreadID) {
  if (id.x >= queryCount) return;
  float4 q = queries[id.x];
  results[id.x] = float4(MomentSampleLevelVisibility(momentMap, momentSampler, q.xy, q.z, 0.0, q.w), 0.0, 0.0, 0.0);
}
)";
    uint32_t n = uint32_t(queries.size());
    Ref<Buffer> in = MakeBuffer(device(), BIND_SHADER_RESOURCE, queries.data(), n * 16, RESOURCE_MISC_BUFFER_STRUCTURED, 16);
    Ref<Buffer> out = MakeBuffer(device(), BIND_UNORDERED_ACCESS, nullptr, n * 16, RESOURCE_MISC_BUFFER_STRUCTURED, 16);
    uint32_t count[4] = {n, 0, 0, 0};
    Ref<Buffer> cb = MakeBuffer(device(), BIND_CONSTANT_BUFFER, count, 16);
    Ref<ShaderResourceView> qs = device().CreateShaderResourceView(in.get());
    Ref<UnorderedAccessView> uav = device().CreateUnorderedAccessView(out.get());
    Ref<ComputeShader> cs = device().CreateComputeShader(CompileHlsl(kLookupCS, "cs_5_0", "main", maps.LightingDefines()));
    ctx().CSSetShader(cs.get());
    ctx().CSSetShaderResources(0, {maps.Srv(), qs.get()});
    ctx().CSSetSamplers(0, {maps.Sampler()});
    ctx().CSSetUnorderedAccessViews(0, {uav.get()});
    ctx().CSSetConstantBuffers(0, {cb.get()});
    ctx().Dispatch((n + 63) / 64, 1, 1);
    std::vector<float> r;
    for (const glm::vec4& v : ReadAs<glm::vec4>(ReadBuffer(device(), ctx(), out.get()))) r.push_back(v.x);
    return r;
  }
};

const char* const kKinds[] = {"vsm", "esm", "evsm2", "evsm4", "msm"};

// (ii) One occluder depth everywhere (a real depth array cleared per layer to 0.4 and 0.6,
// blurred): receivers in front are lit (>= 0.97: exact 1 for the Chebyshev kinds; MSM's bias and
// ESM's exponential fall short of 1 near the occluder), receivers 0.3 behind are shadowed
// (<= 0.05 after each kind's default bleed reduction), in fp32 and 16-bit storage.
TEST_P(MomentMapsTest, SingleOccluderLitInFrontShadowedBehind) {
  const float occluder[2] = {0.4f, 0.6f};
  for (const char* kind : kKinds)
    for (const char* precision : {"fp32", "fp16"}) {
      MomentOptions o = Options(kind, {{"precision", precision}});
      auto maps = Make(o, 16, 16, 2);
      Ref<Texture2D> depth = device().CreateTexture2D(maps->DepthDesc());
      for (uint32_t l = 0; l < 2; ++l) {
        DEPTH_STENCIL_VIEW_DESC dd;
        dd.Format = FORMAT_D32_FLOAT;
        dd.ViewDimension = DSV_DIMENSION_TEXTURE2DARRAY;
        dd.Texture2DArray = {0, l, 1};
        ctx().ClearDepthStencilView(device().CreateDepthStencilView(depth.get(), &dd).get(), CLEAR_DEPTH, occluder[l], 0);
      }
      maps->Convert(ctx(), MomentMaps::MakeDepthSrv(device(), depth.get()).get(), {2.0f, 3.5f});
      std::vector<glm::vec4> q;
      for (uint32_t l = 0; l < 2; ++l)
        for (float dz : {-0.1f, -0.01f, 0.3f}) q.push_back({0.53f, 0.47f, float(l), occluder[l] + dz});
      std::vector<float> v = Lookup(*maps, q);
      for (size_t i = 0; i < q.size(); ++i) {
        bool front = q[i].w < occluder[size_t(q[i].z)];
        std::string what = std::string(kind) + " " + precision + " occluder " + std::to_string(occluder[size_t(q[i].z)]) + " receiver " +
                           std::to_string(q[i].w);
        if (front)
          EXPECT_GE(v[i], 0.97f) << what;
        else
          EXPECT_LE(v[i], 0.05f) << what;
      }
    }
}

// (iii) Light bleeding: occluders at 0.2 (left half) and 0.6 (right half), a 9-texel box blur,
// receivers behind both (truth: visibility 0), read at the texel whose footprint holds 4/9 of
// the near and 5/9 of the far occluder. Without bleed reduction: VSM's Chebyshev bound is loose
// for a two-depth footprint (~0.43 at 0.65); the exponential warp of EVSM makes the far
// occluder dominate; EVSM4 is the min of EVSM2 and a second bound so never leaks more; MSM
// reconstructs a two-depth distribution exactly from four moments, so only its bias leaks.
TEST_P(MomentMapsTest, LightBleedingVsmLeaksMostMsmLeastOrClose) {
  const uint32_t W = 32, H = 8;
  std::vector<float> src(W * H);
  for (uint32_t i = 0; i < src.size(); ++i) src[i] = i % W < W / 2 ? 0.2f : 0.6f;
  Ref<Texture2D> source = Source(W, H, 1, src);
  const float receivers[] = {0.61f, 0.65f, 0.8f};
  std::map<std::string, std::vector<float>> leak, reduced;
  for (const char* kind : {"vsm", "esm", "evsm2", "evsm4", "msm"}) {
    for (bool reduce : {false, true}) {
      MomentOptions o = Options(kind, reduce ? std::map<std::string, std::string>{} : std::map<std::string, std::string>{{"bleed", "0"}});
      o.blurKernel = tech::MomentBlurKernel::Box;
      auto maps = Convert(o, source.get(), {4.0f});
      std::vector<glm::vec4> q;
      for (float z : receivers) q.push_back({(W / 2 + 0.5f) / W, 0.5f, 0.0f, z});
      (reduce ? reduced : leak)[kind] = Lookup(*maps, q);
    }
    std::printf("  leak %-6s", kind);
    for (size_t i = 0; i < std::size(receivers); ++i)
      std::printf("  z=%.2f: %.4f (bleed %.2f: %.4f)", receivers[i], leak[kind][i], Options(kind).bleed, reduced[kind][i]);
    std::printf("\n");
  }
  for (size_t i = 0; i < std::size(receivers); ++i) {
    std::string at = "receiver " + std::to_string(receivers[i]);
    EXPECT_GT(leak["vsm"][i], 0.2f) << at << ": the case must be one where VSM visibly leaks";
    EXPECT_GT(leak["vsm"][i], leak["evsm2"][i]) << at;
    EXPECT_GT(leak["vsm"][i], leak["evsm4"][i]) << at;
    EXPECT_GT(leak["vsm"][i], leak["msm"][i]) << at;
    EXPECT_LE(leak["evsm4"][i], leak["evsm2"][i]) << at;
    EXPECT_LE(leak["msm"][i], std::min(leak["evsm2"][i], leak["evsm4"][i]) + 0.02f) << at << ": MSM least or within 0.02 of the least";
    for (const char* kind : kKinds) EXPECT_LE(reduced[kind][i], leak[kind][i]) << at << " " << kind << ": reduction never adds light";
  }
}

// (iv) 4x MSAA depth (two layers, a sloped triangle over a cleared background so edge pixels mix
// two depths): each texel of the map is the mean of its four samples' moments, computed on the
// CPU from the samples read back with Texture2DMSArray.Load. Tolerance: relative 4 eps (1 + |x|)
// for exp(x) (fp32: x up to 84 in evsm's squares) plus 4 ulps of the mean; 16-bit UNORM:
// 1.5 LSB (rounding to 1/65535 plus the quantisation's float arithmetic).
TEST_P(MomentMapsTest, MsaaResolveAveragesTheSamplesMoments) {
  const uint32_t W = 16, H = 16, L = 2;
  if (device().CheckMultisampleQualityLevels(FORMAT_D32_FLOAT, 4) == 0) GTEST_SKIP() << "no 4x D32_FLOAT";
  MomentOptions probe = Options("vsm", {{"msaa", "4"}});
  auto shape = Make(probe, W, H, L);
  Ref<Texture2D> depth = device().CreateTexture2D(shape->DepthDesc());
  const char* kTriangleVS = R"(
cbuffer Triangle : register(b0) { float4 corner[3]; };  // NDC x, y, depth
float4 main(uint id : SV_VertexID) : SV_Position { return float4(corner[id].xyz, 1.0); }
)";
  Ref<VertexShader> vs = device().CreateVertexShader(CompileHlsl(kTriangleVS, "vs_5_0", "main"));
  RASTERIZER_DESC rd;
  rd.CullMode = CULL_NONE;
  Ref<RasterizerState> rs = device().CreateRasterizerState(rd);
  const float tri[L][12] = {{-0.9f, -0.8f, 0.1f, 0, 0.7f, -0.95f, 0.5f, 0, -0.3f, 0.9f, 0.9f, 0},
                            {0.95f, 0.9f, 0.3f, 0, -0.85f, 0.2f, 0.75f, 0, 0.1f, -0.9f, 0.05f, 0}};
  Ref<Buffer> cb = MakeBuffer(device(), BIND_CONSTANT_BUFFER, nullptr, 48);
  for (uint32_t l = 0; l < L; ++l) {
    DEPTH_STENCIL_VIEW_DESC dd;
    dd.Format = FORMAT_D32_FLOAT;
    dd.ViewDimension = DSV_DIMENSION_TEXTURE2DMSARRAY;
    dd.Texture2DMSArray = {l, 1};
    Ref<DepthStencilView> dsv = device().CreateDepthStencilView(depth.get(), &dd);
    ctx().ClearDepthStencilView(dsv.get(), CLEAR_DEPTH, l == 0 ? 1.0f : 0.85f, 0);
    ctx().OMSetRenderTargets(0, nullptr, dsv.get());
    VIEWPORT vp{0, 0, float(W), float(H), 0, 1};
    ctx().RSSetViewports(1, &vp);
    ctx().RSSetState(rs.get());
    ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    ctx().UpdateSubresource(cb.get(), 0, nullptr, tri[l], 0, 0);
    ctx().VSSetShader(vs.get());
    ctx().VSSetConstantBuffers(0, {cb.get()});
    ctx().PSSetShader(nullptr);
    ctx().Draw(3, 0);
  }
  ctx().OMSetRenderTargets(0, nullptr, nullptr);
  Ref<ShaderResourceView> depthSrv = MomentMaps::MakeDepthSrv(device(), depth.get());

  const char* kSamplesCS = R"(
Texture2DMSArray<float> depthSamples : register(t0);
RWStructuredBuffer<float> samples : register(u0);
[numthreads(64, 1, 1)] void main(uint3 id : SV_DispatchThreadID) {
  uint p = id.x / 4;
  samples[id.x] = depthSamples.Load(int3(p % 16, (p / 16) % 16, p / 256), id.x % 4);
}
)";
  Ref<Buffer> sbuf = MakeBuffer(device(), BIND_UNORDERED_ACCESS, nullptr, W * H * L * 16, RESOURCE_MISC_BUFFER_STRUCTURED, 4);
  Ref<UnorderedAccessView> suav = device().CreateUnorderedAccessView(sbuf.get());
  Ref<ComputeShader> scs = device().CreateComputeShader(CompileHlsl(kSamplesCS, "cs_5_0", "main"));
  ctx().CSSetShader(scs.get());
  ctx().CSSetShaderResources(0, {depthSrv.get()});
  ctx().CSSetUnorderedAccessViews(0, {suav.get()});
  ctx().Dispatch(W * H * L * 4 / 64, 1, 1);
  ctx().CSSetShaderResources(0, {nullptr});
  std::vector<float> samples = ReadAs<float>(ReadBuffer(device(), ctx(), sbuf.get()));

  size_t mixed = 0;
  for (uint32_t p = 0; p < W * H * L; ++p) {
    auto [lo, hi] = std::minmax_element(samples.begin() + p * 4, samples.begin() + p * 4 + 4);
    mixed += *hi - *lo > 0.1f;
  }
  EXPECT_GT(mixed, size_t(10)) << "edge pixels whose samples hold both the triangle and the background";

  for (const auto& [kind, precision] : {std::pair{"vsm", "fp32"}, {"evsm4", "fp32"}, {"msm", "fp16"}, {"esm", "fp32"}}) {
    MomentOptions o = Options(kind, {{"msaa", "4"}, {"precision", precision}});
    auto maps = Make(o, W, H, L, false);
    maps->Convert(ctx(), depthSrv.get(), {});
    const bool unorm = maps->Format() == FORMAT_R16G16B16A16_UNORM;
    double worst = 0, meanDepthGap = 0;
    for (uint32_t l = 0; l < L; ++l) {
      Texels got = Read(*maps, l);
      for (uint32_t i = 0; i < W * H; ++i) {
        const float* s = &samples[((l * W * H) + i) * 4];
        glm::dvec4 mean(0.0);
        double meanDepth = 0;
        for (int k = 0; k < 4; ++k) mean += StoredMoments(o, s[k]) / 4.0, meanDepth += s[k] / 4.0;
        for (int c = 0; c < 4; ++c) {
          double x = o.kind == MomentKind::Esm ? o.exponents.x : (c % 2 ? 2.0 : 1.0) * (c < 2 ? o.exponents.x : o.exponents.y);
          double tol = unorm ? 1.5 / 65535 : (4 * (1 + x) + 4) * std::numeric_limits<float>::epsilon() * std::abs(mean[c]);
          double err = std::abs(got[i][c] - mean[c]);
          worst = std::max(worst, err / std::max(tol, 1e-30));
          EXPECT_LE(err, tol) << kind << " layer " << l << " texel " << i % W << "," << i / W << " channel " << c << ": GPU " << got[i][c]
                              << ", mean of sample moments " << mean[c];
          meanDepthGap = std::max(meanDepthGap, std::abs(StoredMoments(o, meanDepth)[c] - mean[c]) / std::max(std::abs(mean[c]), 1e-30));
        }
      }
    }
    std::printf("  %s %s: worst error %.2f of tolerance; moments of the mean depth would be off by up to %.3g (relative)\n", kind, precision,
                worst, meanDepthGap);
    EXPECT_GT(meanDepthGap, 0.01) << kind << ": the test must tell averaged moments from averaged depths";
  }
}

// (v) The blur equals a CPU separable blur (horizontal then vertical, clamp to edge, the
// shader's tap weights) of the CPU moments, per layer radius, box and Gaussian. Tolerance:
// fp32 2e-6 absolute on values <= 1 (two passes of up to 2 * 32 + 1 float multiply-adds);
// 16-bit UNORM 2.5 LSB (the intermediate is rounded once more than the CPU's).
// Mips: each level is the 2x2 mean of the one above (GenerateMips), within 1e-6.
TEST_P(MomentMapsTest, BlurEqualsCpuSeparableBlurPerLayerRadius) {
  const uint32_t W = 32, H = 32, L = 2;
  std::vector<float> src(W * H * L);
  for (uint32_t i = 0; i < src.size(); ++i) {
    uint32_t x = i % W, y = i / W % H;
    uint32_t hsh = (x * 73856093u) ^ (y * 19349663u) ^ (i / (W * H) * 83492791u);
    src[i] = 0.15f + 0.7f * float(hsh % 1000) / 1000.0f * ((x / 4 + y / 4) % 2 ? 1.0f : 0.3f);
  }
  Ref<Texture2D> source = Source(W, H, L, src);
  const std::vector<float> radii = {2.5f, 1.0f};
  for (auto kernel : {tech::MomentBlurKernel::Box, tech::MomentBlurKernel::Gaussian})
    for (const auto& [kind, precision] : {std::pair{"vsm", "fp32"}, {"msm", "fp16"}}) {
      MomentOptions o = Options(kind, {{"precision", precision}});
      o.blurKernel = kernel;
      auto maps = Convert(o, source.get(), radii);
      const bool unorm = maps->Format() == FORMAT_R16G16B16A16_UNORM;
      const char* kname = kernel == tech::MomentBlurKernel::Box ? "box" : "gaussian";
      for (uint32_t l = 0; l < L; ++l) {
        const double r = radii[l];
        const int reach = int(std::ceil(r));
        auto weight = [&](int i) {
          return kernel == tech::MomentBlurKernel::Box ? std::clamp(r + 1 - std::abs(i), 0.0, 1.0) : std::exp(-double(i * i) / (2 * (r / 2) * (r / 2)));
        };
        std::vector<glm::dvec4> m(W * H), h(W * H), v(W * H);
        for (uint32_t i = 0; i < W * H; ++i) m[i] = StoredMoments(o, src[l * W * H + i]);
        auto pass = [&](const std::vector<glm::dvec4>& in, std::vector<glm::dvec4>& out, int dx, int dy) {
          for (int y = 0; y < int(H); ++y)
            for (int x = 0; x < int(W); ++x) {
              glm::dvec4 sum(0.0);
              double total = 0;
              for (int i = -reach; i <= reach; ++i) total += weight(i);
              for (int i = -reach; i <= reach; ++i) {
                int px = std::clamp(x + dx * i, 0, int(W) - 1), py = std::clamp(y + dy * i, 0, int(H) - 1);
                sum += weight(i) / total * in[py * W + px];
              }
              out[y * W + x] = sum;
            }
        };
        pass(m, h, 1, 0);
        pass(h, v, 0, 1);
        Texels got = Read(*maps, l);
        double worst = 0;
        for (uint32_t i = 0; i < W * H; ++i)
          for (int c = 0; c < 4; ++c) worst = std::max(worst, std::abs(got[i][c] - v[i][c]));
        EXPECT_LE(worst, unorm ? 2.5 / 65535 : 2e-6) << kind << " " << precision << " " << kname << " layer " << l << " radius " << r;
        // The blur must have done something: the unblurred moments differ by far more.
        double change = 0;
        for (uint32_t i = 0; i < W * H; ++i) change = std::max(change, std::abs(m[i].x - v[i].x));
        EXPECT_GT(change, 0.05) << kname << " layer " << l;
        if (unorm) continue;
        Texels top = got, mip1 = Read(*maps, l, 1);
        for (uint32_t y = 0; y < H / 2; ++y)
          for (uint32_t x = 0; x < W / 2; ++x) {
            glm::vec4 box = (top[2 * y * W + 2 * x] + top[2 * y * W + 2 * x + 1] + top[(2 * y + 1) * W + 2 * x] + top[(2 * y + 1) * W + 2 * x + 1]) / 4.0f;
            for (int c = 0; c < 2; ++c) EXPECT_NEAR(mip1[y * (W / 2) + x][c], box[c], 1e-6) << "mip 1 texel " << x << "," << y;
          }
      }
    }
}

// (vi) Requested exponents beyond the format are clamped, and the maps stay finite: 16-bit and
// fp32 maps of depths spanning [0, 1] plus out-of-range values, blurred and mipmapped, hold no
// inf or NaN in any layer or mip, and the largest value (exp(2 c+) at depth 1 for EVSM, exp(c)
// for ESM) uses most of the format's range.
TEST_P(MomentMapsTest, ExponentsBeyondTheFormatAreClampedAndMapsStayFinite) {
  const uint32_t W = 16, H = 16, L = 2;
  std::vector<float> src(W * H * L);
  for (uint32_t i = 0; i < src.size(); ++i) src[i] = float(i % W) / (W - 1);  // 0 .. 1 across each row
  src[3] = -4.0f, src[W + 5] = 9.0f, src[2 * W + 7] = kInf, src[3 * W + 9] = -kInf, src[W * H + 4] = kNaN;
  Ref<Texture2D> source = Source(W, H, L, src);
  struct Case {
    const char* kind;
    const char* precision;
    const char* exponents;
    float expectMax;  // largest stored value: exp of the clamped exponent (times 2 for squares)
  };
  const Case cases[] = {
      {"evsm4", "fp16", "100,100", std::exp(2 * tech::kEvsmMaxExponentFp16)}, {"evsm2", "fp16", "50", std::exp(2 * tech::kEvsmMaxExponentFp16)},
      {"esm", "fp16", "100", std::exp(tech::kEsmMaxExponentFp16)},           {"vsm", "fp16", "auto", 1.0f},
      {"evsm4", "fp32", "1000,1000", std::exp(2 * tech::kEvsmMaxExponentFp32)}, {"esm", "fp32", "1000", std::exp(tech::kEsmMaxExponentFp32)},
      {"msm", "fp16", "auto", 1.0f},
  };
  for (const Case& c : cases) {
    MomentOptions o = Options(c.kind, {{"precision", c.precision}, {"exponents", c.exponents}});
    auto maps = Convert(o, source.get(), {3.0f, 1.5f});
    float largest = 0;
    size_t bad = 0;
    const uint32_t mips = maps->Texture()->GetDesc().MipLevels;
    for (uint32_t l = 0; l < L; ++l)
      for (uint32_t m = 0; m < mips; ++m)
        for (const glm::vec4& t : Read(*maps, l, m))
          for (int k = 0; k < 4; ++k) {
            bad += !std::isfinite(t[k]);
            if (std::isfinite(t[k])) largest = std::max(largest, std::abs(t[k]));
          }
    std::string what = std::string(c.kind) + " " + c.precision + " exponents=" + c.exponents;
    EXPECT_EQ(bad, 0u) << what << ": texels with inf or NaN";
    // The largest value is a blurred texel next to depth 1, so a little below exp(2c); 16-bit
    // rounding may put it a little above.
    EXPECT_LE(largest, c.expectMax * 1.001f) << what;
    EXPECT_GE(largest, c.expectMax * 0.5f) << what << ": the clamp should use most of the range";
  }
}

// (vii) Depth outside [0, 1] (and inf, NaN) in the source neither produces inf/NaN nor reaches
// beyond the blur radius: the map equals the map of the source with those texels clamped
// (negative -> 0, above 1 and NaN -> 1) everywhere, and the map of the source without them at
// every texel farther than the radius (Chebyshev distance > 2 for the box of radius 2) from all
// of them. Lookups with receivers outside [0, 1] are finite too.
TEST_P(MomentMapsTest, DepthOutsideTheUnitRangeDoesNotSpreadBeyondTheBlur) {
  const uint32_t W = 32, H = 32;
  std::vector<float> clean(W * H);
  for (uint32_t i = 0; i < clean.size(); ++i) clean[i] = 0.3f + 0.4f * float((i * 37) % 101) / 101.0f;
  struct Bad {
    uint32_t x, y;
    float value, clamped;
  };
  const Bad bads[] = {{8, 8, -3.0f, 0.0f}, {20, 20, kInf, 1.0f}, {24, 6, kNaN, 1.0f}, {6, 24, 5.0f, 1.0f}, {14, 27, -kInf, 0.0f}};
  std::vector<float> dirty = clean, clamped = clean;
  for (const Bad& b : bads) dirty[b.y * W + b.x] = b.value, clamped[b.y * W + b.x] = b.clamped;
  Ref<Texture2D> sDirty = Source(W, H, 1, dirty), sClean = Source(W, H, 1, clean), sClamped = Source(W, H, 1, clamped);
  for (const char* kind : kKinds) {
    MomentOptions o = Options(kind);
    o.blurKernel = tech::MomentBlurKernel::Box;
    auto a = Convert(o, sDirty.get(), {2.0f}), b = Convert(o, sClean.get(), {2.0f}), c = Convert(o, sClamped.get(), {2.0f});
    Texels ta = Read(*a, 0), tb = Read(*b, 0), tc = Read(*c, 0);
    size_t nonFinite = 0, differFromClamped = 0, spread = 0, near = 0;
    for (uint32_t i = 0; i < W * H; ++i) {
      int x = int(i % W), y = int(i / W);
      bool inReach = false;
      for (const Bad& bd : bads) inReach |= std::max(std::abs(x - int(bd.x)), std::abs(y - int(bd.y))) <= 2;
      for (int k = 0; k < 4; ++k) {
        nonFinite += !std::isfinite(ta[i][k]);
        differFromClamped += ta[i][k] != tc[i][k];
        if (!inReach) spread += ta[i][k] != tb[i][k];
        if (inReach) near += ta[i][k] != tb[i][k];
      }
    }
    EXPECT_EQ(nonFinite, 0u) << kind;
    EXPECT_EQ(differFromClamped, 0u) << kind << ": out-of-range depth must act exactly like its clamped value";
    EXPECT_EQ(spread, 0u) << kind << ": texels beyond the blur radius changed";
    EXPECT_GT(near, 0u) << kind << ": the bad texels should change their neighbourhood";
    for (uint32_t m = 1; m < a->Texture()->GetDesc().MipLevels; ++m)
      for (const glm::vec4& t : Read(*a, 0, m)) EXPECT_TRUE(std::isfinite(t.x) && std::isfinite(t.y) && std::isfinite(t.z) && std::isfinite(t.w)) << kind;
    std::vector<float> v = Lookup(*a, {{0.26f, 0.26f, 0, -1.0f}, {0.63f, 0.63f, 0, 2.0f}, {0.5f, 0.5f, 0, kInf}, {0.1f, 0.9f, 0, kNaN}});
    for (float x : v) EXPECT_TRUE(std::isfinite(x) && x >= 0 && x <= 1) << kind << ": lookup gave " << x;
  }
}

// Radii a GPU pass left in a buffer (here: written at creation, between unrelated words) blur
// exactly as the same radii given on the CPU, including a layer of radius 0 (copied through);
// the blur's constants hold them afterwards; bad regions are errors.
TEST_P(MomentMapsTest, RadiiFromAGpuBufferBlurAsTheSameRadiiFromTheCpu) {
  const uint32_t W = 16, H = 16, L = 3;
  std::vector<float> src(W * H * L);
  for (uint32_t i = 0; i < src.size(); ++i) src[i] = 0.2f + 0.6f * float((i * 2654435761u) % 997u) / 997.0f;
  Ref<Texture2D> source = Source(W, H, L, src);
  const std::vector<float> radii = {2.5f, 0.0f, 1.25f};
  const uint32_t offset = 48;
  std::vector<float> words(offset / 4 + tech::kMaxMomentLayers + 4, 99.0f);
  for (uint32_t l = 0; l < tech::kMaxMomentLayers; ++l) words[offset / 4 + l] = l < L ? radii[l] : 0.0f;
  Ref<Buffer> buffer = MakeBuffer(device(), BIND_SHADER_RESOURCE, words.data(), uint32_t(words.size() * 4));
  Ref<ShaderResourceView> srv = MomentMaps::MakeDepthSrv(device(), source.get());
  auto cpu = Make(Options("evsm4"), W, H, L), gpu = Make(Options("evsm4"), W, H, L);
  cpu->Convert(ctx(), srv.get(), radii);
  gpu->ConvertWithGpuRadii(ctx(), srv.get(), tech::GpuBlurRadii{buffer.get(), offset});
  EXPECT_EQ(gpu->ReadLastBlurRadii(ctx()), radii);
  EXPECT_EQ(cpu->ReadLastBlurRadii(ctx()), radii);
  for (uint32_t l = 0; l < L; ++l) {
    Texels a = Read(*cpu, l), b = Read(*gpu, l);
    size_t differ = 0;
    for (size_t i = 0; i < a.size(); ++i) differ += a[i] != b[i];
    EXPECT_EQ(differ, 0u) << "layer " << l;
  }
  cpu->Convert(ctx(), srv.get(), {});
  EXPECT_TRUE(cpu->ReadLastBlurRadii(ctx()).empty());
  const uint32_t bytes = uint32_t(words.size() * 4);
  EXPECT_THROW(gpu->ConvertWithGpuRadii(ctx(), srv.get(), tech::GpuBlurRadii{}), std::invalid_argument) << "null buffer";
  EXPECT_THROW(gpu->ConvertWithGpuRadii(ctx(), srv.get(), tech::GpuBlurRadii{buffer.get(), 2}), std::invalid_argument) << "unaligned";
  EXPECT_THROW(gpu->ConvertWithGpuRadii(ctx(), srv.get(), tech::GpuBlurRadii{buffer.get(), bytes - 32}), std::invalid_argument) << "past the end";
}

SP_INSTANTIATE_BACKEND_TESTS(MomentMapsTest);

// Bad input refused, no pixels checked: these run on the null backend too.
class MomentMapsValidationTest : public MomentMapsTest {};

// Convert times its passes as "moments" and "blur" when given a timer, and checks its inputs.
TEST_P(MomentMapsValidationTest, ConvertTimesItsPassesAndRejectsBadInputs) {
  std::vector<float> src(8 * 8 * 2, 0.5f);
  Ref<Texture2D> source = Source(8, 8, 2, src);
  auto maps = Make(Options("evsm4"), 8, 8, 2);
  Ref<ShaderResourceView> srv = MomentMaps::MakeDepthSrv(device(), source.get());
  tech::GpuTimer timer(device());
  timer.BeginFrame(ctx());
  maps->Convert(ctx(), srv.get(), {1.0f, 2.0f}, &timer);
  timer.EndFrame(ctx());
  std::vector<tech::FrameTimes> t = timer.Collect(ctx(), true);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_TRUE(t[0].count("moments") && t[0].count("blur"));
  EXPECT_THROW(maps->Convert(ctx(), srv.get(), {1.0f}), std::invalid_argument) << "one radius for two layers";
  auto msaa = Make(Options("evsm4", {{"msaa", "4"}}), 8, 8, 2);
  EXPECT_THROW(msaa->Convert(ctx(), srv.get(), {}), std::invalid_argument) << "single-sampled SRV for msaa=4";
  // Texture with mips + blur temp: (64 + 16 + 4 + 1) texels x 2 layers x 16 bytes, plus 64 x 2 x 16.
  EXPECT_EQ(maps->MemoryBytes(), uint64_t((64 + 16 + 4 + 1) * 2 * 16 + 64 * 2 * 16));
}

SP_INSTANTIATE_VALIDATION_TESTS(MomentMapsValidationTest);

}  // namespace
}  // namespace sp::test
