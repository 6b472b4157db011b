// `bench --path FILE.json`: a built-in path saved to a file and replayed gives exactly the
// metrics of the built-in path (same keys, same frames), and the results name the file; a
// recorded light direction becomes the run's light; a malformed file fails before anything runs.
#include <gtest/gtest.h>

#include "backend-test.h"

#include <fstream>
#include <map>
#include <utility>

#include "bench.h"

namespace sp::test {
namespace {

// Under build/test-output/<suite>/<test>.
std::filesystem::path Dir() { return sp::test::TestOutputDir(); }

bench::BenchOptions Options(const std::string& path, const std::string& out) {
  bench::BenchOptions o;
  o.scenes = {"default"};
  o.techniques = {"basic"};
  o.backends = {Backend::Vulkan};
  o.width = 48;
  o.height = 27;
  o.frames = 3;
  o.path = path;
  o.out = Dir() / out / "results.json";
  o.referenceCache = std::filesystem::path(SHADOWPORT_TEST_OUTPUT_DIR) / "reference-cache";
  o.validate = true;
  return o;
}

// The measured values (timings vary from run to run and are left out).
nlohmann::json Measured(const nlohmann::json& run) {
  nlohmann::json m = run["metrics"];
  for (auto it = m.begin(); it != m.end();) {
    const std::string& k = it.key();
    if (k.find("ms") != std::string::npos || k.find("cpu") != std::string::npos || k.find("gpu") != std::string::npos) it = m.erase(it);
    else ++it;
  }
  return m;
}

TEST(RecordedPathBench, ASavedBuiltinPathGivesTheBuiltinPathsMetrics) {
  scene::Scene s = scene::MakeBuiltinScene("default");
  s.cameraPaths = scene::CameraPathsFor(s);
  std::filesystem::path file = Dir() / "rotate-recorded.json";
  scene::SaveCameraPath(s.cameraPath("rotate"), file);

  nlohmann::json builtin = bench::RunBench(Options("rotate", "builtin"), {});
  nlohmann::json recorded = bench::RunBench(Options(file.string(), "recorded"), {});
  ASSERT_EQ(builtin["runs"].size(), 1u);
  ASSERT_EQ(recorded["runs"].size(), 1u);
  const nlohmann::json& a = builtin["runs"][0];
  const nlohmann::json& b = recorded["runs"][0];
  EXPECT_EQ(a["path"], "rotate");
  EXPECT_EQ(b["path"], file.string()) << "the results name the recorded file";
  EXPECT_EQ(b["checks"]["validation_errors"], 0);
  nlohmann::json ma = Measured(a), mb = Measured(b);
  EXPECT_GT(ma.size(), 5u);
  EXPECT_EQ(ma, mb) << "built-in:\n" << ma.dump(1) << "\nrecorded:\n" << mb.dump(1);
  EXPECT_GT(a["checks"]["judged_pixels"].get<double>(), 0.0);
  EXPECT_EQ(a["checks"]["judged_pixels"], b["checks"]["judged_pixels"]);
}

TEST(RecordedPathBench, ARecordedLightBecomesTheRunsLight) {
  scene::Scene s = scene::MakeBuiltinScene("default");
  s.cameraPaths = scene::CameraPathsFor(s);
  scene::CameraPath p = s.cameraPath("slow-pan");
  // Light from straight above: the default scene's light is oblique, so the pictures differ.
  for (scene::CameraKey& k : p.keys) k.lightDirection = glm::vec3(0.0f, -1.0f, 0.0f);
  std::filesystem::path file = Dir() / "overhead-sun.json";
  scene::SaveCameraPath(p, file);
  scene::SaveCameraPath(s.cameraPath("slow-pan"), Dir() / "scene-sun.json");
  bench::BenchOptions o = Options(file.string(), "overhead");
  o.frames = 1;
  nlohmann::json overhead = bench::RunBench(o, {});
  o = Options((Dir() / "scene-sun.json").string(), "scene-sun");
  o.frames = 1;
  nlohmann::json sceneSun = bench::RunBench(o, {});
  EXPECT_NE(Measured(overhead["runs"][0]), Measured(sceneSun["runs"][0])) << "the recorded light was not used";
}

// A light that turns along the path turns in the run: with two frames, the first is lit as by
// the first key's light and the last as by the last key's, in the techniques and the reference
// (the same misclassification per frame as a path holding either light).
TEST(RecordedPathBench, ALightTurningAlongThePathTurnsInTheRun) {
  scene::Scene s = scene::MakeBuiltinScene("default");
  s.cameraPaths = scene::CameraPathsFor(s);
  scene::CameraPath hold = s.cameraPath("slow-pan"), overhead = hold, turn = hold;
  for (scene::CameraKey& k : overhead.keys) k.lightDirection = glm::vec3(0.0f, -1.0f, 0.0f);
  for (scene::CameraKey& k : hold.keys) k.lightDirection = s.light.direction;
  turn.keys.front().lightDirection = s.light.direction;
  turn.keys.back().lightDirection = glm::vec3(0.0f, -1.0f, 0.0f);
  std::map<std::string, nlohmann::json> series, measured;
  for (const auto& [name, path] : {std::pair<std::string, const scene::CameraPath*>{"hold", &hold}, {"overhead", &overhead}, {"turn", &turn}}) {
    std::filesystem::path file = Dir() / ("light-" + name + ".json");
    scene::SaveCameraPath(*path, file);
    bench::BenchOptions o = Options(file.string(), "light-" + name);
    o.width = 160;
    o.height = 90;
    o.frames = 2;
    nlohmann::json run = bench::RunBench(o, {})["runs"][0];
    series[name] = run["series"]["misclassified_pct"];
    measured[name] = Measured(run);
  }
  EXPECT_EQ(series["turn"][0], series["hold"][0]);
  EXPECT_EQ(series["turn"][1], series["overhead"][1]);
  EXPECT_NE(series["hold"][1], series["overhead"][1]) << "the two lights must give different pictures";
  EXPECT_NE(measured["turn"], measured["hold"]) << "the light did not turn";
  EXPECT_NE(measured["turn"], measured["overhead"]) << "the first frame did not keep the first key's light";
}

TEST(RecordedPathBench, AMalformedFileFailsBeforeAnythingRuns) {
  std::filesystem::path file = Dir() / "one-key.json";
  std::ofstream(file) << R"({"lens": {"fov_y_degrees": 60, "near": 0.1, "far": 100, "up": [0, 1, 0]},
                            "keys": [{"t": 0, "position": [0, 1, 5], "target": [0, 0, 0]}]})";
  try {
    bench::ValidateBenchOptions(Options(file.string(), "bad"));
    ADD_FAILURE() << "accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find(file.string() + ": keys: a path needs at least 2 keys"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sp::test
