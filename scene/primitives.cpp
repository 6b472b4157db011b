// Unit primitives, counter-clockwise seen from outside (glTF's convention), with flat normals on
// flat faces so shadow terminators are not smoothed away.
#include <glm/gtc/constants.hpp>

#include <sp/scene/scene.h>

namespace sp::scene {
namespace {

// Appends a triangle, ordering it counter-clockwise around `normal`.
void AddTriangle(Mesh& m, const Vertex& a, const Vertex& b, const Vertex& c, const glm::vec3& normal) {
  uint32_t base = uint32_t(m.vertices.size());
  m.vertices.push_back(a);
  m.vertices.push_back(b);
  m.vertices.push_back(c);
  bool ccw = glm::dot(glm::cross(b.position - a.position, c.position - a.position), normal) >= 0.0f;
  m.indices.push_back(base);
  m.indices.push_back(ccw ? base + 1 : base + 2);
  m.indices.push_back(ccw ? base + 2 : base + 1);
}

void AddQuad(Mesh& m, glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec3 p3, glm::vec3 n) {
  AddTriangle(m, {p0, n}, {p1, n}, {p2, n}, n);
  AddTriangle(m, {p0, n}, {p2, n}, {p3, n}, n);
}

}  // namespace

Mesh MakeBox() {
  Mesh m;
  m.name = "box";
  const glm::vec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int a = 0; a < 3; ++a) {
    for (float s : {-1.0f, 1.0f}) {
      glm::vec3 n = axes[a] * s;
      glm::vec3 u = axes[(a + 1) % 3] * 0.5f, v = axes[(a + 2) % 3] * 0.5f;
      glm::vec3 c = n * 0.5f;
      AddQuad(m, c - u - v, c + u - v, c + u + v, c - u + v, n);
    }
  }
  m.computeBounds();
  return m;
}

Mesh MakePlane(uint32_t subdivisions) {
  Mesh m;
  m.name = "plane";
  uint32_t n = subdivisions < 1 ? 1 : subdivisions;
  const glm::vec3 up(0, 1, 0);
  for (uint32_t z = 0; z < n; ++z) {
    for (uint32_t x = 0; x < n; ++x) {
      float x0 = float(x) / n - 0.5f, x1 = float(x + 1) / n - 0.5f;
      float z0 = float(z) / n - 0.5f, z1 = float(z + 1) / n - 0.5f;
      AddQuad(m, {x0, 0, z0}, {x1, 0, z0}, {x1, 0, z1}, {x0, 0, z1}, up);
    }
  }
  m.computeBounds();
  return m;
}

Mesh MakeCylinder(uint32_t segments) {
  Mesh m;
  m.name = "cylinder";
  const float r = 0.5f;
  for (uint32_t i = 0; i < segments; ++i) {
    float a0 = glm::two_pi<float>() * i / segments, a1 = glm::two_pi<float>() * (i + 1) / segments;
    glm::vec3 d0(std::cos(a0), 0, std::sin(a0)), d1(std::cos(a1), 0, std::sin(a1));
    glm::vec3 p0 = d0 * r, p1 = d1 * r, up(0, 1, 0);
    // Smooth side normals, flat caps.
    Vertex v00{p0, d0}, v10{p1, d1}, v11{p1 + up, d1}, v01{p0 + up, d0};
    glm::vec3 mid = glm::normalize(d0 + d1);
    AddTriangle(m, v00, v10, v11, mid);
    AddTriangle(m, v00, v11, v01, mid);
    AddTriangle(m, {up, up}, {p0 + up, up}, {p1 + up, up}, up);
    AddTriangle(m, {glm::vec3(0), -up}, {p1, -up}, {p0, -up}, -up);
  }
  m.computeBounds();
  return m;
}

Mesh MakeSphere(uint32_t segments, uint32_t rings) {
  Mesh m;
  m.name = "sphere";
  auto point = [&](uint32_t s, uint32_t r) {
    float theta = glm::pi<float>() * r / rings, phi = glm::two_pi<float>() * s / segments;
    glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
    return Vertex{n * 0.5f, n};
  };
  for (uint32_t r = 0; r < rings; ++r) {
    for (uint32_t s = 0; s < segments; ++s) {
      Vertex a = point(s, r), b = point(s + 1, r), c = point(s + 1, r + 1), d = point(s, r + 1);
      glm::vec3 n = glm::normalize(a.normal + b.normal + c.normal + d.normal);
      if (r != 0) AddTriangle(m, a, b, c, n);
      if (r != rings - 1) AddTriangle(m, a, c, d, n);
    }
  }
  m.computeBounds();
  return m;
}

}  // namespace sp::scene
