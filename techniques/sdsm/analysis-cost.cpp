#include "sdsm/analysis-cost.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <map>
#include <stdexcept>

#include <sp/tech/gpu-timer.h>
#include <sp/tech/technique.h>

namespace sp::tech::sdsm {
namespace {

uint32_t DivUp(uint32_t a, uint32_t b) { return (a + b - 1) / b; }

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The passes in run order; the analysis' own steps carry the names of the docs' table.
const char* const kLimitTexel = "limit: read once (16x16 threads, 1 texel each)";
const char* const kLimitStrip = "limit: read once (64 threads, 64x64 tile)";
const char* const kEmpty = "empty dispatch (1 thread)";
const char* const kReset = "reset";
const char* const kReduce = "reduce (two-pass, as the technique runs it)";
const char* const kReduceAtomic = "reduce (atomic)";
const char* const kHistogram = "histogram";
const char* const kPartitions = "partitions";
const char* const kBounds = "bounds (tight)";
const char* const kWhole = "whole analysis (one Run: reset .. bounds)";

}  // namespace

const PassCost* AnalysisCost::find(const std::string& name) const {
  for (const PassCost& p : passes)
    if (p.name == name) return &p;
  return nullptr;
}

std::vector<float> SyntheticCameraDepth(uint32_t width, uint32_t height, AnalysisFrame* frameOut) {
  const glm::vec3 eye(0.0f, 20.0f, 0.0f), target(0.0f, 14.0f, -100.0f), up(0.0f, 1.0f, 0.0f);
  const float nearZ = 0.5f, farZ = 500.0f;
  glm::mat4 view = glm::lookAtRH(eye, target, up);
  glm::mat4 proj = glm::perspectiveRH_ZO(glm::radians(60.0f), float(width) / float(height), nearZ, farZ);
  glm::mat4 lightView = MakeLightView(eye, glm::normalize(target - eye), up, glm::vec3(-0.4f, -1.0f, -0.3f));
  AnalysisFrame f = AnalysisFrame::Make(view, proj, lightView, width, height);
  f.nearZ = nearZ;
  f.farZ = farZ;
  glm::mat3 toWorld = glm::mat3(glm::inverse(view));
  std::vector<float> depth(size_t(width) * height, 1.0f);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      float ndcX = (float(x) + 0.5f) * f.ndcScale.x + f.ndcOffset.x, ndcY = (float(y) + 0.5f) * f.ndcScale.y + f.ndcOffset.y;
      // The camera ray per unit of view depth, so a hit's ray parameter is its view depth.
      glm::vec3 dir = toWorld * glm::vec3(ndcX * f.rayScale.x + f.rayOffset.x, ndcY * f.rayScale.y + f.rayOffset.y, -1.0f);
      float t = dir.y < 0.0f ? -eye.y / dir.y : INFINITY;
      // Rows of 12 m pillars, 4 m wide every 12 m, every 30 m of depth: occluders and depth gaps.
      for (int row = 1; row <= 12 && dir.z < 0.0f; ++row) {
        float tp = 30.0f * float(row) / -dir.z;
        if (tp >= t) break;
        glm::vec3 p = eye + tp * dir;
        if (p.y >= 0.0f && p.y <= 12.0f && std::fmod(std::abs(p.x) + 2.0f, 12.0f) < 4.0f) {
          t = tp;
          break;
        }
      }
      if (t < farZ * 0.999f) depth[size_t(y) * width + x] = float(double(f.depthB) - double(f.depthA) / double(t));
    }
  if (frameOut) *frameOut = f;
  return depth;
}

AnalysisCost MeasureAnalysisCost(Device& device, uint32_t width, uint32_t height, uint32_t frames, uint32_t warmup) {
  if (width == 0 || height == 0 || width > 16384 || height > 16384)
    throw std::invalid_argument("MeasureAnalysisCost: size must be in [1, 16384]^2, got " + std::to_string(width) + "x" + std::to_string(height));
  if (frames < 1) throw std::invalid_argument("MeasureAnalysisCost: frames must be >= 1");
  if (warmup < 1) throw std::invalid_argument("MeasureAnalysisCost: warmup must be >= 1 (the first frame is reported apart)");
  DeviceContext& ctx = *device.GetImmediateContext();
  AnalysisCost cost;
  cost.width = width;
  cost.height = height;
  cost.frames = frames;

  AnalysisFrame frame;
  std::vector<float> depthValues = SyntheticCameraDepth(width, height, &frame);
  TEXTURE2D_DESC td{};
  td.Width = width;
  td.Height = height;
  td.MipLevels = 1;
  td.ArraySize = 1;
  td.Format = FORMAT_R32_FLOAT;
  td.SampleDesc.Count = 1;
  td.Usage = USAGE_DEFAULT;
  td.BindFlags = BIND_SHADER_RESOURCE;
  SUBRESOURCE_DATA init{depthValues.data(), width * 4, 0};
  Ref<Texture2D> depth = device.CreateTexture2D(td, &init);
  Ref<ShaderResourceView> depthSrv = device.CreateShaderResourceView(depth.get());

  auto t0 = std::chrono::steady_clock::now();
  DepthAnalysis analysis(device);
  cost.createMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  auto cs = [&](const char* entry) { return device.CreateComputeShader(CompileTechniqueShader("sdsm/read-limit.hlsl", "cs_5_0", entry)); };
  Ref<ComputeShader> readTexel = cs("ReadTexel"), readStrip = cs("ReadStrip"), empty = cs("Empty");
  const uint32_t tx = DivUp(width, 16), ty = DivUp(height, 16), sx = DivUp(width, kStripTile), sy = DivUp(height, kStripTile);
  Ref<Buffer> perGroup = MakeRawBuffer(device, std::max(tx * ty, 1u) * 4, BIND_UNORDERED_ACCESS, "sdsm read-limit per-group words");
  Ref<UnorderedAccessView> perGroupUav = MakeRawUav(device, perGroup.get());

  AnalysisSettings settings;
  settings.partitions.count = 4;
  GpuTimer timer(device);
  std::vector<FrameTimes> times;
  auto timed = [&](const char* name, auto&& body) {
    timer.Begin(ctx, name);
    body();
    timer.End(ctx, name);
  };
  auto limit = [&](ComputeShader* shader, uint32_t gx, uint32_t gy) {
    analysis.SetFrame(ctx, frame, settings.partitions);
    ctx.CSSetConstantBuffers(0, {analysis.constants()});
    ctx.CSSetShaderResources(0, {depthSrv.get()});
    ctx.CSSetUnorderedAccessViews(1, {perGroupUav.get()});
    ctx.CSSetShader(shader);
    ctx.Dispatch(gx, gy, 1);
    ctx.CSSetUnorderedAccessViews(1, {nullptr});
  };
  for (uint32_t i = 0; i < warmup + frames; ++i) {
    timer.BeginFrame(ctx);
    timed(kLimitTexel, [&] { limit(readTexel.get(), tx, ty); });
    timed(kLimitStrip, [&] { limit(readStrip.get(), sx, sy); });
    timed(kEmpty, [&] { limit(empty.get(), 1, 1); });
    analysis.SetFrame(ctx, frame, settings.partitions);
    timed(kReset, [&] { analysis.Reset(ctx); });
    timed(kReduce, [&] { analysis.Reduce(ctx, depthSrv.get(), ReduceMode::TwoPass); });
    timed(kReduceAtomic, [&] { analysis.Reduce(ctx, depthSrv.get(), ReduceMode::Atomic); });
    timed(kHistogram, [&] { analysis.BuildHistogram(ctx, depthSrv.get()); });
    timed(kPartitions, [&] { analysis.Partition(ctx); });
    timed(kBounds, [&] { analysis.ReduceBounds(ctx, depthSrv.get()); });
    analysis.Unbind(ctx);
    timed(kWhole, [&] { analysis.Run(ctx, depthSrv.get(), frame, settings); });
    timer.EndFrame(ctx);
    for (FrameTimes& t : timer.Collect(ctx, false)) times.push_back(std::move(t));
  }
  for (FrameTimes& t : timer.Collect(ctx, true)) times.push_back(std::move(t));
  if (times.size() < size_t(warmup) + 1) throw std::runtime_error("MeasureAnalysisCost: the GPU timer dropped frames (disjoint)");

  for (const char* name : {kLimitTexel, kLimitStrip, kEmpty, kReset, kReduce, kReduceAtomic, kHistogram, kPartitions, kBounds, kWhole}) {
    PassCost p;
    p.name = name;
    p.firstMs = times[0].count(name) ? times[0].at(name) : 0.0;
    std::vector<double> v;
    for (size_t i = warmup; i < times.size(); ++i)
      if (times[i].count(name)) v.push_back(times[i].at(name));
    p.medianMs = Median(v);
    cost.passes.push_back(p);
  }
  cost.limitMs = std::min(cost.find(kLimitTexel)->medianMs, cost.find(kLimitStrip)->medianMs);
  return cost;
}

std::string FormatAnalysisCost(const AnalysisCost& c, const std::string& backend) {
  std::string out;
  char line[512];
  std::snprintf(line, sizeof line,
                "\n%s %ux%u: medians of %u frames after warm-up; limit = %.3f ms (the faster read-once pass); shader creation %.0f ms (CPU)\n\n"
                "| pass | median ms | x limit | first frame ms |\n|---|---|---|---|\n",
                backend.c_str(), c.width, c.height, c.frames, c.limitMs, c.createMs);
  out += line;
  auto row = [&](const std::string& name, double ms, double first) {
    std::snprintf(line, sizeof line, "| %s | %.3f | %.2f | %.3f |\n", name.c_str(), ms, c.limitMs > 0 ? ms / c.limitMs : 0.0, first);
    out += line;
  };
  for (const PassCost& p : c.passes) row(p.name, p.medianMs, p.firstMs);
  auto sum = [&](std::initializer_list<const char*> names, bool first) {
    double s = 0;
    for (const char* n : names) s += first ? c.find(n)->firstMs : c.find(n)->medianMs;
    return s;
  };
  row("**reduction + histogram** (reduce two-pass + histogram)", sum({kReduce, kHistogram}, false), sum({kReduce, kHistogram}, true));
  row("sum of the separate passes (reset .. bounds)", sum({kReset, kReduce, kHistogram, kPartitions, kBounds}, false),
      sum({kReset, kReduce, kHistogram, kPartitions, kBounds}, true));
  row("**whole analysis** (one Run, with tight bounds)", c.find(kWhole)->medianMs, c.find(kWhole)->firstMs);
  return out;
}

}  // namespace sp::tech::sdsm
