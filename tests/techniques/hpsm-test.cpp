// Accelerated filtering (common/hpsm.hlsli, techniques/hpsm-maps.h): the secondary maps against a
// construction on the CPU, the accelerated filter against the plain one wherever the maps decide
// (a compute shader over a known depth map, for the comparison filters and for PCSS, whose
// footprint the maps bound by pcss_max_kernel; then basic's, csm's and sdsm's lit passes on a
// plane + box scene; spot's is in spot-technique-test.cpp), the
// chapter's claim that planes decide most of a flat receiver under a low sun where min/max does
// not, and the parameters' errors.
//
// Exactness tolerance: where a map decides, the plain filter's taps each return exactly 1 or 0 and
// their weights sum to the result; box (saturated), gauss (a power of two), poisson (1/16) sum to
// exactly 1 or 0, gathercmp's float weights to 1 within a few ulps. A tap whose coordinate the
// sampler rounds onto a texel outside the footprint would give it a weight of that rounding's size;
// the maps here are powers of two, so coordinates are exact. kExact is that float-rounding bound.
#include <cstring>
#include <glm/glm.hpp>
#include <random>

#include "backend-test.h"
#include "technique-renderer.h"
#include "floating-box.h"
#include "hpsm-maps.h"
#include <sp/tech/renderer.h>

namespace sp::test {
namespace {

constexpr uint32_t kSize = 64;
constexpr double kExact = 4.0 / (1 << 23);  // a few ulps of 1
enum Filter { kHw2x2, kBox, kGauss, kGatherCmp, kPoisson, kPcss };

// The map: a tilted plane (depth 0.4 + 0.003 x + 0.0015 y at texel (x, y)), a box top in front of
// it (texels [20, 36) x [24, 40) at 0.2) and a patch of noise (texels [44, 60) x [4, 20)).
struct DepthMapData {
  std::vector<float> d = std::vector<float>(kSize * kSize);
  DepthMapData() {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> noise(0.3f, 0.7f);
    for (uint32_t y = 0; y < kSize; ++y)
      for (uint32_t x = 0; x < kSize; ++x) {
        float v = 0.4f + 0.003f * float(x) + 0.0015f * float(y);
        if (x >= 20 && x < 36 && y >= 24 && y < 40) v = 0.2f;
        if (x >= 44 && x < 60 && y >= 4 && y < 20) v = noise(rng);
        d[y * kSize + x] = v;
      }
  }
  float At(int x, int y) const { return d[std::clamp(y, 0, int(kSize) - 1) * kSize + std::clamp(x, 0, int(kSize) - 1)]; }
};
const DepthMapData& TheMap() {
  static const DepthMapData m;
  return m;
}

tech::HpsmSettings Settings(tech::ShadowAccel accel, int filter, int kernel, int block = 0, float eps = 1e-6f, const char* build = "gather") {
  tech::ParamValues p = tech::ParamValues::Parse("hpsm", tech::HpsmParams(),
                                                 {{"accel", accel == tech::ShadowAccel::Hpsm ? "hpsm" : "minmax"}, {"hpsm_block", std::to_string(block)},
                                                  {"hpsm_eps", std::to_string(eps)}, {"hpsm_build", build}});
  return tech::ReadHpsmSettings(p, filter, kernel, kSize);
}

// The lookup's input, laid out as the harness's HLSL struct (16-byte aligned vectors).
struct Query {
  glm::vec2 uv{0.5f};
  float depth = 0.5f, pad0 = 0;
  glm::vec2 gradient{0.0f};
  glm::vec2 pixel{0.5f};
};
static_assert(sizeof(Query) == 32);

// PCSS (SHADOW_FILTER 5) over the same map: orthographic, depth range [0, 10] world units and
// 200 texels of penumbra per world unit, so the search radius is M/2 for every receiver (its
// penumbra from the near plane is wider) and the box's width runs from 1 (receivers 0.0005 behind)
// to M; PCSS_TAPS search taps per axis.
const char* const kHarness = R"(
#include "common/hpsm.hlsli"
struct Query { float2 uv; float depth; float pad0; float2 depthGradient; float2 pixel; };
Texture2DArray<float> shadowMap : register(t0);
StructuredBuffer<Query> queries : register(t1);
Texture2DArray<float4> hpsm : register(t2);
SamplerComparisonState shadowCmp : register(s0);
RWStructuredBuffer<float4> output : register(u0);
[numthreads(64, 1, 1)] void main(uint3 id : SV_DispatchThreadID) {
  Query q = queries[id.x];
  ShadowFilterInput i = {q.uv, 0.0, q.depth, float2(1.0 / 64.0, 1.0 / 64.0), float4(0, 0, 1, 1), q.depthGradient, q.pixel};
  uint how;
#if SHADOW_FILTER == 5
  ShadowPcssInput p = {float2(0.0, 10.0), float2(200.0, 200.0), 0.0, PCSS_TAPS, HPSM_PCSS_MAX_KERNEL, 0.0};
  float accelerated = HpsmShadowFilterPcss(shadowMap, shadowCmp, hpsm, i, p, how);
  float plain = ShadowFilterPcss(shadowMap, shadowCmp, i, p);
#else
  float accelerated = HpsmShadowFilter(shadowMap, shadowCmp, hpsm, i, how);
  float plain = ShadowFilter(shadowMap, shadowCmp, i);
#endif
  output[id.x] = float4(plain, accelerated, float(how), 0);
}
)";

class HpsmTest : public BackendTest {
 protected:
  void SetUp() override {
    BackendTest::SetUp();
    // As techniques make a shadow map: R32_TYPELESS with a depth binding, uploaded by a copy.
    tex_ = MakeTexture2D(device(), kSize, kSize, FORMAT_R32_TYPELESS, BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE);
    TEXTURE2D_DESC sd = tex_->GetDesc();
    sd.BindFlags = 0;
    sd.Usage = USAGE_STAGING;
    sd.CPUAccessFlags = CPU_ACCESS_WRITE;
    SUBRESOURCE_DATA init{TheMap().d.data(), kSize * 4, 0};
    Ref<Texture2D> staging = device().CreateTexture2D(sd, &init);
    ctx().CopyResource(tex_.get(), staging.get());
    srv_ = tech::MakeSliceArraySrv(device(), tex_.get());
    SAMPLER_DESC d;
    d.Filter = FILTER_COMPARISON_MIN_MAG_LINEAR_MIP_POINT;
    d.ComparisonFunc = COMPARISON_LESS_EQUAL;
    cmp_ = device().CreateSamplerState(d);
  }

  std::unique_ptr<tech::HpsmMaps> Build(const tech::HpsmSettings& s) {
    auto maps = std::make_unique<tech::HpsmMaps>(device(), s, kSize, kSize, 1);
    maps->Build(ctx(), srv_.get());
    return maps;
  }

  std::vector<glm::vec4> Texels(tech::HpsmMaps& maps) { return ReadAs<glm::vec4>(ReadTexture(device(), ctx(), maps.texture())); }

  // (plain, accelerated, decision) per query.
  std::vector<glm::vec4> Run(const tech::HpsmSettings& s, int filter, int kernel, std::vector<Query> qs, std::vector<hlsl::Define> defines = {}) {
    std::unique_ptr<tech::HpsmMaps> maps = Build(s);
    defines.push_back({"SHADOW_FILTER", std::to_string(filter)});
    defines.push_back({"SHADOW_KERNEL", std::to_string(kernel)});
    for (const hlsl::Define& h : tech::HpsmDefines(s)) defines.push_back(h);
    Ref<ComputeShader> shader = device().CreateComputeShader(CompileHlsl(kHarness, "cs_5_0", "main", defines));
    const size_t count = qs.size();
    while (qs.size() % 64) qs.push_back(qs.front());
    Ref<Buffer> in = MakeBuffer(device(), BIND_SHADER_RESOURCE, qs.data(), uint32_t(qs.size() * sizeof(Query)), RESOURCE_MISC_BUFFER_STRUCTURED, sizeof(Query));
    Ref<Buffer> out = MakeBuffer(device(), BIND_UNORDERED_ACCESS, nullptr, uint32_t(qs.size() * 16), RESOURCE_MISC_BUFFER_STRUCTURED, 16);
    SHADER_RESOURCE_VIEW_DESC sd;
    sd.ViewDimension = SRV_DIMENSION_BUFFER;
    sd.Buffer = {0, uint32_t(qs.size())};
    Ref<ShaderResourceView> inView = device().CreateShaderResourceView(in.get(), &sd);
    UNORDERED_ACCESS_VIEW_DESC ud;
    ud.ViewDimension = UAV_DIMENSION_BUFFER;
    ud.Buffer = {0, uint32_t(qs.size()), 0};
    Ref<UnorderedAccessView> uav = device().CreateUnorderedAccessView(out.get(), &ud);
    ctx().CSSetShader(shader.get());
    ctx().CSSetShaderResources(0, {srv_.get(), inView.get(), maps->srv()});
    ctx().CSSetSamplers(0, {cmp_.get()});
    ctx().CSSetUnorderedAccessViews(0, {uav.get()});
    ctx().Dispatch(uint32_t(qs.size() / 64), 1, 1);
    ctx().ClearState();
    std::vector<glm::vec4> r = ReadAs<glm::vec4>(ReadBuffer(device(), ctx(), out.get()));
    r.resize(count);
    return r;
  }

  Ref<Texture2D> tex_;
  Ref<ShaderResourceView> srv_;
  Ref<SamplerState> cmp_;
};

// --- (1) construction

struct CpuTexel {
  float lo = 0, hi = 0;
  double a = 0, b = 0, c = 0, residual = 0;  // least-squares plane about the support's middle
  int x0, x1, y0, y1;                        // the support, clamped into the map
};

CpuTexel CpuConstruct(int bx, int by, int block, int before, int after) {
  const DepthMapData& m = TheMap();
  CpuTexel t;
  t.x0 = std::max(0, bx * block - before), t.x1 = std::min(int(kSize) - 1, bx * block + block - 1 + after);
  t.y0 = std::max(0, by * block - before), t.y1 = std::min(int(kSize) - 1, by * block + block - 1 + after);
  double cx = (t.x0 + t.x1) * 0.5, cy = (t.y0 + t.y1) * 0.5, sum = 0, sxd = 0, syd = 0, sxx = 0, syy = 0;
  t.lo = 1e30f, t.hi = -1e30f;
  int n = 0;
  for (int y = t.y0; y <= t.y1; ++y)
    for (int x = t.x0; x <= t.x1; ++x, ++n) {
      t.lo = std::min(t.lo, m.At(x, y));
      t.hi = std::max(t.hi, m.At(x, y));
      sum += m.At(x, y);
    }
  t.c = sum / n;
  for (int y = t.y0; y <= t.y1; ++y)
    for (int x = t.x0; x <= t.x1; ++x) {
      sxd += (m.At(x, y) - t.c) * (x - cx), syd += (m.At(x, y) - t.c) * (y - cy);
      sxx += (x - cx) * (x - cx), syy += (y - cy) * (y - cy);
    }
  t.a = sxx > 0 ? sxd / sxx : 0, t.b = syy > 0 ? syd / syy : 0;
  for (int y = t.y0; y <= t.y1; ++y)
    for (int x = t.x0; x <= t.x1; ++x) t.residual = std::max(t.residual, std::abs(m.At(x, y) - (t.c + t.a * (x - cx) + t.b * (y - cy))));
  return t;
}

TEST_P(HpsmTest, SecondaryMapsMatchTheCpuConstruction) {
  struct Case {
    tech::ShadowAccel accel;
    int filter, kernel, block;
  };
  // Block 16: the group's supports no longer fit the build's groupshared tile (direct loads).
  for (Case k : {Case{tech::ShadowAccel::Hpsm, kBox, 3, 0}, Case{tech::ShadowAccel::Hpsm, kGatherCmp, 5, 0}, Case{tech::ShadowAccel::Hpsm, kPoisson, 9, 16},
                 Case{tech::ShadowAccel::MinMax, kBox, 3, 0}, Case{tech::ShadowAccel::MinMax, kBox, 9, 16}}) {
    tech::HpsmSettings s = Settings(k.accel, k.filter, k.kernel, k.block);
    bool hpsm = k.accel == tech::ShadowAccel::Hpsm;
    std::unique_ptr<tech::HpsmMaps> maps = Build(s);
    std::vector<glm::vec4> got = Texels(*maps);
    ASSERT_EQ(got.size(), size_t(maps->blocksX()) * maps->blocksY());
    int planes = 0, minMax = 0, ambiguous = 0;
    for (uint32_t by = 0; by < maps->blocksY(); ++by)
      for (uint32_t bx = 0; bx < maps->blocksX(); ++bx) {
        CpuTexel e = CpuConstruct(int(bx), int(by), s.block, hpsm ? s.reach : 0, hpsm ? s.reach + 1 : 0);
        glm::vec4 g = got[by * maps->blocksX() + bx];
        std::string where = "filter " + std::to_string(k.filter) + " block (" + std::to_string(bx) + ", " + std::to_string(by) + ")";
        // Float sums on the GPU against double here: a residual within 1e-7 of eps may go either way.
        if (hpsm && std::abs(e.residual - s.eps) < 1e-7) {
          ++ambiguous;
          continue;
        }
        if (hpsm && e.residual <= s.eps) {
          ++planes;
          ASSERT_GE(g.w, 0.0f) << where << ": the CPU fits a plane (residual " << e.residual << ")";
          EXPECT_LE(g.w, s.eps) << where;
          EXPECT_NEAR(g.x, e.a, 1e-6) << where;
          EXPECT_NEAR(g.y, e.b, 1e-6) << where;
          EXPECT_NEAR(g.z, e.c, 1e-6) << where;
          // What the lookup relies on: every support texel within the stored residual of the plane.
          double cx = (e.x0 + e.x1) * 0.5, cy = (e.y0 + e.y1) * 0.5;
          for (int y = e.y0; y <= e.y1; ++y)
            for (int x = e.x0; x <= e.x1; ++x)
              ASSERT_LE(std::abs(TheMap().At(x, y) - (double(g.z) + double(g.x) * (x - cx) + double(g.y) * (y - cy))), double(g.w) + 1e-6) << where;
        } else {
          ++minMax;
          EXPECT_EQ(g.w, -1.0f) << where << ": the CPU finds no plane (residual " << e.residual << ")";
          EXPECT_EQ(g.x, e.lo) << where;
          EXPECT_EQ(g.y, e.hi) << where;
        }
      }
    std::printf("[ hpsm ] filter %d kernel %d accel %s block %d: %d plane texels, %d min/max, %d ambiguous\n", k.filter, k.kernel, hpsm ? "hpsm" : "minmax",
                s.block, planes, minMax, ambiguous);
    if (hpsm && s.block == 4) {
      EXPECT_GT(planes, minMax) << "most of the map is the tilted plane";
    }
    EXPECT_GT(minMax, hpsm ? 4 : 10) << "the box's edges and the noise need min/max texels";
    EXPECT_LE(ambiguous, 2);
  }
}

// The Gather build's tile against the Load build's: the same texels, so the same floats bit for bit.
// Supports of 3 + 8 x 4 + 3 (box 5: reach 2 + 3) and of 8 x 4 + 0 (minmax) are odd and even
// extents, and the last group's union is cut by the map's edge; block 16 bypasses the tile.
TEST_P(HpsmTest, GatherAndLoadBuildsAreBitIdentical) {
  struct Case {
    tech::ShadowAccel accel;
    int filter, kernel, block;
  };
  for (Case k : {Case{tech::ShadowAccel::Hpsm, kBox, 3, 0}, Case{tech::ShadowAccel::Hpsm, kBox, 5, 0}, Case{tech::ShadowAccel::Hpsm, kPoisson, 9, 2},
                 Case{tech::ShadowAccel::Hpsm, kPcss, 15, 4}, Case{tech::ShadowAccel::MinMax, kBox, 3, 0}, Case{tech::ShadowAccel::Hpsm, kBox, 3, 16}}) {
    std::vector<glm::vec4> gathered = Texels(*Build(Settings(k.accel, k.filter, k.kernel, k.block, 1e-6f, "gather")));
    std::vector<glm::vec4> loaded = Texels(*Build(Settings(k.accel, k.filter, k.kernel, k.block, 1e-6f, "load")));
    ASSERT_EQ(gathered.size(), loaded.size());
    size_t differing = 0, first = gathered.size();
    for (size_t i = 0; i < gathered.size(); ++i)
      if (std::memcmp(&gathered[i], &loaded[i], sizeof(glm::vec4)) != 0) {
        ++differing;
        first = std::min(first, i);
      }
    EXPECT_EQ(differing, 0u) << "filter " << k.filter << " kernel " << k.kernel << " block " << k.block << ": " << differing << " of " << gathered.size()
                             << " texels differ, first at " << first;
  }
}

// --- (2) accelerated == plain wherever the maps decide

// Lookups over the whole map: receivers on the plane (with a small bias, and with the plane's
// own gradient), in front of and behind it, and at the box's depth.
std::vector<Query> Queries(bool gradient) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  const float offsets[] = {-0.3f, -0.01f, -0.0005f, 0.0005f, 0.01f, 0.3f};
  std::vector<Query> qs;
  for (int k = 0; k < 4096; ++k) {
    Query q;
    q.uv = {u01(rng), u01(rng)};
    glm::vec2 s = q.uv * float(kSize) - 0.5f;
    q.depth = 0.4f + 0.003f * s.x + 0.0015f * s.y + offsets[k % 6];
    if (k % 7 == 0) q.depth = 0.2f + offsets[k % 6] * 0.1f;
    if (gradient) q.gradient = {0.003f * kSize, 0.0015f * kSize};
    q.pixel = {float(k % 61), float(k / 61)};
    qs.push_back(q);
  }
  return qs;
}

void ExpectAcceleratedEqualsPlain(const std::string& what, const std::vector<glm::vec4>& r, double minDecided) {
  int decided = 0, wrong = 0;
  std::array<int, 5> how{};
  double worst = 0;
  for (const glm::vec4& v : r) {
    ++how[size_t(v.z)];
    if (v.z == 4.0f) {
      EXPECT_EQ(v.x, v.y) << what << ": the filtered path must be the plain filter";
      continue;
    }
    ++decided;
    double d = std::abs(double(v.x) - v.y);
    worst = std::max(worst, d);
    wrong += d > kExact;
  }
  std::printf("[ hpsm ] %s: lit/shadowed by min/max %d/%d, by plane %d/%d, filtered %d; worst |accelerated - plain| %.3g\n", what.c_str(), how[0], how[1], how[2],
              how[3], how[4], worst);
  EXPECT_EQ(wrong, 0) << what << ": decided lookups that differ from the plain filter by more than " << kExact << " (worst " << worst << ")";
  EXPECT_GE(decided, minDecided * r.size()) << what << ": too few decided lookups to test anything";
}

TEST_P(HpsmTest, AcceleratedFilterEqualsThePlainOneWhereTheMapsDecide) {
  struct Case {
    int filter, kernel;
  };
  for (Case k : {Case{kHw2x2, 3}, Case{kBox, 3}, Case{kBox, 7}, Case{kGauss, 5}, Case{kGatherCmp, 3}, Case{kGatherCmp, 9}, Case{kPoisson, 5}}) {
    for (tech::ShadowAccel accel : {tech::ShadowAccel::Hpsm, tech::ShadowAccel::MinMax}) {
      for (bool gradient : {false, true}) {
        tech::HpsmSettings s = Settings(accel, k.filter, k.kernel);
        std::string what = std::string(accel == tech::ShadowAccel::Hpsm ? "hpsm" : "minmax") + " filter " + std::to_string(k.filter) + " kernel " +
                           std::to_string(k.kernel) + (gradient ? " with gradient" : "");
        ExpectAcceleratedEqualsPlain(what, Run(s, k.filter, k.kernel, Queries(gradient)), 0.3);
      }
    }
  }
}

// PCSS (filter 5): maps built for pcss_max_kernel M decide exactly where PCSS returns 1 or 0.
TEST_P(HpsmTest, AcceleratedPcssEqualsThePlainOneWhereTheMapsDecide) {
  struct Case {
    int maxKernel, taps;
  };
  for (Case k : {Case{15, 6}, Case{7, 3}, Case{4, 16}}) {
    for (tech::ShadowAccel accel : {tech::ShadowAccel::Hpsm, tech::ShadowAccel::MinMax}) {
      for (bool gradient : {false, true}) {
        tech::HpsmSettings s = Settings(accel, kPcss, k.maxKernel);
        ASSERT_EQ(s.reach, k.maxKernel / 2 + 1);
        std::string what = std::string(accel == tech::ShadowAccel::Hpsm ? "hpsm" : "minmax") + " pcss max kernel " + std::to_string(k.maxKernel) + " taps " +
                           std::to_string(k.taps) + (gradient ? " with gradient" : "");
        ExpectAcceleratedEqualsPlain(what, Run(s, kPcss, 3, Queries(gradient), {{"PCSS_TAPS", std::to_string(k.taps)}}), 0.15);
      }
    }
  }
}

// --- basic's lit pass

std::unique_ptr<tech::Renderer> MakeBasic(Device& device, const scene::Scene& s, uint32_t w, uint32_t h, std::map<std::string, std::string> params) {
  return MakeTechniqueRenderer(device, "basic", s, w, h, params);
}

tech::HpsmCounts Decisions(tech::Renderer& r) {
  auto* source = dynamic_cast<const tech::HpsmCounterSource*>(&r.technique());
  if (!source) throw std::logic_error("the technique reports no hpsm decisions");
  return source->HpsmDecisions();
}

// The floating box's shadow on its floor, unaccelerated and accelerated: the same image. A slope
// bias of 5 texels' depth change covers the 5x5 kernel's reach (3 texels from the receiver), so the
// lit floor is lit for the filter too and the maps have something to decide.
TEST_P(HpsmTest, BasicLitPassIsTheSameWithAndWithoutAcceleration) {
  const uint32_t W = 128, H = 128;
  scene::Scene s = FloatingBox(true);
  // pcss with pcss_max_kernel 5 has the 5x5 box's reach plus one texel (hpsm.hlsli).
  for (const char* filter : {"box", "gathercmp", "pcss"}) {
    std::map<std::string, std::string> p = {{"resolution", "256"}, {"filter", filter}, {"kernel", "5"}, {"pcss_max_kernel", "5"}, {"slope_bias", "5"}};
    std::unique_ptr<tech::Renderer> plain = MakeBasic(device(), s, W, H, p);
    plain->RenderFrame(s.camera, s.light);
    std::vector<uint8_t> reference = plain->ReadColor();
    for (const char* accel : {"hpsm", "minmax"}) {
      p["accel"] = accel;
      std::unique_ptr<tech::Renderer> r = MakeBasic(device(), s, W, H, p);
      r->RenderFrame(s.camera, s.light);
      std::vector<uint8_t> img = r->ReadColor();
      tech::HpsmCounts st = Decisions(*r);
      std::printf("[ hpsm ] floating box, %s, accel=%s: min/max %.3f, plane %.3f, filtered %.3f of %llu lookups\n", filter, accel, st.minMaxFraction(),
                  st.planeFraction(), st.filteredFraction(), (unsigned long long)st.total());
      EXPECT_GT(st.total(), W * H / 2);
      EXPECT_GT(st.filteredFraction(), 0.0) << "the shadow's edge needs the filter";
      EXPECT_LT(st.filteredFraction(), std::string(accel) == "hpsm" ? 0.2 : 0.8) << "the lit floor and the shadow's core need no filter";
      EXPECT_EQ(CompareImages(std::string("floating-box-") + filter + "-" + accel, W, H, reference.data(), img.data(), 0), 0u) << filter << " " << accel;
    }
  }
  // Without counters: the same picture, nothing counted. With them, the lab's variant of the lit
  // pass (six render targets below the counters' u7) counts as the normal one does.
  std::map<std::string, std::string> p = {{"resolution", "256"}, {"filter", "box"}, {"kernel", "5"}, {"slope_bias", "5"}};
  std::unique_ptr<tech::Renderer> plain = MakeBasic(device(), s, W, H, p);
  plain->RenderFrame(s.camera, s.light);
  std::vector<uint8_t> reference = plain->ReadColor();
  p["accel"] = "hpsm";
  p["hpsm_counters"] = "0";
  std::unique_ptr<tech::Renderer> quiet = MakeBasic(device(), s, W, H, p);
  quiet->RenderFrame(s.camera, s.light);
  std::vector<uint8_t> img = quiet->ReadColor();
  EXPECT_EQ(CompareImages("floating-box-no-counters", W, H, reference.data(), img.data(), 0), 0u);
  EXPECT_EQ(Decisions(*quiet).total(), 0u);
  p["hpsm_counters"] = "1";
  tech::Renderer lab(device(), s, MakeConfiguredTechnique(device(), "basic", p), W, H, LabOptions(true));
  lab.RenderFrame(s.camera, s.light);
  uint64_t normal = Decisions(lab).total();
  lab.RenderLitPass(s.camera, s.light, tech::LitPass::Lab);
  EXPECT_EQ(Decisions(lab).total(), 2 * normal) << "the lab pass counts the same lookups again";
  EXPECT_EQ(CompareImages("floating-box-lab", W, H, reference.data(), lab.ReadLab().color.data(), 0), 0u);
}

// csm: several layers (array slices, or atlas regions of one slice clamped by uvClamp), two
// lookups per pixel where cascades blend, and receiver-plane bias (references that vary over the
// footprint). Accelerated and plain draw the same image.
// csm's cascades and sdsm's partitions (csm's lighting code, its constants written on the GPU by
// cull=gpu or from the CPU by cull=readback): each layer gets its own secondary map.
TEST_P(HpsmTest, CsmAndSdsmLitPassesAreTheSameWithAndWithoutAcceleration) {
  const uint32_t W = 128, H = 128;
  scene::Scene s = FloatingBox(true);
  struct Case {
    const char* technique;
    std::map<std::string, std::string> params;
  };
  std::vector<Case> cases;
  for (const char* storage : {"array", "atlas"})
    for (const char* bias : {"slope", "receiver-plane"})
      cases.push_back({"csm", {{"storage", storage}, {"bias", bias}, {"filter", "gathercmp"}, {"kernel", "5"}}});
  cases.push_back({"csm", {{"filter", "pcss"}, {"pcss_max_kernel", "5"}}});
  cases.push_back({"csm", {{"filter", "pcss"}, {"pcss_max_kernel", "5"}, {"bias", "receiver-plane"}}});
  for (const char* cull : {"gpu", "readback"}) cases.push_back({"sdsm", {{"cull", cull}, {"filter", "gathercmp"}, {"kernel", "5"}}});
  for (Case& c : cases) {
    std::map<std::string, std::string> p = {{"cascades", "3"}, {"resolution", "256"}, {"blend", "0.2"}, {"slope_bias", "5"}};
    std::string what = c.technique;
    for (auto& [k, v] : c.params) p[k] = v, what += "-" + k + "-" + v;
    auto make = [&](const std::map<std::string, std::string>& params) {
      return MakeTechniqueRenderer(device(), c.technique, s, W, H, params);
    };
    std::unique_ptr<tech::Renderer> plain = make(p);
    plain->RenderFrame(s.camera, s.light);
    std::vector<uint8_t> reference = plain->ReadColor();
    p["accel"] = "hpsm";
    std::unique_ptr<tech::Renderer> r = make(p);
    r->RenderFrame(s.camera, s.light);
    std::vector<uint8_t> img = r->ReadColor();
    tech::HpsmCounts st = Decisions(*r);
    std::printf("[ hpsm ] %s: min/max %.3f, plane %.3f, filtered %.3f of %llu lookups\n", what.c_str(), st.minMaxFraction(), st.planeFraction(),
                st.filteredFraction(), (unsigned long long)st.total());
    EXPECT_GT(st.total(), W * H / 2) << what;
    EXPECT_LT(st.filteredFraction(), 0.5) << what;
    EXPECT_EQ(CompareImages(what, W, H, reference.data(), img.data(), 0), 0u) << what;
  }
}

// --- (3) the chapter's claim: a flat receiver under a low sun

// A floor under a sun 12 degrees above the horizon and a small box; the camera looks down on
// the floor. The floor's depth in the map changes by many texels' worth across a block, so a
// block's min/max straddles the receiver's reference, while the floor's plane does not.
TEST_P(HpsmTest, PlanesDecideAFlatReceiverUnderALowSunWhereMinMaxDoesNot) {
  const uint32_t W = 128, H = 128;
  scene::Scene s = FloatingBox(false);
  s.light.direction = glm::normalize(glm::vec3(std::cos(glm::radians(12.0f)), -std::sin(glm::radians(12.0f)), 0.3f));
  std::map<std::string, std::string> p = {{"resolution", "256"}, {"filter", "box"}, {"kernel", "3"}};
  std::unique_ptr<tech::Renderer> plain = MakeBasic(device(), s, W, H, p);
  plain->RenderFrame(s.camera, s.light);
  std::vector<uint8_t> reference = plain->ReadColor();
  std::map<std::string, double> decided;
  for (const char* accel : {"hpsm", "minmax"}) {
    p["accel"] = accel;
    std::unique_ptr<tech::Renderer> r = MakeBasic(device(), s, W, H, p);
    r->RenderFrame(s.camera, s.light);
    std::vector<uint8_t> img = r->ReadColor();
    tech::HpsmCounts st = Decisions(*r);
    std::printf("[ hpsm ] low sun, box 3, accel=%s: min/max %.3f, plane %.3f, filtered %.3f of %llu lookups\n", accel, st.minMaxFraction(), st.planeFraction(),
                st.filteredFraction(), (unsigned long long)st.total());
    decided[accel] = 1.0 - st.filteredFraction();
    if (std::string(accel) == "hpsm") {
      EXPECT_GT(st.planeFraction(), 0.6) << "planes decide most of the floor";
    }
    EXPECT_EQ(CompareImages(std::string("low-sun-") + accel, W, H, reference.data(), img.data(), 0), 0u) << accel;
  }
  EXPECT_GT(decided["hpsm"], 0.9);
  EXPECT_LT(decided["minmax"], 0.35) << "min/max should decide little of a receiver this steep in the map";
}

// --- (4) parameters

TEST_P(HpsmTest, BadParametersAreRefusedNamingTheParameter) {
  auto configure = [&](const TechniqueParams& p) { MakeConfiguredTechnique(device(), "basic", p); };
  auto expectError = [&](const TechniqueParams& p, const std::string& param) { ExpectConfigureRefused(device(), "basic", p, param); };
  expectError({{"accel", "fast"}}, "accel");
  expectError({{"accel", "hpsm"}, {"hpsm_block", "-1"}}, "hpsm_block");
  expectError({{"accel", "hpsm"}, {"hpsm_block", "300"}}, "hpsm_block");
  expectError({{"accel", "hpsm"}, {"resolution", "64"}, {"hpsm_block", "128"}}, "hpsm_block");
  expectError({{"accel", "minmax"}, {"filter", "box"}, {"kernel", "5"}, {"hpsm_block", "4"}}, "hpsm_block");
  expectError({{"accel", "minmax"}, {"hpsm_block", "6"}}, "hpsm_block");
  expectError({{"accel", "hpsm"}, {"hpsm_eps", "-0.1"}}, "hpsm_eps");
  expectError({{"accel", "hpsm"}, {"hpsm_eps", "x"}}, "hpsm_eps");
  expectError({{"accel", "hpsm"}, {"hpsm_build", "texelfetch"}}, "hpsm_build");
  EXPECT_NO_THROW(configure({{"accel", "minmax"}, {"filter", "box"}, {"kernel", "5"}, {"hpsm_block", "8"}}));
  // csm: the same parameters, and no accel for moment filters.
  auto csm = [&](const TechniqueParams& p, const std::string& param, const std::string& technique = "csm") {
    ExpectConfigureRefused(device(), technique, p, param);
  };
  csm({{"accel", "hpsm"}, {"filter", "vsm"}}, "accel");
  csm({{"accel", "minmax"}, {"hpsm_block", "3"}}, "hpsm_block");
  // pcss: the footprint is 2 (pcss_max_kernel / 2 + 1) + 2 texels (18 for the default 15).
  csm({{"accel", "minmax"}, {"filter", "pcss"}, {"hpsm_block", "16"}}, "hpsm_block");
  expectError({{"accel", "minmax"}, {"filter", "pcss"}, {"pcss_max_kernel", "7"}, {"hpsm_block", "8"}}, "hpsm_block");
  EXPECT_NO_THROW(configure({{"accel", "minmax"}, {"filter", "pcss"}, {"pcss_max_kernel", "7"}, {"hpsm_block", "16"}}));
  // sdsm: csm's parameters, through its shared settings.
  csm({{"accel", "minmax"}, {"hpsm_block", "3"}}, "hpsm_block", "sdsm");
  csm({{"accel", "hpsm"}, {"hpsm_eps", "-1"}}, "hpsm_eps", "sdsm");
  csm({{"accel", "fast"}}, "accel", "sdsm");
}

SP_INSTANTIATE_BACKEND_TESTS(HpsmTest);

}  // namespace
}  // namespace sp::test
