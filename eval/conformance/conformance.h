// The D3D11 conformance suite: one set of probes, each checking one behaviour the shadow papers
// assume against expectations computed on the CPU from the D3D11 functional specification. The
// same probes run as GoogleTest cases (tests/conformance) and as `shadowport conformance`, which
// prints the feature x backend table and writes it as Markdown and JSON.
#pragma once
#include <functional>
#include <sp/rhi/rhi.h>
#include <string>
#include <vector>

namespace sp::conformance {

// Deviation: the driver departs from D3D11 by a measured, documented amount within a known bound
// (the table shows it; the test suite accepts it); beyond the bound it is a failure.
enum class Status { Pass, Fail, Unsupported, Deviation };
const char* StatusName(Status s);

struct Result {
  Status status = Status::Pass;
  double measuredError = 0;  // largest deviation from the D3D11 expectation
  std::string errorUnit;     // "LSB", "ulp", "pixels", "abs", ...
  double tolerance = 0;      // what the probe allows
  std::string detail;        // why it failed / what is unsupported / what was measured
};

// Helpers a probe uses to report.
Result Pass(double measuredError = 0, std::string unit = "", double tolerance = 0, std::string detail = "");
Result Fail(std::string detail, double measuredError = 0, std::string unit = "", double tolerance = 0);
Result Unsupported(std::string reason);
// Pass if error <= tolerance, else Fail with `what` in the detail.
Result Within(double error, double tolerance, std::string unit, std::string what);
// Like Within, but an error above D3D11's tolerance and at most `knownBound` is a Deviation whose
// detail is `explanation` (what the driver does differently, and why it cannot be corrected).
Result WithinKnownDeviation(double error, double tolerance, double knownBound, std::string unit, std::string what,
                            std::string explanation);

struct Probe {
  std::string group;        // "Depth bias", "Rasterization", "Sampling", ...
  std::string name;         // unique within the group: "D16 positive constant bias"
  std::string description;  // one line: what D3D11 requires
  std::function<Result(Device&)> run;
};

// All registered probes, in registration order (group order as registered).
const std::vector<Probe>& Probes();
struct Registrar {
  Registrar(std::string group, std::string name, std::string description, std::function<Result(Device&)> run);
};

// Registers a probe from a .cpp file in eval/conformance/probes/:
//   SP_PROBE(kGroup, "D16 positive bias", "DepthBias > 0 moves D16 depth by DepthBias LSB") { ...; return Pass(err, "LSB", 1); }
#define SP_PROBE_CONCAT2(a, b) a##b
#define SP_PROBE_CONCAT(a, b) SP_PROBE_CONCAT2(a, b)
#define SP_PROBE(group, name, description)                                                                      \
  static ::sp::conformance::Result SP_PROBE_CONCAT(spProbe_, __LINE__)(::sp::Device & device);                  \
  static ::sp::conformance::Registrar SP_PROBE_CONCAT(spProbeReg_, __LINE__)(group, name, description,          \
                                                                             SP_PROBE_CONCAT(spProbe_, __LINE__)); \
  static ::sp::conformance::Result SP_PROBE_CONCAT(spProbe_, __LINE__)(::sp::Device & device)

// Runs one probe on a device: catches exceptions and driver validation errors raised during the
// probe (either is a failure), and restores the context afterwards.
Result RunProbe(const Probe& probe, Device& device);

struct ProbeRun {
  const Probe* probe = nullptr;
  Backend backend = Backend::Vulkan;
  std::string device;
  Result result;
  double milliseconds = 0;
};

// `shadowport conformance`: runs every probe whose "group/name" contains `filter` on each backend.
std::vector<ProbeRun> RunSuite(const std::vector<Backend>& backends, const std::string& filter, bool verbose);
std::string FormatMarkdown(const std::vector<ProbeRun>& runs);
std::string FormatJson(const std::vector<ProbeRun>& runs);
std::string FormatConsoleTable(const std::vector<ProbeRun>& runs);

}  // namespace sp::conformance
