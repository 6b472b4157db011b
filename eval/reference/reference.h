// The lab's ground truth: exact hard-shadow visibility, ray traced with Embree, for the surface
// points a rasterizer produced. Every technique is judged against these bits, so the tracer is
// built for exactness first (robust BVH traversal, watertight triangles, no back-face culling)
// and speed second (instanced meshes, one Embree scene, all cores).
//
// Resolution of the reference. Rasterized positions are interpolated floats lying near, not
// exactly on, their triangle, so a shadow ray cannot start at the point itself: it would hit its
// own triangle for a large share of pixels (acne). Each ray therefore starts at
//   origin = position + epsilon * normalize(normal),   with tnear = epsilon,
// where epsilon = relativeEpsilon * scene scale, and scene scale = the larger of the scene's
// largest extent and its largest absolute coordinate (float rounding grows with the magnitude of
// coordinates, not only with the scene's size). The normal offset is what prevents acne at grazing
// light: a ray leaving at 1 degree above a plane would need tnear = epsilon / sin(1 deg) to clear
// the rounding noise on its own, while the normal offset clears it at any angle. The consequence:
// occluders within about epsilon of the receiver are missed (a contact shadow thinner than epsilon,
// a crease closer than epsilon), which is the reference's resolution; Epsilon() gives it in world
// units so the lab can report it next to the results.
//
// Area lights (ReferenceLight::size > 0): the light is an extended source and the reference is
// the fraction of it a point sees, estimated with ReferenceOptions::lightSamples rays per pixel
// spread evenly over the solid angle the source subtends (a cone: the sun's disc, or a sphere's
// visible cap), see ReferenceTracer::VisibleSamples. size 0 is the hard reference, unchanged.
//
// Throughput: 12-54 million shadow rays per second per core on the development machine (Embree
// 3.13.5 from Debian), depending on the scene; figures above ReferenceTracer::Visibility in
// reference-tracer.cpp.
#pragma once
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

#include <sp/scene/scene.h>

namespace sp::eval {

struct ReferenceLight {
  enum Type { Directional, Point, Spot } type = Directional;
  glm::vec3 direction{0, -1, 0};  // directional and spot: the way light travels (any length > 0)
  glm::vec3 position{0};          // point and spot
  float spotCosHalfAngle = 0;     // spot: points outside the cone are reported as not lit
  // The source's extent, 0 = ideal (hard shadows). Directional: the angular diameter in degrees of
  // a disc around `direction` (the sun: 0.53), below 180. Point and spot: the radius of a sphere
  // around `position` in world units (scene::PointLight::radius); the spot cone still tests the
  // direction to the sphere's centre.
  float size = 0;

  bool IsArea() const { return size > 0.0f; }
  static ReferenceLight FromScene(const scene::DirectionalLight& light);
  static ReferenceLight MakePoint(const glm::vec3& position, float radius = 0.0f);
  static ReferenceLight MakeSpot(const glm::vec3& position, const glm::vec3& direction, float cosHalfAngle, float radius = 0.0f);
};

struct ReferenceOptions {
  // Ray offset and tnear as a fraction of the scene scale (see the top of this file). Measured on a
  // tilted 1000-unit plane with points interpolated in float: acne at 1e-8, none from 1e-7 up; the
  // default leaves 200x that for the larger rounding of a GPU's interpolation.
  float relativeEpsilon = 2e-5f;
  unsigned threads = 0;       // tracing threads; 0 = std::thread::hardware_concurrency()
  // Passed to rtcNewDevice ("threads=2,verbose=1", ...) after "max_isa=avx2", which avoids a hang
  // in Embree's AVX-512 kernels (see reference-tracer.cpp) unless this string sets an ISA itself.
  std::string embreeConfig;
  // Area lights: rays per pixel, 1..65535. Their directions are a rotated Hammersley set (see
  // reference-tracer.cpp), whose error on a shadow edge falls faster than 1/sqrt(n): measured on
  // the analytic penumbra of tests/eval/area-light-test.cpp, the default's RMS error is 0.36 %
  // (independent random rays: 2.4 % there, up to 0.5 / sqrt(256) = 3.1 % at visibility 1/2).
  unsigned lightSamples = 256;
  // Area lights: the sample pattern of a pixel is rotated by a hash of this seed and the pixel's
  // position and normal, so a result depends on neither thread count nor pixel order.
  uint64_t seed = 0;
};

// Builds one Embree scene from a scene::Scene: each mesh used by an instance becomes one Embree
// scene, each instance an instance geometry (so a mesh repeated 1000 times is stored once). The
// scene::Scene is copied and need not outlive the tracer. Throws std::runtime_error naming the
// problem for a scene without triangles, non-finite vertices or transforms, indices out of range
// and any error Embree reports.
class ReferenceTracer {
 public:
  explicit ReferenceTracer(const scene::Scene& scene, const ReferenceOptions& options = {});
  ~ReferenceTracer();
  ReferenceTracer(const ReferenceTracer&) = delete;
  ReferenceTracer& operator=(const ReferenceTracer&) = delete;

  // For each pixel: the world position and normal the rasterizer produced (so reference and
  // technique judge the same surface point). Writes 1 = lit, 0 = shadowed for pixels with
  // valid[i] != 0 and leaves the others untouched; valid may be null (every pixel valid).
  // Surfaces whose normal faces away from the light are shadowed (0), as are points outside a
  // spot light's cone. Throws std::runtime_error, before writing anything, for a valid pixel with
  // a non-finite position or a zero or non-finite normal, and for an ill-formed light. Thread
  // safe: several calls may run at once.
  // Hard lights only (size 0): throws std::runtime_error for an area light, whose visibility is
  // fractional (use the float overload).
  void Visibility(const glm::vec3* positions, const glm::vec3* normals, const uint8_t* valid, size_t count,
                  const ReferenceLight& light, uint8_t* out) const;
  // Any light: the fraction of the light visible, VisibleSamples / SamplesFor(light); exactly 0 or
  // 1 for a hard light (the uint8 overload's result).
  void Visibility(const glm::vec3* positions, const glm::vec3* normals, const uint8_t* valid, size_t count,
                  const ReferenceLight& light, float* out) const;
  // Any light: how many of SamplesFor(light) rays to the light are unoccluded. Per sample as the
  // hard rules per pixel: a ray leaving below the surface (normal . direction <= 0) counts as
  // occluded, a point outside a spot's cone sees nothing, a point inside a sphere light sees all.
  void VisibleSamples(const glm::vec3* positions, const glm::vec3* normals, const uint8_t* valid, size_t count,
                      const ReferenceLight& light, uint16_t* out) const;
  unsigned SamplesFor(const ReferenceLight& light) const;  // 1 for a hard light, else lightSamples

  float Epsilon() const;           // the ray offset in world units: the reference's resolution
  float SceneScale() const;        // what Epsilon() is relative to
  size_t TriangleCount() const;    // instanced triangles, as traced
  uint64_t TracedRays() const;     // rays cast so far (pixels facing away from the light cast none)

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The scene scale epsilon is relative to (see the top of this file), computed from the instances'
// meshes and transforms, so it does not depend on Scene::finalize() having been called.
float ReferenceSceneScale(const scene::Scene& scene);

// The cache directory when the caller names none: $SHADOWPORT_REFERENCE_CACHE, else `beside` (the
// caller's choice, e.g. a folder next to its output). Never $HOME: a tool writes there only when
// asked to.
std::filesystem::path DefaultReferenceCacheDir(const std::filesystem::path& beside);

// A 64-bit hash of everything in a scene that affects visibility: each instance's mesh positions,
// indices and transform (not normals, colours, names, camera or light).
uint64_t HashSceneGeometry(const scene::Scene& scene);

// Reference results kept on disk so repeated bench runs do not re-trace. A result is found by a
// 64-bit key hashing the scene geometry, the epsilon, the light, the pixel count and either the
// valid pixels' positions and normals or, when the caller gives one, the caller's key (a caller
// key must then change whenever the buffers do). Files are `<key as 16 hex digits>.vis` in the
// cache directory: an 8-byte magic "SPREFVS2", the key, the pixel count, the samples per pixel
// (0 for a hard light) and a 64-bit hash of the payload (uint64 each, little-endian), then for a
// hard light one bit per pixel (bit i%8 of byte i/8, 1 = lit), for an area light one uint16 per
// pixel: its unoccluded samples (ReferenceTracer::VisibleSamples), so a result read back is
// bit-identical to the one traced. The key includes the light's size and, for an area light, the
// sample count and seed. Version 1 files (hard only, no sample field) are never read: the magic
// is part of the key. A missing, truncated or mismatching file is a miss and is rewritten; files
// are written to a temporary name and renamed, so concurrent runs never read half a file.
//
// The tracer (and its BVH) is built only on the first miss, so a run served entirely from the
// cache never builds one. The scene must outlive the cache object.
class ReferenceCache {
 public:
  ReferenceCache(const scene::Scene& scene, std::filesystem::path directory, ReferenceOptions options = {});
  ~ReferenceCache();

  // As ReferenceTracer::Visibility; returns true when the result came from the cache. Throws
  // std::runtime_error naming the file when the cache directory or file cannot be written.
  bool Visibility(const glm::vec3* positions, const glm::vec3* normals, const uint8_t* valid, size_t count,
                  const ReferenceLight& light, uint8_t* out, const std::string& callerKey = {});
  // The same for any light: fractional visibility (ReferenceTracer's float overload).
  bool Visibility(const glm::vec3* positions, const glm::vec3* normals, const uint8_t* valid, size_t count,
                  const ReferenceLight& light, float* out, const std::string& callerKey = {});

  // Called on a miss just before tracing (with the pixel count), so a long-running caller can say
  // what it is waiting for. Empty: nothing is called.
  void SetBeforeTracing(std::function<void(size_t count)> callback) { beforeTracing_ = std::move(callback); }

  const ReferenceTracer& Tracer();  // builds the tracer if no miss has yet
  bool TracerBuilt() const { return tracer_ != nullptr; }
  uint64_t Hits() const { return hits_; }
  uint64_t Misses() const { return misses_; }
  const std::filesystem::path& Directory() const { return directory_; }
  const ReferenceOptions& Options() const { return options_; }
  // The file a call with these arguments reads and writes.
  std::filesystem::path FileFor(const glm::vec3* positions, const glm::vec3* normals, const uint8_t* valid,
                                size_t count, const ReferenceLight& light, const std::string& callerKey = {}) const;

 private:
  uint64_t Key(const glm::vec3* positions, const glm::vec3* normals, const uint8_t* valid, size_t count,
               const ReferenceLight& light, const std::string& callerKey) const;
  // Unoccluded samples per pixel (0/1 for a hard light) from the file or traced; see Visibility.
  bool Samples(const glm::vec3* positions, const glm::vec3* normals, const uint8_t* valid, size_t count,
               const ReferenceLight& light, const std::string& callerKey, std::vector<uint16_t>& samples);

  const scene::Scene& scene_;
  std::filesystem::path directory_;
  ReferenceOptions options_;
  uint64_t sceneHash_ = 0;
  float epsilon_ = 0;
  std::unique_ptr<ReferenceTracer> tracer_;
  uint64_t hits_ = 0, misses_ = 0;
  std::function<void(size_t)> beforeTracing_;
};

}  // namespace sp::eval
