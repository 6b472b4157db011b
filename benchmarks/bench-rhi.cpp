// bench-rhi: the CPU cost of recording through sp:: against the same work written directly for
// Vulkan and for OpenGL, in one process. Benchmarks are named CASE/BACKEND/SIDE (side sp or raw);
// `./shadowport bench-rhi` runs them with repetitions and prints the sp/raw table
// (benchmarks/rhi-table.py).
//
// What is timed: the CPU time of the benchmark thread while it records and submits one
// iteration (Vulkan: vkQueueSubmit / Flush; GL: glFlush / Flush). The wait for the GPU is outside
// the timing (PauseTiming), on both sides: lavapipe and llvmpipe execute the commands on their
// own CPU threads, which thread CPU time does not count, and the targets are 64x64 so that their
// execution stays small next to recording on a two-core machine.
#include <cstdlib>
#include <map>
#include <memory>
#include <string>

#include "bench-cases.h"
#include "raw-gl.h"
#include "raw-vulkan.h"

namespace spbench {
namespace {

// Created on first use and kept for the process's life (never destroyed: the sp:: GL device and
// the raw GL context share the EGL display, whose termination order would otherwise matter).
sp::Device* SpDevice(sp::Backend b) {
  static std::map<sp::Backend, sp::Ref<sp::Device>>* devices = new std::map<sp::Backend, sp::Ref<sp::Device>>;
  sp::Ref<sp::Device>& d = (*devices)[b];
  if (!d) {
    sp::DeviceDesc desc;
    desc.backend = b;
    desc.debug = false;  // validation would dominate the cost; the raw sides run without it too
    d = sp::CreateDevice(desc);
  }
  return d.get();
}
RawVulkan& Vulkan() {
  static RawVulkan* vk = new RawVulkan;
  return *vk;
}
RawGL& GL() {
  static RawGL* gl = new RawGL;
  return *gl;
}

// Google Benchmark calls a benchmark once per repetition: each case is set up once.
Case& GetCase(CaseId id, sp::Backend backend, bool raw) {
  static auto* cases = new std::map<std::string, std::unique_ptr<Case>>;
  std::string key = std::string(CaseName(id)) + sp::BackendName(backend) + (raw ? "raw" : "sp");
  std::unique_ptr<Case>& c = (*cases)[key];
  if (!c) {
    if (!raw) c = MakeSpCase(id, *SpDevice(backend));
    else if (backend == sp::Backend::Vulkan) c = MakeRawVulkanCase(id, Vulkan());
    else c = MakeRawGLCase(id, GL());
  }
  return *c;
}

void Run(benchmark::State& state, CaseId id, sp::Backend backend, bool raw) {
  try {
    RunCase(state, GetCase(id, backend, raw), CaseDraws(id));
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
  }
}

}  // namespace
}  // namespace spbench

int main(int argc, char** argv) {
  using namespace spbench;
  benchmark::Initialize(&argc, argv);
  // SPBENCH_ITERATIONS=N: more iterations, for profiling one case with perf.
  const char* env = std::getenv("SPBENCH_ITERATIONS");
  int iterations = env ? std::atoi(env) : 6;
  for (CaseId id : kCases)
    for (sp::Backend b : {sp::Backend::Vulkan, sp::Backend::OpenGL})
      for (bool raw : {true, false}) {
        std::string name = std::string(CaseName(id)) + "/" + sp::BackendName(b) + "/" + (raw ? "raw" : "sp");
        // A fixed iteration count keeps the run's length and work the same from run to run.
        benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& s) { Run(s, id, b, raw); })
            ->Iterations(iterations)
            ->Unit(benchmark::kMillisecond);
      }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
