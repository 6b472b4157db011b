// The ray-traced reference against shadows known in closed form: a box's shadow under a
// directional light (an independent slab test in double precision), a sphere's shadow disc under
// a point light (tangent cone), and a large plane under light 1 degree above it, which must show
// no acne even with positions rounded as a rasterizer rounds them. Then the contract around it:
// back faces, invalid pixels, instancing, the cache, errors, and a real scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <glm/ext/matrix_transform.hpp>
#include <glm/gtc/constants.hpp>
#include <limits>
#include <random>
#include <thread>

#include "reference.h"
#include <sp/scene/scene.h>

namespace sp::test {
namespace {

namespace fs = std::filesystem;
using eval::ReferenceCache;
using eval::ReferenceLight;
using eval::ReferenceTracer;

struct Pixels {
  std::vector<glm::vec3> positions, normals;
  std::vector<uint8_t> valid;
  void Add(const glm::vec3& p, const glm::vec3& n, bool v = true) {
    positions.push_back(p);
    normals.push_back(n);
    valid.push_back(v ? 1 : 0);
  }
  size_t size() const { return positions.size(); }
};

std::vector<uint8_t> Trace(const ReferenceTracer& t, const Pixels& px, const ReferenceLight& light, uint8_t fill = 7) {
  std::vector<uint8_t> out(px.size(), fill);
  t.Visibility(px.positions.data(), px.normals.data(), px.valid.data(), px.size(), light, out.data());
  return out;
}

glm::mat4 Transform(glm::vec3 pos, glm::vec3 scale, float yawDeg = 0, float pitchDeg = 0) {
  glm::mat4 m = glm::translate(glm::mat4(1.0f), pos);
  m = glm::rotate(m, glm::radians(yawDeg), glm::vec3(0, 1, 0));
  m = glm::rotate(m, glm::radians(pitchDeg), glm::vec3(1, 0, 0));
  return glm::scale(m, scale);
}

scene::Scene FloorScene(float size = 40.0f) {
  scene::Scene s;
  s.name = "floor";
  s.addInstance(s.addMesh(scene::MakePlane(1)), glm::scale(glm::mat4(1.0f), glm::vec3(size, 1, size)), glm::vec3(0.8f));
  return s;
}

// Does the ray from p along dir (t > 0) cross the unit box [-0.5, 0.5]^3 seen through `box`?
// Written independently of the tracer: double precision, the box as six slabs, not triangles.
bool SlabHit(const glm::dmat4& box, const glm::dvec3& p, const glm::dvec3& dir) {
  glm::dmat4 inv = glm::inverse(box);
  glm::dvec3 o = glm::dvec3(inv * glm::dvec4(p, 1.0)), d = glm::dvec3(inv * glm::dvec4(dir, 0.0));
  double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-300) {
      if (o[a] < -0.5 || o[a] > 0.5) return false;
      continue;
    }
    double ta = (-0.5 - o[a]) / d[a], tb = (0.5 - o[a]) / d[a];
    t0 = std::max(t0, std::min(ta, tb));
    t1 = std::min(t1, std::max(ta, tb));
  }
  return t0 <= t1;
}

TEST(ReferenceTracer, DirectionalBoxShadowMatchesSlabTestAwayFromTheBoundary) {
  scene::Scene s = FloorScene();
  const glm::mat4 box = Transform({1.0f, 4.0f, -0.5f}, {2.0f, 1.5f, 3.0f}, 30.0f, 12.0f);
  s.addInstance(s.addMesh(scene::MakeBox()), box, glm::vec3(0.8f));
  s.finalize();
  ReferenceTracer tracer(s);
  const glm::vec3 dir = glm::normalize(glm::vec3(0.6f, -1.0f, 0.35f));

  Pixels px;
  for (int z = -120; z <= 120; ++z)
    for (int x = -120; x <= 120; ++x) px.Add({x * 0.1f, 0.0f, z * 0.1f}, {0, 1, 0});
  std::vector<uint8_t> out = Trace(tracer, px, ReferenceLight::FromScene({dir}));

  // Points within delta of the shadow's outline are left out: there the answer depends on the
  // tessellation and on epsilon, not on the tracer being right.
  const double delta = 0.02;
  const glm::dvec3 towards = -glm::dvec3(dir);
  size_t checked = 0, shadowed = 0, mismatches = 0;
  for (size_t i = 0; i < px.size(); ++i) {
    glm::dvec3 p(px.positions[i]);
    bool hit = SlabHit(glm::dmat4(box), p, towards), boundary = false;
    for (int k = 0; k < 8 && !boundary; ++k) {
      double a = k * glm::quarter_pi<double>();
      boundary = SlabHit(glm::dmat4(box), p + delta * glm::dvec3(std::cos(a), 0, std::sin(a)), towards) != hit;
    }
    if (boundary) continue;
    ++checked;
    shadowed += hit;
    if (out[i] != (hit ? 0 : 1) && ++mismatches <= 10) ADD_FAILURE() << "floor point " << p.x << ", " << p.z << ": slab says " << hit;
  }
  EXPECT_EQ(mismatches, 0u);
  EXPECT_GT(checked, px.size() * 9 / 10);
  EXPECT_GT(shadowed, 500u);   // the shadow is really on the grid
}

TEST(ReferenceTracer, PointLightSphereShadowIsTheTangentConeDisc) {
  scene::Scene s = FloorScene();
  const float r = 1.0f, h = 2.0f, H = 6.0f;
  const uint32_t segments = 64, rings = 32;
  s.addInstance(s.addMesh(scene::MakeSphere(segments, rings)), Transform({0, h, 0}, glm::vec3(2 * r)), glm::vec3(0.8f));
  s.finalize();
  ReferenceTracer tracer(s);

  // The cone from the light tangent to a sphere of radius rs meets the floor in a disc of radius
  // H tan(a) with sin(a) = rs / (H - h). The tessellated sphere lies between its inscribed sphere
  // (faces at least cos(pi / rings) of the radius away) and its circumscribed one.
  auto discRadius = [&](double rs) { return H * rs / std::sqrt((H - h) * (H - h) - rs * rs); };
  const double inner = discRadius(r * std::cos(glm::pi<double>() / std::min(rings, segments / 2))), outer = discRadius(r);
  const double margin = 0.03;

  Pixels px;
  std::vector<double> radius;
  for (int ri = 0; ri <= 300; ++ri)
    for (int a = 0; a < 48; ++a) {
      double rho = ri * 0.02, phi = a * glm::two_pi<double>() / 48 + 0.01 * ri;
      px.Add({float(rho * std::cos(phi)), 0.0f, float(rho * std::sin(phi))}, {0, 1, 0});
      radius.push_back(rho);
    }
  std::vector<uint8_t> point = Trace(tracer, px, ReferenceLight::MakePoint({0, H, 0}));
  size_t inside = 0, outside = 0;
  for (size_t i = 0; i < px.size(); ++i) {
    if (radius[i] < inner - margin) {
      ++inside;
      ASSERT_EQ(point[i], 0) << "radius " << radius[i] << " is inside the disc (" << inner << ")";
    } else if (radius[i] > outer + margin) {
      ++outside;
      ASSERT_EQ(point[i], 1) << "radius " << radius[i] << " is outside the disc (" << outer << ")";
    }
  }
  EXPECT_GT(inside, 1000u);
  EXPECT_GT(outside, 8000u);

  // A spot light at the same place, pointing down with a 30 degree half angle: the same shadow
  // inside the cone, nothing lit outside it (the cone meets the floor at H tan 30).
  const double coneRadius = H * std::tan(glm::radians(30.0));
  std::vector<uint8_t> spot = Trace(tracer, px, ReferenceLight::MakeSpot({0, H, 0}, {0, -1, 0}, std::cos(glm::radians(30.0f))));
  for (size_t i = 0; i < px.size(); ++i) {
    if (radius[i] < coneRadius - margin) {
      ASSERT_EQ(spot[i], point[i]) << "radius " << radius[i];
    } else if (radius[i] > coneRadius + margin) {
      ASSERT_EQ(spot[i], 0) << "radius " << radius[i];
    }
  }
}

// Positions as a rasterizer makes them: vertices transformed in float, then interpolated with
// float barycentrics, so they lie near the triangle within rounding, above or below it.
Pixels RasterizedPoints(const scene::Scene& s, uint32_t instance, size_t count, uint32_t seed) {
  const scene::Instance& inst = s.instances[instance];
  const scene::Mesh& mesh = s.meshes[inst.mesh];
  const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(inst.transform)));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  Pixels px;
  for (size_t k = 0; k < count && mesh.triangleCount() > 0; ++k) {
    size_t t = rng() % mesh.triangleCount();
    glm::vec3 v[3], n(0);
    for (int c = 0; c < 3; ++c) {
      const scene::Vertex& vert = mesh.vertices[mesh.indices[3 * t + c]];
      v[c] = glm::vec3(inst.transform * glm::vec4(vert.position, 1.0f));
      n += normalMatrix * vert.normal;
    }
    float b0 = u(rng), b1 = u(rng);
    if (b0 + b1 > 1.0f) b0 = 1.0f - b0, b1 = 1.0f - b1;
    float b2 = 1.0f - b0 - b1;
    px.Add(b0 * v[0] + b1 * v[1] + b2 * v[2], glm::normalize(n));
  }
  return px;
}

TEST(ReferenceTracer, GrazingLightShowsNoAcneOnALargeTiltedPlane) {
  // A 1000-unit plane far from the origin, tilted about an oblique axis, once as an instance
  // (Embree carries each ray into object space) and once baked into world-space vertices.
  const glm::mat4 m = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(250.0f, -80.0f, 130.0f)), glm::radians(37.0f),
                                  glm::normalize(glm::vec3(1, 2, 3))) *
                      glm::scale(glm::mat4(1.0f), glm::vec3(1000.0f, 1.0f, 1000.0f));
  const glm::vec3 normal = glm::normalize(glm::transpose(glm::inverse(glm::mat3(m))) * glm::vec3(0, 1, 0));
  const glm::vec3 tangent = glm::normalize(glm::mat3(m) * glm::vec3(1, 0, 0));
  const glm::vec3 centre(m[3]);

  for (bool baked : {false, true}) {
    scene::Scene s;
    s.name = baked ? "tilted-plane-baked" : "tilted-plane";
    scene::Mesh plane = scene::MakePlane(8);
    if (baked)
      for (scene::Vertex& v : plane.vertices) v.position = glm::vec3(m * glm::vec4(v.position, 1.0f));
    s.addInstance(s.addMesh(plane), baked ? glm::mat4(1.0f) : m, glm::vec3(0.8f));
    s.finalize();
    ReferenceTracer tracer(s);
    Pixels px = RasterizedPoints(s, 0, 20000, 7);
    if (baked)  // normals of a baked mesh are still the object-space ones
      for (glm::vec3& n : px.normals) n = normal;

    for (float elevationDeg : {1.0f, 0.25f}) {
      float e = glm::radians(elevationDeg);
      glm::vec3 travel = std::cos(e) * tangent - std::sin(e) * normal;
      std::vector<uint8_t> out = Trace(tracer, px, ReferenceLight::FromScene({travel}));
      EXPECT_EQ(std::count(out.begin(), out.end(), 1), std::ptrdiff_t(px.size())) << s.name << " at " << elevationDeg << " degrees";
    }
    // A point light 20 units above the plane, 1500 units off to the side: 0.5 to 1.2 degrees.
    std::vector<uint8_t> out = Trace(tracer, px, ReferenceLight::MakePoint(centre + 1500.0f * tangent + 20.0f * normal));
    EXPECT_EQ(std::count(out.begin(), out.end(), 1), std::ptrdiff_t(px.size())) << s.name << " point light";

    // The points really are rounded off the plane: with an epsilon below float rounding the same
    // rays hit their own plane. (Measured: acne at 1e-8 of the scene scale, none from 1e-7 up.)
    eval::ReferenceOptions tiny;
    tiny.relativeEpsilon = 1e-9f;
    const float e = glm::radians(1.0f);
    std::vector<uint8_t> acne = Trace(ReferenceTracer(s, tiny), px, ReferenceLight::FromScene({std::cos(e) * tangent - std::sin(e) * normal}));
    EXPECT_GT(std::count(acne.begin(), acne.end(), 0), std::ptrdiff_t(px.size() / 20)) << s.name;
  }
}

TEST(ReferenceTracer, GrazingLightStillCastsLongShadows) {
  // The offset that prevents acne must not hide a real occluder: a unit cube on the floor under
  // light 5 degrees above the horizon throws a shadow 1 / tan(5 deg) = 11.4 units long.
  scene::Scene s = FloorScene();
  s.addInstance(s.addMesh(scene::MakeBox()), Transform({0, 0.5f, 0}, glm::vec3(1)), glm::vec3(0.8f));
  s.finalize();
  ReferenceTracer tracer(s);
  const float e = glm::radians(5.0f);
  Pixels px;
  for (float x = 0.6f; x < 11.0f; x += 0.1f) px.Add({x, 0.0f, 0.0f}, {0, 1, 0});   // in the shadow
  for (float x = 12.0f; x < 19.0f; x += 0.1f) px.Add({x, 0.0f, 0.0f}, {0, 1, 0});  // beyond it
  std::vector<uint8_t> out = Trace(tracer, px, ReferenceLight::FromScene({{std::cos(e), -std::sin(e), 0.0f}}));
  for (size_t i = 0; i < px.size(); ++i) EXPECT_EQ(out[i], px.positions[i].x < 11.0f ? 0 : 1) << "x = " << px.positions[i].x;
}

// Embree against a brute-force test of every world-space triangle in double precision, on a
// cluttered scene of instanced boxes, spheres and cylinders with rotations, non-uniform and
// negative scales. Rays passing within a small margin of a triangle's edge or ending near epsilon
// are left out: there the answer depends on rounding, not on the tracer being right.
TEST(ReferenceTracer, AgreesWithBruteForceOnAClutteredScene) {
  scene::Scene s = FloorScene(30.0f);
  const uint32_t meshes[3] = {s.addMesh(scene::MakeBox()), s.addMesh(scene::MakeSphere(16, 8)), s.addMesh(scene::MakeCylinder(12))};
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int k = 0; k < 40; ++k) {
    glm::vec3 pos(u(rng) * 20 - 10, u(rng) * 4, u(rng) * 20 - 10), scale(0.5f + 2 * u(rng), 0.5f + 2 * u(rng), 0.5f + 2 * u(rng));
    if (k % 5 == 0) scale.x = -scale.x;
    s.addInstance(meshes[k % 3], Transform(pos, scale, 360 * u(rng), 90 * u(rng)), glm::vec3(0.8f));
  }
  s.finalize();
  ReferenceTracer tracer(s);
  const double eps = tracer.Epsilon();

  std::vector<glm::dvec3> tri;
  for (const scene::Instance& inst : s.instances)
    for (uint32_t i : s.meshes[inst.mesh].indices) tri.push_back(glm::dvec3(inst.transform * glm::vec4(s.meshes[inst.mesh].vertices[i].position, 1.0f)));
  // 1 = occluded, 0 = clear, -1 = too close to call.
  auto brute = [&](const glm::dvec3& o, const glm::dvec3& d, double tfar) {
    const double margin = 1e-4;
    int result = 0;
    for (size_t k = 0; k < tri.size(); k += 3) {
      glm::dvec3 e1 = tri[k + 1] - tri[k], e2 = tri[k + 2] - tri[k], pv = glm::cross(d, e2);
      double det = glm::dot(e1, pv);
      if (std::abs(det) < 1e-12 * glm::length(e1) * glm::length(e2)) continue;  // ray in the triangle's plane
      glm::dvec3 tv = o - tri[k], qv = glm::cross(tv, e1);
      double b1 = glm::dot(tv, pv) / det, b2 = glm::dot(d, qv) / det, t = glm::dot(e2, qv) / det;
      double inside = std::min({b1, b2, 1 - b1 - b2}) * std::min(glm::length(e1), glm::length(e2));
      if (inside < -margin) continue;
      bool nearT = std::abs(t - eps) < margin || std::abs(t - tfar) < margin;
      if (inside < margin || nearT) {
        if (t > eps - margin && t < tfar + margin) result = result == 1 ? 1 : -1;
        continue;
      }
      if (t > eps && t < tfar) return 1;
    }
    return result;
  };

  Pixels px;
  for (uint32_t k = 0; k < s.instances.size(); ++k) {
    Pixels some = RasterizedPoints(s, k, k == 0 ? 400 : 40, 100 + k);
    for (size_t i = 0; i < some.size(); ++i) px.Add(some.positions[i], some.normals[i]);
  }
  const glm::vec3 lightPos(4.0f, 12.0f, -3.0f);
  for (ReferenceLight light : {ReferenceLight::FromScene({{0.5f, -0.8f, 0.3f}}), ReferenceLight::MakePoint(lightPos)}) {
    std::vector<uint8_t> out = Trace(tracer, px, light);
    size_t compared = 0, occluded = 0, mismatches = 0;
    for (size_t i = 0; i < px.size(); ++i) {
      glm::dvec3 p(px.positions[i]), n = glm::normalize(glm::dvec3(px.normals[i]));
      glm::dvec3 o = p + n * eps, d;
      double tfar;
      if (light.type == ReferenceLight::Directional) {
        d = -glm::normalize(glm::dvec3(light.direction));
        tfar = std::numeric_limits<double>::infinity();
      } else {
        d = glm::normalize(glm::dvec3(lightPos) - o);
        tfar = glm::length(glm::dvec3(lightPos) - o) - eps;
      }
      if (glm::dot(n, d) < 1e-3) continue;  // back faces are covered elsewhere; near-tangent ones are ambiguous
      int expected = brute(o, d, tfar);
      if (expected < 0) continue;
      ++compared;
      occluded += expected;
      if (out[i] != 1 - expected && ++mismatches <= 10)
        ADD_FAILURE() << "point " << p.x << ", " << p.y << ", " << p.z << " light type " << light.type << ": brute force says " << (expected ? "occluded" : "clear");
    }
    EXPECT_EQ(mismatches, 0u) << "light type " << light.type;
    EXPECT_GT(compared, px.size() / 3);
    EXPECT_GT(occluded, compared / 10);
    EXPECT_LT(occluded, compared * 9 / 10);
  }
}

TEST(ReferenceTracer, BackFacingReceiversAreShadowedAndInvalidPixelsUntouched) {
  scene::Scene s = FloorScene();
  s.finalize();
  ReferenceTracer tracer(s);
  Pixels px;
  px.Add({1, 0, 1}, {0, 1, 0});
  px.Add({1, 0, 1}, {0, -1, 0});               // facing away
  px.Add({2, 0, 2}, {1, 0, 0});                // perpendicular to the light: not lit either
  px.Add({3, 0, 3}, {0, 1, 0}, false);         // invalid
  px.Add({4, 0, 4}, {0, 1, 0}, false);         // invalid, and garbage must not matter:
  px.positions.back() = glm::vec3(std::numeric_limits<float>::quiet_NaN());
  px.Add({5, 0, 5}, {0, 3, 0});                // normals need not be unit length
  for (ReferenceLight light : {ReferenceLight::FromScene({{0, -1, 0}}), ReferenceLight::MakePoint({0, 10, 0}),
                               ReferenceLight::MakeSpot({0, 10, 0}, {0, -1, 0}, 0.5f)}) {
    std::vector<uint8_t> out = Trace(tracer, px, light, 7);
    EXPECT_EQ(out, (std::vector<uint8_t>{1, 0, 0, 7, 7, 1})) << "light type " << light.type;
  }
}

TEST(ReferenceTracer, InstancedMeshesOccludeAtEachTransform) {
  // One box mesh, five instances: plain, rotated, mirrored (negative scale), flattened to zero
  // height (Embree cannot invert that; it is baked) and tall. Light straight down.
  scene::Scene s = FloorScene();
  uint32_t box = s.addMesh(scene::MakeBox());
  const glm::vec3 centres[5] = {{-8, 3, -8}, {8, 3, -8}, {-8, 3, 8}, {8, 3, 8}, {0, 5, 0}};
  s.addInstance(box, Transform(centres[0], glm::vec3(2)), glm::vec3(0.8f));
  s.addInstance(box, Transform(centres[1], glm::vec3(2), 45.0f, 20.0f), glm::vec3(0.8f));
  s.addInstance(box, Transform(centres[2], {-2, 2, 2}), glm::vec3(0.8f));
  s.addInstance(box, Transform(centres[3], {2, 0, 2}), glm::vec3(0.8f));
  s.addInstance(box, Transform(centres[4], {2, 6, 2}), glm::vec3(0.8f));
  s.finalize();
  ReferenceTracer tracer(s);
  EXPECT_EQ(tracer.TriangleCount(), 2u + 5u * 12u);

  Pixels px;
  for (const glm::vec3& c : centres) px.Add({c.x + 0.3f, 0, c.z - 0.2f}, {0, 1, 0});  // under each box
  for (const glm::vec3& c : centres) px.Add({c.x + 3.0f, 0, c.z}, {0, 1, 0});         // beside each
  std::vector<uint8_t> out = Trace(tracer, px, ReferenceLight::FromScene({{0, -1, 0}}));
  EXPECT_EQ(out, (std::vector<uint8_t>{0, 0, 0, 0, 0, 1, 1, 1, 1, 1}));
  // The tops of the boxes see the light: their own triangles do not shadow them.
  Pixels tops;
  tops.Add({-8, 4, -8}, {0, 1, 0});
  tops.Add({0, 8, 0}, {0, 1, 0});
  EXPECT_EQ(Trace(tracer, tops, ReferenceLight::FromScene({{0, -1, 0}})), (std::vector<uint8_t>{1, 1}));
  // No mask means every pixel is valid.
  std::vector<uint8_t> unmasked(px.size(), 7);
  tracer.Visibility(px.positions.data(), px.normals.data(), nullptr, px.size(), ReferenceLight::FromScene({{0, -1, 0}}), unmasked.data());
  EXPECT_EQ(unmasked, out);
}

TEST(ReferenceTracer, ThreadCountAndConcurrentCallsDoNotChangeResults) {
  scene::Scene s = scene::MakeBuiltinScene("default");
  Pixels px;
  for (int z = -200; z < 200; ++z)
    for (int x = -200; x < 200; ++x) px.Add({x * 0.05f, 0.0f, z * 0.05f}, {0, 1, 0}, (x * 7 + z) % 11 != 0);
  const ReferenceLight light = ReferenceLight::FromScene(s.light);
  eval::ReferenceOptions one, many;
  one.threads = 1;
  many.threads = 8;
  std::vector<uint8_t> expected = Trace(ReferenceTracer(s, one), px, light);
  ReferenceTracer tracer(s, many);
  std::vector<uint8_t> a, b;
  std::thread other([&] { a = Trace(tracer, px, light); });
  b = Trace(tracer, px, light);
  other.join();
  EXPECT_EQ(a, expected);
  EXPECT_EQ(b, expected);
  EXPECT_GT(std::count(expected.begin(), expected.end(), 0), 1000);
  EXPECT_EQ(tracer.TracedRays(), 2 * uint64_t(std::count(px.valid.begin(), px.valid.end(), 1)));  // all face the light
}

fs::path CacheDir(const std::string& name) {
#ifdef SHADOWPORT_TEST_OUTPUT_DIR
  fs::path dir = fs::path(SHADOWPORT_TEST_OUTPUT_DIR) / "reference-cache" / name;
#else
  fs::path dir = fs::temp_directory_path() / "shadowport-reference-test" / name;
#endif
  fs::remove_all(dir);
  return dir;
}

TEST(ReferenceCache, SecondCallIsServedFromDiskWithoutTracing) {
  scene::Scene s = scene::MakeBuiltinScene("default");
  const fs::path dir = CacheDir("second-call");
  Pixels px;
  for (int z = -60; z < 60; ++z)
    for (int x = -60; x < 60; ++x) px.Add({x * 0.15f, 0.0f, z * 0.15f}, {0, 1, 0}, (x + z) % 7 != 0);
  const ReferenceLight light = ReferenceLight::FromScene(s.light);
  std::vector<uint8_t> expected = Trace(ReferenceTracer(s), px, light);

  auto run = [&](ReferenceCache& cache, const ReferenceLight& l, const std::string& key = {}) {
    std::vector<uint8_t> out(px.size(), 7);
    bool hit = cache.Visibility(px.positions.data(), px.normals.data(), px.valid.data(), px.size(), l, out.data(), key);
    return std::make_pair(hit, out);
  };
  {
    ReferenceCache first(s, dir);
    auto [hit, out] = run(first, light);
    EXPECT_FALSE(hit);
    EXPECT_EQ(out, expected);
    ASSERT_TRUE(first.TracerBuilt());
    EXPECT_GT(first.Tracer().TracedRays(), 0u);
    EXPECT_TRUE(fs::exists(first.FileFor(px.positions.data(), px.normals.data(), px.valid.data(), px.size(), light)));
  }
  // A new object, as a new bench run would make: the result comes from the file and no tracer
  // (no BVH, no ray) is ever made.
  ReferenceCache second(s, dir);
  auto [hit, out] = run(second, light);
  EXPECT_TRUE(hit);
  EXPECT_EQ(out, expected);
  EXPECT_FALSE(second.TracerBuilt());
  EXPECT_EQ(second.Hits(), 1u);

  // Anything that changes the answer changes the key: another light, a moved pixel.
  ReferenceLight other = light;
  other.direction.x += 0.01f;
  EXPECT_FALSE(run(second, other).first);
  px.positions[5].y += 1e-3f;
  EXPECT_FALSE(run(second, light).first);
  px.positions[5].y -= 1e-3f;

  // A caller's key stands for the buffers.
  EXPECT_FALSE(run(second, light, "frame-17").first);
  auto [keyHit, keyOut] = run(second, light, "frame-17");
  EXPECT_TRUE(keyHit);
  EXPECT_EQ(keyOut, expected);

  // A damaged file is a miss, traced again and rewritten.
  fs::path file = second.FileFor(px.positions.data(), px.normals.data(), px.valid.data(), px.size(), light);
  fs::resize_file(file, fs::file_size(file) - 3);
  ReferenceCache third(s, dir);
  auto [damagedHit, damagedOut] = run(third, light);
  EXPECT_FALSE(damagedHit);
  EXPECT_EQ(damagedOut, expected);
  EXPECT_TRUE(run(third, light).first);
}

TEST(ReferenceTracer, ErrorsNameWhatIsWrong) {
  auto message = [](auto&& f) {
    try {
      f();
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  scene::Scene empty;
  empty.name = "nothing";
  EXPECT_NE(message([&] { ReferenceTracer t(empty); }).find("scene 'nothing': no triangles"), std::string::npos);
  scene::Scene noInstances = empty;
  noInstances.addMesh(scene::MakeBox());
  EXPECT_NE(message([&] { ReferenceTracer t(noInstances); }).find("no triangles"), std::string::npos);
  scene::Scene dangling = FloorScene();
  dangling.instances[0].mesh = 3;
  EXPECT_NE(message([&] { ReferenceTracer t(dangling); }).find("instance 0 refers to mesh 3"), std::string::npos);
  scene::Scene nanVertex = FloorScene();
  nanVertex.meshes[0].vertices[2].position.y = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NE(message([&] { ReferenceTracer t(nanVertex); }).find("vertex 2 has a non-finite position"), std::string::npos);
  eval::ReferenceOptions badConfig;
  badConfig.embreeConfig = "threads=many";
  EXPECT_NE(message([&] { ReferenceTracer t(FloorScene(), badConfig); }).find("rtcNewDevice(\"max_isa=avx2,threads=many\") failed"), std::string::npos);

  scene::Scene s = FloorScene();
  ReferenceTracer tracer(s);
  Pixels px;
  px.Add({0, 0, 0}, {0, 1, 0});
  px.Add({1, 0, 0}, {0, 0, 0});
  px.Add({2, std::numeric_limits<float>::quiet_NaN(), 0}, {0, 1, 0});
  EXPECT_NE(message([&] { Trace(tracer, px, {}); }).find("pixel 1 has a zero or non-finite normal"), std::string::npos);
  px.normals[1] = {0, 1, 0};
  std::vector<uint8_t> out(px.size(), 7);
  EXPECT_NE(message([&] { tracer.Visibility(px.positions.data(), px.normals.data(), px.valid.data(), px.size(), {}, out.data()); })
                .find("pixel 2 has a non-finite position"),
            std::string::npos);
  EXPECT_EQ(out, std::vector<uint8_t>(px.size(), 7)) << "nothing is written when the input is rejected";
  ReferenceCache cache(s, CacheDir("errors"));
  EXPECT_NE(message([&] { cache.Visibility(px.positions.data(), px.normals.data(), px.valid.data(), px.size(), {}, out.data()); })
                .find("pixel 2 has a non-finite position"),
            std::string::npos);
  px.valid[2] = 0;
  EXPECT_NE(message([&] { Trace(tracer, px, ReferenceLight::FromScene({{0, 0, 0}})); }).find("light direction"), std::string::npos);
  EXPECT_EQ(Trace(tracer, px, {}), (std::vector<uint8_t>{1, 1, 7}));
}

// The real scene beside the project: a few thousand rays from points on its own triangles, with
// its own light, trace without error and find both light and shadow.
TEST(ReferenceTracer, TracesTheShadowColumnsScene) {
  if (!fs::exists(scene::SharedScenesDir() / "ShadowColumns")) GTEST_SKIP() << "no " << scene::SharedScenesDir() / "ShadowColumns";
  scene::Scene s = scene::LoadScene("ShadowColumns");
  ReferenceTracer tracer(s);
  EXPECT_EQ(tracer.TriangleCount(), s.triangleCount());
  Pixels px;
  std::mt19937 rng(3);
  for (int k = 0; k < 40; ++k) {
    Pixels some = RasterizedPoints(s, uint32_t(rng() % s.instances.size()), 100, rng());
    for (size_t i = 0; i < some.size(); ++i) px.Add(some.positions[i], some.normals[i]);
  }
  std::vector<uint8_t> out = Trace(tracer, px, ReferenceLight::FromScene(s.light));
  size_t lit = std::count(out.begin(), out.end(), 1), dark = std::count(out.begin(), out.end(), 0);
  EXPECT_EQ(lit + dark, px.size());
  EXPECT_GT(lit, 0u);
  EXPECT_GT(dark, 0u);
  EXPECT_GT(tracer.TracedRays(), 0u);
  EXPECT_LE(tracer.TracedRays(), px.size());
}

}  // namespace
}  // namespace sp::test
