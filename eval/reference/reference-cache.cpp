// Reference results on disk, keyed by what determines them (see ReferenceCache in reference.h).
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <stdexcept>
#include <system_error>

#include "reference-detail.h"
#include "reference.h"

namespace sp::eval {
namespace {

namespace fs = std::filesystem;

constexpr char kMagic[8] = {'S', 'P', 'R', 'E', 'F', 'V', 'S', '2'};
constexpr size_t kHeaderBytes = 40;  // magic, key, count, samples per pixel, checksum

// A streaming 64-bit hash (MurmurHash3's mixing, fed 8 bytes at a time). Not cryptographic: keys
// only need to tell apart the inputs one lab produces, which 64 well-mixed bits do.
class Hasher {
 public:
  void Add(const void* data, size_t n) {
    const auto* p = static_cast<const uint8_t*>(data);
    length_ += n;
    for (; n >= 8; p += 8, n -= 8) {
      uint64_t w;
      std::memcpy(&w, p, 8);
      Mix(w);
    }
    if (n) {
      uint64_t w = 0;
      std::memcpy(&w, p, n);
      Mix(w ^ (uint64_t(n) << 56));
    }
  }
  template <typename T>
  void Value(const T& v) {
    Add(&v, sizeof(T));
  }
  void Word(uint64_t w) {
    length_ += 8;
    Mix(w);
  }
  uint64_t Digest() const {
    uint64_t k = h_ ^ length_;
    k ^= k >> 33;
    k *= 0xff51afd7ed558ccdull;
    k ^= k >> 33;
    k *= 0xc4ceb9ad1a85ec53ull;
    k ^= k >> 33;
    return k;
  }

 private:
  static uint64_t Rotl(uint64_t x, int r) { return (x << r) | (x >> (64 - r)); }
  void Mix(uint64_t w) {
    w *= 0x87c37b91114253d5ull;
    w = Rotl(w, 31);
    w *= 0x4cf5ad432745937full;
    h_ ^= w;
    h_ = Rotl(h_, 27) * 5 + 0x52dce729;
  }
  uint64_t h_ = 0x5350524546455231ull;
  uint64_t length_ = 0;
};

std::string Hex(uint64_t v) {
  char s[17];
  std::snprintf(s, sizeof s, "%016llx", static_cast<unsigned long long>(v));
  return s;
}

uint64_t Checksum(const std::vector<uint8_t>& payload) {
  Hasher h;
  h.Add(payload.data(), payload.size());
  return h.Digest();
}

// The payload of `count` pixels: one bit each for a hard light (samples 0), else a uint16 each.
size_t PayloadBytes(size_t count, uint64_t samples) { return samples ? 2 * count : (count + 7) / 8; }

// Reads `file` into `payload` when it is a complete result for `key`, `count` and `samples`;
// anything else (absent, truncated, another format, corrupted) is a miss.
bool Load(const fs::path& file, uint64_t key, size_t count, uint64_t samples, std::vector<uint8_t>& payload) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return false;
  char header[kHeaderBytes];
  if (!in.read(header, kHeaderBytes)) return false;
  uint64_t fileKey, fileCount, fileSamples, checksum;
  std::memcpy(&fileKey, header + 8, 8);
  std::memcpy(&fileCount, header + 16, 8);
  std::memcpy(&fileSamples, header + 24, 8);
  std::memcpy(&checksum, header + 32, 8);
  if (std::memcmp(header, kMagic, 8) != 0 || fileKey != key || fileCount != count || fileSamples != samples) return false;
  payload.assign(PayloadBytes(count, samples), 0);
  if (!in.read(reinterpret_cast<char*>(payload.data()), std::streamsize(payload.size()))) return false;
  if (in.peek() != std::char_traits<char>::eof()) return false;
  return Checksum(payload) == checksum;
}

void Store(const fs::path& file, uint64_t key, size_t count, uint64_t samples, const std::vector<uint8_t>& payload) {
  std::error_code ec;
  fs::create_directories(file.parent_path(), ec);
  if (ec) throw std::runtime_error("ReferenceCache: cannot create cache directory " + file.parent_path().string() + ": " + ec.message());
  // A unique temporary name, renamed into place, so a concurrent reader sees the old file or the
  // whole new one.
  std::random_device rd;
  uint64_t salt = (uint64_t(rd()) << 32) ^ uint64_t(std::chrono::steady_clock::now().time_since_epoch().count());
  fs::path tmp = file;
  tmp += ".tmp-" + Hex(salt);
  {
    std::ofstream o(tmp, std::ios::binary | std::ios::trunc);
    uint64_t header[4] = {key, uint64_t(count), samples, Checksum(payload)};
    o.write(kMagic, 8);
    o.write(reinterpret_cast<const char*>(header), sizeof header);
    o.write(reinterpret_cast<const char*>(payload.data()), std::streamsize(payload.size()));
    o.close();
    if (!o) {
      fs::remove(tmp, ec);
      throw std::runtime_error("ReferenceCache: cannot write cache file " + tmp.string());
    }
  }
  fs::rename(tmp, file, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw std::runtime_error("ReferenceCache: cannot rename " + tmp.string() + " to " + file.string() + ": " + ec.message());
  }
}

}  // namespace

fs::path DefaultReferenceCacheDir(const fs::path& beside) {
  if (const char* e = std::getenv("SHADOWPORT_REFERENCE_CACHE"); e && *e) return e;
  return beside;
}

uint64_t HashSceneGeometry(const scene::Scene& scene) {
  Hasher h;
  h.Word(scene.instances.size());
  for (const scene::Instance& inst : scene.instances) {
    h.Word(inst.mesh);
    h.Value(inst.transform);
  }
  h.Word(scene.meshes.size());
  for (const scene::Mesh& m : scene.meshes) {
    h.Word(m.vertices.size());
    for (const scene::Vertex& v : m.vertices) h.Value(v.position);
    h.Word(m.indices.size());
    h.Add(m.indices.data(), m.indices.size() * sizeof(uint32_t));
  }
  return h.Digest();
}

ReferenceCache::ReferenceCache(const scene::Scene& scene, fs::path directory, ReferenceOptions options)
    : scene_(scene), directory_(std::move(directory)), options_(std::move(options)) {
  sceneHash_ = HashSceneGeometry(scene);
  epsilon_ = options_.relativeEpsilon * ReferenceSceneScale(scene);
}

ReferenceCache::~ReferenceCache() = default;

const ReferenceTracer& ReferenceCache::Tracer() {
  if (!tracer_) tracer_ = std::make_unique<ReferenceTracer>(scene_, options_);
  return *tracer_;
}

uint64_t ReferenceCache::Key(const glm::vec3* positions, const glm::vec3* normals, const uint8_t* valid, size_t count,
                             const ReferenceLight& light, const std::string& callerKey) const {
  Hasher h;
  h.Add(kMagic, 8);
  h.Word(sceneHash_);
  h.Value(epsilon_);
  h.Word(uint64_t(light.type));
  h.Value(light.direction);
  h.Value(light.position);
  h.Value(light.spotCosHalfAngle);
  h.Value(light.size);
  if (light.IsArea()) {
    h.Word(options_.lightSamples);
    h.Word(options_.seed);
  }
  h.Word(count);
  if (!callerKey.empty()) {
    h.Word(1);
    h.Add(callerKey.data(), callerKey.size());
    return h.Digest();
  }
  h.Word(0);
  // Only valid pixels count: what a G-buffer holds where nothing was drawn does not change the
  // result. Which pixels are valid is folded in 64 at a time.
  uint64_t mask = 0;
  for (size_t i = 0; i < count; ++i) {
    bool v = !valid || valid[i];
    mask |= uint64_t(v) << (i & 63);
    if (v) {
      float pn[6] = {positions[i].x, positions[i].y, positions[i].z, normals[i].x, normals[i].y, normals[i].z};
      h.Add(pn, sizeof pn);
    }
    if ((i & 63) == 63) h.Word(mask), mask = 0;
  }
  h.Word(mask);
  return h.Digest();
}

fs::path ReferenceCache::FileFor(const glm::vec3* positions, const glm::vec3* normals, const uint8_t* valid, size_t count,
                                 const ReferenceLight& light, const std::string& callerKey) const {
  return directory_ / (Hex(Key(positions, normals, valid, count, light, callerKey)) + ".vis");
}

bool ReferenceCache::Samples(const glm::vec3* positions, const glm::vec3* normals, const uint8_t* valid, size_t count,
                             const ReferenceLight& light, const std::string& callerKey, std::vector<uint16_t>& samples) {
  if (light.IsArea() && (options_.lightSamples < 1 || options_.lightSamples > 65535))
    throw std::runtime_error("ReferenceCache: lightSamples " + std::to_string(options_.lightSamples) + " is outside 1..65535");
  const uint64_t perPixel = light.IsArea() ? options_.lightSamples : 0;
  const uint64_t key = Key(positions, normals, valid, count, light, callerKey);
  const fs::path file = directory_ / (Hex(key) + ".vis");
  std::vector<uint8_t> payload;
  samples.assign(count, 0);
  if (Load(file, key, count, perPixel, payload)) {
    for (size_t i = 0; i < count; ++i)
      if (perPixel)
        std::memcpy(&samples[i], &payload[2 * i], 2);
      else
        samples[i] = (payload[i >> 3] >> (i & 7)) & 1;
    ++hits_;
    return true;
  }
  ++misses_;
  if (beforeTracing_) beforeTracing_(count);
  // The file holds every pixel (invalid ones as 0) while the caller's `out` keeps its invalid ones.
  Tracer().VisibleSamples(positions, normals, valid, count, light, samples.data());
  payload.assign(PayloadBytes(count, perPixel), 0);
  for (size_t i = 0; i < count; ++i) {
    if (perPixel)
      std::memcpy(&payload[2 * i], &samples[i], 2);
    else
      payload[i >> 3] |= uint8_t((samples[i] & 1) << (i & 7));
  }
  Store(file, key, count, perPixel, payload);
  return false;
}

bool ReferenceCache::Visibility(const glm::vec3* positions, const glm::vec3* normals, const uint8_t* valid, size_t count,
                                const ReferenceLight& light, uint8_t* out, const std::string& callerKey) {
  // Validated here too, so a bad buffer fails the same way whether or not its result is cached.
  detail::ValidateVisibilityInputs("ReferenceCache::Visibility", positions, normals, valid, count, light, out);
  if (count == 0) return false;
  if (light.IsArea())
    throw std::runtime_error("ReferenceCache::Visibility: the light has size " + std::to_string(light.size) +
                             ", an area light, whose visibility is fractional: use the float overload");
  std::vector<uint16_t> samples;
  bool hit = Samples(positions, normals, valid, count, light, callerKey, samples);
  for (size_t i = 0; i < count; ++i)
    if (!valid || valid[i]) out[i] = uint8_t(samples[i]);
  return hit;
}

bool ReferenceCache::Visibility(const glm::vec3* positions, const glm::vec3* normals, const uint8_t* valid, size_t count,
                                const ReferenceLight& light, float* out, const std::string& callerKey) {
  detail::ValidateVisibilityInputs("ReferenceCache::Visibility", positions, normals, valid, count, light, out);
  if (count == 0) return false;
  std::vector<uint16_t> samples;
  bool hit = Samples(positions, normals, valid, count, light, callerKey, samples);
  // As ReferenceTracer::Visibility divides, so a result from the file equals one traced.
  const float n = light.IsArea() ? float(options_.lightSamples) : 1.0f;
  for (size_t i = 0; i < count; ++i)
    if (!valid || valid[i]) out[i] = float(samples[i]) / n;
  return hit;
}

}  // namespace sp::eval
