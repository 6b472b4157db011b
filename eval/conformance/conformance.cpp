#include "conformance.h"

#include <chrono>
#include <cstdio>
#include <iomanip>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

namespace sp::conformance {

const char* StatusName(Status s) {
  switch (s) {
    case Status::Pass: return "pass";
    case Status::Fail: return "FAIL";
    case Status::Unsupported: return "not supported";
    case Status::Deviation: return "driver deviation";
  }
  return "?";
}

Result Pass(double err, std::string unit, double tol, std::string detail) { return {Status::Pass, err, std::move(unit), tol, std::move(detail)}; }
Result Fail(std::string detail, double err, std::string unit, double tol) { return {Status::Fail, err, std::move(unit), tol, std::move(detail)}; }
Result Unsupported(std::string reason) { return {Status::Unsupported, 0, "", 0, std::move(reason)}; }
Result Within(double err, double tol, std::string unit, std::string what) {
  if (err <= tol) return Pass(err, std::move(unit), tol);
  std::ostringstream s;
  s << what << ": error " << err << " " << unit << " exceeds " << tol;
  return Fail(s.str(), err, std::move(unit), tol);
}

Result WithinKnownDeviation(double err, double tol, double knownBound, std::string unit, std::string what, std::string explanation) {
  if (err <= tol) return Pass(err, std::move(unit), tol);
  if (err <= knownBound) {
    std::ostringstream s;
    s << explanation << " (" << what << ": " << err << " " << unit << ", D3D11 allows " << tol << ")";
    return {Status::Deviation, err, std::move(unit), tol, s.str()};
  }
  return Within(err, tol, std::move(unit), what);
}

static std::vector<Probe>& Mutable() {
  static std::vector<Probe> probes;
  return probes;
}

const std::vector<Probe>& Probes() { return Mutable(); }

Registrar::Registrar(std::string group, std::string name, std::string description, std::function<Result(Device&)> run) {
  Mutable().push_back({std::move(group), std::move(name), std::move(description), std::move(run)});
}

Result RunProbe(const Probe& probe, Device& device) {
  DeviceContext& ctx = *device.GetImmediateContext();
  uint64_t before = device.ValidationErrorCount();
  Result r;
  ctx.ClearState();
  try {
    r = probe.run(device);
  } catch (const std::exception& e) {
    r = Fail(std::string("exception: ") + e.what());
  }
  ctx.ClearState();
  ctx.WaitIdle();
  if (device.ValidationErrorCount() != before) {
    r.status = Status::Fail;
    r.detail = "driver validation error: " + device.LastValidationError() + (r.detail.empty() ? "" : "; " + r.detail);
  }
  return r;
}

std::vector<ProbeRun> RunSuite(const std::vector<Backend>& backends, const std::string& filter, bool verbose) {
  std::vector<ProbeRun> runs;
  for (Backend b : backends) {
    DeviceDesc dd;
    dd.backend = b;
    dd.debug = true;
    dd.messageCallback = [](MessageSeverity, std::string_view) {};  // counted by the device, reported per probe
    Ref<Device> device;
    std::string deviceError;
    try {
      device = CreateDevice(dd);
    } catch (const std::exception& e) {
      deviceError = e.what();
    }
    for (const Probe& p : Probes()) {
      std::string id = p.group + "/" + p.name;
      if (!filter.empty() && id.find(filter) == std::string::npos) continue;
      ProbeRun run;
      run.probe = &p;
      run.backend = b;
      auto t0 = std::chrono::steady_clock::now();
      if (device) {
        run.device = device->Info().deviceName;
        run.result = RunProbe(p, *device);
      } else {
        run.result = Fail("device creation failed: " + deviceError);
      }
      run.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      if (verbose)
        std::fprintf(stderr, "%-6s %-60s %s %s\n", BackendName(b), id.c_str(), StatusName(run.result.status), run.result.detail.c_str());
      runs.push_back(std::move(run));
    }
  }
  return runs;
}

namespace {

std::string Cell(const Result& r) {
  std::ostringstream s;
  s << StatusName(r.status);
  if (r.status != Status::Unsupported && !r.errorUnit.empty()) s << " (" << std::setprecision(3) << r.measuredError << " " << r.errorUnit << ")";
  return s.str();
}

// Probes in registration order with their result per backend.
std::vector<std::pair<const Probe*, std::map<Backend, const ProbeRun*>>> Table(const std::vector<ProbeRun>& runs) {
  std::vector<std::pair<const Probe*, std::map<Backend, const ProbeRun*>>> rows;
  for (const ProbeRun& r : runs) {
    auto it = std::find_if(rows.begin(), rows.end(), [&](auto& row) { return row.first == r.probe; });
    if (it == rows.end()) {
      rows.push_back({r.probe, {}});
      it = rows.end() - 1;
    }
    it->second[r.backend] = &r;
  }
  return rows;
}

std::vector<Backend> BackendsOf(const std::vector<ProbeRun>& runs) {
  std::vector<Backend> b;
  for (const ProbeRun& r : runs)
    if (std::find(b.begin(), b.end(), r.backend) == b.end()) b.push_back(r.backend);
  return b;
}

}  // namespace

std::string FormatMarkdown(const std::vector<ProbeRun>& runs) {
  std::vector<Backend> backends = BackendsOf(runs);
  std::ostringstream s;
  std::map<Backend, std::string> devices;
  for (const ProbeRun& r : runs) devices[r.backend] = r.device;
  s << "| group | behaviour |";
  for (Backend b : backends) s << " " << (b == Backend::Vulkan ? "Vulkan" : "OpenGL") << " (" << devices[b] << ") |";
  s << "\n|---|---|";
  for (size_t i = 0; i < backends.size(); ++i) s << "---|";
  s << "\n";
  size_t pass = 0, total = 0, deviations = 0, unsupported = 0;
  for (auto& [probe, byBackend] : Table(runs)) {
    s << "| " << probe->group << " | " << probe->name << " |";
    for (Backend b : backends) {
      auto it = byBackend.find(b);
      s << " " << (it == byBackend.end() ? "-" : Cell(it->second->result));
      if (it != byBackend.end() && it->second->result.status != Status::Pass)
        s << ": " << it->second->result.detail;
      s << " |";
      if (it != byBackend.end()) {
        ++total;
        pass += it->second->result.status == Status::Pass;
        deviations += it->second->result.status == Status::Deviation;
        unsupported += it->second->result.status == Status::Unsupported;
      }
    }
    s << "\n";
  }
  s << "\n" << pass << " of " << total << " probe runs pass; " << deviations << " show a bounded driver deviation, " << unsupported
    << " are not supported, " << (total - pass - deviations - unsupported) << " fail.\n";
  return s.str();
}

std::string FormatJson(const std::vector<ProbeRun>& runs) {
  nlohmann::json j;
  j["probes"] = nlohmann::json::array();
  for (auto& [probe, byBackend] : Table(runs)) {
    nlohmann::json p = {{"group", probe->group}, {"name", probe->name}, {"description", probe->description}, {"results", nlohmann::json::object()}};
    for (auto& [b, run] : byBackend) {
      const Result& r = run->result;
      const char* status = r.status == Status::Pass ? "pass" : r.status == Status::Fail ? "fail" : r.status == Status::Deviation ? "deviation" : "unsupported";
      p["results"][BackendName(b)] = {{"status", status},
                                     {"measured_error", r.measuredError},
                                     {"unit", r.errorUnit},
                                     {"tolerance", r.tolerance},
                                     {"detail", r.detail},
                                     {"device", run->device},
                                     {"ms", run->milliseconds}};
    }
    j["probes"].push_back(p);
  }
  return j.dump(2);
}

std::string FormatConsoleTable(const std::vector<ProbeRun>& runs) {
  std::vector<Backend> backends = BackendsOf(runs);
  std::ostringstream s;
  s << std::left << std::setw(22) << "group" << std::setw(58) << "behaviour";
  for (Backend b : backends) s << std::setw(30) << BackendName(b);
  s << "\n";
  for (auto& [probe, byBackend] : Table(runs)) {
    s << std::setw(22) << probe->group.substr(0, 21) << std::setw(58) << probe->name.substr(0, 57);
    for (Backend b : backends) {
      auto it = byBackend.find(b);
      s << std::setw(30) << (it == byBackend.end() ? "-" : Cell(it->second->result));
    }
    s << "\n";
    for (Backend b : backends) {
      auto it = byBackend.find(b);
      if (it != byBackend.end() && it->second->result.status != Status::Pass && !it->second->result.detail.empty())
        s << "    " << BackendName(b) << ": " << it->second->result.detail << "\n";
    }
  }
  return s.str();
}

}  // namespace sp::conformance
