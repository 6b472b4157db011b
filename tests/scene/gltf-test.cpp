// glTF loading: the real scenes beside the project load with the documented triangle counts and
// bounds, and malformed files give an error naming the file and the problem, never a crash.
#include <functional>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include <sp/scene/scene.h>

namespace sp::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Counts computed from the files' JSON directly (index accessor counts, POSITION min/max), an
// independent check of the loader. ../shared/scenes/README.md quotes 16,646 triangles for
// ShadowColumns; the file holds 16,638 in 183 primitives, which is what is checked here.
TEST(GltfLoader, SharedScenesLoadWithTheFilesTriangleCountsAndBounds) {
  for (const std::string& name : scene::SharedSceneNames()) {
    scene::Scene s = scene::LoadScene(name);
    fs::path file;
    for (const auto& f : fs::directory_iterator(scene::SharedScenesDir() / name))
      if (f.path().extension() == ".gltf") file = f.path();
    json j = json::parse(std::ifstream(file));
    size_t triangles = 0;
    glm::vec3 mn(1e30f), mx(-1e30f);
    for (const json& m : j["meshes"])
      for (const json& p : m["primitives"]) {
        triangles += j["accessors"][p["indices"].get<int>()]["count"].get<size_t>() / 3;
        const json& pos = j["accessors"][p["attributes"]["POSITION"].get<int>()];
        for (int a = 0; a < 3; ++a) {
          mn[a] = std::min(mn[a], pos["min"][a].get<float>());
          mx[a] = std::max(mx[a], pos["max"][a].get<float>());
        }
      }
    size_t loaded = 0;
    for (const scene::Mesh& m : s.meshes) loaded += m.triangleCount();
    EXPECT_EQ(loaded, triangles) << name;
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(s.bounds.min[a], mn[a], 1e-3f * (1 + std::abs(mn[a]))) << name;
      EXPECT_NEAR(s.bounds.max[a], mx[a], 1e-3f * (1 + std::abs(mx[a]))) << name;
    }
    for (const scene::Mesh& m : s.meshes)
      for (const scene::Vertex& v : m.vertices) ASSERT_NEAR(glm::length(v.normal), 1.0f, 1e-3f) << name << " " << m.name;
  }
}

class MalformedGltf : public ::testing::Test {
 protected:
  void SetUp() override {
    // One folder per test: ctest runs them in parallel, and one test rewriting tri.bin while
    // another reads it made the reader see an empty file.
    dir_ = fs::path(SHADOWPORT_TEST_OUTPUT_DIR) / "malformed-gltf" / ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::create_directories(dir_);
    // A valid one-triangle file to break in different ways.
    float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    uint16_t idx[3] = {0, 1, 2};
    std::ofstream bin(dir_ / "tri.bin", std::ios::binary);
    bin.write(reinterpret_cast<const char*>(pos), sizeof pos);
    bin.write(reinterpret_cast<const char*>(idx), sizeof idx);
    base_ = json::parse(R"({
      "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
      "meshes": [{"name": "tri", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
      "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]},
        {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
      "buffers": [{"uri": "tri.bin", "byteLength": 42}]})");
  }

  std::string LoadError(const json& j, const std::string& name) {
    fs::path p = dir_ / (name + ".gltf");
    std::ofstream(p) << j.dump();
    try {
      scene::LoadGltf(p);
    } catch (const std::exception& e) {
      return e.what();
    }
    return "";
  }

  fs::path dir_;
  json base_;
};

TEST_F(MalformedGltf, ValidBaseLoads) {
  std::ofstream(dir_ / "ok.gltf") << base_.dump();
  scene::Scene s = scene::LoadGltf(dir_ / "ok.gltf");
  ASSERT_EQ(s.triangleCount(), 1u);
  EXPECT_NEAR(s.meshes[0].vertices[0].normal.z, 1.0f, 1e-6f);  // generated: counter-clockwise faces +z
}

TEST_F(MalformedGltf, ErrorsNameFileAndElement) {
  json j = base_;
  j["accessors"][0]["count"] = 4;  // reads past its bufferView
  std::string e = LoadError(j, "past-view");
  EXPECT_NE(e.find("past-view.gltf"), std::string::npos) << e;
  EXPECT_NE(e.find("accessor 0"), std::string::npos) << e;

  j = base_;
  j["meshes"][0]["primitives"][0]["indices"] = 7;
  e = LoadError(j, "bad-accessor");
  EXPECT_FALSE(e.empty());
  EXPECT_NE(e.find("bad-accessor.gltf"), std::string::npos) << e;

  j = base_;
  j["bufferViews"][1]["byteLength"] = 600;  // beyond the 42-byte buffer
  e = LoadError(j, "past-buffer");
  EXPECT_FALSE(e.empty());

  j = base_;
  j["nodes"][0]["mesh"] = 3;
  e = LoadError(j, "bad-mesh");
  EXPECT_NE(e.find("mesh 3"), std::string::npos) << e;

  j = base_;
  j["accessors"][0]["type"] = "VEC2";
  e = LoadError(j, "wrong-type");
  EXPECT_NE(e.find("wrong type"), std::string::npos) << e;

  j = base_;
  j["buffers"][0]["uri"] = "missing.bin";
  e = LoadError(j, "missing-bin");
  EXPECT_FALSE(e.empty());

  std::ofstream(dir_ / "not-json.gltf") << "{ this is not json";
  try {
    scene::LoadGltf(dir_ / "not-json.gltf");
    ADD_FAILURE() << "expected an error";
  } catch (const std::exception& ex) {
    EXPECT_NE(std::string(ex.what()).find("not-json.gltf"), std::string::npos) << ex.what();
  }
  EXPECT_THROW(scene::LoadGltf(dir_ / "does-not-exist.gltf"), std::runtime_error);
}

// A file may claim any count; the loader must check it against the bytes that exist before it
// allocates for it (2^40 vertices would be 32 TiB of positions).
TEST_F(MalformedGltf, HugeCountsAreErrorsNotAllocations) {
  for (int accessor : {0, 1}) {  // the positions, then the indices
    json j = base_;
    j["accessors"][accessor]["count"] = 1099511627776ull;
    std::string name = "huge-count-" + std::to_string(accessor);
    std::string e = LoadError(j, name);
    EXPECT_NE(e.find(name + ".gltf"), std::string::npos) << e;
    EXPECT_NE(e.find("accessor " + std::to_string(accessor)), std::string::npos) << e;
  }
  json j = base_;
  j["bufferViews"][0]["byteOffset"] = 18446744073709551000ull;  // offset + length wraps around
  std::string e = LoadError(j, "wrapping-offset");
  EXPECT_NE(e.find("wrapping-offset.gltf"), std::string::npos) << e;
}

TEST_F(MalformedGltf, OutOfRangeIndexIsAnError) {
  std::ofstream bin(dir_ / "tri.bin", std::ios::binary | std::ios::in | std::ios::out);
  bin.seekp(36 + 4);
  uint16_t bad = 9;
  bin.write(reinterpret_cast<const char*>(&bad), 2);
  bin.close();
  std::string e = LoadError(base_, "bad-index");
  EXPECT_NE(e.find("index 9"), std::string::npos) << e;
}


// KHR_lights_punctual: a point light and a spot light on nodes with transforms, a directional one.
class GltfLights : public MalformedGltf {
 protected:
  json WithLights(const json& lights) {
    json j = base_;
    j["extensionsUsed"] = {"KHR_lights_punctual"};
    j["extensions"]["KHR_lights_punctual"]["lights"] = lights;
    j["scenes"][0]["nodes"] = {0, 1, 2, 3};
    // Node 1: translated to (1, 2, 3). Node 2: at (0, 4, 0), rotated -90 degrees about x, so its -z
    // points down (-y). Node 3: rotated +90 degrees about y, so its -z points along -x.
    const double h = std::sqrt(0.5);
    j["nodes"].push_back({{"translation", {1, 2, 3}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    j["nodes"].push_back({{"translation", {0, 4, 0}}, {"rotation", {-h, 0, 0, h}}, {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
    j["nodes"].push_back({{"rotation", {0, h, 0, h}}, {"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}});
    return j;
  }
  json GoodLights() {
    return json::parse(R"([
      {"type": "point", "color": [1, 0.5, 0.25], "intensity": 4, "range": 7, "extras": {"radius": 0.25}},
      {"type": "spot", "name": "lamp", "intensity": 2, "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.6}},
      {"type": "directional", "intensity": 3, "extras": {"angularDiameterDegrees": 0.53}}])");
  }
};

TEST_F(GltfLights, PointSpotAndDirectionalLightsLoad) {
  std::ofstream(dir_ / "lights.gltf") << WithLights(GoodLights()).dump();
  scene::Scene s = scene::LoadGltf(dir_ / "lights.gltf");
  ASSERT_EQ(s.pointLights.size(), 1u);
  ASSERT_EQ(s.spotLights.size(), 1u);
  const scene::PointLight& p = s.pointLights[0];
  EXPECT_EQ(p.position, glm::vec3(1, 2, 3));
  EXPECT_EQ(p.color, glm::vec3(4, 2, 1));
  EXPECT_EQ(p.range, 7.0f);
  const scene::SpotLight& sp = s.spotLights[0];
  EXPECT_NEAR(glm::distance(sp.position, glm::vec3(0, 4, 0)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::distance(sp.direction, glm::vec3(0, -1, 0)), 0.0f, 1e-5f);
  EXPECT_EQ(sp.color, glm::vec3(2));
  EXPECT_FLOAT_EQ(sp.innerConeAngle, 0.2f);
  EXPECT_FLOAT_EQ(sp.outerConeAngle, 0.6f);
  // No range given: the distance to the farthest corner of the scene's bounds (the triangle spans
  // (0,0,0)-(1,1,0); from (0,4,0) the farthest corner is (1,0,0)).
  EXPECT_NEAR(sp.range, std::sqrt(17.0f), 1e-5f);
  EXPECT_NEAR(glm::distance(glm::normalize(s.light.direction), glm::vec3(-1, 0, 0)), 0.0f, 1e-5f);
  // Sizes for soft shadows from the lights' extras; none given: 0 (hard).
  EXPECT_EQ(p.radius, 0.25f);
  EXPECT_EQ(sp.radius, 0.0f);
  EXPECT_EQ(s.light.angularDiameterDegrees, 0.53f);
}

TEST_F(GltfLights, BadLightDataIsAnErrorNamingFileAndLight) {
  struct Case {
    const char* name;
    std::function<void(json&)> edit;
    const char* expect;
  };
  const Case cases[] = {
      {"negative-range", [](json& l) { l[0]["range"] = -1; }, "range"},
      {"negative-intensity", [](json& l) { l[0]["intensity"] = -2; }, "intensity"},
      {"short-color", [](json& l) { l[0]["color"] = {1, 1}; }, "color"},
      {"negative-color", [](json& l) { l[0]["color"] = {1, -1, 1}; }, "color"},
      {"outer-too-wide", [](json& l) { l[1]["spot"]["outerConeAngle"] = 1.7; }, "cone"},
      {"inner-past-outer", [](json& l) { l[1]["spot"]["innerConeAngle"] = 0.7; }, "cone"},
      {"negative-inner", [](json& l) { l[1]["spot"]["innerConeAngle"] = -0.1; }, "cone"},
      {"unknown-type", [](json& l) { l[0]["type"] = "area"; }, "type"},
      {"negative-radius", [](json& l) { l[0]["extras"]["radius"] = -0.5; }, "extras.radius"},
      {"text-radius", [](json& l) { l[1]["extras"]["radius"] = "big"; }, "extras.radius (not a number)"},
      {"sun-too-wide", [](json& l) { l[2]["extras"]["angularDiameterDegrees"] = 180; }, "extras.angularDiameterDegrees"},
  };
  for (const Case& c : cases) {
    json lights = GoodLights();
    c.edit(lights);
    std::string e = LoadError(WithLights(lights), c.name);
    EXPECT_NE(e.find(std::string(c.name) + ".gltf"), std::string::npos) << c.name << ": " << e;
    EXPECT_NE(e.find(c.expect), std::string::npos) << c.name << ": " << e;
    EXPECT_NE(e.find("light "), std::string::npos) << c.name << ": " << e;
  }
  json j = WithLights(GoodLights());
  j["nodes"][1]["extensions"]["KHR_lights_punctual"]["light"] = 5;
  std::string e = LoadError(j, "missing-light");
  EXPECT_NE(e.find("light 5"), std::string::npos) << e;
  EXPECT_NE(e.find("missing-light.gltf"), std::string::npos) << e;
}

}  // namespace
}  // namespace sp::test
