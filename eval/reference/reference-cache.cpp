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

constexpr char kMagic[8] = {'S', 'P', 'R', 'E', 'F', 'V', 'S', '1'};
constexpr size_t kHeaderBytes = 32;  // magic, key, count, checksum

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

uint64_t Checksum(const std::vector<uint8_t>& bits) {
  Hasher h;
  h.Add(bits.data(), bits.size());
  return h.Digest();
}

// Reads `file` into `bits` when it is a complete result for `key` and `count`; anything else
// (absent, truncated, another format, corrupted) is a miss.
bool Load(const fs::path& file, uint64_t key, size_t count, std::vector<uint8_t>& bits) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return false;
  char header[kHeaderBytes];
  if (!in.read(header, kHeaderBytes)) return false;
  uint64_t fileKey, fileCount, checksum;
  std::memcpy(&fileKey, header + 8, 8);
  std::memcpy(&fileCount, header + 16, 8);
  std::memcpy(&checksum, header + 24, 8);
  if (std::memcmp(header, kMagic, 8) != 0 || fileKey != key || fileCount != count) return false;
  bits.assign((count + 7) / 8, 0);
  if (!in.read(reinterpret_cast<char*>(bits.data()), std::streamsize(bits.size()))) return false;
  if (in.peek() != std::char_traits<char>::eof()) return false;
  return Checksum(bits) == checksum;
}

void Store(const fs::path& file, uint64_t key, size_t count, const std::vector<uint8_t>& bits) {
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
    uint64_t header[3] = {key, uint64_t(count), Checksum(bits)};
    o.write(kMagic, 8);
    o.write(reinterpret_cast<const char*>(header), sizeof header);
    o.write(reinterpret_cast<const char*>(bits.data()), std::streamsize(bits.size()));
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

bool ReferenceCache::Visibility(const glm::vec3* positions, const glm::vec3* normals, const uint8_t* valid, size_t count,
                                const ReferenceLight& light, uint8_t* out, const std::string& callerKey) {
  // Validated here too, so a bad buffer fails the same way whether or not its result is cached.
  detail::ValidateVisibilityInputs("ReferenceCache::Visibility", positions, normals, valid, count, light, out);
  if (count == 0) return false;
  const uint64_t key = Key(positions, normals, valid, count, light, callerKey);
  const fs::path file = directory_ / (Hex(key) + ".vis");
  std::vector<uint8_t> bits;
  if (Load(file, key, count, bits)) {
    for (size_t i = 0; i < count; ++i)
      if (!valid || valid[i]) out[i] = (bits[i >> 3] >> (i & 7)) & 1;
    ++hits_;
    return true;
  }
  ++misses_;
  if (beforeTracing_) beforeTracing_(count);
  // Traced into a scratch buffer: the file holds every pixel while `out` keeps its invalid ones.
  std::vector<uint8_t> result(count, 0);
  Tracer().Visibility(positions, normals, valid, count, light, result.data());
  bits.assign((count + 7) / 8, 0);
  for (size_t i = 0; i < count; ++i) {
    if (valid && !valid[i]) continue;
    out[i] = result[i];
    bits[i >> 3] |= uint8_t(result[i] << (i & 7));
  }
  Store(file, key, count, bits);
  return false;
}

}  // namespace sp::eval
