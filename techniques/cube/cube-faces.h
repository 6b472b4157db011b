// Cube-map face geometry shared by the cube technique and its tests: D3D11's TextureCube face
// order and (s, t) axes, which GL and Vulkan share (the same table in the GL 4.5 spec, 8.13, and
// Vulkan's cube map face selection), with t = 0 on the face's first row in memory on all three.
//
// Face f of a direction d (from the light): the major axis ma = max(|x|, |y|, |z|) picks the face,
// then u = (sc / ma + 1) / 2, v = (tc / ma + 1) / 2 with
//   face 0 +X: sc = -z, tc = -y     face 1 -X: sc = +z, tc = -y
//   face 2 +Y: sc = +x, tc = +z     face 3 -Y: sc = +x, tc = -z
//   face 4 +Z: sc = +x, tc = -y     face 5 -Z: sc = -x, tc = -y
// Rendering face f: NDC x = sc / ma, NDC y = -tc / ma (D3D: NDC +y is row 0, where v = 0), and
// planar window z = a + b / ma with a = far / (far - near), b = -far near / (far - near): the same
// near and far on every face, so z depends on ma alone (King, "Shadow Mapping Algorithms").
#pragma once
#include <glm/glm.hpp>

namespace sp::tech::cube {

struct FaceAxes {
  glm::vec3 s, t, major;  // sc = dot(s, d), tc = dot(t, d), ma = dot(major, d)
};

inline FaceAxes Face(int f) {
  static const FaceAxes kFaces[6] = {
      {{0, 0, -1}, {0, -1, 0}, {1, 0, 0}},  {{0, 0, 1}, {0, -1, 0}, {-1, 0, 0}}, {{1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
      {{1, 0, 0}, {0, 0, -1}, {0, -1, 0}}, {{1, 0, 0}, {0, -1, 0}, {0, 0, 1}},  {{-1, 0, 0}, {0, -1, 0}, {0, 0, -1}},
  };
  return kFaces[f];
}

// The face a direction selects; ties go to z, then y (any choice is right at a tie: both faces
// hold the same depth there).
inline int FaceOf(const glm::vec3& d) {
  glm::vec3 a = glm::abs(d);
  if (a.z >= a.x && a.z >= a.y) return d.z >= 0 ? 4 : 5;
  if (a.y >= a.x) return d.y >= 0 ? 2 : 3;
  return d.x >= 0 ? 0 : 1;
}

inline float DepthA(float nearZ, float farZ) { return farZ / (farZ - nearZ); }
inline float DepthB(float nearZ, float farZ) { return -farZ * nearZ / (farZ - nearZ); }

// World -> clip of face f for a light at `position`.
inline glm::mat4 FaceViewProj(int f, const glm::vec3& position, float nearZ, float farZ) {
  FaceAxes ax = Face(f);
  float a = DepthA(nearZ, farZ), b = DepthB(nearZ, farZ);
  // Rows of the clip transform of d = p - position: (s.d, -t.d, a ma + b, ma).
  glm::vec4 rows[4] = {glm::vec4(ax.s, 0), glm::vec4(-ax.t, 0), glm::vec4(a * ax.major, b), glm::vec4(ax.major, 0)};
  glm::mat4 m(0.0f);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m[c][r] = rows[r][c];
  glm::mat4 translate(1.0f);
  translate[3] = glm::vec4(-position, 1.0f);
  return m * translate;
}

// Planar window z of a point at light-relative direction d (what face rendering stores).
inline float WindowZ(const glm::vec3& d, float nearZ, float farZ) {
  glm::vec3 a = glm::abs(d);
  float ma = glm::max(a.x, glm::max(a.y, a.z));
  return DepthA(nearZ, farZ) + DepthB(nearZ, farZ) / ma;
}

}  // namespace sp::tech::cube
