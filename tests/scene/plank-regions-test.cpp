// The regions stacked-planks and single-plank carry for the lab (scene::Scene::regions), checked
// against the scenes' own geometry by casting the 3-degree sun's rays on the CPU: the same boxes
// in both scenes; no sun ray from any point of "beside-high-penumbra" or "far" reaches the high
// plank (so the area light's visibility there is the low plank's alone, as in single-plank);
// "beside-high-penumbra" comes within 3 cm of the high plank's penumbra (moved that much towards
// it, some rays do reach it); "under-high-penumbra" holds the high plank's penumbra; and each
// holds both umbra and penumbra of the low plank.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <sp/scene/scene.h>

#include "scene-rays.h"

namespace sp::test {
namespace {

using scene::Bounds;
using scene::Instance;
using scene::Scene;

constexpr float kSunDegrees = 3.0f;  // what the regions are laid out for (close-scenes.cpp)

// Directions towards the sun disc of angular diameter kSunDegrees: a 9 x 9 grid over the disc's
// square, those inside it (the centre and the rim included).
std::vector<glm::vec3> SunRays(const glm::vec3& lightDirection) {
  glm::vec3 w = -glm::normalize(lightDirection);
  glm::vec3 u = glm::normalize(glm::cross(w, glm::vec3(0, 0, 1))), v = glm::cross(w, u);
  float r = std::tan(glm::radians(0.5f * kSunDegrees));
  std::vector<glm::vec3> rays;
  for (int j = -4; j <= 4; ++j)
    for (int i = -4; i <= 4; ++i)
      if (i * i + j * j <= 16) rays.push_back(glm::normalize(w + r * (float(i) / 4 * u + float(j) / 4 * v)));
  return rays;
}

// Fraction of the sun rays from p that `inst` blocks.
float Blocked(const Scene& s, const Instance& inst, const glm::vec3& p, const std::vector<glm::vec3>& rays) {
  int hit = 0;
  for (const glm::vec3& d : rays) hit += RayHit(s, inst, p, d) > 0.0f;
  return float(hit) / float(rays.size());
}

// The plank instances by height: the floor tiles are at y = 0, the low plank at 0.6, the high at 3.
const Instance& PlankAt(const Scene& s, float y) {
  for (const Instance& inst : s.instances)
    if (std::abs(0.5f * (inst.worldBounds.min.y + inst.worldBounds.max.y) - y) < 0.1f) return inst;
  ADD_FAILURE() << s.name << " has no plank at y = " << y;
  return s.instances.front();
}

const scene::Region& RegionNamed(const Scene& s, const std::string& name) {
  for (const scene::Region& r : s.regions)
    if (r.name == name) return r;
  ADD_FAILURE() << s.name << " has no region " << name;
  return s.regions.front();
}

// Floor points of a box on a grid of n x n.
std::vector<glm::vec3> FloorGrid(const Bounds& b, int n) {
  std::vector<glm::vec3> p;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      p.push_back({b.min.x + (b.max.x - b.min.x) * float(i) / float(n - 1), 0.0f, b.min.z + (b.max.z - b.min.z) * float(j) / float(n - 1)});
  return p;
}

TEST(PlankRegions, SameInBothScenesAndClearOfTheHighPlanksPenumbra) {
  Scene stacked = scene::MakeBuiltinScene("stacked-planks"), single = scene::MakeBuiltinScene("single-plank");
  ASSERT_EQ(stacked.regions.size(), 3u);
  ASSERT_EQ(single.regions.size(), stacked.regions.size());
  for (size_t k = 0; k < stacked.regions.size(); ++k) {
    EXPECT_EQ(single.regions[k].name, stacked.regions[k].name);
    ASSERT_EQ(single.regions[k].boxes.size(), stacked.regions[k].boxes.size());
    for (size_t b = 0; b < stacked.regions[k].boxes.size(); ++b) {
      EXPECT_EQ(single.regions[k].boxes[b].min, stacked.regions[k].boxes[b].min);
      EXPECT_EQ(single.regions[k].boxes[b].max, stacked.regions[k].boxes[b].max);
    }
  }
  std::vector<glm::vec3> rays = SunRays(stacked.light.direction);
  const Instance& high = PlankAt(stacked, 3.0f);
  const Instance& low = PlankAt(stacked, 0.6f);
  for (const char* name : {"beside-high-penumbra", "far"}) {
    for (const Bounds& b : RegionNamed(stacked, name).boxes) {
      EXPECT_LE(b.min.y, 0.0f);
      EXPECT_GE(b.max.y, 0.0f) << "the regions are on the floor";
      int umbra = 0, penumbra = 0;
      for (const glm::vec3& p : FloorGrid(b, 21)) {
        ASSERT_EQ(Blocked(stacked, high, p, rays), 0.0f) << name << ": the high plank blocks part of the sun at " << p.x << ", " << p.z;
        float f = Blocked(stacked, low, p, rays);
        umbra += f == 1.0f;
        penumbra += f > 0.0f && f < 1.0f;
      }
      EXPECT_GT(umbra, 0) << name << " holds none of the low plank's umbra";
      EXPECT_GT(penumbra, 0) << name << " holds none of the low plank's penumbra";
    }
  }
  // Tight: 3 cm towards the high plank's shadow from each crossing strip's inner edge, the high
  // plank blocks part of the sun (the strips start right at its penumbra's end).
  const scene::Region& crossing = RegionNamed(stacked, "beside-high-penumbra");
  ASSERT_EQ(crossing.boxes.size(), 2u);
  // The high plank's shadow's centre: its centre moved along the light down to the floor.
  glm::vec3 c = 0.5f * (high.worldBounds.min + high.worldBounds.max);
  float highCentreX = c.x + c.y * stacked.light.direction.x / -stacked.light.direction.y;
  for (const Bounds& b : crossing.boxes) {
    bool leftOfShadow = b.max.x < highCentreX;
    float inner = leftOfShadow ? b.max.x + 0.03f : b.min.x - 0.03f;
    float blocked = 0.0f;
    for (float z = b.min.z; z <= b.max.z; z += 0.05f) blocked = std::max(blocked, Blocked(stacked, high, {inner, 0.0f, z}, rays));
    EXPECT_GT(blocked, 0.0f) << "the crossing strip at x " << b.min.x << ".." << b.max.x << " is more than 3 cm from the high plank's penumbra";
    EXPECT_LT(blocked, 1.0f) << "3 cm in from the strip is already the high plank's umbra";
  }
  // Under the high plank's penumbra: it blocks part of the sun somewhere in each box, all of it
  // nowhere on the box's outer edge, and the low plank's umbra and penumbra are there too.
  for (const Bounds& b : RegionNamed(stacked, "under-high-penumbra").boxes) {
    int partial = 0, lowUmbra = 0, lowPenumbra = 0;
    for (const glm::vec3& p : FloorGrid(b, 21)) {
      float f = Blocked(stacked, high, p, rays), g = Blocked(stacked, low, p, rays);
      partial += f > 0.0f && f < 1.0f;
      lowUmbra += g == 1.0f;
      lowPenumbra += g > 0.0f && g < 1.0f;
    }
    EXPECT_GT(partial, 0);
    EXPECT_GT(lowUmbra, 0);
    EXPECT_GT(lowPenumbra, 0);
  }
}

}  // namespace
}  // namespace sp::test
