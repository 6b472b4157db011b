// sdsm with moment filters and a world-space blur on both backends: with cull=gpu the blur radii
// come from the GPU fit (nothing is read back while rendering) and equal the radii the CPU derives
// from the readback-mode fit, every partition blurs the same world distance within its padding,
// and a static camera renders the same image in both modes.
#include <cmath>
#include <cstdio>

#include "backend-test.h"
#include "technique-renderer.h"
#include "floating-box.h"
#include <sp/tech/renderer.h>
#include "sdsm/sdsm-technique.h"

namespace sp::test {
namespace {

using tech::sdsm::PartitionFit;
using tech::sdsm::SdsmTechnique;
using Params = std::map<std::string, std::string>;

class SdsmMomentsTest : public BackendTest {
 protected:
  std::unique_ptr<tech::Renderer> MakeRenderer(const scene::Scene& s, uint32_t w, uint32_t h, const Params& params) {
    return MakeTechniqueRenderer(device(), "sdsm", s, w, h, params);
  }
  static SdsmTechnique& Sdsm(tech::Renderer& r) { return static_cast<SdsmTechnique&>(r.technique()); }
};

// Two frames of a static camera per mode. The GPU fit does FitPartition's operations in the same
// order, so its radii may differ from the CPU's in the last bit only (the fits themselves are
// compared to 1e-5 in sdsm-technique-test) and the images are expected to be identical.
TEST_P(SdsmMomentsTest, GpuBlurRadiiEqualReadbackRadiiAndRenderTheSameImage) {
  const uint32_t W = 160, H = 120;
  const float blur = 0.1f;
  scene::Scene s = FloatingBox(true);
  for (const char* filter : {"evsm4", "vsm"}) {
    SCOPED_TRACE(filter);
    std::vector<uint8_t> img[2];
    std::vector<float> radii[2];
    std::vector<PartitionFit> fits[2];
    float padBase = 0;  // the filter's padding; the rest of a fit's padding is the blur's
    for (int gpu = 0; gpu < 2; ++gpu) {
      Params p = {{"filter", filter}, {"blur", "0.1"}, {"resolution", "256"}, {"cull", gpu ? "gpu" : "readback"}};
      std::unique_ptr<tech::Renderer> r = MakeRenderer(s, W, H, p);
      for (int i = 0; i < 2; ++i) r->RenderFrame(s.camera, s.light);
      img[gpu] = r->ReadColor();
      SdsmTechnique& t = Sdsm(*r);
      EXPECT_EQ(t.frameReadbacks(), gpu ? 0u : 2u);
      padBase = float(t.settings().csm.fit.padTexels);
      ASSERT_NE(t.moments(), nullptr);
      // What the blur pass read from its constants, in both modes.
      std::vector<float> used = t.moments()->ReadLastBlurRadii(ctx());
      if (gpu) {
        EXPECT_TRUE(t.lastBlurRadii().empty());
        EXPECT_EQ(used, t.ReadGpuBlurRadii(ctx())) << "the blur's constants hold the fit buffer's radii";
        fits[gpu] = t.ReadGpuFits(ctx());
      } else {
        EXPECT_EQ(used, t.lastBlurRadii());
        fits[gpu] = t.lastFits();
      }
      radii[gpu] = used;
    }
    ASSERT_EQ(radii[0].size(), 4u);
    ASSERT_EQ(radii[1].size(), 4u);
    ASSERT_EQ(fits[0].size(), 4u);
    ASSERT_EQ(fits[1].size(), 4u);
    int blurred = 0;
    for (size_t p = 0; p < 4; ++p) {
      SCOPED_TRACE("partition " + std::to_string(p));
      EXPECT_NEAR(radii[1][p], radii[0][p], 1e-5f * radii[0][p]);
      ASSERT_EQ(fits[0][p].empty, fits[1][p].empty);
      if (fits[0][p].empty) {
        EXPECT_EQ(radii[1][p], 0.0f);
        continue;
      }
      // The same world distance in every partition, unless the padding caps it (never past it).
      const PartitionFit& f = fits[1][p];
      const float padBlur = f.padTexels - padBase;
      EXPECT_LE(radii[1][p], padBlur + 1e-6f);
      if (radii[1][p] < padBlur) {
        EXPECT_NEAR(radii[1][p] * f.texelWorld, blur, 1e-5f * blur);
      }
      blurred += radii[1][p] > 1.0f;
      std::printf("[%s %s] partition %zu: radius %.4f texels (readback %.4f), texel %.5f, padding for the blur %.0f\n", BackendName(backend()),
                  filter, p, radii[1][p], radii[0][p], f.texelWorld, padBlur);
    }
    EXPECT_GE(blurred, 2);
    EXPECT_EQ(CompareImages(std::string("sdsm-") + filter + "-gpu-vs-readback", W, H, img[1].data(), img[0].data(), 0), 0u);
  }
}

// Without a blur the gpu mode skips the blur passes, as the CPU modes do.
TEST_P(SdsmMomentsTest, GpuModeWithoutBlurRunsNoBlurPass) {
  scene::Scene s = FloatingBox(true);
  std::unique_ptr<tech::Renderer> r = MakeRenderer(s, 64, 48, {{"filter", "vsm"}, {"resolution", "128"}, {"cull", "gpu"}});
  r->RenderFrame(s.camera, s.light);
  SdsmTechnique& t = Sdsm(*r);
  EXPECT_TRUE(t.moments()->ReadLastBlurRadii(ctx()).empty());
  for (float radius : t.ReadGpuBlurRadii(ctx())) EXPECT_EQ(radius, 0.0f);
  EXPECT_EQ(t.frameReadbacks(), 0u);
}

SP_INSTANTIATE_BACKEND_TESTS(SdsmMomentsTest);

}  // namespace
}  // namespace sp::test
