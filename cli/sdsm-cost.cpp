// `shadowport sdsm-cost`: the SDSM analysis passes timed against one read of the depth buffer
// (techniques/sdsm/analysis-cost.h), per backend and size, as Markdown tables.
#include <cstdio>

#include "cli.h"
#include "sdsm/analysis-cost.h"

namespace sp::cli {

int RunSdsmCost(const Args& a) {
  a.expectOnly({"backend", "size", "frames", "warmup", "validate"});
  std::vector<Backend> backends;
  std::string which = a.get("backend", "both");
  if (which == "both") {
    backends = {Backend::Vulkan, Backend::OpenGL};
  } else {
    Backend b;
    if (!ParseBackend(which, &b)) throw std::invalid_argument("--backend must be vulkan, gl or both (got '" + which + "')");
    backends = {b};
  }
  uint32_t frames = uint32_t(ParseCount(a.get("frames", "20"), "frames", 1, 1000));
  uint32_t warmup = uint32_t(ParseCount(a.get("warmup", "3"), "warmup", 1, 100));
  std::vector<std::pair<uint32_t, uint32_t>> sizes;
  for (const std::string& s : SplitList(a.get("size", "640x360"), "size")) {
    uint32_t w, h;
    ParseSize(s, &w, &h);
    sizes.push_back({w, h});
  }
  int status = 0;
  for (Backend backend : backends) {
    DeviceDesc dd;
    dd.backend = backend;
    dd.debug = a.has("validate");
    Ref<Device> device = CreateDevice(dd);
    for (auto [w, h] : sizes) {
      tech::sdsm::AnalysisCost cost = tech::sdsm::MeasureAnalysisCost(*device, w, h, frames, warmup);
      std::printf("%s", tech::sdsm::FormatAnalysisCost(cost, BackendName(backend)).c_str());
      std::fflush(stdout);
    }
    if (device->ValidationErrorCount()) {
      std::fprintf(stderr, "%s: %llu validation errors\n", BackendName(backend), (unsigned long long)device->ValidationErrorCount());
      status = 1;
    }
  }
  return status;
}

}  // namespace sp::cli
