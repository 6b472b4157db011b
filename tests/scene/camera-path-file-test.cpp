// Camera paths as files (the viewer records them, the lab replays them): a saved path loads back
// equal, key by key and bit for bit; a recorder maps its seconds onto [0, 1] and skips frames whose
// clock did not advance; keys timed in seconds are mapped the same way; every kind of malformed
// file is refused naming the file and the key or field; a scene resolves a file name as a path.
#include <gtest/gtest.h>

#include "backend-test.h"

#include <fstream>
#include <glm/gtc/constants.hpp>

#include <sp/scene/scene.h>

namespace sp::scene {
namespace {

// Under build/test-output/<suite>/<test>.
std::filesystem::path Dir() { return sp::test::TestOutputDir(); }

std::filesystem::path Write(const std::string& name, const std::string& text) {
  std::filesystem::path p = Dir() / name;
  std::ofstream(p) << text;
  return p;
}

CameraPath Sample(bool withLight) {
  CameraPath p;
  p.name = "sample";
  p.lens.fovY = glm::radians(47.5f);
  p.lens.nearZ = 0.25f;
  p.lens.farZ = 321.0f;
  p.lens.up = glm::normalize(glm::vec3(0.1f, 1.0f, 0.0f));
  // Values with no short decimal form, so a writer that rounds loses bits.
  p.keys = {{0.0f, {-4.0f, 7.0f, 14.0f}, {1.0f, 1.0f, 0.0f}},
            {1.0f / 3.0f, {-3.9f, 7.1f, 13.7f}, {1.1f, 0.9f, glm::pi<float>()}},
            {1.0f, {-3.5f, 7.4f, 12.9f}, {1.3f, 0.8f, -0.1f}}};
  if (withLight)
    for (size_t i = 0; i < p.keys.size(); ++i) p.keys[i].lightDirection = glm::normalize(glm::vec3(-0.55f + 0.01f * float(i), -0.65f, -0.5f));
  return p;
}

void ExpectSame(const CameraPath& a, const CameraPath& b) {
  EXPECT_EQ(a.lens.fovY, b.lens.fovY);
  EXPECT_EQ(a.lens.nearZ, b.lens.nearZ);
  EXPECT_EQ(a.lens.farZ, b.lens.farZ);
  EXPECT_EQ(a.lens.up, b.lens.up);
  ASSERT_EQ(a.keys.size(), b.keys.size());
  for (size_t i = 0; i < a.keys.size(); ++i) {
    EXPECT_EQ(a.keys[i].time, b.keys[i].time) << "key " << i;
    EXPECT_EQ(a.keys[i].position, b.keys[i].position) << "key " << i;
    EXPECT_EQ(a.keys[i].target, b.keys[i].target) << "key " << i;
    EXPECT_EQ(a.keys[i].lightDirection, b.keys[i].lightDirection) << "key " << i;
  }
}

TEST(CameraPathFile, SavedPathLoadsBackEqual) {
  for (bool light : {false, true}) {
    CameraPath p = Sample(light);
    std::filesystem::path f = Dir() / (light ? "with-light.json" : "camera-only.json");
    SaveCameraPath(p, f);
    CameraPath q = LoadCameraPath(f);
    EXPECT_EQ(q.name, f.string());
    ExpectSame(p, q);
    // And it is the same motion: the spline sees the same keys.
    for (double t : {0.0, 0.2, 0.5, 0.9, 1.0}) {
      EXPECT_EQ(p.at(t).position, q.at(t).position) << t;
      EXPECT_EQ(p.at(t).target, q.at(t).target) << t;
    }
  }
}

TEST(CameraPathFile, RecorderMapsSecondsOntoThePathAndSkipsPausedFrames) {
  CameraPathRecorder rec;
  Camera c;
  c.fovY = glm::radians(50.0f);
  c.nearZ = 0.3f;
  c.farZ = 90.0f;
  EXPECT_THROW(rec.path(), std::runtime_error);
  const double seconds[] = {10.0, 10.5, 10.5, 10.25, 12.0};  // a paused frame, then one from the past
  for (size_t i = 0; i < 5; ++i) {
    c.position = glm::vec3(float(i), 2.0f, 3.0f);
    c.target = glm::vec3(float(i), 0.0f, 0.0f);
    rec.add(seconds[i], c, glm::vec3(0.0f, -2.0f, 0.0f));
  }
  ASSERT_EQ(rec.size(), 3u);
  EXPECT_EQ(rec.durationSeconds(), 2.0);
  CameraPath p = rec.path("flight");
  EXPECT_EQ(p.name, "flight");
  ASSERT_EQ(p.keys.size(), 3u);
  EXPECT_EQ(p.keys[0].time, 0.0f);
  EXPECT_EQ(p.keys[1].time, 0.25f);
  EXPECT_EQ(p.keys[2].time, 1.0f);
  EXPECT_EQ(p.keys[2].position, glm::vec3(4.0f, 2.0f, 3.0f));
  EXPECT_EQ(p.keys[1].lightDirection, glm::vec3(0.0f, -1.0f, 0.0f));  // stored as a unit vector
  EXPECT_EQ(p.lens.fovY, c.fovY);
  std::filesystem::path f = Dir() / "flight.json";
  rec.save(f);
  ExpectSame(p, LoadCameraPath(f));
}

TEST(CameraPathFile, KeysInSecondsAreMappedOntoThePath) {
  auto f = Write("seconds.json", R"({"lens": {"fov_y_degrees": 60, "near": 0.1, "far": 100, "up": [0, 1, 0]},
    "keys": [{"time": 3.0, "position": [0, 1, 5], "target": [0, 0, 0]},
             {"time": 4.0, "position": [1, 1, 5], "target": [1, 0, 0]},
             {"time": 7.0, "position": [2, 1, 5], "target": [2, 0, 0]}]})");
  CameraPath p = LoadCameraPath(f);
  ASSERT_EQ(p.keys.size(), 3u);
  EXPECT_EQ(p.keys[0].time, 0.0f);
  EXPECT_EQ(p.keys[1].time, 0.25f);
  EXPECT_EQ(p.keys[2].time, 1.0f);
  EXPECT_FALSE(p.keys[0].lightDirection.has_value());
  EXPECT_FLOAT_EQ(p.lens.fovY, glm::radians(60.0f));
}

struct Bad {
  const char* name;
  const char* keys;      // the "keys" array's text, or a whole document when it starts with '{'
  const char* expected;  // after "<file>: "
};

TEST(CameraPathFile, MalformedFilesAreRefusedNamingTheFileAndTheKey) {
  const char* lens = R"("lens": {"fov_y_degrees": 60, "near": 0.1, "far": 100, "up": [0, 1, 0]})";
  const Bad cases[] = {
      {"missing-position", R"([{"t": 0, "position": [0, 1, 5], "target": [0, 0, 0]}, {"t": 1, "target": [0, 0, 0]}])",
       "keys[1]: 'position' is missing"},
      {"nan", R"([{"t": 0, "position": [0, 1, 5], "target": [0, 0, 0]}, {"t": 1, "position": [0, null, 5], "target": [0, 0, 0]}])",
       "keys[1].position[1]: must be a finite number (got null)"},
      {"huge", R"([{"t": 0, "position": [0, 1, 5], "target": [0, 0, 0]}, {"t": 1, "position": [0, 1e39, 5], "target": [0, 0, 0]}])",
       "keys[1].position[1]: must be a finite number"},
      {"one-key", R"([{"t": 0, "position": [0, 1, 5], "target": [0, 0, 0]}])", "keys: a path needs at least 2 keys (got 1)"},
      {"not-increasing",
       R"([{"time": 0, "position": [0, 1, 5], "target": [0, 0, 0]}, {"time": 2, "position": [0, 1, 5], "target": [0, 0, 0]},
           {"time": 2, "position": [0, 1, 5], "target": [0, 0, 0]}])",
       "keys[2].time: times must increase (2.000000 after 2.000000)"},
      {"t-not-to-one", R"([{"t": 0, "position": [0, 1, 5], "target": [0, 0, 0]}, {"t": 0.5, "position": [0, 1, 5], "target": [0, 0, 0]}])",
       "keys: 't' runs from 0 at the first key to 1 at the last"},
      {"no-time", R"([{"t": 0, "position": [0, 1, 5], "target": [0, 0, 0]}, {"position": [0, 1, 5], "target": [0, 0, 0]}])",
       "keys[1]: 't' is missing (keys[0] gives 't')"},
      {"light-on-one-key",
       R"([{"t": 0, "position": [0, 1, 5], "target": [0, 0, 0]}, {"t": 1, "position": [0, 1, 5], "target": [0, 0, 0], "light_direction": [0, -1, 0]}])",
       "keys[1]: 'light_direction' must be given on every key or on none"},
      {"zero-light",
       R"([{"t": 0, "position": [0, 1, 5], "target": [0, 0, 0], "light_direction": [0, 0, 0]}, {"t": 1, "position": [0, 1, 5], "target": [0, 0, 0], "light_direction": [0, -1, 0]}])",
       "keys[0].light_direction: must not be zero"},
      {"short-vector", R"([{"t": 0, "position": [0, 1], "target": [0, 0, 0]}, {"t": 1, "position": [0, 1, 5], "target": [0, 0, 0]}])",
       "keys[0].position: must be an array of 3 numbers (got [0,1])"},
      {"no-lens", R"({"keys": []})", "'lens' is missing"},
      {"bad-near", R"({"lens": {"fov_y_degrees": 60, "near": 0, "far": 100, "up": [0, 1, 0]}, "keys": []})", "lens.near: must be above 0"},
      {"not-json", R"({"lens": )", "not valid JSON"},
  };
  for (const Bad& b : cases) {
    std::string text = b.keys[0] == '{' ? b.keys : std::string("{") + lens + ", \"keys\": " + b.keys + "}";
    std::filesystem::path f = Write(std::string(b.name) + ".json", text);
    try {
      LoadCameraPath(f);
      ADD_FAILURE() << b.name << ": accepted";
    } catch (const std::runtime_error& e) {
      std::string want = f.string() + ": " + b.expected;
      EXPECT_NE(std::string(e.what()).find(want), std::string::npos) << b.name << ": got \"" << e.what() << "\", want \"" << want << "\"";
    }
  }
  try {
    LoadCameraPath(Dir() / "no-such-file.json");
    ADD_FAILURE() << "a missing file was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no-such-file.json: cannot open the camera path file"), std::string::npos) << e.what();
  }
}

TEST(CameraPathFile, SceneResolvesAFileAsAPathAndUsesItsLight) {
  Scene s = MakeBuiltinScene("default");
  s.cameraPaths = CameraPathsFor(s);
  CameraPath p = s.cameraPath("rotate");
  p.keys[0].lightDirection = p.keys.back().lightDirection = glm::vec3(0.0f, -1.0f, 0.0f);
  for (size_t i = 1; i + 1 < p.keys.size(); ++i) p.keys[i].lightDirection = glm::vec3(0.0f, -1.0f, 0.0f);
  std::filesystem::path f = Dir() / "rotate.json";
  SaveCameraPath(p, f);
  EXPECT_TRUE(IsCameraPathFile(f.string()));
  EXPECT_TRUE(IsCameraPathFile("not-there.json"));
  EXPECT_FALSE(IsCameraPathFile("slow-pan"));
  const CameraPath& loaded = s.cameraPathOrFile(f.string());
  EXPECT_EQ(loaded.name, f.string());
  EXPECT_EQ(&s.cameraPath(f.string()), &loaded);
  ExpectSame(p, loaded);
  EXPECT_EQ(s.cameraPathOrFile("dolly").name, "dolly");
  EXPECT_THROW(s.cameraPathOrFile("nosuch"), std::invalid_argument);
  EXPECT_TRUE(s.useRecordedLight(loaded));
  EXPECT_EQ(s.light.direction, glm::vec3(0.0f, -1.0f, 0.0f));
  p.keys.back().lightDirection = glm::vec3(1.0f, 0.0f, 0.0f);
  EXPECT_FALSE(s.useRecordedLight(p)) << "a light that turns along the path is reported";
}

}  // namespace
}  // namespace sp::scene
