// `shadowport conformance`: the D3D11 conformance table (feature x backend) on this machine.
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "cli.h"
#include "conformance.h"

namespace sp::cli {

int RunConformance(const Args& a) {
  a.expectOnly({"backend", "out", "filter", "verbose"});
  std::vector<Backend> backends;
  std::string which = a.get("backend", "both");
  if (which == "both") {
    backends = {Backend::Vulkan, Backend::OpenGL};
  } else {
    // The probes read back pixels; the null backend runs their Misuse group in the tests.
    backends = {ParseRenderingBackend(which, "vulkan, gl or both")};
  }
  std::vector<conformance::ProbeRun> runs = conformance::RunSuite(backends, a.get("filter"), a.has("verbose"));
  std::printf("%s", conformance::FormatConsoleTable(runs).c_str());
  std::filesystem::path dir = a.get("out", "out/conformance");
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "conformance.md") << "# D3D11 conformance\n\n" << conformance::FormatMarkdown(runs);
  std::ofstream(dir / "conformance.json") << conformance::FormatJson(runs);
  size_t failed = 0;
  for (const auto& r : runs) failed += r.result.status == conformance::Status::Fail;
  std::printf("\n%zu probe runs, %zu failed; table written to %s and %s\n", runs.size(), failed, (dir / "conformance.md").string().c_str(),
              (dir / "conformance.json").string().c_str());
  return failed ? 1 : 0;
}

}  // namespace sp::cli
