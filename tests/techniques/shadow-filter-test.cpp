// shaders-hlsl/common/shadow-filter.hlsli: every filter, run in a compute shader on a small
// Texture2DArray of known depths, against the same kernel evaluated on the CPU from D3D11's rules.
//
// A SampleCmpLevelZero tap is D3D11's comparison filter (functional spec 7.18.7): each of the
// four texels around the tap gives 1 when `reference <= texel`, and the 0/1 results are weighted
// bilinearly (texel centres at (i + 0.5) / W). D3D11 guarantees only 8 fractional bits of the
// texel coordinate, so every bilinear weight may be off by 1/256: a tap may be off by 1/256 of
// the difference of its results per axis (cs::SampleLevelCpu's tolerance), and a kernel by the
// sum of its taps' tolerances times their weights. GatherCmp returns the four 0/1 results
// unweighted; the gathercmp filter weights them in float itself, so it must match its CPU kernel
// to float rounding (kGatherSlack). Where a tap's reference (computed by the GPU in float) lies
// within kAmbiguous of a texel, the comparison may go either way, and the tap's weight is added
// to the tolerance (only with receiver-plane bias; without it references are exact floats).
#include <glm/glm.hpp>
#include <random>

#include "backend-test.h"
#include "probes/sampling-util.h"

namespace sp::test {
namespace {

namespace cs = conformance::sampling;

constexpr uint32_t kSize = 32, kLayers = 3;
constexpr float kTexel = 1.0f / kSize;
enum Layer { kSteps, kPlane, kWall };
enum Filter { kHw2x2, kBox, kGauss, kGatherCmp, kPoisson };
const char* const kFilterNames[] = {"hw2x2", "box", "gauss", "gathercmp", "poisson"};
constexpr double kGatherSlack = 1e-5;  // ~100 float products and sums of values <= 1
constexpr double kAmbiguous = 1e-5;    // float error of a reference built from depth, gradient and offsets

// The tilted plane of layer kPlane: depth = a u + b v + c (between 0.3 and 0.8).
constexpr float kPlaneA = 0.3f, kPlaneB = -0.2f, kPlaneC = 0.5f;
float PlaneDepth(float u, float v) { return kPlaneA * u + kPlaneB * v + kPlaneC; }
// Layer kWall: lit (1) inside texels [8, 24) of both axes, a wall at depth 0 around it.
const glm::vec4 kWallRect(0.25f, 0.25f, 0.75f, 0.75f);

// The map: kSteps holds 3x3-texel blocks of depths k/64 (so every kernel straddles edges and
// references k/64 hit texel values exactly), kPlane the plane sampled at texel centres, kWall the wall.
struct Map {
  std::vector<float> texels = std::vector<float>(kSize * kSize * kLayers);
  Map() {
    for (uint32_t y = 0; y < kSize; ++y)
      for (uint32_t x = 0; x < kSize; ++x) {
        uint32_t bx = x / 3, by = y / 3;
        At(kSteps, x, y) = float(8 + (bx * 37 + by * 11 + bx * by * 5) % 49) / 64.0f;
        At(kPlane, x, y) = PlaneDepth((x + 0.5f) * kTexel, (y + 0.5f) * kTexel);
        bool inside = x >= 8 && x < 24 && y >= 8 && y < 24;
        At(kWall, x, y) = inside ? 1.0f : 0.0f;
      }
  }
  float& At(int layer, uint32_t x, uint32_t y) { return texels[(layer * kSize + y) * kSize + x]; }
  float At(int layer, int x, int y) const {
    return texels[(layer * kSize + std::clamp(y, 0, int(kSize) - 1)) * kSize + std::clamp(x, 0, int(kSize) - 1)];
  }
  // The 0/1 results of `reference <= texel` over one layer, as an image cs::SampleLevelCpu filters.
  cs::MipChain Compared(int layer, double reference) const {
    cs::MipChain c{kSize, kSize, {std::vector<float>(kSize * kSize)}};
    for (uint32_t t = 0; t < kSize * kSize; ++t) c.levels[0][t] = reference <= texels[layer * kSize * kSize + t] ? 1.0f : 0.0f;
    return c;
  }
};
const Map& TheMap() {
  static const Map m;
  return m;
}

// ShadowFilterInput as the test's shader reads it (members ordered so that HLSL's structured
// buffer layout and std430 agree: no vector straddles a 16-byte boundary).
struct Query {
  glm::vec2 uv{0.5f};
  float layer = 0, depth = 0.5f;
  glm::vec2 texelSize{kTexel};
  glm::vec2 gradient{0.0f};
  glm::vec4 uvClamp{0, 0, 1, 1};
  glm::vec2 pixel{0.5f};
  glm::vec2 pad{0.0f};
};
static_assert(sizeof(Query) == 64);

// The compute shaders' bindings and the start of their main(): the query as ShadowFilterInput i.
const std::string kQueryShaderStart = R"(
struct Query { float2 uv; float layer; float depth; float2 texelSize; float2 depthGradient; float4 uvClamp; float2 pixel; float2 pad; };
Texture2DArray<float> shadowMap : register(t0);
SamplerComparisonState shadowCmp : register(s0);
StructuredBuffer<Query> queries : register(t1);
RWStructuredBuffer<float4> output : register(u0);
[numthreads(64, 1, 1)] void main(uint3 id : SV_DispatchThreadID) {
  Query q = queries[id.x];
  ShadowFilterInput i = {q.uv, q.layer, q.depth, q.texelSize, q.uvClamp, q.depthGradient, q.pixel};
)";
const std::string kFilterShader = "#include \"common/shadow-filter.hlsli\"\n" + kQueryShaderStart + R"(
  output[id.x] = float4(ShadowFilter(shadowMap, shadowCmp, i), 0, 0, 0);
}
)";

// The library's other functions, and its Poisson table and rotation, one case per thread:
// mode 0 ReceiverPlaneDepthGradient(a.xyz, b.xyz); 1 NormalOffset(a.xyz, b.xyz, b.w, a.w);
// 2 Poisson point a.x and rotation of pixel b.xy.
const char* const kMathShader = R"(
#define SHADOW_FILTER 4
#include "common/shadow-filter.hlsli"
struct MathCase { float4 a; float4 b; float4 mode; };
StructuredBuffer<MathCase> cases : register(t1);
RWStructuredBuffer<float4> output : register(u0);
[numthreads(64, 1, 1)] void main(uint3 id : SV_DispatchThreadID) {
  MathCase c = cases[id.x];
  float4 r = float4(0, 0, 0, 0);
  if (c.mode.x == 0) r.xy = ReceiverPlaneDepthGradient(c.a.xyz, c.b.xyz);
  else if (c.mode.x == 1) r.xyz = NormalOffset(c.a.xyz, c.b.xyz, c.b.w, c.a.w);
  else r = float4(kShadowPoissonDisk[uint(c.a.x)], ShadowFilterRotation(c.b.xy));
  output[id.x] = r;
}
)";
struct MathCase {
  glm::vec4 a{0.0f}, b{0.0f}, mode{0.0f};  // mode.x as above
};

// ShadowFilterPcss with an orthographic ShadowPcssInput from the defines PCSS_NEAR, PCSS_FAR,
// PCSS_SCALE, PCSS_TAPS and PCSS_MAX.
const std::string kPcssShader = "#define SHADOW_FILTER 5\n#include \"common/shadow-pcss.hlsli\"\n" + kQueryShaderStart + R"(
  ShadowPcssInput p = {float2(PCSS_NEAR, PCSS_FAR), float2(PCSS_SCALE, PCSS_SCALE), 0.0, PCSS_TAPS, PCSS_MAX, 0.0};
  output[id.x] = float4(ShadowFilterPcss(shadowMap, shadowCmp, i, p), 0, 0, 0);
}
)";

// --- The kernels on the CPU, step by step as the HLSL defines them

// ShadowFilterSetup, in float as the shader computes it.
struct Frame {
  glm::vec2 s, lo, hi;  // receiver, first and last texel centre inside uvClamp (texel space)
  float reference;      // depth less the receiver-plane footprint term
};
Frame FrameOf(const Query& q) {
  glm::vec2 size = 1.0f / q.texelSize;
  return {q.uv * size - 0.5f, glm::round(glm::vec2(q.uvClamp) * size), glm::round(glm::vec2(q.uvClamp.z, q.uvClamp.w) * size) - 1.0f,
          q.depth - glm::dot(glm::abs(q.gradient), q.texelSize)};
}
double Reference(const Query& q, const Frame& f, glm::vec2 p) {
  return double(f.reference) + double((p.x - f.s.x) * q.texelSize.x) * q.gradient.x + double((p.y - f.s.y) * q.texelSize.y) * q.gradient.y;
}
bool HasGradient(const Query& q) { return q.gradient != glm::vec2(0.0f); }

struct Tap {
  glm::vec2 offset;  // texel space, from the receiver
  double weight;
};

uint32_t Pcg(uint32_t v) {
  uint32_t state = v * 747796405u + 2891336453u;
  uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}
// The per-pixel rotation as (cos, sin): PCG of x + PCG(y), its top 24 bits as a fraction of a turn.
glm::vec2 Rotation(glm::vec2 pixel) {
  double angle = double(Pcg(uint32_t(pixel.x) + Pcg(uint32_t(pixel.y))) >> 8) * (6.283185307179586 / 16777216.0);
  return {float(std::cos(angle)), float(std::sin(angle))};
}

// The taps of the SampleCmp-based filters; `disk` is the Poisson table (read from the shader).
// C(n, k), exact in double for the widths used (at most C(14, 7) = 3432).
double Binomial(int n, int k) {
  double c = 1;
  for (int i = 1; i <= k; ++i) c = c * (n - k + i) / i;
  return c;
}

std::vector<Tap> Taps(Filter filter, int n, const Query& q, const std::vector<glm::vec2>& disk) {
  std::vector<Tap> taps;
  const int h = n / 2;
  if (filter == kHw2x2) taps.push_back({{0, 0}, 1.0});
  if (filter == kBox || filter == kGauss)
    for (int y = -h; y <= h; ++y)
      for (int x = -h; x <= h; ++x)
        taps.push_back({{float(x), float(y)}, filter == kBox ? 1.0 / (n * n) : Binomial(n - 1, x + h) * Binomial(n - 1, y + h) / std::pow(4.0, n - 1)});
  if (filter == kPoisson) {
    glm::vec2 r = Rotation(q.pixel);
    for (glm::vec2 p : disk) {
      glm::vec2 d = p * (n * 0.5f);
      taps.push_back({{d.x * r.x - d.y * r.y, d.x * r.y + d.y * r.x}, 1.0 / disk.size()});
    }
  }
  return taps;
}

// A SampleCmp kernel: each tap clamped into uvClamp, with its receiver-plane reference, filtered
// by D3D11's rules (cs::SampleLevelCpu on the 0/1 comparison image) and weighted.
cs::Expected TapKernel(const Query& q, const std::vector<Tap>& taps) {
  const Map& m = TheMap();
  const Frame f = FrameOf(q);
  cs::Expected sum;
  double lastRef = -1;
  cs::MipChain compared;
  for (const Tap& t : taps) {
    glm::vec2 p = glm::clamp(f.s + t.offset, f.lo, f.hi);
    glm::vec2 uv = (p + 0.5f) * q.texelSize;
    double ref = HasGradient(q) ? Reference(q, f, p) : q.depth;
    if (ref != lastRef) compared = m.Compared(int(q.layer), lastRef = ref);
    cs::Expected e = cs::SampleLevelCpu(compared, 0, uv.x, uv.y, cs::SamplerModel{});
    sum.value += t.weight * e.value;
    sum.tol += t.weight * e.tol;
    int i0 = int(std::floor(p.x)), j0 = int(std::floor(p.y));
    bool ambiguous = false;
    for (int k = 0; k < 4 && HasGradient(q); ++k) ambiguous |= std::abs(m.At(int(q.layer), i0 + k % 2, j0 + k / 2) - ref) < kAmbiguous;
    if (ambiguous) sum.tol += t.weight;
  }
  return sum;
}

// The box kernel texel by texel, with one reference per 2x2 block (its centre), as gathercmp
// defines it: footprint texel t = floor(s) - N/2 + (a, b), weight w(a) w(b) / N^2 with
// w = (1 - f, 1, ..., 1, f), reading texel clamp(t, lo, hi).
cs::Expected FootprintKernel(const Query& q, int n) {
  const Map& m = TheMap();
  const Frame f = FrameOf(q);
  const glm::vec2 first = glm::floor(f.s) - float(n / 2), frac = f.s - glm::floor(f.s);
  auto w = [&](int a, int axis) { return a == 0 ? 1.0 - frac[axis] : a == n ? double(frac[axis]) : 1.0; };
  cs::Expected sum{0, kGatherSlack};
  for (int b = 0; b <= n; ++b)
    for (int a = 0; a <= n; ++a) {
      glm::vec2 t = first + glm::vec2(a, b), c = glm::clamp(t, f.lo, f.hi);
      glm::vec2 block = glm::clamp(first + glm::vec2(a - a % 2, b - b % 2), f.lo, f.hi - 1.0f);
      double ref = Reference(q, f, block + 0.5f), texel = m.At(int(q.layer), int(c.x), int(c.y));
      double weight = w(a, 0) * w(b, 1) / (n * n);
      sum.value += weight * (ref <= texel ? 1.0 : 0.0);
      if (HasGradient(q) && std::abs(texel - ref) < kAmbiguous) sum.tol += weight;
    }
  return sum;
}

// --- Queries

// Reproducible uniform floats in [lo, hi) (mt19937's output is specified exactly).
struct Random {
  std::mt19937 gen{20240611};
  float operator()(float lo, float hi) { return lo + (hi - lo) * float(gen() >> 8) / 16777216.0f; }
};

// A mix that exercises every part of the kernels: the steps layer with references on texel values
// (LESS_EQUAL ties) and between them, centres past the map's edges (the taps clamp to the whole
// layer), the plane with references just above and below it, and receiver-plane gradients.
std::vector<Query> GeneralQueries() {
  const Map& m = TheMap();
  Random r;
  std::vector<Query> qs;
  for (int i = 0; i < 160; ++i) {
    Query q;
    q.pixel = {float(i) + 0.5f, 3.5f};
    if (i < 96) {
      q.uv = {r(-0.05f, 1.05f), r(-0.05f, 1.05f)};
      int k = int(r(0, 1) * 49);
      q.depth = i % 2 ? m.At(kSteps, int(r(0, kSize)), int(r(0, kSize))) : (8 + k + 0.5f) / 64.0f;
      if (i >= 64) q.gradient = {r(-0.1f, 0.1f), r(-0.1f, 0.1f)};
    } else {
      q.layer = kPlane;
      q.uv = {r(0.0f, 1.0f), r(0.0f, 1.0f)};
      q.depth = PlaneDepth(q.uv.x, q.uv.y) + r(-0.03f, 0.03f);
      if (i >= 128) q.gradient = {kPlaneA, kPlaneB};
    }
    qs.push_back(q);
  }
  return qs;
}

std::string Describe(const Query& q) {
  return "uv (" + cs::Fmt(q.uv.x) + ", " + cs::Fmt(q.uv.y) + ") layer " + cs::Fmt(q.layer) + " depth " + cs::Fmt(q.depth) + " gradient (" +
         cs::Fmt(q.gradient.x) + ", " + cs::Fmt(q.gradient.y) + ") pixel (" + cs::Fmt(q.pixel.x) + ", " + cs::Fmt(q.pixel.y) + ")";
}

// Fails the test with the worst case when any result is outside its expectation.
void ExpectMatches(const std::string& what, const std::vector<float>& got, const std::vector<cs::Expected>& want, const std::vector<Query>& qs) {
  cs::Worst worst;
  for (size_t i = 0; i < got.size(); ++i) worst.Add(got[i], want[i], Describe(qs[i]));
  conformance::Result r = worst.Finish("abs");
  EXPECT_EQ(r.status, conformance::Status::Pass) << what << ": " << r.detail;
}

// At least an eighth of the results strictly between 0 and 1: the data exercise the filtering
// (hw2x2 gets about a fifth, the wider kernels most).
void ExpectPartlyLit(const std::string& what, const std::vector<float>& got) {
  size_t partial = std::count_if(got.begin(), got.end(), [](float v) { return v > 0.001f && v < 0.999f; });
  EXPECT_GE(partial * 8, got.size()) << what << ": too few penumbra results to test the kernel";
}

// --- The map on a device, and the shaders that read it

class FilterRig {
 public:
  explicit FilterRig(Device& dev) : dev_(dev) {
    // A shadow map as techniques make one: R32_TYPELESS with a depth binding, read as R32_FLOAT.
    // Depth textures take no initial data in D3D11: upload through a staging copy.
    tex_ = MakeTexture2D(dev_, kSize, kSize, FORMAT_R32_TYPELESS, BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE, nullptr, 1, kLayers);
    TEXTURE2D_DESC sd = tex_->GetDesc();
    sd.BindFlags = 0;
    sd.Usage = USAGE_STAGING;
    sd.CPUAccessFlags = CPU_ACCESS_WRITE;
    std::vector<SUBRESOURCE_DATA> init;
    for (uint32_t l = 0; l < kLayers; ++l) init.push_back({TheMap().texels.data() + l * kSize * kSize, kSize * 4, 0});
    Ref<Texture2D> staging = dev_.CreateTexture2D(sd, init.data());
    ctx().CopyResource(tex_.get(), staging.get());
    SHADER_RESOURCE_VIEW_DESC vd;
    vd.Format = FORMAT_R32_FLOAT;
    vd.ViewDimension = SRV_DIMENSION_TEXTURE2DARRAY;
    vd.Texture2DArray = {0, 1, 0, kLayers};
    srv_ = dev_.CreateShaderResourceView(tex_.get(), &vd);
    SAMPLER_DESC d;
    d.Filter = FILTER_COMPARISON_MIN_MAG_LINEAR_MIP_POINT;
    d.ComparisonFunc = COMPARISON_LESS_EQUAL;
    cmp_ = dev_.CreateSamplerState(d);
  }

  std::vector<float> Filtered(Filter filter, int n, const std::vector<Query>& qs) {
    ShaderBytecode code = CompileHlsl(kFilterShader, "cs_5_0", "main", {{"SHADOW_FILTER", std::to_string(int(filter))}, {"SHADOW_KERNEL", std::to_string(n)}});
    std::vector<float> r;
    for (const glm::vec4& v : Dispatch(code, qs)) r.push_back(v.x);
    return r;
  }

  std::vector<float> FilteredPcss(const std::vector<hlsl::Define>& defines, const std::vector<Query>& qs) {
    std::vector<float> r;
    for (const glm::vec4& v : Dispatch(CompileHlsl(kPcssShader, "cs_5_0", "main", defines), qs)) r.push_back(v.x);
    return r;
  }

  std::vector<glm::vec4> Math(const std::vector<MathCase>& cases) { return Dispatch(CompileHlsl(kMathShader, "cs_5_0", "main"), cases); }

  std::vector<glm::vec2> PoissonDisk() {
    std::vector<MathCase> cases;
    for (int k = 0; k < 16; ++k) cases.push_back({{float(k), 0, 0, 0}, {}, {2, 0, 0, 0}});
    std::vector<glm::vec2> disk;
    for (const glm::vec4& v : Math(cases)) disk.push_back({v.x, v.y});
    return disk;
  }

 private:
  DeviceContext& ctx() { return *dev_.GetImmediateContext(); }

  // Runs `code` over `in` (t1; the map at t0, the sampler at s0); one float4 per element.
  template <class In>
  std::vector<glm::vec4> Dispatch(const ShaderBytecode& code, std::vector<In> in) {
    const size_t count = in.size();
    while (in.size() % 64) in.push_back(in.front());
    Ref<ComputeShader> shader = dev_.CreateComputeShader(code);
    Ref<Buffer> input = MakeBuffer(dev_, BIND_SHADER_RESOURCE, in.data(), uint32_t(in.size() * sizeof(In)), RESOURCE_MISC_BUFFER_STRUCTURED, sizeof(In));
    Ref<Buffer> out = MakeBuffer(dev_, BIND_UNORDERED_ACCESS, nullptr, uint32_t(in.size() * 16), RESOURCE_MISC_BUFFER_STRUCTURED, 16);
    SHADER_RESOURCE_VIEW_DESC sd;
    sd.ViewDimension = SRV_DIMENSION_BUFFER;
    sd.Buffer = {0, uint32_t(in.size())};
    Ref<ShaderResourceView> inputView = dev_.CreateShaderResourceView(input.get(), &sd);
    UNORDERED_ACCESS_VIEW_DESC ud;
    ud.ViewDimension = UAV_DIMENSION_BUFFER;
    ud.Buffer = {0, uint32_t(in.size()), 0};
    Ref<UnorderedAccessView> uav = dev_.CreateUnorderedAccessView(out.get(), &ud);
    ctx().CSSetShader(shader.get());
    ctx().CSSetShaderResources(0, {srv_.get(), inputView.get()});
    ctx().CSSetSamplers(0, {cmp_.get()});
    ctx().CSSetUnorderedAccessViews(0, {uav.get()});
    ctx().Dispatch(uint32_t(in.size() / 64), 1, 1);
    ctx().ClearState();
    std::vector<glm::vec4> r = ReadAs<glm::vec4>(ReadBuffer(dev_, ctx(), out.get()));
    r.resize(count);
    return r;
  }

  Device& dev_;
  Ref<Texture2D> tex_;
  Ref<ShaderResourceView> srv_;
  Ref<SamplerState> cmp_;
};

class ShadowFilterTest : public BackendTest {
 protected:
  void SetUp() override {
    BackendTest::SetUp();
    rig_ = std::make_unique<FilterRig>(device());
  }
  void TearDown() override {
    rig_.reset();
    BackendTest::TearDown();
  }

  // The filter against its CPU kernel (taps for SampleCmp filters, the footprint for gathercmp).
  void ExpectMatchesCpu(Filter filter, int n, const std::vector<Query>& qs, const std::vector<float>& got) {
    std::vector<glm::vec2> disk = filter == kPoisson ? rig_->PoissonDisk() : std::vector<glm::vec2>{};
    std::vector<cs::Expected> want;
    for (const Query& q : qs) want.push_back(filter == kGatherCmp ? FootprintKernel(q, n) : TapKernel(q, Taps(filter, n, q, disk)));
    ExpectMatches(std::string(kFilterNames[filter]) + " " + std::to_string(n) + "x" + std::to_string(n), got, want, qs);
  }

  std::unique_ptr<FilterRig> rig_;
};

TEST_P(ShadowFilterTest, Hw2x2EqualsTheBilinearComparisonFilter) {
  std::vector<Query> qs = GeneralQueries();
  std::vector<float> got = rig_->Filtered(kHw2x2, 3, qs);
  ExpectMatchesCpu(kHw2x2, 1, qs, got);
  ExpectPartlyLit("hw2x2", got);
}

TEST_P(ShadowFilterTest, BoxAndGaussMatchTheirCpuKernels) {
  std::vector<Query> qs = GeneralQueries();
  for (Filter filter : {kBox, kGauss})
    for (int n = 3; n <= 9; n += 2) {
      std::vector<float> got = rig_->Filtered(filter, n, qs);
      ExpectMatchesCpu(filter, n, qs, got);
      ExpectPartlyLit(std::string(kFilterNames[filter]) + " " + std::to_string(n), got);
    }
}

// gathercmp builds the box kernel; without receiver-plane bias the two differ only by the
// SampleCmp taps' 8-bit weights (the box's CPU tolerance). With it, a texel is compared with the
// reference at its 2x2 block's centre (within half a texel) instead of at each tap reading it
// (within one texel), so the results agree wherever no footprint texel lies within
// dot(|gradient|, texelSize) (one texel of receiver slope) of the plane's reference at the texel.
TEST_P(ShadowFilterTest, GatherCmpBuildsTheBoxKernel) {
  const Map& m = TheMap();
  std::vector<Query> qs = GeneralQueries();
  for (int n = 3; n <= 9; n += 2) {
    std::vector<float> gather = rig_->Filtered(kGatherCmp, n, qs), box = rig_->Filtered(kBox, n, qs);
    ExpectMatchesCpu(kGatherCmp, n, qs, gather);
    cs::Worst worst;
    int compared = 0;
    for (size_t i = 0; i < qs.size(); ++i) {
      const Query& q = qs[i];
      const Frame f = FrameOf(q);
      bool separated = true;
      for (int b = -n / 2; b <= n / 2 + 1; ++b)
        for (int a = -n / 2; a <= n / 2 + 1; ++a) {
          glm::vec2 c = glm::clamp(glm::floor(f.s) + glm::vec2(a, b), f.lo, f.hi);
          double band = glm::dot(glm::abs(q.gradient), q.texelSize) + kAmbiguous;
          separated &= !HasGradient(q) || std::abs(m.At(int(q.layer), int(c.x), int(c.y)) - Reference(q, f, c)) > band;
        }
      if (!separated) continue;
      ++compared;
      // The two CPU kernels are one kernel, up to float rounding of the tap positions: check that first.
      cs::Expected footprint = FootprintKernel(q, n), taps = TapKernel(q, Taps(kBox, n, q, {}));
      worst.AddError(std::abs(footprint.value - taps.value), kGatherSlack, "CPU footprint vs taps, " + Describe(q));
      worst.Add(gather[i], {box[i], taps.tol + kGatherSlack}, "gathercmp vs box, " + Describe(q));
    }
    conformance::Result r = worst.Finish("abs");
    EXPECT_EQ(r.status, conformance::Status::Pass) << n << "x" << n << ": " << r.detail;
    EXPECT_GT(compared, int(qs.size() * 3 / 4)) << n << "x" << n;
  }
}

// The wide kernels (loops, not unrolled: SHADOW_UNROLL_MAX) against the same CPU kernels: box,
// gauss and poisson up to 15, gathercmp up to 31 (wider than the 32-texel map's half: clamping
// into uvClamp is exercised on every query). Gauss 15's weights are integers up to 3432^2 < 2^24
// over 4^14: exact in float, so its tolerance is the taps' alone.
TEST_P(ShadowFilterTest, WideKernelsMatchTheirCpuKernels) {
  std::vector<Query> qs = GeneralQueries();
  const std::pair<Filter, int> cases[] = {{kBox, 11}, {kBox, 15}, {kGauss, 13}, {kGauss, 15}, {kPoisson, 15}, {kGatherCmp, 15}, {kGatherCmp, 31}};
  for (auto [filter, n] : cases) {
    std::vector<float> got = rig_->Filtered(filter, n, qs);
    ExpectMatchesCpu(filter, n, qs, got);
    ExpectPartlyLit(std::string(kFilterNames[filter]) + " " + std::to_string(n), got);
  }
}

TEST_P(ShadowFilterTest, PoissonIsDeterministicAndMatchesItsCpuTaps) {
  // The table: 16 points in the unit disc, spread out (minimum spacing) and centred.
  std::vector<glm::vec2> disk = rig_->PoissonDisk();
  glm::vec2 mean(0.0f);
  float spacing = 2;
  for (size_t i = 0; i < disk.size(); ++i) {
    EXPECT_LE(glm::length(disk[i]), 1.0f) << i;
    mean += disk[i] / float(disk.size());
    for (size_t j = 0; j < i; ++j) spacing = std::min(spacing, glm::distance(disk[i], disk[j]));
  }
  EXPECT_GE(spacing, 0.5f);
  EXPECT_LT(glm::length(mean), 0.01f);
  // The shader's rotation is the CPU's PCG hash of the pixel (sincos to float accuracy).
  std::vector<MathCase> rot;
  for (int i = 0; i < 64; ++i) rot.push_back({{0, 0, 0, 0}, {float(i * 37 % 1920) + 0.5f, float(i * 53 % 1080) + 0.5f, 0, 0}, {2, 0, 0, 0}});
  std::vector<glm::vec4> gotRot = rig_->Math(rot);
  for (size_t i = 0; i < rot.size(); ++i) {
    glm::vec2 want = Rotation(rot[i].b);
    EXPECT_NEAR(gotRot[i].z, want.x, 2e-6) << i;
    EXPECT_NEAR(gotRot[i].w, want.y, 2e-6) << i;
  }
  std::vector<Query> qs = GeneralQueries();
  for (int n = 3; n <= 9; n += 2) {
    std::vector<float> first = rig_->Filtered(kPoisson, n, qs), second = rig_->Filtered(kPoisson, n, qs);
    EXPECT_EQ(0, std::memcmp(first.data(), second.data(), first.size() * 4)) << "poisson " << n << " differs between two runs";
    ExpectMatchesCpu(kPoisson, n, qs, first);
    ExpectPartlyLit("poisson " + std::to_string(n), first);
  }
}

// The same lookup from every pixel of a 16x16 block, on steps the 9-texel disc straddles: the
// rotation must change the result between almost every pair of neighbours.
TEST_P(ShadowFilterTest, PoissonRotationVariesBetweenNeighbouringPixels) {
  std::vector<Query> qs;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      Query q;
      q.uv = {0.43f, 0.57f};
      q.depth = 32.5f / 64.0f;
      q.pixel = {100.5f + x, 200.5f + y};
      qs.push_back(q);
    }
  std::vector<float> got = rig_->Filtered(kPoisson, 9, qs);
  ExpectMatchesCpu(kPoisson, 9, qs, got);
  int pairs = 0, differing = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      if (x < 15) ++pairs, differing += got[y * 16 + x] != got[y * 16 + x + 1];
      if (y < 15) ++pairs, differing += got[y * 16 + x] != got[(y + 1) * 16 + x];
    }
  EXPECT_GE(differing * 10, pairs * 9) << differing << " of " << pairs << " neighbouring pairs differ";
}

// Centres all over the wall layer, inside the lit rectangle and up to two texels past it: with the
// rectangle as uvClamp no tap reaches the wall (fully lit, up to float rounding of the weights);
// with the whole layer every filter reaches it from some of them (the check has teeth).
TEST_P(ShadowFilterTest, UvClampKeepsEveryTapInsideTheRectangle) {
  std::vector<Query> qs;
  Random r;
  for (int i = 0; i < 128; ++i) {
    Query q;
    q.layer = kWall;
    q.uv = {r(0.25f - 2 * kTexel, 0.75f + 2 * kTexel), r(0.25f - 2 * kTexel, 0.75f + 2 * kTexel)};
    if (i % 8 == 0) q.uv.x = i % 16 ? 0.25f : 0.75f;  // exactly on the rectangle's edges too
    q.depth = 0.5f;
    q.gradient = i % 2 ? glm::vec2(0.3f, -0.2f) : glm::vec2(0.0f);
    q.pixel = {float(i) + 0.5f, 0.5f};
    q.uvClamp = kWallRect;
    qs.push_back(q);
  }
  std::vector<Query> unclamped = qs;
  for (Query& q : unclamped) q.uvClamp = {0, 0, 1, 1};
  for (Filter filter : {kHw2x2, kBox, kGauss, kGatherCmp, kPoisson})
    for (int n : {3, 9}) {
      std::string name = std::string(kFilterNames[filter]) + " " + std::to_string(n);
      std::vector<float> got = rig_->Filtered(filter, n, qs);
      float darkest = *std::min_element(got.begin(), got.end());
      EXPECT_GE(darkest, 1.0f - 1e-6f) << name << ": a tap read outside uvClamp";
      std::vector<float> control = rig_->Filtered(filter, n, unclamped);
      EXPECT_LT(*std::min_element(control.begin(), control.end()), 0.9f) << name << ": the wall is out of the kernel's reach";
      if (filter == kHw2x2) break;
    }
}

// A receiver on the plane the map holds, with no constant bias: each 7x7 tap compares the plane
// at its own position (the gradient from ReceiverPlaneDepthGradient of the exact derivatives of
// an affine screen-to-map mapping) and is lit; with one reference for all taps, the downhill
// ones see the plane lower than the receiver: acne.
TEST_P(ShadowFilterTest, ReceiverPlaneBiasRemovesAcneOnATiltedPlane) {
  const glm::vec2 dUv_dx(0.002f, -0.0007f), dUv_dy(0.0005f, 0.0019f);
  auto dz = [](glm::vec2 d) { return kPlaneA * d.x + kPlaneB * d.y; };
  std::vector<glm::vec4> g = rig_->Math({{{dUv_dx, dz(dUv_dx), 0}, {dUv_dy, dz(dUv_dy), 0}, {0, 0, 0, 0}}});
  const glm::vec2 gradient(g[0].x, g[0].y);
  EXPECT_NEAR(gradient.x, kPlaneA, 1e-4);
  EXPECT_NEAR(gradient.y, kPlaneB, 1e-4);
  std::vector<Query> qs, flat;
  Random r;
  for (int i = 0; i < 64; ++i) {
    Query q;
    q.layer = kPlane;
    q.uv = {r(0.2f, 0.8f), r(0.2f, 0.8f)};
    q.depth = PlaneDepth(q.uv.x, q.uv.y);
    q.pixel = {float(i) + 0.5f, 0.5f};
    flat.push_back(q);
    q.gradient = gradient;
    qs.push_back(q);
  }
  for (Filter filter : {kBox, kGauss, kGatherCmp, kPoisson}) {
    std::string name = std::string(kFilterNames[filter]) + " 7x7";
    std::vector<float> biased = rig_->Filtered(filter, 7, qs), plain = rig_->Filtered(filter, 7, flat);
    EXPECT_GE(*std::min_element(biased.begin(), biased.end()), 1.0f - 1e-6f) << name << " with receiver-plane bias";
    EXPECT_LT(*std::max_element(plain.begin(), plain.end()), 1.0f) << name << " without it should show acne";
    ExpectMatchesCpu(filter, 7, qs, biased);
  }
}

TEST_P(ShadowFilterTest, ReceiverPlaneDepthGradientInvertsTheJacobian) {
  struct Case { glm::vec3 ddx, ddy; glm::vec2 want; std::string what; };
  // (u, v) = M (x, y) + o and depth = a u + b v + c give ddx = (M00, M10, a M00 + b M10), ddy likewise.
  auto affine = [](glm::mat2 m, glm::vec2 ab) {
    return std::make_pair(glm::vec3(m[0], glm::dot(ab, m[0])), glm::vec3(m[1], glm::dot(ab, m[1])));
  };
  std::vector<Case> cases;
  const std::pair<glm::mat2, glm::vec2> mappings[] = {{glm::mat2(0.002f, -0.0007f, 0.0005f, 0.0019f), {0.3f, -0.2f}},
                                                       {glm::mat2(0.0f, 0.001f, -0.001f, 0.0f), {-1.5f, 0.25f}},  // 90 degrees
                                                       {glm::mat2(1e-5f, 2e-6f, -3e-6f, 4e-5f), {0.01f, 2.0f}}};
  for (auto& [m, ab] : mappings) {
    auto [dx, dy] = affine(m, ab);
    cases.push_back({dx, dy, ab, "affine"});
  }
  cases.push_back({{0.001f, 0.002f, 0.3f}, {0.002f, 0.004f, 0.6f}, {0, 0}, "parallel rows (singular)"});
  cases.push_back({{0, 0, 0}, {0, 0, 0}, {0, 0}, "zero derivatives"});
  cases.push_back({{0.001f, 0.002f, 0.3f}, {0.0010001f, 0.002f, 0.6f}, {0, 0}, "nearly parallel (ratio 5e-5)"});
  std::vector<MathCase> mc;
  for (const Case& c : cases) mc.push_back({{c.ddx, 0}, {c.ddy, 0}, {0, 0, 0, 0}});
  std::vector<glm::vec4> got = rig_->Math(mc);
  for (size_t i = 0; i < cases.size(); ++i) {
    float tol = 1e-4f * std::max(1.0f, glm::length(cases[i].want));
    EXPECT_NEAR(got[i].x, cases[i].want.x, tol) << cases[i].what;
    EXPECT_NEAR(got[i].y, cases[i].want.y, tol) << cases[i].what;
  }
}

TEST_P(ShadowFilterTest, NormalOffsetGrowsFromFacingTheLightToGrazing) {
  const float texel = 0.05f, scale = 2.0f, s = std::sqrt(0.5f);
  struct Case { glm::vec3 normal, toLight, want; };
  const Case cases[] = {
      {{0, 1, 0}, {0, 1, 0}, {0, 0, 0}},                                 // facing the light: no offset
      {{0, 3, 0}, {0, 0.5f, 0}, {0, 0, 0}},                              // inputs need not be unit length
      {{0, 1, 0}, {1, 0, 0}, {0, texel * scale, 0}},                     // grazing: one texel times scale
      {{0, 1, 0}, {s, s, 0}, {0, texel * scale * (1 - s), 0}},           // 45 degrees
      {{0, 0, -2}, {0, 0, 1}, {0, 0, -texel * scale}},                   // facing away: full offset
      {{s, s, 0}, {0, 1, 0}, {s * texel * scale * (1 - s), s * texel * scale * (1 - s), 0}},
  };
  std::vector<MathCase> mc;
  for (const Case& c : cases) mc.push_back({{c.normal, scale}, {c.toLight, texel}, {1, 0, 0, 0}});
  std::vector<glm::vec4> got = rig_->Math(mc);
  for (size_t i = 0; i < std::size(cases); ++i)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[i][k], cases[i].want[k], 1e-6f) << "case " << i << " component " << k;
}

// The library in a pixel shader too: ddx/ddy feed the receiver-plane bias, SampleCmpLevelZero and
// GatherCmp under a non-uniform branch; every filter compiles for ps_5_0 and the driver takes it.
TEST_P(ShadowFilterTest, EveryFilterCompilesForPixelShaders) {
  const char* src = R"(
#include "common/shadow-filter.hlsli"
Texture2DArray<float> shadowMap : register(t0);
SamplerComparisonState shadowCmp : register(s0);
struct In { float4 pos : SV_Position; float3 coord : COORD; float3 normal : NORMAL; };
float4 main(In p) : SV_Target {
  float2 gradient = ReceiverPlaneDepthGradient(ddx(p.coord), ddy(p.coord));
  ShadowFilterInput i = {p.coord.xy, 1, p.coord.z, float2(1.0 / 1024, 1.0 / 1024), float4(0, 0, 0.5, 0.5), gradient, p.pos.xy};
  float lit = 1;
  if (p.coord.z < 1) lit = ShadowFilter(shadowMap, shadowCmp, i);
  return float4(NormalOffset(p.normal, float3(0, 1, 0), 0.01, 1.0), lit);
}
)";
  for (Filter filter : {kHw2x2, kBox, kGauss, kGatherCmp, kPoisson}) {
    ShaderBytecode b = CompileHlsl(src, "ps_5_0", "main", {{"SHADOW_FILTER", std::to_string(int(filter))}, {"SHADOW_KERNEL", "9"}});
    EXPECT_NO_THROW(device().CreatePixelShader(b)) << kFilterNames[filter];
  }
}

// ShadowFilterPcss (shadow-pcss.hlsli) against its three steps on the CPU, orthographic, without
// receiver-plane gradient: the search grid's Loads, the mean linearised blocker depth, and the box
// of real width w (clamped to [1, max]) over texel cells, each texel weighted by its cell's
// overlap with [s - w/2, s + w/2] per axis. The wall layer has one blocker depth (the width is
// constant, 6.3 texels, or clamped to 4); the steps layer many, so the mean and the width vary per
// query. Tolerance kGatherSlack, plus 1 where a search tap lies within 1e-4 of a texel boundary
// (float rounding may then pick the other texel).
TEST_P(ShadowFilterTest, PcssMatchesItsCpuSteps) {
  struct Case { Layer layer; float scale, maxKernel; };
  const float nearZ = 10, farZ = 20;
  const int taps = 5;
  for (const Case& c : {Case{kWall, 1.26f, 31}, Case{kWall, 1.26f, 4}, Case{kSteps, 3.0f, 31}}) {
    const Map& m = TheMap();
    Random r;
    std::vector<Query> qs;
    for (int i = 0; i < 128; ++i) {
      Query q;
      q.layer = float(c.layer);
      q.uv = {r(0.1f, 0.9f), r(0.1f, 0.9f)};
      q.depth = 0.5f;
      qs.push_back(q);
    }
    std::vector<float> got = rig_->FilteredPcss({{"PCSS_NEAR", cs::Fmt(nearZ)}, {"PCSS_FAR", cs::Fmt(farZ)}, {"PCSS_SCALE", cs::Fmt(c.scale)},
                                                 {"PCSS_TAPS", std::to_string(taps)}, {"PCSS_MAX", cs::Fmt(c.maxKernel)}}, qs);
    std::vector<cs::Expected> want;
    for (const Query& q : qs) {
      const Frame f = FrameOf(q);
      auto linear = [&](float d) { return nearZ + d * (farZ - nearZ); };
      const float dR = linear(q.depth);
      const float radius = std::min(0.5f * (c.scale * (dR - nearZ)), 0.5f * c.maxKernel), step = 2.0f * radius / float(taps - 1);
      int blockers = 0;
      double depthSum = 0, tol = kGatherSlack;
      for (int y = 0; y < taps; ++y)
        for (int x = 0; x < taps; ++x) {
          glm::vec2 p = f.s - radius + step * glm::vec2(x, y) + 0.5f;
          if (glm::any(glm::lessThan(glm::abs(p - glm::round(p)), glm::vec2(1e-4f)))) tol = 1;
          glm::vec2 t = glm::clamp(glm::floor(p), f.lo, f.hi);
          float stored = m.At(int(q.layer), int(t.x), int(t.y));
          if (stored < q.depth) ++blockers, depthSum += linear(stored);
        }
      if (blockers == 0) {
        want.push_back({1.0, tol});
        continue;
      }
      const double w = std::clamp(c.scale * (dR - depthSum / blockers), 1.0, double(c.maxKernel));
      auto overlap = [&](int t, int axis) { return std::max(0.0, std::min(t + 0.5, f.s[axis] + w / 2) - std::max(t - 0.5, f.s[axis] - w / 2)); };
      double sum = 0;
      for (int ty = int(std::floor(f.s.y - w / 2 + 0.5)); ty <= int(std::floor(f.s.y + w / 2 + 0.5)); ++ty)
        for (int tx = int(std::floor(f.s.x - w / 2 + 0.5)); tx <= int(std::floor(f.s.x + w / 2 + 0.5)); ++tx) {
          float texel = m.At(int(q.layer), std::clamp(tx, int(f.lo.x), int(f.hi.x)), std::clamp(ty, int(f.lo.y), int(f.hi.y)));
          sum += overlap(tx, 0) * overlap(ty, 1) * (q.depth <= texel ? 1.0 : 0.0);
        }
      want.push_back({sum / (w * w), tol});
    }
    std::string name = std::string(c.layer == kWall ? "wall" : "steps") + " scale " + cs::Fmt(c.scale) + " max " + cs::Fmt(c.maxKernel);
    ExpectMatches("pcss " + name, got, want, qs);
    ExpectPartlyLit("pcss " + name, got);
  }
}

SP_INSTANTIATE_BACKEND_TESTS(ShadowFilterTest);

// Both backends run Mesa's one sampler (llvmpipe/lavapipe) and the toolchain's fixed arithmetic,
// so every filter, the Poisson rotation included, must give bit-identical results. Elsewhere each
// backend is within 2/256 of the exact kernel (8-bit weights on two axes), so 4/256 of each other.
TEST(ShadowFilterCrossBackend, EveryFilterGivesTheSameResultOnBothBackends) {
  const std::vector<Query> qs = GeneralQueries();
  const Backend backends[2] = {Backend::Vulkan, Backend::OpenGL};
  std::vector<float> results[2][5];
  bool mesa = true;
  for (int b = 0; b < 2; ++b) {
    DeviceDesc dd;
    dd.backend = backends[b];
    Ref<Device> dev = CreateDevice(dd);
    mesa &= dev->Info().deviceName.find("llvmpipe") != std::string::npos;
    FilterRig rig(*dev);
    for (Filter f : {kHw2x2, kBox, kGauss, kGatherCmp, kPoisson}) results[b][f] = rig.Filtered(f, 5, qs);
    EXPECT_EQ(dev->ValidationErrorCount(), 0u) << dev->LastValidationError();
  }
  for (Filter f : {kHw2x2, kBox, kGauss, kGatherCmp, kPoisson})
    for (size_t i = 0; i < qs.size(); ++i) {
      if (mesa) EXPECT_EQ(results[0][f][i], results[1][f][i]) << kFilterNames[f] << " " << Describe(qs[i]);
      else EXPECT_NEAR(results[0][f][i], results[1][f][i], 4.0 / 256) << kFilterNames[f] << " " << Describe(qs[i]);
    }
}

}  // namespace
}  // namespace sp::test
