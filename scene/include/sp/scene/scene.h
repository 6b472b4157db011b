// The scene model shared by the renderer, the techniques and (later) the reference ray tracer:
// meshes with positions and normals, instances with transforms and world bounds, a camera and a
// light. Right-handed, +y up, as glTF; clip-space depth in [0, 1] as D3D.
#pragma once
#include <filesystem>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

namespace sp::scene {

struct Bounds {
  glm::vec3 min{1e30f};
  glm::vec3 max{-1e30f};

  bool empty() const { return min.x > max.x; }
  bool contains(const glm::vec3& p) const { return glm::all(glm::greaterThanEqual(p, min)) && glm::all(glm::lessThanEqual(p, max)); }
  void extend(const glm::vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  void extend(const Bounds& b) {
    if (!b.empty()) extend(b.min), extend(b.max);
  }
  glm::vec3 center() const { return (min + max) * 0.5f; }
  glm::vec3 extent() const { return max - min; }
  Bounds transformed(const glm::mat4& m) const;  // bounds of the 8 transformed corners
  void corners(glm::vec3 out[8]) const;
};

struct Vertex {
  glm::vec3 position;
  glm::vec3 normal;
};
static_assert(sizeof(Vertex) == 24, "Vertex is uploaded as is");

struct Mesh {
  std::string name;
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;  // triangle list
  Bounds bounds;                  // object space

  size_t triangleCount() const { return indices.size() / 3; }
  void computeBounds();
};

struct Instance {
  uint32_t mesh = 0;
  glm::mat4 transform{1.0f};
  glm::vec3 albedo{0.7f};
  Bounds worldBounds;  // filled by Scene::finalize()
};

struct Camera {
  glm::vec3 position{0, 5, 10};
  glm::vec3 target{0, 0, 0};
  glm::vec3 up{0, 1, 0};
  float fovY = glm::radians(60.0f);
  float nearZ = 0.1f;
  float farZ = 200.0f;

  glm::mat4 view() const;
  glm::mat4 projection(float aspect) const;  // right-handed, depth 0..1
  glm::vec3 forward() const { return glm::normalize(target - position); }
};

struct DirectionalLight {
  glm::vec3 direction{-0.4f, -1.0f, -0.3f};  // the way the light travels
  glm::vec3 color{1.0f, 0.96f, 0.9f};
  float ambient = 0.18f;
  // The light's source as a disc of this angular diameter around `direction`, in degrees (the
  // sun: 0.53); 0 = an ideal directional light with hard shadows. Soft-shadow techniques and the
  // lab's ray-traced reference read it, so both judge the same penumbra.
  float angularDiameterDegrees = 0.0f;

  glm::vec3 towardsLight() const { return -glm::normalize(direction); }
};

// Local lights. The renderer's lit pass shades every point and spot light of the scene beside the
// directional light, with glTF's recommended (KHR_lights_punctual) falloff: intensity
//   color * clamp(1 - (d / range)^4, 0, 1) / d^2
// at distance d, times N.L, and for spot lights the cone factor
//   t = clamp((cos(angle to axis) - cos(outer)) / max(1e-3, cos(inner) - cos(outer)), 0, 1), t^2.
// They are unshadowed unless a local-light technique (e.g. "cube") shadows them. Scenes whose point
// is local lights (the "point-light-room") make their directional light dim.
//
// An omni light for point-light shadow techniques (cube or dual-paraboloid maps).
struct PointLight {
  glm::vec3 position{0.0f};
  glm::vec3 color{1.0f};  // linear intensity at the light, before attenuation
  float range = 10.0f;    // distance where the light's contribution reaches zero: the shadow far plane
  float radius = 0.0f;    // the emitter as a sphere of this radius (world units), 0 = a point: hard shadows
};

// A spot light: a point light limited to a cone about `direction`.
struct SpotLight {
  glm::vec3 position{0.0f};
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  // the cone's axis, the way the light travels
  glm::vec3 color{1.0f};                   // linear intensity on the axis, before attenuation
  float range = 10.0f;                     // as PointLight::range
  float innerConeAngle = 0.0f;             // radians from the axis: full intensity inside
  float outerConeAngle = 0.7853982f;       // radians, in (innerConeAngle, pi/2]: no light outside
  float radius = 0.0f;                     // as PointLight::radius
};

// A camera position and look-at point at one time of a path.
struct CameraKey {
  float time = 0.0f;  // in [0, 1], increasing along the path; the first is 0 and the last 1
  glm::vec3 position{0.0f};
  glm::vec3 target{0.0f, 0.0f, -1.0f};
  // The directional light's direction at this key (DirectionalLight::direction, unit length), when
  // the path was recorded with one (a viewer that turns the sun); nothing for the built-in paths.
  std::optional<glm::vec3> lightDirection;
};

// A deterministic camera motion parameterised by t in [0, 1], for temporal measurements: position
// and target follow Catmull-Rom splines through the keys (C1, passing through every key, straight
// lines for two keys), so sampling at any frame rate gives continuous motion.
struct CameraPath {
  std::string name;
  Camera lens;  // fovY, nearZ, farZ and up of every frame; its position and target are unused
  std::vector<CameraKey> keys;

  Camera at(double t) const;  // t is clamped to [0, 1]
  // The light's direction at t when the keys carry one (interpolated linearly between keys and
  // normalised), else nothing: a recorded sun turn replays in the viewer and the bench alike.
  std::optional<glm::vec3> lightAt(double t) const;
};

// Camera paths as JSON files, so a path flown in the viewer becomes a lab run (`shadowport bench
// --path recorded.json`; docs/viewer-ui.md gives the format). Save writes every key with its `t`;
// Load also takes keys timed in seconds (`time`, mapped onto [0, 1]) and throws
// std::runtime_error naming the file and the offending key or field for malformed input (a missing
// field, a value that is not a finite number, fewer than 2 keys, times that do not increase, light
// directions on some keys only). A loaded path is named after the file as given.
void SaveCameraPath(const CameraPath& path, const std::filesystem::path& file);
CameraPath LoadCameraPath(const std::filesystem::path& file);
// Whether a --path value names a file rather than one of a scene's paths: it ends in .json or is
// an existing file.
bool IsCameraPathFile(const std::string& nameOrFile);

// Records a path from the frames a viewer draws: add() once per frame with the time in seconds;
// a frame whose time does not advance (a paused clock) adds nothing. The lens (fovY, near, far, up)
// is the first frame's.
class CameraPathRecorder {
 public:
  void add(double seconds, const Camera& camera, const std::optional<glm::vec3>& lightDirection = std::nullopt);
  size_t size() const { return seconds_.size(); }
  double durationSeconds() const { return seconds_.empty() ? 0.0 : seconds_.back() - seconds_.front(); }
  void clear();
  // The keys so far, times mapped onto [0, 1]; throws std::runtime_error with fewer than 2.
  CameraPath path(const std::string& name = "recorded") const;
  void save(const std::filesystem::path& file) const { SaveCameraPath(path(file.stem().string()), file); }

 private:
  Camera lens_;
  std::vector<double> seconds_;
  std::vector<CameraKey> keys_;
};

// A named part of the world that the lab also judges on its own (bench results' "regions"): the
// union of axis-aligned world boxes, built by a procedural scene from its own geometry where a
// technique's known failure is confined to a small area that the whole frame's metrics average
// away (stacked-planks' crossing).
struct Region {
  std::string name;
  std::vector<Bounds> boxes;
  bool contains(const glm::vec3& p) const {
    for (const Bounds& b : boxes)
      if (b.contains(p)) return true;
    return false;
  }
};

struct Scene {
  std::string name;
  std::vector<Mesh> meshes;
  std::vector<Instance> instances;
  Camera camera;
  DirectionalLight light;
  std::vector<PointLight> pointLights;  // empty unless the scene is about omni shadows
  std::vector<SpotLight> spotLights;    // empty unless the scene has spot lights
  // Every built-in scene has "slow-pan", "rotate" and "dolly" (see StandardCameraPaths), starting
  // at `camera`, plus paths of its own; LoadScene gives glTF scenes the three standard ones.
  std::vector<CameraPath> cameraPaths;
  Bounds bounds;  // world space, filled by finalize()
  std::vector<Region> regions;  // empty for most scenes

  uint32_t addMesh(Mesh mesh);
  void addInstance(uint32_t mesh, const glm::mat4& transform, const glm::vec3& albedo);
  // Computes mesh and world bounds; call after building.
  void finalize();
  size_t triangleCount() const;
  // Throws std::invalid_argument listing the scene's paths for an unknown name.
  const CameraPath& cameraPath(const std::string& name) const;
  // As cameraPath, but a name that IsCameraPathFile is loaded (LoadCameraPath) and added to the
  // scene's paths under that name first (replacing one loaded before).
  const CameraPath& cameraPathOrFile(const std::string& nameOrFile);
  // A lab run has one light (the reference is traced for it): a path recorded with the light's
  // direction sets `light` to its first key's. Returns false when the recorded light turns along
  // the path, which the caller reports (only the camera's motion is replayed then).
  bool useRecordedLight(const CameraPath& path);
};

struct SceneOptions {
  // Instanced triangles wanted (Scene::triangleCount()); 0 = the scene's natural size. Built-in
  // scenes land within +-30% of targets from 1e4 to 2.5e6 (more instances and finer tessellation;
  // meshes are shared between instances, so memory grows much more slowly than the count).
  uint64_t targetTriangles = 0;
};

// Built-in procedural scenes, deterministic. Throws std::invalid_argument listing the names for
// unknown ones, and for targets above kMaxTargetTriangles.
Scene MakeBuiltinScene(const std::string& name);
Scene MakeBuiltinScene(const std::string& name, const SceneOptions& options);
std::vector<std::string> BuiltinSceneNames();
constexpr uint64_t kMaxTargetTriangles = 50'000'000;

// "slow-pan": a sideways move of 1/8 of a shadow texel per 1/60 of the path, the texel being that
// of a 2048^2 map fitted to the scene's bounding sphere (what the basic technique renders), so the
// lab's temporal metric sees shadow instability rather than camera motion; "rotate": a 20 degree
// yaw to the left about the camera position; "dolly": forward along the view by a fifth of the
// distance to the target. All start at `camera` and keep its lens.
std::vector<CameraPath> StandardCameraPaths(const Camera& camera, const Bounds& bounds);
// The scene's own paths, or the standard ones where it has none.
std::vector<CameraPath> CameraPathsFor(const Scene& scene);

// A glTF 2.0 file (.gltf + .bin or .glb). Throws std::runtime_error naming the file and the
// offending element for anything malformed. KHR_lights_punctual lights attached to nodes become
// Scene::pointLights and Scene::spotLights (color = color * intensity; position and direction
// (the node's -z) from the node's world transform; a light without range gets the distance from
// it to the farthest corner of the scene's bounds); the first directional light sets
// Scene::light's direction. Bad light data (negative or non-finite range or intensity, a colour
// that is not three non-negative numbers, spot cone angles outside 0 <= inner < outer <= pi/2,
// an unknown type, a node referring to a light that does not exist) is an error naming the light.
Scene LoadGltf(const std::filesystem::path& path);

// A built-in scene name, a scene of ../shared/scenes by folder name (ShadowColumns, TankScene,
// FlightHelmet), or a path to a .gltf/.glb file.
Scene LoadScene(const std::string& nameOrPath);
// As above; a non-zero options.targetTriangles is only valid for built-in scenes (the others have
// a fixed size) and throws std::invalid_argument for the rest.
Scene LoadScene(const std::string& nameOrPath, const SceneOptions& options);
std::filesystem::path SharedScenesDir();  // $SHADOWPORT_SCENES_DIR, else ../shared/scenes of the source tree
std::vector<std::string> SharedSceneNames();

// Primitive meshes (unit sized, centred at the origin unless stated).
Mesh MakeBox();                                        // [-0.5, 0.5]^3
Mesh MakeCylinder(uint32_t segments);                  // radius 0.5, y in [0, 1]
Mesh MakePlane(uint32_t subdivisions);                 // xz in [-0.5, 0.5], y = 0, facing +y
Mesh MakeSphere(uint32_t segments, uint32_t rings);    // radius 0.5

}  // namespace sp::scene
