// Camera paths: cubic Hermite interpolation with Catmull-Rom tangents over non-uniform key times,
// evaluated in double so slow paths far from the origin still move smoothly.
#include <algorithm>
#include <cmath>
#include <glm/ext/matrix_transform.hpp>
#include <stdexcept>

#include <sp/scene/scene.h>

namespace sp::scene {

namespace {

using dvec3 = glm::dvec3;

// Finite-difference tangent at key i (per unit of t); one-sided at the ends, which makes a
// two-key path a straight line travelled at constant speed.
dvec3 Tangent(const std::vector<CameraKey>& k, size_t i, dvec3 (*get)(const CameraKey&)) {
  size_t a = i == 0 ? 0 : i - 1, b = i + 1 == k.size() ? i : i + 1;
  double dt = double(k[b].time) - double(k[a].time);
  return dt > 0.0 ? (get(k[b]) - get(k[a])) / dt : dvec3(0.0);
}

dvec3 Position(const CameraKey& k) { return dvec3(k.position); }
dvec3 Target(const CameraKey& k) { return dvec3(k.target); }

}  // namespace

Camera CameraPath::at(double t) const {
  Camera c = lens;
  if (keys.empty()) return c;
  t = std::clamp(t, double(keys.front().time), double(keys.back().time));
  size_t i = 0;
  while (i + 2 < keys.size() && t > double(keys[i + 1].time)) ++i;
  if (keys.size() == 1 || t <= double(keys.front().time)) {
    c.position = keys.front().position;
    c.target = keys.front().target;
    return c;
  }
  if (t >= double(keys.back().time)) {
    c.position = keys.back().position;
    c.target = keys.back().target;
    return c;
  }
  double h = double(keys[i + 1].time) - double(keys[i].time);
  double s = h > 0.0 ? (t - double(keys[i].time)) / h : 1.0;
  double s2 = s * s, s3 = s2 * s;
  double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
  auto eval = [&](dvec3 (*get)(const CameraKey&)) {
    return h00 * get(keys[i]) + h10 * h * Tangent(keys, i, get) + h01 * get(keys[i + 1]) + h11 * h * Tangent(keys, i + 1, get);
  };
  c.position = glm::vec3(eval(Position));
  c.target = glm::vec3(eval(Target));
  return c;
}

std::optional<glm::vec3> CameraPath::lightAt(double t) const {
  if (keys.empty() || !keys.front().lightDirection) return std::nullopt;
  size_t i = 1;
  while (i + 1 < keys.size() && double(keys[i].time) < t) ++i;
  if (keys.size() == 1) return keys.front().lightDirection;
  float f = std::clamp(float((t - keys[i - 1].time) / std::max(1e-6f, keys[i].time - keys[i - 1].time)), 0.0f, 1.0f);
  return glm::normalize(glm::mix(*keys[i - 1].lightDirection, *keys[i].lightDirection, f));
}

const CameraPath& Scene::cameraPath(const std::string& pathName) const {
  for (const CameraPath& p : cameraPaths)
    if (p.name == pathName) return p;
  std::string list;
  for (const CameraPath& p : cameraPaths) list += (list.empty() ? "" : ", ") + p.name;
  throw std::invalid_argument("scene '" + name + "' has no camera path '" + pathName + "' (paths: " + (list.empty() ? "none" : list) + ")");
}

std::vector<CameraPath> StandardCameraPaths(const Camera& camera, const Bounds& bounds) {
  glm::vec3 forward = camera.forward();
  glm::vec3 right = glm::cross(forward, camera.up);
  right = glm::length(right) > 1e-6f ? glm::normalize(right) : glm::vec3(1, 0, 0);
  std::vector<CameraPath> paths;

  // 1/8 texel per 1/60 of the path, for a 2048^2 map over the bounding sphere's diameter.
  double diameter = bounds.empty() ? 1.0 : double(glm::length(bounds.extent()));
  float pan = float(60.0 * (diameter / 2048.0) / 8.0);
  CameraPath p;
  p.name = "slow-pan";
  p.lens = camera;
  p.keys = {{0.0f, camera.position, camera.target}, {1.0f, camera.position + right * pan, camera.target + right * pan}};
  paths.push_back(p);

  p.name = "rotate";
  p.keys.clear();
  const float yawDegrees = 20.0f;
  const int steps = 17;  // a key every 1.25 degrees keeps the spline within 3e-5 of the circle's radius
  glm::vec3 look = camera.target - camera.position;
  for (int i = 0; i < steps; ++i) {
    float t = float(i) / float(steps - 1);
    glm::mat4 r = glm::rotate(glm::mat4(1.0f), glm::radians(yawDegrees * t), camera.up);
    p.keys.push_back({t, camera.position, camera.position + glm::vec3(r * glm::vec4(look, 0.0f))});
  }
  paths.push_back(p);

  p.name = "dolly";
  glm::vec3 move = forward * (0.2f * glm::length(look));
  p.keys = {{0.0f, camera.position, camera.target}, {1.0f, camera.position + move, camera.target + move}};
  paths.push_back(p);
  return paths;
}

std::vector<CameraPath> CameraPathsFor(const Scene& scene) {
  return scene.cameraPaths.empty() ? StandardCameraPaths(scene.camera, scene.bounds) : scene.cameraPaths;
}

}  // namespace sp::scene
