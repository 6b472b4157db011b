// The Embree side of the reference: scene conversion, error reporting and parallel shadow rays.
#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <vector>

#include "reference-detail.h"
#include "reference.h"

namespace sp::eval {
namespace {

std::string Str(const glm::vec3& v) {
  std::ostringstream s;
  s << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return s.str();
}

bool Finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

bool Finite(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

const char* ErrorName(RTCError e) {
  switch (e) {
    case RTC_ERROR_NONE: return "RTC_ERROR_NONE";
    case RTC_ERROR_UNKNOWN: return "RTC_ERROR_UNKNOWN";
    case RTC_ERROR_INVALID_ARGUMENT: return "RTC_ERROR_INVALID_ARGUMENT";
    case RTC_ERROR_INVALID_OPERATION: return "RTC_ERROR_INVALID_OPERATION";
    case RTC_ERROR_OUT_OF_MEMORY: return "RTC_ERROR_OUT_OF_MEMORY";
    case RTC_ERROR_UNSUPPORTED_CPU: return "RTC_ERROR_UNSUPPORTED_CPU";
    case RTC_ERROR_CANCELLED: return "RTC_ERROR_CANCELLED";
  }
  return "unknown RTCError";
}

// Embree inverts instance transforms to carry rays into object space, which fails for a zero
// scale (a mesh flattened to a plane still casts a shadow) and cannot express projective
// matrices; such instances are baked into world-space triangles instead.
bool NeedsBaking(const glm::mat4& m) {
  if (m[0][3] != 0.0f || m[1][3] != 0.0f || m[2][3] != 0.0f || m[3][3] != 1.0f) return true;
  glm::mat3 a(m);
  float volume = glm::length(a[0]) * glm::length(a[1]) * glm::length(a[2]);
  return !(std::abs(glm::determinant(a)) > 1e-6f * volume);
}

// A shadow ray from origin along dir, occluded by anything in (tnear, tfar).
void SetShadowRay(RTCRay& r, const glm::vec3& origin, const glm::vec3& dir, float tnear, float tfar, unsigned id) {
  r.org_x = origin.x, r.org_y = origin.y, r.org_z = origin.z;
  r.dir_x = dir.x, r.dir_y = dir.y, r.dir_z = dir.z;
  r.tnear = tnear;
  r.tfar = tfar;
  r.time = 0.0f;
  r.mask = 0xFFFFFFFFu;
  r.id = id;
  r.flags = 0;
}

// Runs `work` on min(threads, chunks) threads, the calling one included; `work` takes chunks
// from a shared counter until none is left.
template <class Work>
void OnThreads(unsigned threads, size_t chunks, Work&& work) {
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < unsigned(std::min<size_t>(threads, chunks)); ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
}

}  // namespace

ReferenceLight ReferenceLight::FromScene(const scene::DirectionalLight& light) {
  ReferenceLight l;
  l.type = Directional;
  l.direction = light.direction;
  l.size = light.angularDiameterDegrees;
  return l;
}

ReferenceLight ReferenceLight::MakePoint(const glm::vec3& position, float radius) {
  ReferenceLight l;
  l.type = Point;
  l.position = position;
  l.size = radius;
  return l;
}

ReferenceLight ReferenceLight::MakeSpot(const glm::vec3& position, const glm::vec3& direction, float cosHalfAngle, float radius) {
  ReferenceLight l;
  l.type = Spot;
  l.position = position;
  l.direction = direction;
  l.spotCosHalfAngle = cosHalfAngle;
  l.size = radius;
  return l;
}

void detail::ValidateVisibilityInputs(const char* who, const glm::vec3* positions, const glm::vec3* normals,
                                      const uint8_t* valid, size_t count, const ReferenceLight& light, const void* out) {
  const std::string w = std::string(who) + ": ";
  if (count == 0) return;
  if (!positions || !normals || !out) throw std::runtime_error(w + "positions, normals and out must not be null");
  if (light.type != ReferenceLight::Directional && light.type != ReferenceLight::Point && light.type != ReferenceLight::Spot)
    throw std::runtime_error(w + "unknown light type " + std::to_string(int(light.type)));
  if (light.type != ReferenceLight::Point && (!Finite(light.direction) || !(glm::length(light.direction) > 0.0f)))
    throw std::runtime_error(w + "light direction " + Str(light.direction) + " is zero or not finite");
  if (light.type != ReferenceLight::Directional && !Finite(light.position))
    throw std::runtime_error(w + "light position " + Str(light.position) + " is not finite");
  if (light.type == ReferenceLight::Spot && !std::isfinite(light.spotCosHalfAngle))
    throw std::runtime_error(w + "spotCosHalfAngle is not finite");
  if (!std::isfinite(light.size) || light.size < 0.0f)
    throw std::runtime_error(w + "light size " + std::to_string(light.size) + " is negative or not finite");
  if (light.type == ReferenceLight::Directional && !(light.size < 180.0f))
    throw std::runtime_error(w + "directional light angular diameter " + std::to_string(light.size) +
                             " degrees is not below 180");
  for (size_t i = 0; i < count; ++i) {
    if (valid && !valid[i]) continue;
    if (!Finite(positions[i]))
      throw std::runtime_error(w + "pixel " + std::to_string(i) + " has a non-finite position " + Str(positions[i]));
    if (!Finite(normals[i]) || !(glm::length(normals[i]) > 0.0f))
      throw std::runtime_error(w + "pixel " + std::to_string(i) + " has a zero or non-finite normal " + Str(normals[i]));
  }
}

float ReferenceSceneScale(const scene::Scene& scene) {
  scene::Bounds world;
  for (const scene::Instance& inst : scene.instances) {
    if (inst.mesh >= scene.meshes.size()) continue;
    scene::Bounds local;
    for (const scene::Vertex& v : scene.meshes[inst.mesh].vertices) local.extend(v.position);
    world.extend(local.transformed(inst.transform));
  }
  if (world.empty()) return 0.0f;
  glm::vec3 e = world.extent();
  glm::vec3 a = glm::max(glm::abs(world.min), glm::abs(world.max));
  return std::max({e.x, e.y, e.z, a.x, a.y, a.z});
}

struct ReferenceTracer::Impl {
  RTCDevice device = nullptr;
  RTCScene top = nullptr;
  std::vector<RTCScene> meshScenes;  // by mesh index; null for meshes no instance needs
  float scale = 0, epsilon = 0;
  size_t triangles = 0;
  unsigned threads = 1;
  unsigned samples = 1;
  uint64_t seed = 0;
  mutable std::atomic<uint64_t> traced{0};
  mutable std::mutex errorMutex;
  mutable std::string error;  // the first message Embree reported since the last Check

  ~Impl() {
    if (top) rtcReleaseScene(top);
    for (RTCScene s : meshScenes)
      if (s) rtcReleaseScene(s);
    if (device) rtcReleaseDevice(device);
  }

  static void OnError(void* user, RTCError code, const char* message) {
    Impl* self = static_cast<Impl*>(user);
    std::lock_guard lock(self->errorMutex);
    if (self->error.empty()) self->error = std::string(ErrorName(code)) + ": " + (message ? message : "");
  }

  // Embree reports errors through the callback and carries on with a broken object, so every
  // step that can fail is followed by a check that turns the first recorded error into an
  // exception naming the step.
  void Check(const std::string& step) const {
    std::string message;
    {
      std::lock_guard lock(errorMutex);
      message.swap(error);
    }
    RTCError code = rtcGetDeviceError(device);
    if (message.empty() && code != RTC_ERROR_NONE) message = ErrorName(code);
    if (!message.empty()) throw std::runtime_error("ReferenceTracer: Embree error while " + step + ": " + message);
  }

  RTCScene BuildMeshScene(const scene::Mesh& mesh) {
    RTCScene s = rtcNewScene(device);
    Check("creating the scene of mesh '" + mesh.name + "'");
    rtcSetSceneFlags(s, RTC_SCENE_FLAG_ROBUST);
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), mesh.vertices.size()));
    auto* i = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                             3 * sizeof(uint32_t), mesh.triangleCount()));
    if (!v || !i) {
      rtcReleaseGeometry(g);
      rtcReleaseScene(s);
      Check("allocating the buffers of mesh '" + mesh.name + "'");
      throw std::runtime_error("ReferenceTracer: Embree returned no buffer for mesh '" + mesh.name + "'");
    }
    for (size_t k = 0; k < mesh.vertices.size(); ++k) {
      const glm::vec3& p = mesh.vertices[k].position;
      v[3 * k] = p.x, v[3 * k + 1] = p.y, v[3 * k + 2] = p.z;
    }
    std::copy(mesh.indices.begin(), mesh.indices.begin() + 3 * mesh.triangleCount(), i);
    rtcCommitGeometry(g);
    rtcAttachGeometry(s, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(s);
    Check("building the BVH of mesh '" + mesh.name + "'");
    return s;
  }
};

ReferenceTracer::ReferenceTracer(const scene::Scene& scene, const ReferenceOptions& options)
    : impl_(std::make_unique<Impl>()) {
  Impl& I = *impl_;
  const std::string where = "ReferenceTracer: scene '" + scene.name + "': ";
  if (!(options.relativeEpsilon > 0.0f) || !std::isfinite(options.relativeEpsilon))
    throw std::runtime_error(where + "relativeEpsilon must be positive and finite");

  // Validate everything Embree would otherwise read out of bounds or silently turn into NaN.
  std::vector<bool> used(scene.meshes.size(), false);
  for (size_t k = 0; k < scene.instances.size(); ++k) {
    const scene::Instance& inst = scene.instances[k];
    if (inst.mesh >= scene.meshes.size())
      throw std::runtime_error(where + "instance " + std::to_string(k) + " refers to mesh " + std::to_string(inst.mesh) +
                               " but the scene has " + std::to_string(scene.meshes.size()) + " meshes");
    if (!Finite(inst.transform)) throw std::runtime_error(where + "instance " + std::to_string(k) + " has a non-finite transform");
    used[inst.mesh] = true;
    I.triangles += scene.meshes[inst.mesh].triangleCount();
  }
  if (I.triangles == 0)
    throw std::runtime_error(where + "no triangles to trace (" + std::to_string(scene.meshes.size()) + " meshes, " +
                             std::to_string(scene.instances.size()) + " instances)");
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    if (!used[m]) continue;
    const scene::Mesh& mesh = scene.meshes[m];
    const std::string name = "mesh " + std::to_string(m) + " '" + mesh.name + "'";
    if (mesh.indices.size() % 3 != 0)
      throw std::runtime_error(where + name + " has " + std::to_string(mesh.indices.size()) + " indices, not a multiple of 3");
    for (size_t k = 0; k < mesh.vertices.size(); ++k)
      if (!Finite(mesh.vertices[k].position))
        throw std::runtime_error(where + name + " vertex " + std::to_string(k) + " has a non-finite position " +
                                 Str(mesh.vertices[k].position));
    for (size_t k = 0; k < mesh.indices.size(); ++k)
      if (mesh.indices[k] >= mesh.vertices.size())
        throw std::runtime_error(where + name + " index " + std::to_string(k) + " is " + std::to_string(mesh.indices[k]) +
                                 " but the mesh has " + std::to_string(mesh.vertices.size()) + " vertices");
  }

  if (options.lightSamples < 1 || options.lightSamples > 65535)
    throw std::runtime_error(where + "lightSamples " + std::to_string(options.lightSamples) + " is outside 1..65535");
  I.samples = options.lightSamples;
  I.seed = options.seed;

  I.scale = ReferenceSceneScale(scene);
  I.epsilon = options.relativeEpsilon * I.scale;
  I.threads = options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency());

  // Debian's Embree 3.13.5 sometimes never returns from rtcOccluded1M with coherent rays in a
  // robust scene when it runs its AVX-512 kernels (reproduced: 22 of 30 runs of this project's
  // tests hung in that call; none with AVX2 kernels, per-ray calls, incoherent streams or
  // rtcOccluded16 packets). Capping the ISA at AVX2 keeps both robustness and coherent streams at
  // no measured cost; a caller's own "isa" or "max_isa" setting takes precedence.
  std::string config = options.embreeConfig;
  if (config.find("isa") == std::string::npos) config = "max_isa=avx2" + (config.empty() ? "" : "," + config);
  I.device = rtcNewDevice(config.c_str());
  if (!I.device) throw std::runtime_error(where + "rtcNewDevice(\"" + config + "\") failed: " + ErrorName(rtcGetDeviceError(nullptr)));
  rtcSetDeviceErrorFunction(I.device, &Impl::OnError, &I);
  I.Check("creating the device with config \"" + config + "\"");

  I.top = rtcNewScene(I.device);
  I.Check("creating the top-level scene");
  rtcSetSceneFlags(I.top, RTC_SCENE_FLAG_ROBUST);

  I.meshScenes.assign(scene.meshes.size(), nullptr);
  std::vector<float> bakedPositions;
  std::vector<uint32_t> bakedIndices;
  for (size_t k = 0; k < scene.instances.size(); ++k) {
    const scene::Instance& inst = scene.instances[k];
    const scene::Mesh& mesh = scene.meshes[inst.mesh];
    if (mesh.triangleCount() == 0) continue;
    if (NeedsBaking(inst.transform)) {
      uint32_t base = uint32_t(bakedPositions.size() / 3);
      for (const scene::Vertex& v : mesh.vertices) {
        glm::vec4 h = inst.transform * glm::vec4(v.position, 1.0f);
        glm::vec3 p = glm::vec3(h) / h.w;
        if (!Finite(p))
          throw std::runtime_error(where + "instance " + std::to_string(k) + " maps a vertex of mesh '" + mesh.name + "' to " + Str(p));
        bakedPositions.insert(bakedPositions.end(), {p.x, p.y, p.z});
      }
      for (size_t t = 0; t < 3 * mesh.triangleCount(); ++t) bakedIndices.push_back(base + mesh.indices[t]);
      continue;
    }
    if (!I.meshScenes[inst.mesh]) I.meshScenes[inst.mesh] = I.BuildMeshScene(mesh);
    RTCGeometry g = rtcNewGeometry(I.device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(g, I.meshScenes[inst.mesh]);
    rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &inst.transform[0][0]);
    rtcCommitGeometry(g);
    rtcAttachGeometry(I.top, g);
    rtcReleaseGeometry(g);
    I.Check("adding instance " + std::to_string(k) + " of mesh '" + mesh.name + "'");
  }
  if (!bakedIndices.empty()) {
    RTCGeometry g = rtcNewGeometry(I.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    void* v = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), bakedPositions.size() / 3);
    void* i = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), bakedIndices.size() / 3);
    if (v && i) {
      std::copy(bakedPositions.begin(), bakedPositions.end(), static_cast<float*>(v));
      std::copy(bakedIndices.begin(), bakedIndices.end(), static_cast<uint32_t*>(i));
    }
    rtcCommitGeometry(g);
    rtcAttachGeometry(I.top, g);
    rtcReleaseGeometry(g);
    I.Check("adding the triangles of instances with singular or projective transforms");
  }
  rtcCommitScene(I.top);
  I.Check("building the top-level BVH");
}

ReferenceTracer::~ReferenceTracer() = default;

float ReferenceTracer::Epsilon() const { return impl_->epsilon; }
float ReferenceTracer::SceneScale() const { return impl_->scale; }
size_t ReferenceTracer::TriangleCount() const { return impl_->triangles; }
uint64_t ReferenceTracer::TracedRays() const { return impl_->traced.load(); }

// Rays go to Embree as streams of up to 1024 neighbouring pixels (rtcOccluded1M, coherent), which
// Embree packetizes itself. Measured on the development machine (2 vCPUs that deliver one core's
// throughput: two busy threads take twice as long as one), Release, max_isa=avx2, shadow rays for
// a 1920x1080 G-buffer made by primary rays from each scene's camera, best of 9 calls; ranges are
// over runs on a machine shared with other builds:
//   ShadowColumns, 16.6k triangles (0.97 M rays)               12-29 M rays/s
//   default at 2.5 M instanced triangles (1.32 M rays)         31-54 M rays/s
//   terrain-city at 2.5 M triangles, 4219 instances (1.51 M)   19-31 M rays/s, BVH build 0.3 s
//   canyon-city at 2.5 M triangles (1.20 M rays)               17-23 M rays/s
// AVX-512 kernels measured the same within that noise. On the same inputs, rtcOccluded1 per ray
// and incoherent streams were 1.5-3.3x slower, rtcOccluded16 packets 12-19% and rtcOccluded8
// packets 25-31% slower.
void ReferenceTracer::Visibility(const glm::vec3* positions, const glm::vec3* normals, const uint8_t* valid, size_t count,
                                 const ReferenceLight& light, uint8_t* out) const {
  if (count == 0) return;
  detail::ValidateVisibilityInputs("ReferenceTracer::Visibility", positions, normals, valid, count, light, out);
  if (light.IsArea())
    throw std::runtime_error("ReferenceTracer::Visibility: the light has size " + std::to_string(light.size) +
                             ", an area light, whose visibility is fractional: use the float overload");
  const Impl& I = *impl_;
  const float eps = I.epsilon;
  glm::vec3 axis(0);
  if (light.type != ReferenceLight::Point) axis = glm::normalize(light.direction);
  const glm::vec3 towardsLight = -axis;

  constexpr size_t kChunk = 1024;
  const size_t chunks = (count + kChunk - 1) / kChunk;
  std::atomic<size_t> nextChunk{0};
  std::atomic<uint64_t> rayCount{0};
  auto work = [&] {
    std::vector<RTCRay> rays(kChunk);
    std::vector<size_t> pixel(kChunk);
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    // Pixels of a chunk are neighbours on screen, so their shadow rays are close and, for a
    // directional light, parallel: Embree groups them into packets.
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    uint64_t cast = 0;
    for (size_t c; (c = nextChunk.fetch_add(1)) < chunks;) {
      const size_t begin = c * kChunk, end = std::min(count, begin + kChunk);
      unsigned n = 0;
      for (size_t i = begin; i < end; ++i) {
        if (valid && !valid[i]) continue;
        const glm::vec3 p = positions[i];
        const glm::vec3 normal = glm::normalize(normals[i]);
        glm::vec3 toward = towardsLight;
        if (light.type != ReferenceLight::Directional) {
          glm::vec3 toLight = light.position - p;
          float dist = glm::length(toLight);
          // A light within epsilon of the surface is below the reference's resolution: call it lit.
          if (!(dist > eps)) {
            out[i] = 1;
            continue;
          }
          toward = toLight / dist;
          if (light.type == ReferenceLight::Spot && glm::dot(-toward, axis) < light.spotCosHalfAngle) {
            out[i] = 0;
            continue;
          }
        }
        if (!(glm::dot(normal, toward) > 0.0f)) {
          out[i] = 0;
          continue;
        }
        const glm::vec3 origin = p + normal * eps;
        glm::vec3 dir = toward;
        float tfar = std::numeric_limits<float>::infinity();
        if (light.type != ReferenceLight::Directional) {
          // Aimed from the offset origin so the ray ends at the light itself; occluders within
          // epsilon of the light are missed, as they are near the receiver.
          glm::vec3 fromOrigin = light.position - origin;
          float len = glm::length(fromOrigin);
          dir = fromOrigin / len;
          tfar = len - eps;
          if (!(tfar > eps)) {
            out[i] = 1;
            continue;
          }
        }
        SetShadowRay(rays[n], origin, dir, eps, tfar, n);
        pixel[n++] = i;
      }
      if (n == 0) continue;
      rtcOccluded1M(I.top, &context, rays.data(), n, sizeof(RTCRay));
      for (unsigned k = 0; k < n; ++k) out[pixel[k]] = rays[k].tfar >= 0.0f ? 1 : 0;
      cast += n;
    }
    rayCount += cast;
  };
  OnThreads(I.threads, chunks, work);
  I.traced += rayCount.load();
  I.Check("tracing shadow rays");
}


unsigned ReferenceTracer::SamplesFor(const ReferenceLight& light) const { return light.IsArea() ? impl_->samples : 1u; }

void ReferenceTracer::Visibility(const glm::vec3* positions, const glm::vec3* normals, const uint8_t* valid, size_t count,
                                 const ReferenceLight& light, float* out) const {
  if (count == 0) return;
  detail::ValidateVisibilityInputs("ReferenceTracer::Visibility", positions, normals, valid, count, light, out);
  std::vector<uint16_t> seen(count, 0);
  VisibleSamples(positions, normals, valid, count, light, seen.data());
  const float n = float(SamplesFor(light));
  for (size_t i = 0; i < count; ++i)
    if (!valid || valid[i]) out[i] = float(seen[i]) / n;
}

namespace {

uint64_t SplitMix(uint64_t z) {
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

uint64_t Bits(const glm::vec3& v) {
  uint32_t b[3];
  std::memcpy(b, &v, sizeof b);
  return SplitMix(SplitMix(SplitMix(b[0]) ^ b[1]) ^ b[2]);
}

float RadicalInverse2(uint32_t i) {
  i = (i << 16) | (i >> 16);
  i = ((i & 0x00ff00ffu) << 8) | ((i & 0xff00ff00u) >> 8);
  i = ((i & 0x0f0f0f0fu) << 4) | ((i & 0xf0f0f0f0u) >> 4);
  i = ((i & 0x33333333u) << 2) | ((i & 0xccccccccu) >> 2);
  i = ((i & 0x55555555u) << 1) | ((i & 0xaaaaaaaau) >> 1);
  return float(i >> 8) * 0x1p-24f;
}

// Shirley and Chiu's concentric map of the unit square onto the unit disc: area preserving and of
// low distortion, so the square's even spread of points stays even on the disc.
glm::vec2 ConcentricDisc(float u, float v) {
  float a = 2.0f * u - 1.0f, b = 2.0f * v - 1.0f;
  if (a == 0.0f && b == 0.0f) return {0.0f, 0.0f};
  constexpr float kQuarterPi = 0.785398163f;
  if (std::abs(a) > std::abs(b)) return a * glm::vec2(std::cos(kQuarterPi * b / a), std::sin(kQuarterPi * b / a));
  return b * glm::vec2(std::sin(kQuarterPi * a / b), std::cos(kQuarterPi * a / b));
}

// The cone of directions from a point to an area light: its axis and 1 - cos(half angle), with
// the sphere's centre distance and radius for where a ray reaches the light (directional: none).
// Per-sample work is in float, which the measured throughput needed (it was as slow as the
// tracing in double); 1 - cos is carried as such, never as cos, so tiny cones keep their size.
struct LightCone {
  glm::vec3 axis, t1, t2;
  float oneMinusCos = 0;
  float distance = 0, radius = 0;
};

// Directions uniform in the cone's solid angle: a disc point at radius r maps to 1 - cos(theta) =
// r^2 (1 - cos(half angle)), which is uniform in solid angle because the disc map keeps area.
// Returns the direction and sets *oneMinusCosTheta.
glm::vec3 ConeDirection(const LightCone& c, float u, float v, float* oneMinusCosTheta) {
  glm::vec2 d = ConcentricDisc(u, v);
  float r2 = glm::dot(d, d);
  float m = r2 * c.oneMinusCos;
  *oneMinusCosTheta = m;
  if (r2 == 0.0f) return c.axis;
  float sinTheta = std::sqrt(std::max(0.0f, m * (2.0f - m)));
  return (1.0f - m) * c.axis + (sinTheta / std::sqrt(r2)) * (d.x * c.t1 + d.y * c.t2);
}

}  // namespace

// Area lights: each pixel casts lightSamples rays over the light's cone, the n points of a
// Hammersley set ((k + 1/2) / n, radical inverse of k) shifted modulo 1 by a per-pixel offset
// (Cranley-Patterson rotation, which keeps the estimate unbiased), carried onto the disc by the
// concentric map and onto the cone by equal solid angle. A straight shadow edge across the disc
// then errs by O(log n / n) rather than a random set's O(1/sqrt(n)). The offset hashes the seed
// with the pixel's position and normal, so results are the same on every run, thread count and
// pixel order. Rays go to rtcOccluded1M in streams of whole pixels (each pixel's rays share an
// origin and are coherent). Measured rays/s: docs/lab.md, "Area lights in the reference".
void ReferenceTracer::VisibleSamples(const glm::vec3* positions, const glm::vec3* normals, const uint8_t* valid, size_t count,
                                     const ReferenceLight& light, uint16_t* out) const {
  if (count == 0) return;
  detail::ValidateVisibilityInputs("ReferenceTracer::VisibleSamples", positions, normals, valid, count, light, out);
  if (!light.IsArea()) {
    std::vector<uint8_t> hard(count, 0);
    Visibility(positions, normals, valid, count, light, hard.data());
    for (size_t i = 0; i < count; ++i)
      if (!valid || valid[i]) out[i] = hard[i];
    return;
  }
  const Impl& I = *impl_;
  const float eps = I.epsilon;
  const unsigned n = I.samples;
  glm::dvec3 spotAxis(0);
  if (light.type != ReferenceLight::Point) spotAxis = glm::normalize(glm::dvec3(light.direction));
  const double sunOneMinusCos = 2.0 * std::pow(std::sin(glm::radians(double(light.size)) / 4.0), 2.0);

  const size_t pixelsPerChunk = std::max<size_t>(1, 4096 / n);
  const size_t chunks = (count + pixelsPerChunk - 1) / pixelsPerChunk;
  std::atomic<size_t> nextChunk{0};
  std::atomic<uint64_t> rayCount{0};
  auto work = [&] {
    std::vector<RTCRay> rays(pixelsPerChunk * n);
    std::vector<uint32_t> owner(pixelsPerChunk * n);
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    uint64_t total = 0;
    for (size_t c; (c = nextChunk.fetch_add(1)) < chunks;) {
      const size_t begin = c * pixelsPerChunk, end = std::min(count, begin + pixelsPerChunk);
      unsigned cast = 0;
      for (size_t i = begin; i < end; ++i) {
        if (valid && !valid[i]) continue;
        out[i] = 0;
        const glm::vec3 p = positions[i];
        const glm::vec3 normal = glm::normalize(normals[i]);
        const glm::vec3 origin = p + normal * eps;
        LightCone cone;
        glm::dvec3 axis;
        double oneMinusCos;
        if (light.type == ReferenceLight::Directional) {
          axis = -spotAxis;
          oneMinusCos = sunOneMinusCos;
        } else {
          glm::dvec3 toCentre = glm::dvec3(light.position) - glm::dvec3(origin);
          double distance = glm::length(toCentre);
          // Inside the sphere (or within epsilon of it) the whole light is seen, as a hard light
          // within epsilon of the surface is.
          if (!(distance > double(light.size) + eps)) {
            out[i] = uint16_t(n);
            continue;
          }
          axis = toCentre / distance;
          if (light.type == ReferenceLight::Spot &&
              glm::dot(glm::normalize(glm::dvec3(light.position) - glm::dvec3(p)), -spotAxis) < light.spotCosHalfAngle)
            continue;
          double s = double(light.size) / distance;
          oneMinusCos = s * s / (1.0 + std::sqrt(1.0 - s * s));
          cone.distance = float(distance);
          cone.radius = light.size;
        }
        // Duff et al.'s branchless orthonormal basis around the axis.
        double sign = std::copysign(1.0, axis.z), q = -1.0 / (sign + axis.z), r = axis.x * axis.y * q;
        cone.axis = glm::vec3(axis);
        cone.t1 = glm::vec3(glm::dvec3(1.0 + sign * axis.x * axis.x * q, sign * r, -sign * axis.x));
        cone.t2 = glm::vec3(glm::dvec3(r, sign + axis.y * axis.y * q, -axis.y));
        cone.oneMinusCos = float(oneMinusCos);
        const uint64_t h = SplitMix(I.seed ^ Bits(p) ^ SplitMix(Bits(normal)));
        const float su = float(h >> 40) * 0x1p-24f, sv = float((h >> 8) & 0xffffffu) * 0x1p-24f;
        unsigned seen = 0;
        for (unsigned k = 0; k < n; ++k) {
          float u = (float(k) + 0.5f) / float(n) + su, v = RadicalInverse2(k) + sv;
          float m;
          glm::vec3 d = ConeDirection(cone, u >= 1.0f ? u - 1.0f : u, v >= 1.0f ? v - 1.0f : v, &m);
          if (!(glm::dot(normal, d) > 0.0f)) continue;  // below the surface: its own shadow
          float tfar = std::numeric_limits<float>::infinity();
          if (light.type != ReferenceLight::Directional) {
            // Up to the sphere's near side, less epsilon as for a hard light.
            float sin2 = m * (2.0f - m);
            float t = cone.distance * (1.0f - m) - std::sqrt(std::max(0.0f, cone.radius * cone.radius - cone.distance * cone.distance * sin2));
            tfar = t - eps;
            if (!(tfar > eps)) {
              ++seen;
              continue;
            }
          }
          SetShadowRay(rays[cast], origin, d, eps, tfar, cast);
          owner[cast++] = uint32_t(i - begin);
        }
        out[i] = uint16_t(seen);
      }
      if (cast == 0) continue;
      rtcOccluded1M(I.top, &context, rays.data(), cast, sizeof(RTCRay));
      for (unsigned k = 0; k < cast; ++k)
        if (rays[k].tfar >= 0.0f) ++out[begin + owner[k]];
      total += cast;
    }
    rayCount += total;
  };
  OnThreads(I.threads, chunks, work);
  I.traced += rayCount.load();
  I.Check("tracing area-light shadow rays");
}

}  // namespace sp::eval
