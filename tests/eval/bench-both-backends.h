// Runs the bench on one scene and technique on Vulkan and OpenGL (validation on, no messages
// allowed), for the tests that judge a technique against the reference on both backends.
#pragma once
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <map>
#include <string>

#include "bench.h"
#include <sp/rhi/rhi.h>

namespace sp::test {

inline std::array<bench::RunResult, 2> BenchOnBothBackends(const scene::Scene& s, const std::string& technique,
                                                           const std::map<std::string, std::string>& params, uint32_t width, uint32_t height) {
  eval::ReferenceCache cache(s, std::filesystem::path(SHADOWPORT_TEST_OUTPUT_DIR) / "reference-cache");
  std::array<bench::RunResult, 2> r;
  const Backend backends[2] = {Backend::Vulkan, Backend::OpenGL};
  for (int i = 0; i < 2; ++i) {
    bench::RunSpec spec;
    spec.scene = &s;
    spec.technique = technique;
    spec.params = params;
    spec.backend = backends[i];
    spec.width = width;
    spec.height = height;
    spec.frames = 1;
    spec.validate = true;
    r[i] = bench::RunOne(spec, cache);
    EXPECT_EQ(r[i].validationErrors, 0u) << BackendName(backends[i]) << ": " << r[i].lastValidationError;
  }
  return r;
}

// Both backends run on Mesa's shared rasterizer: every accuracy figure must be the same.
inline void ExpectSameAccuracyOnMesa(const std::array<bench::RunResult, 2>& r, const std::string& what) {
  bool mesa = r[0].device.find("llvmpipe") != std::string::npos && r[1].device.find("llvmpipe") != std::string::npos;
  if (!mesa) return;
  EXPECT_EQ(r[0].accuracy.falseLit, r[1].accuracy.falseLit) << what;
  EXPECT_EQ(r[0].accuracy.falseShadow, r[1].accuracy.falseShadow) << what;
  EXPECT_EQ(r[0].accuracy.absErrorSum, r[1].accuracy.absErrorSum) << what;
  EXPECT_EQ(r[0].texelsPerPixelMedian, r[1].texelsPerPixelMedian) << what;
}

}  // namespace sp::test
