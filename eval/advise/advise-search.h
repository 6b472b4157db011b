// The search of `shadowport advise`: measures configurations with the bench (bench::RunOne, the
// same metrics as `shadowport bench`), caches every measurement, refines around the Pareto front.
#pragma once
#include <atomic>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "advise.h"

namespace sp::advise {

struct SearchOptions {
  std::string scene = "default", path = "slow-pan";
  Backend backend = Backend::Vulkan;
  uint32_t width = 320, height = 180, frames = 4;
  std::vector<std::string> techniques;  // bench's TechniqueSpec texts; fixed parameters are not searched
  std::vector<std::string> axes = DefaultAxes();
  int maxResolution = 4096;  // the largest shadow-map resolution searched
  SelectOptions select;
  std::filesystem::path out = "out/advise";
  std::filesystem::path cache;  // empty: <out>/cache
  size_t maxRuns = 200;         // configurations measured at most (cached ones count)
  bool exhaustive = false;      // every lattice point instead of the search
  int confirm = 3;              // runs timing each configuration the answer rests on (ms only)
  // Set (e.g. by SIGINT) to stop after the measurement in progress; the search then throws
  // Interrupted with the cache and state file written.
  const std::atomic<bool>* interrupt = nullptr;
};

struct Interrupted : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct SearchResult {
  std::vector<Measurement> measured;  // every configuration the search looked at, in order
  Selection selection;
  std::vector<size_t> front;
  size_t newMeasurements = 0, fromCache = 0, planned = 0;
  size_t timingRuns = 0, timingRunsFromCache = 0;  // the confirmation's further runs
  size_t refused = 0;  // lattice points the technique refused to configure (skipped)
  std::vector<size_t> defaults;  // each technique's all-default configuration (measured too)
  std::filesystem::path cacheDir;
  std::string revision;
};

// The build's and shaders' identity, part of every cache key: a hash of this program's binary and
// of every file in the shader directory, so a rebuild or a shader edit never reuses old figures.
std::string BuildRevision();

// Throws std::invalid_argument for an unknown scene, technique, path or parameter, naming it.
SearchResult Search(const SearchOptions& o, const std::function<void(const std::string&)>& progress);

// Writes `text` to `path` through a temporary file and a rename, so an interrupted write leaves the
// old file or the new one, never half of one.
void WriteAtomically(const std::filesystem::path& path, const std::string& text);

}  // namespace sp::advise
