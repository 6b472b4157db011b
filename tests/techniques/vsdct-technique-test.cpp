// The vsdct technique (cube faces as tiles of a 2D atlas, an indirection cube, 2D PCF): in the
// cube technique's closed room around a point light, the spheres cast exactly the shadows a CPU
// segment-sphere test gives, with the 2x2 filter and with a 5x5 box through guard bands (both
// backends, validation on); the guard bands remove the seam that clamping taps into a face leaves
// (measured against the box-filtered visibility computed on the CPU); both backends draw the same
// image; bad parameters and lights are errors naming them.
#include <array>

#include "backend-test.h"
#include "technique-renderer.h"
#include "cross-backend.h"
#include "cube-room.h"
#include "cube/cube-faces.h"
#include <sp/tech/renderer.h>

namespace sp::test {
namespace {

class VsdctTechniqueTest : public BackendTest {
 public:
  std::unique_ptr<tech::Renderer> MakeRenderer(const scene::Scene& s, uint32_t w, uint32_t h, const std::map<std::string, std::string>& params) {
    return MakeTechniqueRenderer(device(), "vsdct", s, w, h, params);
  }

  // cube's room test; a kernel's taps reach its half width plus the bilinear texel, and points
  // that near a second wall are left out (WithinKernelOfACorner).
  void CheckRoomShadows(const std::map<std::string, std::string>& params) {
    float reach = params.count("filter") && params.at("filter") != "hw2x2" ? float(std::stoi(params.at("kernel")) / 2 + 1) : 0.0f;
    CubeRoom room = MakeCubeRoom();
    RoomCheck total = ExpectExactRoomShadows(*MakeRenderer(room.scene, 160, 120, params), room, 160, 120, reach, std::stof(params.at("resolution")));
    EXPECT_EQ(device().ValidationErrorCount(), 0u) << device().LastValidationError();
    ::testing::Test::RecordProperty("checked", std::to_string(total.checked));
  }
};

TEST_P(VsdctTechniqueTest, SpheresAroundAPointLightCastTheirExactShadowsOnEveryFace) { CheckRoomShadows({{"resolution", "512"}}); }

TEST_P(VsdctTechniqueTest, BoxAndGaussKernelsThroughGuardBandsCastTheSameExactShadows) {
  CheckRoomShadows({{"resolution", "512"}, {"filter", "box"}, {"kernel", "5"}, {"guard", "3"}});
  CheckRoomShadows({{"resolution", "512"}, {"filter", "gauss"}, {"kernel", "5"}, {"guard", "3"}});
}

// The box filter's visibility at a room-surface receiver (point p, normal n) computed on the CPU
// in face f's widened texel grid: texel (i, j) of the face (i, j may leave 0..R-1: the guard band)
// holds the nearest surface along the ray from the light through its centre, a sphere or a wall;
// a tap compares it with the receiver's plane there (the technique's receiver-plane bias), so a
// texel is lit when it holds the receiver's own wall and shadowed when it holds a sphere. The
// (N+1)^2 footprint from floor(s) - N/2 with weights (1-f, 1, ..., 1, f) / N per axis
// (common/shadow-filter.hlsli). A footprint ray that grazes a tessellated sphere or meets another
// wall (a concave corner, decided by both surfaces' biases) is not known; -1 where such rays
// weigh more than 5 %.
double ExpectedBoxVisibility(const CubeRoom& room, glm::vec3 p, glm::vec3 n, int kernel, uint32_t R, int* face, glm::vec2* faceTexel) {
  glm::vec3 d = p - room.light;
  int f = tech::cube::FaceOf(d);
  tech::cube::FaceAxes ax = tech::cube::Face(f);
  float ma = glm::dot(ax.major, d);
  glm::vec2 uv = (glm::vec2(glm::dot(ax.s, d), glm::dot(ax.t, d)) / ma + 1.0f) * 0.5f;
  glm::dvec2 s = glm::dvec2(uv) * double(R) - 0.5;
  glm::dvec2 first = glm::floor(s), fr = s - first;
  *face = f;
  *faceTexel = uv * float(R);
  const double inner = std::cos(glm::pi<double>() / CubeRoom::kRings) - 1e-3;
  const glm::dvec3 L(room.light), N(n);
  double sum = 0, unknown = 0;
  for (int j = 0; j <= kernel; ++j)
    for (int i = 0; i <= kernel; ++i) {
      double wx = i == 0 ? 1 - fr.x : i == kernel ? fr.x : 1.0, wy = j == 0 ? 1 - fr.y : j == kernel ? fr.y : 1.0;
      if (wx * wy == 0) continue;
      glm::dvec2 t = first - double(kernel / 2) + glm::dvec2(i, j) + 0.5;
      glm::dvec3 dir = glm::normalize(glm::dvec3(ax.major) + (2 * t.x / R - 1) * glm::dvec3(ax.s) + (2 * t.y / R - 1) * glm::dvec3(ax.t));
      bool shadow = false, graze = false;
      for (const CubeRoom::Sphere& sp : room.spheres) {
        glm::dvec3 c = glm::dvec3(sp.center) - L;
        double along = glm::dot(c, dir), miss = glm::length(c - dir * along) / sp.radius;
        if (along <= 0) continue;
        if (miss < inner) shadow = true;
        else if (miss <= 1.001) graze = true;
      }
      // The wall the ray leaves the room through, against the receiver's plane along the ray.
      double tWall = 1e30;
      int wallAxis = 0;
      for (int k = 0; k < 3; ++k) {
        if (std::abs(dir[k]) < 1e-12) continue;
        double tk = ((dir[k] > 0 ? room.hi[k] : room.lo[k]) - L[k]) / dir[k];
        if (tk < tWall) tWall = tk, wallAxis = k;
      }
      // Another wall: how far in front of the receiver's plane it is decides, against the depth
      // and slope biases of both surfaces (a concave corner): not known here.
      graze |= std::abs(N[wallAxis]) < 0.5;
      if (graze && !shadow) unknown += wx * wy;
      else sum += shadow ? 0 : wx * wy;
    }
  // Unknown taps count half: the answer is then within 0.025 of the truth, well inside the 0.1
  // that makes a pixel wrong.
  if (unknown > 0.05 * kernel * kernel) return -1;
  return (sum + 0.5 * unknown) / (kernel * kernel);
}

// Wrong pixels (rendered visibility more than 0.25 from the CPU's box-filtered one) near a cube
// face edge (within the kernel's reach, in face texels) and elsewhere, for the scene camera, which
// sees the edge sphere's shadow crossing the +X/-Y edge.
struct SeamCount {
  int nearChecked = 0, nearWrong = 0, farChecked = 0, farWrong = 0;
  double nearRate() const { return nearChecked ? double(nearWrong) / nearChecked : 0; }
  double farRate() const { return farChecked ? double(farWrong) / farChecked : 0; }
};

SeamCount CountSeamErrors(const CubeRoom& room, const std::vector<uint8_t>& img, uint32_t W, uint32_t H, int kernel, uint32_t R) {
  SeamCount n;
  const scene::Camera& cam = room.scene.camera;
  std::vector<RoomPixel> expected = AnalyticRoom(room, cam, W, H);
  const double ambient = room.scene.light.ambient;
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      const RoomPixel& e = expected[y * W + x];
      if (e.code < 0) continue;
      double light = RoomLocalLight(room.scene, e.surface, e.normal);
      // Enough light to read a visibility from the colour, and not so much that it saturates.
      if (EncodeSrgb8(0.8 * (ambient + light)) - EncodeSrgb8(0.8 * ambient) < 48 || 0.8 * (ambient + light) > 0.98) continue;
      int face;
      glm::vec2 t;
      double v = ExpectedBoxVisibility(room, e.surface, e.normal, kernel, R, &face, &t);
      if (v < 0) continue;
      double g = img[(y * W + x) * 4 + 1] / 255.0;
      double linear = g <= 0.04045 ? g / 12.92 : std::pow((g + 0.055) / 1.055, 2.4);
      double got = (linear / 0.8 - ambient) / light;
      bool wrong = std::abs(got - v) > 0.1;
      float edge = std::min({t.x, t.y, float(R) - t.x, float(R) - t.y});
      if (edge < float(kernel / 2 + 1)) {
        ++n.nearChecked, n.nearWrong += wrong;
      } else {
        ++n.farChecked, n.farWrong += wrong;
      }
    }
  return n;
}

// The room with a row of small spheres just past the +X/-Y face edge, on the -Y side: their
// shadow on the floor runs along the seam (the line x = 3 on the floor) a few texels from it, so
// a kernel centred on the +X side of the edge must read it from beyond the edge.
CubeRoom MakeSeamRoom() {
  CubeRoom room = MakeCubeRoom();
  scene::Scene& s = room.scene;
  uint32_t sphere = s.instances.back().mesh;
  for (float z = -1.8f; z <= -0.35f; z += 0.15f) {
    CubeRoom::Sphere sp{room.light + 1.5f * glm::normalize(glm::vec3(1.0f, -1.18f, z)), 0.12f};
    room.spheres.push_back(sp);
    s.addInstance(sphere, glm::scale(glm::translate(glm::mat4(1.0f), sp.center), glm::vec3(2 * sp.radius)), glm::vec3(0.5f));
  }
  s.finalize();
  return room;
}

// Clamping taps into the face (guard=0) leaves a seam: the kernel's taps past the edge reread
// the face's edge texels instead of the neighbouring face's depth. With a guard band the error
// near face edges is no larger than elsewhere.
TEST_P(VsdctTechniqueTest, GuardBandsRemoveTheSeamThatClampingLeaves) {
  const uint32_t W = 256, H = 192, R = 128;
  const int kernel = 9;
  CubeRoom room = MakeSeamRoom();
  SeamCount n[2];
  for (int g = 0; g < 2; ++g) {
    std::unique_ptr<tech::Renderer> r = MakeRenderer(
        room.scene, W, H, {{"resolution", std::to_string(R)}, {"filter", "box"}, {"kernel", std::to_string(kernel)}, {"guard", g ? "5" : "0"}});
    r->RenderFrame(room.scene.camera, room.scene.light);
    std::vector<uint8_t> img = r->ReadColor();
    n[g] = CountSeamErrors(room, img, W, H, kernel, R);
    if (g == 0) WritePng(TestOutputDir() / "seam-clamp.png", W, H, img.data());
  }
  EXPECT_EQ(device().ValidationErrorCount(), 0u) << device().LastValidationError();
  ::testing::Test::RecordProperty("clamp_near_wrong", std::to_string(n[0].nearWrong) + "/" + std::to_string(n[0].nearChecked));
  ::testing::Test::RecordProperty("clamp_far_wrong", std::to_string(n[0].farWrong) + "/" + std::to_string(n[0].farChecked));
  ::testing::Test::RecordProperty("guard_near_wrong", std::to_string(n[1].nearWrong) + "/" + std::to_string(n[1].nearChecked));
  ::testing::Test::RecordProperty("guard_far_wrong", std::to_string(n[1].farWrong) + "/" + std::to_string(n[1].farChecked));
  EXPECT_GT(n[1].nearChecked, 300) << "the camera must see the face edges";
  EXPECT_EQ(n[0].nearChecked, n[1].nearChecked);
  EXPECT_GE(n[0].nearWrong, n[1].nearWrong + 10) << "clamping must show a seam (guard=0: " << n[0].nearWrong << ", guard=5: " << n[1].nearWrong << ")";
  EXPECT_EQ(n[1].nearWrong, 0) << "guard=5 must read the neighbouring face's depth past the edge";
  EXPECT_LE(n[1].nearRate(), n[1].farRate()) << "guard=5: " << n[1].nearWrong << " of " << n[1].nearChecked << " near face edges, " << n[1].farWrong
                                              << " of " << n[1].farChecked << " elsewhere";
}

// resolution_from=screen (King: "with VSDCT, a smaller tile"): inside the light's range the tiles
// are the largest, from 200 m away the smallest; the exact shadows hold with it.
TEST_P(VsdctTechniqueTest, ScreenSizedTilesFollowTheLightsSizeOnScreen) {
  std::map<std::string, std::string> params = {{"resolution", "512"}, {"resolution_from", "screen"}, {"min_resolution", "64"}};
  CheckRoomShadows(params);
  CubeRoom room = MakeCubeRoom();
  std::unique_ptr<tech::Renderer> r = MakeRenderer(room.scene, 160, 120, params);
  auto atlasBytes = [](uint64_t face) { return 3 * (face + 10) * 2 * (face + 10) * 4 + 6 * 16; };  // guard 5 on each side
  r->RenderFrame(room.scene.camera, room.scene.light);
  EXPECT_EQ(r->technique().Stats().memoryBytes, atlasBytes(512));
  scene::Camera far = room.scene.camera;
  far.position = {0.0f, 3.0f, 200.0f};
  far.target = {0.0f, 3.0f, 0.0f};
  far.farZ = 400.0f;
  r->RenderFrame(far, room.scene.light);
  EXPECT_EQ(r->technique().Stats().memoryBytes, atlasBytes(64));
  EXPECT_EQ(r->technique().Layers()[0].width, 64u);
}

// Faces without a visible receiver are not rendered (their tiles stay cleared), as in cube.
TEST_P(VsdctTechniqueTest, FacesWithoutVisibleReceiversAreSkipped) {
  ExpectTheFaceWithoutReceiversSkipped([&](const scene::Scene& s, uint32_t w, uint32_t h, int cull) {
    return MakeRenderer(s, w, h, {{"resolution", "256"}, {"cull_faces", std::to_string(cull)}});
  });
}

SP_INSTANTIATE_BACKEND_TESTS(VsdctTechniqueTest);

// Bad input refused by name, no pixels checked: these run on the null backend too.
class VsdctTechniqueValidationTest : public VsdctTechniqueTest {};

TEST_P(VsdctTechniqueValidationTest, BadParametersAndLightsAreErrors) {
  CubeRoom room = MakeCubeRoom();
  auto render = [&](const std::map<std::string, std::string>& params) { MakeRenderer(room.scene, 16, 16, params)->RenderFrame(room.scene.camera, room.scene.light); };
  ExpectBadPointLightChoicesRefused(room, render);
  auto error = [&](const std::map<std::string, std::string>& params) -> std::string {
    try {
      render(params);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  std::string e = error({{"filter", "box"}, {"kernel", "7"}, {"guard", "3"}});
  EXPECT_NE(e.find("guard=3"), std::string::npos) << e;
  EXPECT_NE(e.find("kernel=7"), std::string::npos) << e;
  EXPECT_NE(error({{"guard", "65"}}).find("guard"), std::string::npos);
  EXPECT_EQ(error({{"filter", "box"}, {"kernel", "7"}, {"guard", "0"}}), "") << "guard=0 clamps instead";
}

SP_INSTANTIATE_VALIDATION_TESTS(VsdctTechniqueValidationTest);

class VsdctTechniqueCrossBackend : public ::testing::TestWithParam<const char*> {};

TEST_P(VsdctTechniqueCrossBackend, RoomRendersIdenticallyOnBothBackends) {
  const uint32_t W = 160, H = 120;
  CubeRoom room = MakeCubeRoom();
  CrossBackendFrame f = RenderOnBothBackends("vsdct", {{"resolution", "256"}, {"filter", GetParam()}, {"kernel", "5"}}, room.scene, W, H);
  size_t differing = CompareImages(std::string("vsdct-room-") + GetParam(), W, H, f.images[0].data(), f.images[1].data(), 0);
  if (f.mesa) {
    EXPECT_EQ(differing, 0u) << "Vulkan and GL images differ on Mesa; see the heat map in " << TestOutputDir();
  } else {
    EXPECT_LT(differing, size_t(W * H / 200)) << "more than 0.5% of pixels differ across backends";
  }
}

INSTANTIATE_TEST_SUITE_P(Filter, VsdctTechniqueCrossBackend, ::testing::Values("hw2x2", "box", "gauss", "gathercmp", "poisson"));

}  // namespace
}  // namespace sp::test
