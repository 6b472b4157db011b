// glTF loading: the real scenes beside the project load with the documented triangle counts and
// bounds, and malformed files give an error naming the file and the problem, never a crash.
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

TEST_F(MalformedGltf, OutOfRangeIndexIsAnError) {
  std::ofstream bin(dir_ / "tri.bin", std::ios::binary | std::ios::in | std::ios::out);
  bin.seekp(36 + 4);
  uint16_t bad = 9;
  bin.write(reinterpret_cast<const char*>(&bad), 2);
  bin.close();
  std::string e = LoadError(base_, "bad-index");
  EXPECT_NE(e.find("index 9"), std::string::npos) << e;
}

}  // namespace
}  // namespace sp::test
