// SDSM GPU analysis (techniques/sdsm/depth-analysis.h) against its CPU reference, on both
// backends: a synthetic camera depth buffer (200x120, not a multiple of the 16x16 tile, with sky)
// reduced to min/max view depth (both reduce modes, bit-exact), its log-depth histogram (exact),
// the three partition schemes (GPU vs CPU, from the depth buffer and from uploaded histograms with
// a depth gap and a distant occluder), per-partition light-space bounds (bit-exact), the readback
// modes, the GPU timer scope and a bandwidth estimate of the reduction.
#include <cmath>
#include <cstring>
#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <random>

#include "backend-test.h"
#include <sp/scene/scene.h>
#include "sdsm/analysis-readback.h"
#include "sdsm/depth-analysis.h"

namespace sp::test {
namespace {

using namespace tech::sdsm;

constexpr uint32_t W = 200, H = 120, N = 1024;
constexpr float kNear = 0.5f, kFar = 300.0f;

uint32_t Bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}

// A camera depth buffer made of view depths placed at chosen histogram-bin centres of the range
// [zLow, zHigh], so the bins do not depend on the last bits of log(). Sky: the top 9 rows and
// about 15% of the rest.
struct SyntheticDepth {
  std::vector<float> depth;       // device depth, 1 = sky
  std::vector<int> designBin;     // intended bin, -1 for sky
};

SyntheticDepth MakeDepth(const AnalysisFrame& f, uint32_t seed, float zLow = 0.75f, float zHigh = 180.0f) {
  SyntheticDepth s;
  s.depth.assign(size_t(W) * H, 1.0f);
  s.designBin.assign(size_t(W) * H, -1);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  const double l0 = std::log(double(zLow)), l1 = std::log(double(zHigh));
  for (uint32_t y = 9; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      if (u01(rng) < 0.15f) continue;
      // Two populations with an empty stretch between them (bins 300..649).
      int bin = u01(rng) < 0.6f ? int(rng() % 300) : 650 + int(rng() % (N - 650));
      double z = std::exp(l0 + (bin + 0.5) / N * (l1 - l0));
      s.depth[y * W + x] = float(double(f.depthB) - double(f.depthA) / z);
      s.designBin[y * W + x] = bin;
    }
  // The extremes, one of them in the last, partial tile.
  s.depth[50 * W + 5] = float(double(f.depthB) - double(f.depthA) / zLow);
  s.designBin[50 * W + 5] = 0;
  s.depth[(H - 1) * W + W - 1] = float(double(f.depthB) - double(f.depthA) / zHigh);
  s.designBin[(H - 1) * W + W - 1] = N - 1;
  return s;
}

struct CpuAnalysis {
  float zMin = INFINITY, zMax = 0.0f;
  uint32_t samples = 0;
  std::vector<uint32_t> histogram = std::vector<uint32_t>(N, 0);
};

CpuAnalysis AnalyseOnCpu(const AnalysisFrame& f, const std::vector<float>& depth) {
  CpuAnalysis a;
  for (float d : depth)
    if (d < 1.0f) {
      float z = f.ViewDepth(d);
      a.zMin = std::min(a.zMin, z);
      a.zMax = std::max(a.zMax, z);
      ++a.samples;
    }
  for (float d : depth)
    if (d < 1.0f) ++a.histogram[HistogramBin(f.ViewDepth(d), a.zMin, a.zMax, N)];
  return a;
}

class SdsmAnalysisTest : public BackendTest {
 protected:
  void SetUp() override {
    BackendTest::SetUp();
    camera_.position = {3.0f, 6.0f, 12.0f};
    camera_.target = {0.0f, 1.0f, 0.0f};
    camera_.nearZ = kNear;
    camera_.farZ = kFar;
    glm::mat4 lightView = MakeLightView(camera_.position, camera_.forward(), camera_.up, glm::vec3(-0.4f, -1.0f, -0.3f));
    frame_ = AnalysisFrame::Make(camera_.view(), camera_.projection(float(W) / H), lightView, W, H);
    analysis_ = std::make_unique<DepthAnalysis>(device(), N);
    // The camera depth as a renderer has it: R32_TYPELESS with a D32 depth view and an R32_FLOAT
    // SRV. Depth-stencil resources cannot be updated, so the values go through a colour twin.
    depth_ = MakeTexture2D(device(), W, H, FORMAT_R32_TYPELESS, BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE);
    upload_ = MakeTexture2D(device(), W, H, FORMAT_R32_TYPELESS, BIND_SHADER_RESOURCE);
    SHADER_RESOURCE_VIEW_DESC sd;
    sd.Format = FORMAT_R32_FLOAT;
    sd.ViewDimension = SRV_DIMENSION_TEXTURE2D;
    sd.Texture2D = {0, 1};
    depthSrv_ = device().CreateShaderResourceView(depth_.get(), &sd);
  }

  void UploadDepth(const std::vector<float>& depth) {
    ctx().UpdateSubresource(upload_.get(), 0, nullptr, depth.data(), W * 4, 0);
    ctx().CopyResource(depth_.get(), upload_.get());
  }

  std::vector<uint32_t> Results() { return ReadAs<uint32_t>(ReadBuffer(device(), ctx(), analysis_->results())); }
  std::vector<uint32_t> Histogram() { return ReadAs<uint32_t>(ReadBuffer(device(), ctx(), analysis_->histogram())); }

  // Runs only the partition pass on an uploaded range and histogram.
  AnalysisResults PartitionUploaded(const PartitionSettings& p, float zMin, float zMax, const std::vector<uint32_t>& h) {
    analysis_->SetFrame(ctx(), frame_, p);
    AnalysisResults r;
    r.zMin = zMin;
    r.zMax = zMax;
    std::vector<uint32_t> words = EncodeResults(r);
    ctx().UpdateSubresource(analysis_->results(), 0, nullptr, words.data(), 0, 0);
    ctx().UpdateSubresource(analysis_->histogram(), 0, nullptr, h.data(), 0, 0);
    analysis_->Partition(ctx());
    analysis_->Unbind(ctx());
    return DecodeResults(Results().data());
  }

  scene::Camera camera_;
  AnalysisFrame frame_;
  std::unique_ptr<DepthAnalysis> analysis_;
  Ref<Texture2D> depth_, upload_;
  Ref<ShaderResourceView> depthSrv_;
};

void ExpectSplitsNear(const std::vector<float>& gpu, const std::vector<float>& cpu, const std::string& what) {
  ASSERT_EQ(gpu.size(), cpu.size()) << what;
  for (size_t i = 0; i < cpu.size(); ++i) EXPECT_NEAR(gpu[i], cpu[i], 2e-5f * cpu[i]) << what << " split " << i;
  // The ends are the tight range itself, not recomputed through exp/log.
  EXPECT_EQ(Bits(gpu.front()), Bits(cpu.front())) << what;
  EXPECT_EQ(Bits(gpu.back()), Bits(cpu.back())) << what;
}

TEST_P(SdsmAnalysisTest, ReduceGivesTheCpuMinMaxExactlyInBothModes) {
  SyntheticDepth s = MakeDepth(frame_, 1);
  CpuAnalysis cpu = AnalyseOnCpu(frame_, s.depth);
  UploadDepth(s.depth);
  for (ReduceMode mode : {ReduceMode::TwoPass, ReduceMode::Atomic}) {
    SCOPED_TRACE(mode == ReduceMode::TwoPass ? "two-pass" : "atomic");
    analysis_->SetFrame(ctx(), frame_, {});
    analysis_->Reset(ctx());
    analysis_->Reduce(ctx(), depthSrv_.get(), mode);
    analysis_->Unbind(ctx());
    std::vector<uint32_t> r = Results();
    EXPECT_EQ(r[kWordMin], Bits(cpu.zMin));
    EXPECT_EQ(r[kWordMax], Bits(cpu.zMax));
  }
  // All sky: the neutral elements survive, and the partitions fall back to the camera range.
  UploadDepth(std::vector<float>(size_t(W) * H, 1.0f));
  for (ReduceMode mode : {ReduceMode::TwoPass, ReduceMode::Atomic}) {
    analysis_->Run(ctx(), depthSrv_.get(), frame_, {mode, {PartitionScheme::KMeans, 3}});
    AnalysisResults r = DecodeResults(Results().data());
    EXPECT_EQ(Bits(r.zMin), 0x7f800000u);
    EXPECT_EQ(r.zMax, 0.0f);
    EXPECT_FALSE(r.covered());
    EXPECT_EQ(r.samples, 0u);
    std::vector<float> expect = ComputePartitions({PartitionScheme::KMeans, 3}, r.zMin, r.zMax, std::vector<uint32_t>(N, 0), frame_.nearZ, frame_.farZ).splits;
    ExpectSplitsNear(r.splits, expect, "all sky");
    for (const LightBounds& b : r.bounds) EXPECT_TRUE(b.empty());
  }
}

TEST_P(SdsmAnalysisTest, HistogramEqualsTheCpuHistogram) {
  SyntheticDepth s = MakeDepth(frame_, 2);
  CpuAnalysis cpu = AnalyseOnCpu(frame_, s.depth);
  // The data are what they were designed to be: every sample in its intended bin.
  for (size_t i = 0; i < s.depth.size(); ++i)
    if (s.designBin[i] >= 0) {
      ASSERT_EQ(HistogramBin(frame_.ViewDepth(s.depth[i]), cpu.zMin, cpu.zMax, N), uint32_t(s.designBin[i])) << i;
    }
  UploadDepth(s.depth);
  for (ReduceMode mode : {ReduceMode::TwoPass, ReduceMode::Atomic}) {
    analysis_->Run(ctx(), depthSrv_.get(), frame_, {mode, {}});
    EXPECT_EQ(Histogram(), cpu.histogram);
    EXPECT_EQ(Results()[kWordSamples], cpu.samples);
  }
}

TEST_P(SdsmAnalysisTest, PartitionsFromTheDepthBufferMatchTheCpuReference) {
  SyntheticDepth s = MakeDepth(frame_, 3);
  CpuAnalysis cpu = AnalyseOnCpu(frame_, s.depth);
  UploadDepth(s.depth);
  for (PartitionScheme scheme : {PartitionScheme::Log, PartitionScheme::AdaptiveLog, PartitionScheme::KMeans})
    for (uint32_t K : {1u, 4u, 8u}) {
      PartitionSettings p{scheme, K};
      analysis_->Run(ctx(), depthSrv_.get(), frame_, {ReduceMode::Atomic, p});
      AnalysisResults r = DecodeResults(Results().data());
      ASSERT_EQ(r.partitionCount, K);
      ExpectSplitsNear(r.splits, ComputePartitions(p, cpu.zMin, cpu.zMax, cpu.histogram, kNear, kFar).splits,
                       PartitionSchemeName(scheme) + " K=" + std::to_string(K));
    }
}

// Samples at depths 1..~4 and ~300..1000 of [1, 1000]: bins [0, 200) and [700, 1024) occupied.
std::vector<uint32_t> GapHistogram() {
  std::vector<uint32_t> h(N, 0);
  for (uint32_t b = 0; b < 200; ++b) h[b] = 50 + (b * 37) % 91;
  for (uint32_t b = 700; b < N; ++b) h[b] = 20 + (b * 53) % 61;
  return h;
}

TEST_P(SdsmAnalysisTest, AdaptiveLogMovesSplitsToTheEndOfADepthGapAndLogDoesNot) {
  const float zMin = 1.0f, zMax = 1000.0f;
  std::vector<uint32_t> h = GapHistogram();
  const float gapStart = DepthAtBinPosition(200, zMin, zMax, N), gapEnd = DepthAtBinPosition(700, zMin, zMax, N);
  auto inGap = [&](float z) { return z > gapStart * 1.0001f && z < gapEnd * 0.9999f; };
  for (uint32_t K : {2u, 3u, 4u, 6u}) {
    SCOPED_TRACE("K=" + std::to_string(K));
    PartitionSettings logP{PartitionScheme::Log, K}, adaptiveP{PartitionScheme::AdaptiveLog, K};
    std::vector<float> logCpu = ComputePartitions(logP, zMin, zMax, h, kNear, kFar).splits;
    std::vector<float> adaptiveCpu = ComputePartitions(adaptiveP, zMin, zMax, h, kNear, kFar).splits;
    ExpectSplitsNear(PartitionUploaded(logP, zMin, zMax, h).splits, logCpu, "log");
    ExpectSplitsNear(PartitionUploaded(adaptiveP, zMin, zMax, h).splits, adaptiveCpu, "adaptive-log");
    int logInGap = 0, adaptiveAtGapEnd = 0;
    for (uint32_t i = 1; i < K; ++i) {
      logInGap += inGap(logCpu[i]);
      EXPECT_FALSE(inGap(adaptiveCpu[i])) << "adaptive split " << i << " at " << adaptiveCpu[i] << " lies in the gap";
      adaptiveAtGapEnd += std::abs(adaptiveCpu[i] - gapEnd) < 1e-5f * gapEnd;
    }
    EXPECT_EQ(adaptiveAtGapEnd, 1) << "one adaptive split sits at the far end of the gap";
    EXPECT_GT(logInGap, 0) << "log puts splits inside the gap";
    // Every adaptive partition holds samples; no partition reaches across the gap.
    for (uint32_t p = 0; p < K; ++p) {
      uint32_t b0 = HistogramBin(adaptiveCpu[p], zMin, zMax, N), b1 = HistogramBin(adaptiveCpu[p + 1], zMin, zMax, N);
      uint64_t n = 0;
      for (uint32_t b = b0; b < std::min(b1 + 1, N); ++b) n += h[b];
      EXPECT_GT(n, 0u) << "adaptive partition " << p;
      EXPECT_FALSE(adaptiveCpu[p] < gapStart && adaptiveCpu[p + 1] > gapEnd * 1.0001f) << "partition " << p << " spans the gap";
    }
  }
}

// Most samples within 1..8 of a range reaching 1000 (a distant mountain): a few far ones.
TEST_P(SdsmAnalysisTest, KMeansPutsAClusterOnAFewDistantSamples) {
  const float zMin = 1.0f, zMax = 1000.0f;
  std::vector<uint32_t> h(N, 0);
  const uint32_t nearEnd = HistogramBin(8.0f, zMin, zMax, N);  // bin ~308
  for (uint32_t b = 0; b <= nearEnd; ++b) h[b] = 400 + (b * 29) % 200;
  for (uint32_t b = N - 6; b < N; ++b) h[b] = 3;
  const uint32_t K = 4;
  for (PartitionScheme scheme : {PartitionScheme::Log, PartitionScheme::AdaptiveLog, PartitionScheme::KMeans}) {
    PartitionSettings p{scheme, K};
    PartitionResult cpu = ComputePartitions(p, zMin, zMax, h, kNear, kFar);
    ExpectSplitsNear(PartitionUploaded(p, zMin, zMax, h).splits, cpu.splits, PartitionSchemeName(scheme));
    // Which partitions hold near and far samples.
    std::vector<int> nearIn(K, 0), farIn(K, 0);
    for (uint32_t b = 0; b < N; ++b)
      if (h[b]) (b <= nearEnd ? nearIn : farIn)[PartitionOf(DepthAtBinPosition(b + 0.5f, zMin, zMax, N), cpu.splits)] = 1;
    int mixed = 0, farOnly = 0, empty = 0;
    for (uint32_t q = 0; q < K; ++q) mixed += nearIn[q] && farIn[q], farOnly += farIn[q] && !nearIn[q], empty += !nearIn[q] && !farIn[q];
    if (scheme == PartitionScheme::KMeans) {
      ASSERT_EQ(cpu.centres.size(), K);
      EXPECT_GE(cpu.centres.back(), float(N - 6)) << "the last centre sits on the distant samples";
      EXPECT_EQ(farOnly, 1) << "one partition for the distant samples alone";
      EXPECT_EQ(mixed, 0);
    }
    if (scheme == PartitionScheme::AdaptiveLog) {
      EXPECT_EQ(mixed, 1) << "adaptive-log keeps the few far samples with near ones";
    }
    if (scheme == PartitionScheme::Log) {
      EXPECT_EQ(empty, 1) << "log spends a partition on the empty middle";
    }
  }
}

TEST_P(SdsmAnalysisTest, LightSpaceBoundsEqualTheCpuReductionBitExactly) {
  SyntheticDepth s = MakeDepth(frame_, 4);
  UploadDepth(s.depth);
  for (uint32_t K : {1u, 3u, 8u}) {
    analysis_->Run(ctx(), depthSrv_.get(), frame_, {ReduceMode::TwoPass, {PartitionScheme::AdaptiveLog, K}});
    std::vector<uint32_t> words = Results();
    AnalysisResults r = DecodeResults(words.data());
    ASSERT_EQ(r.bounds.size(), K);
    // The CPU reduction over the same pixels, assigned with the GPU's splits.
    std::vector<uint32_t> expect(8 * K, 0);
    for (uint32_t p = 0; p < K; ++p) expect[p * 8] = expect[p * 8 + 1] = expect[p * 8 + 2] = 0xffffffffu;
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x) {
        float d = s.depth[y * W + x];
        if (d >= 1.0f) continue;
        float z = frame_.ViewDepth(d);
        uint32_t p = PartitionOf(z, r.splits);
        glm::vec3 l = frame_.LightPosition(x, y, z);
        uint32_t* e = &expect[p * 8];
        for (int a = 0; a < 3; ++a) {
          e[a] = std::min(e[a], OrderedKey(l[a]));
          e[4 + a] = std::max(e[4 + a], OrderedKey(l[a]));
        }
        ++e[3];
      }
    for (uint32_t p = 0; p < K; ++p) {
      if (expect[p * 8 + 3] == 0) {
        EXPECT_EQ(words[kWordBounds + p * 8 + 3], 0u);
        continue;
      }
      for (int w = 0; w < 7; ++w) EXPECT_EQ(words[kWordBounds + p * 8 + w], expect[p * 8 + w]) << "K=" << K << " partition " << p << " word " << w;
    }
    // Light space really is where the pixels are: a sample reconstructed through the inverse
    // camera matrices lands inside its partition's box.
    glm::mat4 inv = glm::inverse(camera_.projection(float(W) / H) * camera_.view());
    uint32_t x = 120, y = 60;
    float d = s.depth[y * W + x];
    glm::vec4 w = inv * glm::vec4((x + 0.5f) / W * 2 - 1, 1 - (y + 0.5f) / H * 2, d, 1.0f);
    glm::vec3 l = glm::vec3(frame_.lightView * glm::vec4(glm::vec3(w) / w.w, 1.0f));
    const LightBounds& b = r.bounds[PartitionOf(frame_.ViewDepth(d), r.splits)];
    EXPECT_TRUE(glm::all(glm::greaterThanEqual(l, b.min - 1e-3f)) && glm::all(glm::lessThanEqual(l, b.max + 1e-3f)));
  }
}

TEST_P(SdsmAnalysisTest, ReadbackModesReturnTheSameResultsStalledOrLate) {
  const uint32_t frames = 5, latency = 2;
  AnalysisReadback none(device(), ReadbackMode::None), stall(device(), ReadbackMode::Stall),
      late(device(), ReadbackMode::Latent, latency);
  std::vector<std::vector<uint32_t>> truth;
  for (uint32_t f = 0; f < frames; ++f) {
    // Each frame sees a different range, so results of different frames differ.
    UploadDepth(MakeDepth(frame_, 10 + f, 0.75f + f, 180.0f - 10.0f * f).depth);
    analysis_->Run(ctx(), depthSrv_.get(), frame_, {ReduceMode::Atomic, {PartitionScheme::Log, 3}});
    none.Capture(ctx(), analysis_->results());
    stall.Capture(ctx(), analysis_->results());
    late.Capture(ctx(), analysis_->results());
    truth.push_back(Results());
    EXPECT_FALSE(none.Latest().has_value());
    ASSERT_TRUE(stall.Latest().has_value());
    EXPECT_EQ(stall.LatestCapture(), int64_t(f));
    EXPECT_EQ(stall.LatestWords(), truth[f]);
    if (f < latency) {
      EXPECT_FALSE(late.Latest().has_value()) << "frame " << f;
      continue;
    }
    ASSERT_TRUE(late.Latest().has_value());
    EXPECT_EQ(late.LatestCapture(), int64_t(f - latency));
    EXPECT_EQ(late.LatestWords(), truth[f - latency]);
    EXPECT_NE(late.LatestWords(), truth[f]);
    EXPECT_EQ(late.Latest()->zMin, DecodeResults(truth[f - latency].data()).zMin);
  }
}

TEST_P(SdsmAnalysisTest, PassesAreTimedAsAnalysis) {
  UploadDepth(MakeDepth(frame_, 5).depth);
  tech::GpuTimer timer(device());
  timer.BeginFrame(ctx());
  analysis_->Run(ctx(), depthSrv_.get(), frame_, {}, &timer);
  timer.EndFrame(ctx());
  std::vector<tech::FrameTimes> times = timer.Collect(ctx(), true);
  ASSERT_EQ(times.size(), 1u);
  ASSERT_TRUE(times[0].count("analysis"));
  EXPECT_GT(times[0].at("analysis"), 0.0);
}

SP_INSTANTIATE_BACKEND_TESTS(SdsmAnalysisTest);

// Memory traffic of the reduction relative to reading the depth buffer once (printed, no
// assertion on time): the tree reduction reads each pixel once; the two-pass variant adds the
// per-tile results, the atomic one a pair of atomics per tile instead.
TEST(SdsmAnalysisTraffic, ReductionReadsTheDepthBufferAboutOnce) {
  for (auto [w, h] : {std::pair{W, H}, std::pair{1920u, 1080u}, std::pair{3840u, 2160u}})
    for (ReduceMode mode : {ReduceMode::TwoPass, ReduceMode::Atomic}) {
      AnalysisTraffic t = EstimateTraffic(w, h, mode, N);
      double ratio = double(t.reduceReadBytes + t.reduceWrittenBytes) / double(t.depthBufferBytes);
      double all = double(t.reduceReadBytes + t.reduceWrittenBytes + t.histogramReadBytes + t.histogramWrittenBytes + t.boundsReadBytes) /
                   double(t.depthBufferBytes);
      std::printf("[sdsm traffic] %ux%u %-8s depth %8.2f KiB, reduction reads %8.2f KiB + writes %6.2f KiB = %.4fx one depth read; "
                  "reduce + histogram + bounds at most %.4fx\n",
                  w, h, mode == ReduceMode::TwoPass ? "two-pass" : "atomic", t.depthBufferBytes / 1024.0, t.reduceReadBytes / 1024.0,
                  t.reduceWrittenBytes / 1024.0, ratio, all);
      EXPECT_LT(ratio, 1.05);
      EXPECT_GE(ratio, 1.0);
    }
}

}  // namespace
}  // namespace sp::test
