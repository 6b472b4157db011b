// glTF 2.0 (.gltf + .bin, .glb) into the scene model with tinygltf. Every accessor is
// bounds-checked here, so a malformed file gives an error naming the file and the element, never
// an out-of-range read.
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/ext/scalar_constants.hpp>
#include <glm/gtc/constants.hpp>
#include <limits>
#include <stdexcept>
#include <tiny_gltf.h>

#include <sp/scene/scene.h>

namespace sp::scene {
namespace {

class GltfError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Reader {
  const tinygltf::Model& model;
  std::string file;

  [[noreturn]] void fail(const std::string& what) const { throw GltfError(file + ": " + what); }

  // Raw bytes of accessor `index`: pointer to the first element, element stride and count.
  const uint8_t* access(int index, const std::string& what, int type, std::initializer_list<int> componentTypes, size_t* stride,
                        size_t* count) const {
    if (index < 0 || size_t(index) >= model.accessors.size()) fail(what + " refers to accessor " + std::to_string(index) + ", which does not exist");
    const tinygltf::Accessor& a = model.accessors[index];
    std::string name = what + " (accessor " + std::to_string(index) + ")";
    if (a.sparse.isSparse) fail(name + " is sparse, which is not supported");
    if (a.type != type) fail(name + " has the wrong type (" + std::to_string(a.type) + ")");
    bool typeOk = false;
    for (int c : componentTypes) typeOk |= a.componentType == c;
    if (!typeOk) fail(name + " has an unsupported component type " + std::to_string(a.componentType));
    if (a.bufferView < 0 || size_t(a.bufferView) >= model.bufferViews.size()) fail(name + " has no valid bufferView");
    const tinygltf::BufferView& v = model.bufferViews[a.bufferView];
    if (v.buffer < 0 || size_t(v.buffer) >= model.buffers.size()) fail(name + ": bufferView " + std::to_string(a.bufferView) + " has no valid buffer");
    const tinygltf::Buffer& b = model.buffers[v.buffer];
    size_t elemSize = size_t(tinygltf::GetComponentSizeInBytes(a.componentType)) * size_t(tinygltf::GetNumComponentsInType(a.type));
    size_t s = v.byteStride ? v.byteStride : elemSize;
    if (s < elemSize) fail(name + ": byteStride " + std::to_string(s) + " is smaller than an element");
    size_t start = v.byteOffset + a.byteOffset;
    size_t end = a.count ? start + s * (a.count - 1) + elemSize : start;
    if (v.byteOffset + v.byteLength > b.data.size()) fail("bufferView " + std::to_string(a.bufferView) + " reaches past the end of buffer " + std::to_string(v.buffer));
    if (end > v.byteOffset + v.byteLength) fail(name + " reads past the end of bufferView " + std::to_string(a.bufferView));
    *stride = s;
    *count = a.count;
    return b.data.data() + start;
  }

  std::vector<glm::vec3> vec3s(int index, const std::string& what) const {
    size_t stride, count;
    const uint8_t* p = access(index, what, TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT}, &stride, &count);
    std::vector<glm::vec3> out(count);
    for (size_t i = 0; i < count; ++i) {
      std::memcpy(&out[i], p + i * stride, sizeof(glm::vec3));
      if (!std::isfinite(out[i].x) || !std::isfinite(out[i].y) || !std::isfinite(out[i].z))
        fail(what + " (accessor " + std::to_string(index) + ") holds a non-finite value at element " + std::to_string(i));
    }
    return out;
  }

  std::vector<uint32_t> indices(int index, const std::string& what, size_t vertexCount) const {
    size_t stride, count;
    const uint8_t* p = access(index, what, TINYGLTF_TYPE_SCALAR,
                              {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
                              &stride, &count);
    int ct = model.accessors[index].componentType;
    std::vector<uint32_t> out(count);
    for (size_t i = 0; i < count; ++i) {
      const uint8_t* e = p + i * stride;
      uint32_t v = 0;
      if (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) v = *e;
      else if (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) { uint16_t s; std::memcpy(&s, e, 2); v = s; }
      else std::memcpy(&v, e, 4);
      if (v >= vertexCount) fail(what + " (accessor " + std::to_string(index) + "): index " + std::to_string(v) + " at element " + std::to_string(i) +
                                 " is out of range (" + std::to_string(vertexCount) + " vertices)");
      out[i] = v;
    }
    return out;
  }
};

glm::mat4 NodeTransform(const tinygltf::Node& n) {
  if (n.matrix.size() == 16) {
    glm::dmat4 m = glm::make_mat4(n.matrix.data());
    return glm::mat4(m);
  }
  glm::mat4 m(1.0f);
  if (n.translation.size() == 3) m = glm::translate(m, glm::vec3(n.translation[0], n.translation[1], n.translation[2]));
  if (n.rotation.size() == 4) m *= glm::mat4_cast(glm::quat(float(n.rotation[3]), float(n.rotation[0]), float(n.rotation[1]), float(n.rotation[2])));
  if (n.scale.size() == 3) m = glm::scale(m, glm::vec3(n.scale[0], n.scale[1], n.scale[2]));
  return m;
}

// Smooth normals for primitives without NORMAL: area-weighted face normals per vertex.
void ComputeNormals(Mesh& m) {
  for (Vertex& v : m.vertices) v.normal = glm::vec3(0);
  for (size_t i = 0; i + 2 < m.indices.size(); i += 3) {
    Vertex &a = m.vertices[m.indices[i]], &b = m.vertices[m.indices[i + 1]], &c = m.vertices[m.indices[i + 2]];
    glm::vec3 n = glm::cross(b.position - a.position, c.position - a.position);
    a.normal += n, b.normal += n, c.normal += n;
  }
  for (Vertex& v : m.vertices) v.normal = glm::length(v.normal) > 0 ? glm::normalize(v.normal) : glm::vec3(0, 1, 0);
}

// Triangle lists from strips and fans, keeping glTF's counter-clockwise front faces.
std::vector<uint32_t> ToTriangleList(int mode, const std::vector<uint32_t>& idx) {
  if (mode == TINYGLTF_MODE_TRIANGLES) return std::vector<uint32_t>(idx.begin(), idx.begin() + idx.size() / 3 * 3);
  std::vector<uint32_t> out;
  for (size_t i = 2; i < idx.size(); ++i) {
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      if (i % 2 == 0) out.insert(out.end(), {idx[i - 2], idx[i - 1], idx[i]});
      else out.insert(out.end(), {idx[i - 1], idx[i - 2], idx[i]});
    } else {
      out.insert(out.end(), {idx[0], idx[i - 1], idx[i]});
    }
  }
  return out;
}

// A KHR_lights_punctual light checked against the extension's rules; `what` names it in errors.
struct LightData {
  std::string type;
  glm::vec3 color{1.0f};  // times intensity
  float range = 0.0f;     // 0: none given
  float inner = 0.0f, outer = 0.0f;
  float size = 0.0f;  // extras: directional angularDiameterDegrees, point/spot radius; 0 = hard
};

LightData CheckLight(const Reader& r, const tinygltf::Light& l, const std::string& what) {
  LightData d;
  d.type = l.type;
  if (l.type != "point" && l.type != "spot" && l.type != "directional")
    r.fail(what + " has type '" + l.type + "' (KHR_lights_punctual has directional, point and spot)");
  if (!std::isfinite(l.intensity) || l.intensity < 0) r.fail(what + " has intensity " + std::to_string(l.intensity) + " (must be finite and >= 0)");
  // tinygltf reads an absent range as 0; the extension requires a given range to be > 0.
  if (!std::isfinite(l.range) || l.range < 0) r.fail(what + " has range " + std::to_string(l.range) + " (must be > 0)");
  if (!l.color.empty()) {
    if (l.color.size() != 3) r.fail(what + " has a color of " + std::to_string(l.color.size()) + " numbers (must be 3)");
    for (double c : l.color)
      if (!std::isfinite(c) || c < 0) r.fail(what + " has a color component " + std::to_string(c) + " (must be finite and >= 0)");
    d.color = glm::vec3(float(l.color[0]), float(l.color[1]), float(l.color[2]));
  }
  d.color *= float(l.intensity);
  d.range = float(l.range);
  if (l.type == "spot") {
    double in = l.spot.innerConeAngle, out = l.spot.outerConeAngle;
    if (!std::isfinite(in) || !std::isfinite(out) || in < 0 || in >= out || out > glm::half_pi<double>() + 1e-9)
      r.fail(what + " has spot cone angles inner " + std::to_string(in) + ", outer " + std::to_string(out) +
             " (must be 0 <= inner < outer <= pi/2)");
    d.inner = float(in);
    d.outer = float(out);
  }
  // The extension has punctual lights only; a light's size for soft shadows travels in its extras
  // (scene.h: DirectionalLight::angularDiameterDegrees, PointLight/SpotLight::radius, in world
  // units, the node's scale not applied).
  const char* sizeKey = l.type == "directional" ? "angularDiameterDegrees" : "radius";
  if (l.extras.IsObject() && l.extras.Has(sizeKey)) {
    const tinygltf::Value& v = l.extras.Get(sizeKey);
    double size = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
    double limit = l.type == "directional" ? 180.0 : std::numeric_limits<double>::infinity();
    if (!v.IsNumber() || !std::isfinite(size) || size < 0 || size >= limit)
      r.fail(what + " has extras." + sizeKey + " " + (v.IsNumber() ? std::to_string(size) : std::string("(not a number)")) +
             (l.type == "directional" ? " (must be degrees in [0, 180))" : " (must be finite and >= 0)"));
    d.size = float(size);
  }
  return d;
}

// The light index a node's KHR_lights_punctual extension names, or -1.
int NodeLight(const Reader& r, const tinygltf::Node& node, int nodeIndex) {
  auto ext = node.extensions.find("KHR_lights_punctual");
  if (ext == node.extensions.end()) return -1;
  const tinygltf::Value& v = ext->second;
  std::string what = "node " + std::to_string(nodeIndex) + " KHR_lights_punctual";
  if (!v.IsObject() || !v.Has("light") || !v.Get("light").IsNumber()) r.fail(what + " has no numeric 'light'");
  double index = v.Get("light").GetNumberAsDouble();
  if (index < 0 || index >= double(r.model.lights.size()) || index != std::floor(index))
    r.fail(what + " refers to light " + std::to_string(index) + ", which does not exist (" + std::to_string(r.model.lights.size()) + " lights)");
  return int(index);
}

}  // namespace

Scene LoadGltf(const std::filesystem::path& path) {
  std::string file = path.string();
  if (!std::filesystem::exists(path)) throw std::runtime_error(file + ": no such file");
  tinygltf::TinyGLTF loader;
  // The scenes carry geometry only; never decode images (and never fail on them).
  loader.SetImageLoader([](tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) { return true; }, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  std::string ext = path.extension().string();
  bool ok = (ext == ".glb" || ext == ".GLB") ? loader.LoadBinaryFromFile(&model, &err, &warn, file) : loader.LoadASCIIFromFile(&model, &err, &warn, file);
  if (!ok) throw std::runtime_error(file + ": " + (err.empty() ? std::string("not a valid glTF 2.0 file") : err));
  Reader r{model, file};

  Scene s;
  s.name = path.stem().string();
  // (mesh, primitive) -> scene mesh index, so instanced meshes are uploaded once.
  std::map<std::pair<int, int>, uint32_t> meshOf;
  size_t skipped = 0;

  std::vector<int> roots;
  int sceneIndex = model.defaultScene >= 0 ? model.defaultScene : 0;
  if (sceneIndex < int(model.scenes.size())) roots = model.scenes[sceneIndex].nodes;
  else
    for (size_t i = 0; i < model.nodes.size(); ++i) roots.push_back(int(i));

  struct Item {
    int node;
    glm::mat4 parent;
    int depth;
  };
  std::vector<Item> stack;
  bool directionalSet = false;
  for (int n : roots) stack.push_back({n, glm::mat4(1.0f), 0});
  while (!stack.empty()) {
    Item it = stack.back();
    stack.pop_back();
    if (it.node < 0 || size_t(it.node) >= model.nodes.size()) r.fail("a scene refers to node " + std::to_string(it.node) + ", which does not exist");
    if (it.depth > 64) r.fail("the node hierarchy is deeper than 64 levels (a cycle?)");
    const tinygltf::Node& node = model.nodes[it.node];
    glm::mat4 world = it.parent * NodeTransform(node);
    for (int c : node.children) stack.push_back({c, world, it.depth + 1});
    if (int li = NodeLight(r, node, it.node); li >= 0) {
      const tinygltf::Light& l = model.lights[li];
      LightData d = CheckLight(r, l, "light " + std::to_string(li) + (l.name.empty() ? "" : " '" + l.name + "'"));
      glm::vec3 position(world[3]);
      glm::vec3 axis = glm::vec3(world * glm::vec4(0, 0, -1, 0));  // lights shine along the node's -z
      if (!(glm::length(axis) > 0)) r.fail("node " + std::to_string(it.node) + " carries light " + std::to_string(li) + " with a degenerate transform");
      axis = glm::normalize(axis);
      if (d.type == "point") s.pointLights.push_back({position, d.color, d.range, d.size});
      else if (d.type == "spot") s.spotLights.push_back({position, axis, d.color, d.range, d.inner, d.outer, d.size});
      else if (!directionalSet) s.light.direction = axis, s.light.angularDiameterDegrees = d.size, directionalSet = true;
    }
    if (node.mesh < 0) continue;
    if (size_t(node.mesh) >= model.meshes.size()) r.fail("node " + std::to_string(it.node) + " refers to mesh " + std::to_string(node.mesh) + ", which does not exist");
    const tinygltf::Mesh& mesh = model.meshes[node.mesh];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const tinygltf::Primitive& prim = mesh.primitives[p];
      std::string what = "mesh '" + mesh.name + "' primitive " + std::to_string(p);
      if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP && prim.mode != TINYGLTF_MODE_TRIANGLE_FAN && prim.mode != -1) {
        ++skipped;  // points and lines cast no shadows here
        continue;
      }
      auto key = std::make_pair(node.mesh, int(p));
      auto found = meshOf.find(key);
      if (found == meshOf.end()) {
        auto pos = prim.attributes.find("POSITION");
        if (pos == prim.attributes.end()) r.fail(what + " has no POSITION");
        std::vector<glm::vec3> positions = r.vec3s(pos->second, what + " POSITION");
        Mesh m;
        m.name = mesh.name.empty() ? "mesh" + std::to_string(node.mesh) : mesh.name;
        if (mesh.primitives.size() > 1) m.name += "#" + std::to_string(p);
        m.vertices.resize(positions.size());
        for (size_t i = 0; i < positions.size(); ++i) m.vertices[i].position = positions[i];
        std::vector<uint32_t> idx;
        if (prim.indices >= 0) {
          idx = r.indices(prim.indices, what + " indices", positions.size());
        } else {
          idx.resize(positions.size());
          for (size_t i = 0; i < idx.size(); ++i) idx[i] = uint32_t(i);
        }
        m.indices = ToTriangleList(prim.mode == -1 ? TINYGLTF_MODE_TRIANGLES : prim.mode, idx);
        auto nrm = prim.attributes.find("NORMAL");
        if (nrm != prim.attributes.end()) {
          std::vector<glm::vec3> normals = r.vec3s(nrm->second, what + " NORMAL");
          if (normals.size() != positions.size()) r.fail(what + ": NORMAL and POSITION have different counts");
          for (size_t i = 0; i < normals.size(); ++i) {
            float len = glm::length(normals[i]);
            m.vertices[i].normal = len > 0 ? normals[i] / len : glm::vec3(0, 1, 0);
          }
        } else {
          ComputeNormals(m);
        }
        found = meshOf.emplace(key, s.addMesh(std::move(m))).first;
      }
      s.addInstance(found->second, world, glm::vec3(0.72f));
    }
  }
  if (s.instances.empty()) r.fail("no triangle geometry found" + (skipped ? " (" + std::to_string(skipped) + " point/line primitives skipped)" : std::string()));
  s.finalize();

  // A camera that sees the whole scene from above one corner, and a low light for long shadows.
  glm::vec3 c = s.bounds.center(), e = s.bounds.extent();
  float radius = glm::length(e) * 0.5f;
  s.camera.target = c;
  s.camera.position = c + glm::normalize(glm::vec3(0.6f, 0.55f, 0.8f)) * radius * 1.6f;
  s.camera.nearZ = radius * 0.01f;
  s.camera.farZ = radius * 4.0f;
  if (!directionalSet) s.light.direction = glm::normalize(glm::vec3(-0.5f, -0.7f, -0.35f));
  // Lights without a range reach the whole scene: the distance to its farthest corner.
  auto reach = [&](const glm::vec3& p) {
    glm::vec3 corners[8];
    s.bounds.corners(corners);
    float d = 0;
    for (const glm::vec3& k : corners) d = std::max(d, glm::length(k - p));
    return std::max(d, 1e-3f);
  };
  for (PointLight& l : s.pointLights)
    if (l.range == 0) l.range = reach(l.position);
  for (SpotLight& l : s.spotLights)
    if (l.range == 0) l.range = reach(l.position);
  return s;
}

}  // namespace sp::scene
