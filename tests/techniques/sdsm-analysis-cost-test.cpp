// The SDSM analysis cost measurement (techniques/sdsm/analysis-cost.h), on both backends: every
// pass is timed, the table has the rows the issue asks for, bad parameters are refused by name,
// and the synthetic depth buffer is the scene it claims (CPU geometry: sky above the horizon,
// the ground plane's view depth below it, a pillar in front of the ground).
#include <algorithm>
#include <cmath>
#include <glm/ext/matrix_transform.hpp>
#include <stdexcept>

#include "backend-test.h"
#include "sdsm/analysis-cost.h"

namespace sp::test {
namespace {

using namespace tech::sdsm;

class SdsmAnalysisCostTest : public BackendTest {};

TEST_P(SdsmAnalysisCostTest, TimesEveryPassAgainstTheReadOnceLimit) {
  AnalysisCost c = MeasureAnalysisCost(device(), 200, 120, 2, 1);
  ASSERT_EQ(c.passes.size(), 10u);
  for (const PassCost& p : c.passes) EXPECT_GT(p.medianMs, 0.0) << p.name;
  EXPECT_GT(c.limitMs, 0.0);
  EXPECT_DOUBLE_EQ(c.limitMs, std::min(c.passes[0].medianMs, c.passes[1].medianMs));
  std::string table = FormatAnalysisCost(c, BackendName(GetParam()));
  for (const char* row : {"reduction + histogram", "whole analysis", "bounds (tight)", "histogram", "x limit"})
    EXPECT_NE(table.find(row), std::string::npos) << row << " missing in\n" << table;
}

TEST_P(SdsmAnalysisCostTest, RefusesBadParametersByName) {
  auto message = [&](uint32_t w, uint32_t h, uint32_t frames, uint32_t warmup) {
    try {
      MeasureAnalysisCost(device(), w, h, frames, warmup);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(0, 120, 2, 1).find("size"), std::string::npos);
  EXPECT_NE(message(200, 120, 0, 1).find("frames"), std::string::npos);
  EXPECT_NE(message(200, 120, 2, 0).find("warmup"), std::string::npos);
}

SP_INSTANTIATE_BACKEND_TESTS(SdsmAnalysisCostTest);

TEST(SdsmAnalysisCostDepth, SkyAboveTheHorizonGroundAndPillarsBelow) {
  const uint32_t w = 160, h = 90;
  AnalysisFrame f;
  std::vector<float> d = SyntheticCameraDepth(w, h, &f);
  ASSERT_EQ(d.size(), size_t(w) * h);
  // Eye 20 m up looking 6 m down over 100 m: the horizon is above the image centre.
  for (uint32_t x = 0; x < w; ++x) EXPECT_EQ(d[x], 1.0f) << "top row is sky at x=" << x;
  // Every bottom-row pixel sees the ground (its ray per unit view depth descends dir.y, so the
  // ground is at view depth 20 / -dir.y) or a pillar in front of it, never anything farther.
  glm::mat3 toWorld = glm::mat3(glm::inverse(glm::lookAtRH(glm::vec3(0, 20, 0), glm::vec3(0, 14, -100), glm::vec3(0, 1, 0))));
  uint32_t ground = 0, pillar = 0, y = h - 1;
  for (uint32_t x = 0; x < w; ++x) {
    float ndcX = (x + 0.5f) * f.ndcScale.x + f.ndcOffset.x, ndcY = (y + 0.5f) * f.ndcScale.y + f.ndcOffset.y;
    glm::vec3 dir = toWorld * glm::vec3(ndcX * f.rayScale.x + f.rayOffset.x, ndcY * f.rayScale.y + f.rayOffset.y, -1.0f);
    ASSERT_LT(dir.y, 0.0f);
    float expect = 20.0f / -dir.y, z = f.ViewDepth(d[y * w + x]);
    ASSERT_LT(d[y * w + x], 1.0f) << "x=" << x;
    if (std::abs(z - expect) <= 1e-3f * expect) {
      ++ground;
    } else {
      EXPECT_LT(z, expect) << "x=" << x << ": farther than the ground";
      ++pillar;
    }
  }
  EXPECT_GT(ground, 0u);
  EXPECT_GT(pillar, 0u);
}

}  // namespace
}  // namespace sp::test
