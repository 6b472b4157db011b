// The bench's option handling that needs no device: technique specs with fixed parameters, where
// the reference cache goes when nobody says, and the cross-backend image comparison.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>

#include "backend-test.h"
#include "bench.h"

namespace sp::test {
namespace {

using bench::ParseTechniqueSpec;

// --light-gamma: the light travels at exactly gamma to the view direction, from above at 90.
TEST(BenchLightGamma, LightTravelsAtTheAngleToTheView) {
  for (glm::vec3 forward : {glm::vec3(0, 0, -1), glm::vec3(0.3f, -0.4f, -1), glm::vec3(0, -1, 0), glm::vec3(1, 0.2f, 0)})
    for (float g : {0.0f, 1.0f, 30.0f, 90.0f, 150.0f, 179.0f, 180.0f}) {
      glm::vec3 d = bench::LightAtGamma(forward, g);
      float angle = glm::degrees(std::acos(std::clamp(glm::dot(d, glm::normalize(forward)), -1.0f, 1.0f)));
      EXPECT_NEAR(angle, g, 0.01f) << "forward " << forward.x << "," << forward.y << "," << forward.z;
      EXPECT_NEAR(glm::length(d), 1.0f, 1e-5f);
    }
  EXPECT_LT(bench::LightAtGamma(glm::vec3(0, 0, -1), 90.0f).y, -0.999f);  // overhead: straight down
  bench::BenchOptions o;
  o.lightGammas = {200.0f};
  EXPECT_THROW(bench::ValidateBenchOptions(o), std::invalid_argument);
}

TEST(BenchTechniqueSpec, NameAloneAndNameWithParameters) {
  bench::TechniqueSpec plain = ParseTechniqueSpec("basic");
  EXPECT_EQ(plain.name, "basic");
  EXPECT_TRUE(plain.params.empty());

  bench::TechniqueSpec csm = ParseTechniqueSpec("csm:filter=gauss:kernel=5");
  EXPECT_EQ(csm.name, "csm");
  EXPECT_EQ(csm.params, (std::map<std::string, std::string>{{"filter", "gauss"}, {"kernel", "5"}}));
}

TEST(BenchTechniqueSpec, ListValuesKeepTheirColons) {
  bench::TechniqueSpec t = ParseTechniqueSpec("csm:split=manual:splits=0.1:0.3:0.6:cascades=4");
  EXPECT_EQ(t.params.at("splits"), "0.1:0.3:0.6");
  EXPECT_EQ(t.params.at("split"), "manual");
  EXPECT_EQ(t.params.at("cascades"), "4");
}

TEST(BenchTechniqueSpec, MalformedSpecsAreRejected) {
  for (const char* bad : {"", "csm:", ":csm", "filter=gauss", "csm::kernel=5", "csm:=5", "csm:kernel=3:kernel=5"})
    EXPECT_THROW(ParseTechniqueSpec(bad), std::invalid_argument) << "'" << bad << "'";
}

TEST(BenchTechniqueSpec, SpecParametersAreValidatedAndMayNotAlsoBeSwept) {
  bench::BenchOptions o;
  o.techniques = {"basic", "csm:filter=gauss:kernel=5"};
  EXPECT_NO_THROW(bench::ValidateBenchOptions(o));

  o.techniques = {"csm:filter=nosuch"};
  EXPECT_THROW(bench::ValidateBenchOptions(o), std::invalid_argument);

  o.techniques = {"csm:kernel=5"};
  o.params["kernel"] = {"3", "7"};
  try {
    bench::ValidateBenchOptions(o);
    FAIL() << "a parameter fixed by the spec and swept by --param was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("kernel is set both"), std::string::npos) << e.what();
  }
}

TEST(BenchReferenceCache, BesideTheResultsUnlessTheUserSaysOtherwise) {
  bench::BenchOptions o;
  o.out = "some/dir/results.json";
  {
    ScopedEnv env("SHADOWPORT_REFERENCE_CACHE", std::nullopt);
    EXPECT_EQ(bench::ReferenceCacheDir(o), std::filesystem::path("some/dir/reference-cache"));
    o.out = "results.json";
    EXPECT_EQ(bench::ReferenceCacheDir(o), std::filesystem::path("./reference-cache"));
  }
  {
    ScopedEnv env("SHADOWPORT_REFERENCE_CACHE", "/elsewhere/cache");
    EXPECT_EQ(bench::ReferenceCacheDir(o), std::filesystem::path("/elsewhere/cache"));
    o.referenceCache = "explicit";
    EXPECT_EQ(bench::ReferenceCacheDir(o), std::filesystem::path("explicit"));
  }
}

TEST(ImageDiff, CountsDifferingPixelsAndTheLargestChannelDifference) {
  const uint32_t w = 64, h = 8;
  std::vector<uint8_t> a(size_t(w) * h * 4, 100), b = a;
  EXPECT_EQ(eval::DiffImages(w, h, a.data(), b.data()).differingPixels, 0u);
  b[(3 * w + 5) * 4 + 1] = 103;  // green +3
  b[(7 * w + 60) * 4 + 0] = 0;   // red -100
  b[(1 * w + 1) * 4 + 3] = 0;    // alpha is not part of the picture
  eval::ImageDiff d = eval::DiffImages(w, h, a.data(), b.data());
  EXPECT_EQ(d.pixels, uint64_t(w) * h);
  EXPECT_EQ(d.differingPixels, 2u);
  EXPECT_EQ(d.maxDifference, 100);
  ASSERT_GT(d.imageHeight, h);  // the legend strip
  ASSERT_EQ(d.heatmap.size(), size_t(w) * d.imageHeight * 4);
  auto px = [&](uint32_t x, uint32_t y) { return &d.heatmap[(size_t(y) * w + x) * 4]; };
  // Differing pixels are red and brighter than any unchanged one.
  EXPECT_GT(px(5, 3)[0], 140);
  EXPECT_LT(px(5, 3)[1], 60);
  EXPECT_GT(px(60, 7)[0], px(5, 3)[0]);
  EXPECT_EQ(px(0, 0)[0], px(0, 0)[1]);  // unchanged: grey
  EXPECT_EQ(px(1, 1)[0], px(1, 1)[1]);
}

}  // namespace
}  // namespace sp::test
