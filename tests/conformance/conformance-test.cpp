// Every conformance probe (eval/conformance/probes) as a test on each backend, with a fresh device
// and validation on. A probe the driver cannot run is skipped with its reason. The Misuse group
// checks only what the core refuses, so it runs on the null backend as well.
#include <gtest/gtest.h>

#include <cctype>

#include "backend-test.h"
#include "conformance.h"

namespace sp::test {
namespace {

using conformance::Probes;

class D3D11Conformance : public ::testing::TestWithParam<std::tuple<Backend, size_t>> {};

TEST_P(D3D11Conformance, Probe) {
  auto [backend, index] = GetParam();
  const conformance::Probe& probe = Probes()[index];
  std::vector<std::string> errors;
  DeviceDesc dd;
  dd.backend = backend;
  dd.debug = true;
  dd.messageCallback = [&](MessageSeverity s, std::string_view t) {
    if (s == MessageSeverity::Error) errors.emplace_back(t);
  };
  Ref<Device> device = CreateDevice(dd);
  conformance::Result r = conformance::RunProbe(probe, *device);
  RecordProperty("measured_error", std::to_string(r.measuredError) + " " + r.errorUnit);
  if (r.status == conformance::Status::Unsupported) GTEST_SKIP() << probe.group << " / " << probe.name << ": " << r.detail;
  if (r.status == conformance::Status::Deviation) {
    // Known and bounded driver deviations are reported, not failed (docs/conformance.md lists them).
    RecordProperty("driver_deviation", r.detail);
    std::printf("[ DEVIATION] %s / %s: %s\n", probe.group.c_str(), probe.name.c_str(), r.detail.c_str());
    return;
  }
  EXPECT_EQ(r.status, conformance::Status::Pass) << probe.group << " / " << probe.name << " (" << probe.description << "): " << r.detail;
  for (const std::string& e : errors) ADD_FAILURE() << "validation error: " << e;
}

std::string ProbeTestName(const ::testing::TestParamInfo<std::tuple<Backend, size_t>>& info) {
  const conformance::Probe& p = Probes()[std::get<1>(info.param)];
  std::string name = BackendTestName(std::get<0>(info.param)) + "_" + p.group + "_" + p.name;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Probes, D3D11Conformance,
                         ::testing::Combine(::testing::Values(Backend::Vulkan, Backend::OpenGL), ::testing::Range(size_t(0), Probes().size())),
                         ProbeTestName);

std::vector<std::tuple<Backend, size_t>> NullBackendProbes() {
  std::vector<std::tuple<Backend, size_t>> out;
  for (size_t i = 0; i < Probes().size(); ++i)
    if (Probes()[i].group == "Misuse") out.emplace_back(Backend::Null, i);
  return out;
}
INSTANTIATE_TEST_SUITE_P(NullProbes, D3D11Conformance, ::testing::ValuesIn(NullBackendProbes()), ProbeTestName);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(D3D11Conformance);

}  // namespace
}  // namespace sp::test
