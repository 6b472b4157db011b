// Camera paths as JSON files (SaveCameraPath / LoadCameraPath) and the viewer's recorder. The
// format is in docs/viewer-ui.md; a file written by an older or newer build is still read as long
// as the fields below are there, since unknown fields are ignored.
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include <sp/scene/scene.h>

namespace sp::scene {

namespace {

using nlohmann::json;

constexpr const char* kFormat = "shadowport-camera-path";

json Vec(const glm::vec3& v) { return json::array({v.x, v.y, v.z}); }

// Every error names the file and where in it, so a hand-edited or truncated recording is fixed
// without guessing.
struct Reader {
  std::string file;

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw std::runtime_error(file + ": " + where + (where.empty() ? "" : ": ") + what);
  }
  const json& field(const json& obj, const char* name, const std::string& where) const {
    if (!obj.is_object()) fail(where, "expected an object");
    auto it = obj.find(name);
    if (it == obj.end()) fail(where, std::string("'") + name + "' is missing");
    return *it;
  }
  // null is what a NaN or an infinity becomes when written by nlohmann-json (and most writers).
  float number(const json& v, const std::string& where) const {
    if (!v.is_number()) fail(where, "must be a finite number (got " + v.dump() + ")");
    double d = v.get<double>();
    if (!std::isfinite(d) || std::fabs(d) > 3.0e38) fail(where, "must be a finite number (got " + v.dump() + ")");
    return float(d);
  }
  glm::vec3 vec3(const json& v, const std::string& where) const {
    if (!v.is_array() || v.size() != 3) fail(where, "must be an array of 3 numbers (got " + v.dump() + ")");
    return {number(v[0], where + "[0]"), number(v[1], where + "[1]"), number(v[2], where + "[2]")};
  }
  glm::vec3 direction(const json& v, const std::string& where) const {
    glm::vec3 d = vec3(v, where);
    float length = glm::length(d);
    if (!(length > 1e-6f)) fail(where, "must not be zero");
    // A vector already of unit length (as saved) is kept bit for bit: normalising it again can
    // move its last bits, and a replayed path should be the recorded one exactly.
    return std::fabs(length - 1.0f) < 1e-6f ? d : d / length;
  }
};

}  // namespace

void SaveCameraPath(const CameraPath& path, const std::filesystem::path& file) {
  json keys = json::array();
  for (const CameraKey& k : path.keys) {
    json j = {{"t", k.time}, {"position", Vec(k.position)}, {"target", Vec(k.target)}};
    if (k.lightDirection) j["light_direction"] = Vec(*k.lightDirection);
    keys.push_back(std::move(j));
  }
  json doc = {{"format", kFormat},
              {"version", 1},
              {"name", path.name},
              {"lens", {{"fov_y_degrees", glm::degrees(path.lens.fovY)}, {"near", path.lens.nearZ}, {"far", path.lens.farZ}, {"up", Vec(path.lens.up)}}},
              {"keys", std::move(keys)}};
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  std::ofstream out(file);
  if (!out) throw std::runtime_error(file.string() + ": cannot write the camera path");
  out << doc.dump(1) << "\n";
  if (!out) throw std::runtime_error(file.string() + ": writing the camera path failed");
}

CameraPath LoadCameraPath(const std::filesystem::path& file) {
  Reader r{file.string()};
  std::ifstream in(file);
  if (!in) r.fail("", "cannot open the camera path file");
  json doc;
  try {
    doc = json::parse(in);
  } catch (const json::parse_error& e) {
    r.fail("", std::string("not valid JSON (") + e.what() + ")");
  }
  if (!doc.is_object()) r.fail("", "expected a JSON object with 'lens' and 'keys'");
  if (auto f = doc.find("format"); f != doc.end() && *f != kFormat) r.fail("format", "expected \"" + std::string(kFormat) + "\" (got " + f->dump() + ")");

  CameraPath path;
  path.name = file.string();
  const json& lens = r.field(doc, "lens", "");
  path.lens.fovY = glm::radians(r.number(r.field(lens, "fov_y_degrees", "lens"), "lens.fov_y_degrees"));
  path.lens.nearZ = r.number(r.field(lens, "near", "lens"), "lens.near");
  path.lens.farZ = r.number(r.field(lens, "far", "lens"), "lens.far");
  path.lens.up = r.direction(r.field(lens, "up", "lens"), "lens.up");
  if (!(path.lens.fovY > 0.0f && path.lens.fovY < glm::radians(180.0f))) r.fail("lens.fov_y_degrees", "must be in (0, 180)");
  if (!(path.lens.nearZ > 0.0f)) r.fail("lens.near", "must be above 0");
  if (!(path.lens.farZ > path.lens.nearZ)) r.fail("lens.far", "must be above lens.near");

  const json& keys = r.field(doc, "keys", "");
  if (!keys.is_array()) r.fail("keys", "must be an array");
  if (keys.size() < 2) r.fail("keys", "a path needs at least 2 keys (got " + std::to_string(keys.size()) + ")");
  // Keys give either `t` (on [0, 1]) or `time` (seconds, as recorded); one kind per file, so a
  // mixed file is a mistake rather than two clocks silently merged.
  const char* clock = keys[0].is_object() && keys[0].contains("time") && !keys[0].contains("t") ? "time" : "t";
  std::vector<double> times;
  for (size_t i = 0; i < keys.size(); ++i) {
    std::string at = "keys[" + std::to_string(i) + "]";
    const json& k = keys[i];
    CameraKey key;
    const json* tv = nullptr;
    if (k.is_object() && k.contains(clock)) tv = &k[clock];
    if (!tv) r.fail(at, std::string("'") + clock + "' is missing" + (i ? std::string(" (keys[0] gives '") + clock + "')" : " (each key needs 't' or 'time')"));
    double t = r.number(*tv, at + "." + clock);
    if (i > 0 && !(t > times.back()))
      r.fail(at + "." + clock, "times must increase (" + std::to_string(t) + " after " + std::to_string(times.back()) + ")");
    times.push_back(t);
    key.position = r.vec3(r.field(k, "position", at), at + ".position");
    key.target = r.vec3(r.field(k, "target", at), at + ".target");
    if (glm::length(key.target - key.position) < 1e-6f) r.fail(at, "target equals position (no view direction)");
    if (auto l = k.find("light_direction"); l != k.end()) key.lightDirection = r.direction(*l, at + ".light_direction");
    if (i > 0 && key.lightDirection.has_value() != path.keys[0].lightDirection.has_value())
      r.fail(at, "'light_direction' must be given on every key or on none");
    path.keys.push_back(key);
  }
  if (std::string(clock) == "t") {
    if (times.front() != 0.0 || times.back() != 1.0)
      r.fail("keys", "'t' runs from 0 at the first key to 1 at the last (got " + std::to_string(times.front()) + " .. " +
                         std::to_string(times.back()) + "); give 'time' in seconds instead to have it mapped");
  }
  for (size_t i = 0; i < times.size(); ++i) path.keys[i].time = float((times[i] - times.front()) / (times.back() - times.front()));
  return path;
}

bool IsCameraPathFile(const std::string& nameOrFile) {
  std::error_code ec;
  return std::filesystem::path(nameOrFile).extension() == ".json" || std::filesystem::is_regular_file(nameOrFile, ec);
}

const CameraPath& Scene::cameraPathOrFile(const std::string& nameOrFile) {
  if (!IsCameraPathFile(nameOrFile)) return cameraPath(nameOrFile);
  CameraPath loaded = LoadCameraPath(nameOrFile);
  for (CameraPath& p : cameraPaths)
    if (p.name == loaded.name) return p = std::move(loaded);
  cameraPaths.push_back(std::move(loaded));
  return cameraPaths.back();
}

bool Scene::useRecordedLight(const CameraPath& path) {
  if (path.keys.empty() || !path.keys[0].lightDirection) return true;
  light.direction = *path.keys[0].lightDirection;
  for (const CameraKey& k : path.keys)
    if (!k.lightDirection || glm::dot(*k.lightDirection, light.direction) < 0.99999f) return false;
  return true;
}

void CameraPathRecorder::add(double seconds, const Camera& camera, const std::optional<glm::vec3>& lightDirection) {
  if (!seconds_.empty() && !(seconds > seconds_.back())) return;
  if (seconds_.empty()) lens_ = camera;
  CameraKey k;
  k.position = camera.position;
  k.target = camera.target;
  if (lightDirection) k.lightDirection = glm::normalize(*lightDirection);
  seconds_.push_back(seconds);
  keys_.push_back(k);
}

void CameraPathRecorder::clear() {
  seconds_.clear();
  keys_.clear();
}

CameraPath CameraPathRecorder::path(const std::string& name) const {
  if (keys_.size() < 2)
    throw std::runtime_error("camera path '" + name + "': recorded " + std::to_string(keys_.size()) + " frame(s); a path needs at least 2");
  CameraPath p;
  p.name = name;
  p.lens = lens_;
  p.keys = keys_;
  double span = seconds_.back() - seconds_.front();
  for (size_t i = 0; i < keys_.size(); ++i) p.keys[i].time = float((seconds_[i] - seconds_.front()) / span);
  // Float rounding must not move the ends, which CameraPath::at clamps to.
  p.keys.front().time = 0.0f;
  p.keys.back().time = 1.0f;
  return p;
}

}  // namespace sp::scene
