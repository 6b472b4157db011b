// Finding scenes by name: built-in procedural scenes, the real scenes beside the project, files.
#include <cstdlib>
#include <stdexcept>

#include <sp/scene/scene.h>

namespace sp::scene {

namespace {

struct SharedScene {
  const char* name;
  const char* file;  // relative to SharedScenesDir()
  // Viewpoint chosen for shadow work: the long axis of ShadowColumns seen from its end, as the
  // DirectX SDK's cascaded-shadow sample does.
  bool customView;
  glm::vec3 eye, target, lightDirection;
};

const SharedScene kShared[] = {
    {"ShadowColumns", "ShadowColumns/testscene.gltf", true, {100.0f, 12.0f, 8.0f}, {-120.0f, 0.0f, -6.0f}, {-0.45f, -0.6f, 0.66f}},
    {"TankScene", "TankScene/TankScene.gltf", false, {}, {}, {}},
    {"FlightHelmet", "FlightHelmet/FlightHelmet.gltf", false, {}, {}, {}},
};

}  // namespace

std::filesystem::path SharedScenesDir() {
  if (const char* e = std::getenv("SHADOWPORT_SCENES_DIR"); e && *e) return e;
  return std::filesystem::path(SHADOWPORT_SHARED_DIR) / "scenes";
}

std::vector<std::string> SharedSceneNames() {
  std::vector<std::string> v;
  for (const SharedScene& s : kShared) v.push_back(s.name);
  return v;
}

Scene LoadScene(const std::string& nameOrPath) { return LoadScene(nameOrPath, SceneOptions{}); }

Scene LoadScene(const std::string& nameOrPath, const SceneOptions& options) {
  for (const std::string& b : BuiltinSceneNames())
    if (b == nameOrPath) return MakeBuiltinScene(nameOrPath, options);
  if (options.targetTriangles)
    throw std::invalid_argument("scene '" + nameOrPath + "' has a fixed size: a triangle target applies to built-in scenes only");
  for (const SharedScene& sh : kShared) {
    if (nameOrPath != sh.name) continue;
    Scene s = LoadGltf(SharedScenesDir() / sh.file);
    s.name = sh.name;
    if (sh.customView) {
      s.camera.position = sh.eye;
      s.camera.target = sh.target;
      s.camera.nearZ = 0.5f;
      s.camera.farZ = 1200.0f;
      s.light.direction = glm::normalize(sh.lightDirection);
    }
    s.cameraPaths = StandardCameraPaths(s.camera, s.bounds);
    return s;
  }
  std::filesystem::path p(nameOrPath);
  if (p.extension() == ".gltf" || p.extension() == ".glb") {
    Scene s = LoadGltf(p);
    s.cameraPaths = StandardCameraPaths(s.camera, s.bounds);
    return s;
  }
  std::string names;
  for (const std::string& b : BuiltinSceneNames()) names += (names.empty() ? "" : ", ") + b;
  for (const SharedScene& sh : kShared) names += std::string(", ") + sh.name;
  throw std::invalid_argument("unknown scene '" + nameOrPath + "' (built-in and shared scenes: " + names + "; or a path to a .gltf/.glb file)");
}

}  // namespace sp::scene
