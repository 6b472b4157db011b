// Accelerated filtering on the cube technique (accel, shaders-hlsl/cube/hpsm.hlsli): in the room of
// cube-room.h, where a point light's six faces each see a wall (one plane per face) and spheres cast
// shadows onto every face and across a face edge, the accelerated lit pass draws the plain one's
// image bit for bit from all three room cameras, the walls are decided by planes, and the shadows
// stay exactly those of the CPU's segment-sphere test; bad combinations are refused by name, and
// paraboloid and vsdct refuse accel with their reason.
#include "backend-test.h"
#include "technique-renderer.h"
#include "cube-room.h"
#include <sp/tech/hpsm-counters.h>
#include <sp/tech/renderer.h>

namespace sp::test {
namespace {

class CubeHpsmTest : public BackendTest {
 public:
  std::unique_ptr<tech::Renderer> MakeRenderer(const scene::Scene& s, uint32_t w, uint32_t h, const std::map<std::string, std::string>& params) {
    return MakeTechniqueRenderer(device(), "cube", s, w, h, params);
  }
};

TEST_P(CubeHpsmTest, AcceleratedLookupsDrawThePlainImageOnEveryFace) {
  const uint32_t W = 128, H = 96;
  CubeRoom room = MakeCubeRoom();
  struct Case {
    const char* filter;
    const char* kernel;
  };
  for (Case k : {Case{"hw2x2", "3"}, Case{"box", "5"}, Case{"gauss", "3"}}) {
    std::map<std::string, std::string> p = {{"resolution", "256"}, {"filter", k.filter}, {"kernel", k.kernel}};
    std::unique_ptr<tech::Renderer> plain = MakeRenderer(room.scene, W, H, p);
    for (const char* accel : {"hpsm", "minmax"}) {
      p["accel"] = accel;
      std::unique_ptr<tech::Renderer> r = MakeRenderer(room.scene, W, H, p);
      tech::HpsmCounts all;
      int camera = 0;
      for (const scene::Camera& cam : RoomCameras(room)) {
        plain->RenderFrame(cam, room.scene.light);
        std::vector<uint8_t> reference = plain->ReadColor();
        r->RenderFrame(cam, room.scene.light);
        std::vector<uint8_t> img = r->ReadColor();
        tech::HpsmCounts st = dynamic_cast<const tech::HpsmCounterSource&>(r->technique()).HpsmDecisions();
        for (int i = 0; i < 5; ++i) all.n[i] += st.n[i];
        std::string name = std::string("cube-accel-") + k.filter + "-" + accel + "-" + std::to_string(camera++);
        EXPECT_EQ(CompareImages(name, W, H, reference.data(), img.data(), 0), 0u) << name;
      }
      std::printf("[ cube ] %s %s, accel=%s: min/max %.3f (lit %llu, shadowed %llu), plane %.3f (lit %llu, shadowed %llu), filtered %.3f of %llu lookups\n",
                  k.filter, k.kernel, accel, all.minMaxFraction(), (unsigned long long)all.n[0], (unsigned long long)all.n[1], all.planeFraction(),
                  (unsigned long long)all.n[2], (unsigned long long)all.n[3], all.filteredFraction(), (unsigned long long)all.total());
      EXPECT_GT(all.total(), 3u * W * H / 2) << "the room's walls are lit by the point light";
      EXPECT_GT(all.filteredFraction(), 0.0) << "shadow edges and face edges need the filter";
      EXPECT_GT(all.n[1] + all.n[3], 0u) << "the spheres' umbrae are decided shadowed";
      if (std::string(accel) == "hpsm") {
        EXPECT_GT(all.planeFraction(), 0.6) << k.filter << ": each wall is one plane in a face's perspective map";
      }
    }
  }
}

// The exact shadows of the plain lookups hold with the maps deciding (box 5 at 512 texels).
TEST_P(CubeHpsmTest, AcceleratedLookupsKeepTheExactShadows) {
  CubeRoom room = MakeCubeRoom();
  std::unique_ptr<tech::Renderer> r = MakeRenderer(room.scene, 160, 120, {{"resolution", "512"}, {"filter", "box"}, {"kernel", "5"}, {"accel", "hpsm"}});
  ExpectExactRoomShadows(*r, room, 160, 120, 3.0f, 512.0f);
}

TEST_P(CubeHpsmTest, BadAccelParametersAreRefusedByName) {
  auto expectError = [&](const TechniqueParams& p, const std::string& what) { ExpectConfigureRefused(device(), "cube", p, what); };
  expectError({{"accel", "hpsm"}, {"storage", "radial"}}, "storage=depth");
  expectError({{"accel", "minmax"}, {"filter", "pcss"}}, "not offered with filter=pcss");
  expectError({{"accel", "fast"}}, "accel");
  expectError({{"accel", "minmax"}, {"hpsm_block", "6"}}, "hpsm_block");
  expectError({{"accel", "hpsm"}, {"resolution", "64"}, {"hpsm_block", "128"}}, "hpsm_block");
  expectError({{"accel", "hpsm"}, {"resolution_from", "screen"}, {"min_resolution", "16"}, {"hpsm_block", "32"}}, "hpsm_block");
  expectError({{"accel", "hpsm"}, {"resolution", "16"}, {"filter", "box"}, {"kernel", "15"}}, "resolution");
  expectError({{"accel", "hpsm"}, {"hpsm_build", "fetch"}}, "hpsm_build");
  // The other point-light techniques refuse accel by name, with their reason.
  for (const char* name : {"paraboloid", "vsdct"}) {
    ExpectConfigureRefused(device(), name, {{"accel", "hpsm"}}, std::string(name) + ": accel=hpsm is not offered: ");
    EXPECT_NO_THROW(MakeConfiguredTechnique(device(), name, {{"accel", "none"}})) << name;
  }
}

SP_INSTANTIATE_BACKEND_TESTS(CubeHpsmTest);

}  // namespace
}  // namespace sp::test
