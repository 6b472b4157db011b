// The basic technique end to end: the shadow it draws matches an analytic shadow computed on the
// CPU, the default scene renders identically on both backends, and every lit-pass variant and
// every shader in shaders-hlsl/ compiles and links on both backends.
#include <filesystem>
#include <fstream>
#include <glm/ext/matrix_transform.hpp>
#include <regex>

#include "backend-test.h"
#include "technique-renderer.h"
#include "cross-backend.h"
#include "floating-box.h"
#include <sp/tech/renderer.h>

namespace sp::test {
namespace {

class BasicTechniqueTest : public BackendTest {
 protected:
  std::unique_ptr<tech::Renderer> MakeRenderer(const scene::Scene& s, uint32_t w, uint32_t h,
                                               const std::map<std::string, std::string>& params = {}) {
    return MakeTechniqueRenderer(device(), "basic", s, w, h, params);
  }
};

TEST_P(BasicTechniqueTest, ShadowMatchesAnalyticShadowOfAFloatingBox) {
  const uint32_t W = 128, H = 128;
  scene::Scene s = FloatingBox(false);
  std::unique_ptr<tech::Renderer> r = MakeRenderer(s, W, H, {{"resolution", "1024"}});
  r->RenderFrame(s.camera, s.light);
  std::vector<uint8_t> img = r->ReadColor();

  // Pixels within 2 of the analytic edge may differ (the 2x2 PCF and the map's texel grid).
  Comparison c = CompareWithAnalytic(img, AnalyticFloor(s, W, H), W, H, 2);
  EXPECT_GT(c.checked, int(W * H / 2));
  EXPECT_GT(c.shadow, 200) << "the test scene must contain a sizeable shadow";
  EXPECT_EQ(c.wrong, 0) << "pixels whose shadowing differs from the analytic answer";
  if (c.wrong) WritePng(TestOutputDir() / "floating-box.png", W, H, img.data());
}

// The lit pass, and the lab's variant of it (which needs ShadowLocate and ShadowTexel from the
// technique's include), compile and link for every registered technique on this backend; every
// technique reports its map layers once configured.
TEST_P(BasicTechniqueTest, LitPassOfEveryTechniqueCreatesOnThisBackend) {
  for (const std::string& name : tech::TechniqueNames()) {
    std::unique_ptr<tech::Technique> t = tech::CreateTechnique(name);
    for (tech::LitPass pass : {tech::LitPass::Normal, tech::LitPass::Lab}) {
      auto [vs, ps] = tech::Renderer::CompileLitShaders(*t, pass);
      EXPECT_NO_THROW(device().CreateVertexShader(vs)) << name;
      EXPECT_NO_THROW(device().CreatePixelShader(ps)) << name;
    }
    t->Configure(device(), tech::ParamValues::Parse(name, t->Params(), {}));
    std::vector<tech::ShadowLayer> layers = t->Layers();
    EXPECT_FALSE(layers.empty()) << name;
    for (const tech::ShadowLayer& l : layers) EXPECT_TRUE(l.width > 0 && l.height > 0) << name;
  }
}

// The lab's colour target holds what the normal lit pass draws, so the lab's pictures show what
// users see.
TEST_P(BasicTechniqueTest, LabLitPassDrawsTheSameColourAsTheNormalOne) {
  const uint32_t W = 96, H = 64;
  scene::Scene s = scene::MakeBuiltinScene("default");
  tech::Renderer r(device(), s, MakeConfiguredTechnique(device(), "basic", {{"resolution", "512"}}), W, H, LabOptions(true));
  r.RenderFrame(s.camera, s.light);
  std::vector<uint8_t> normal = r.ReadColor();
  r.RenderFrame(s.camera, s.light, tech::LitPass::Lab);
  tech::LabBuffers lab = r.ReadLab();
  EXPECT_EQ(CompareImages("lab-colour", W, H, normal.data(), lab.color.data(), 0), 0u);
  size_t drawn = 0, inMap = 0;
  for (size_t i = 0; i < lab.size(); ++i) {
    drawn += lab.drawn(i);
    inMap += lab.receiving(i) && lab.lookup[i].x == 0.0f && lab.lookup[i].w > 0.0f;
  }
  EXPECT_GT(drawn, lab.size() / 2);
  EXPECT_GT(inMap, lab.size() / 4) << "receiving pixels read layer 0 with a positive texel density";
}

// Every .hlsl file declares its entry points with `//! <target> <entry>` lines; each compiles
// for both targets and the driver accepts the result.
TEST_P(BasicTechniqueTest, EveryShaderInShadersHlslCompilesAndCreates) {
  int compiled = 0;
  std::regex entryLine(R"(^//!\s+(\w+)\s+(\w+)\s*$)");
  for (const auto& f : std::filesystem::recursive_directory_iterator(ShaderDir())) {
    if (f.path().extension() != ".hlsl") continue;
    std::ifstream in(f.path());
    std::string line;
    while (std::getline(in, line)) {
      std::smatch m;
      if (!std::regex_match(line, m, entryLine)) continue;
      std::string rel = std::filesystem::relative(f.path(), ShaderDir()).string();
      ShaderBytecode b = CompileShaderFile(rel, m[1].str(), m[2].str());
      EXPECT_FALSE(b.spirv.empty());
      EXPECT_FALSE(b.glsl.empty());
      if (b.stage == ShaderStage::Vertex) {
        EXPECT_NO_THROW(device().CreateVertexShader(b)) << rel;
      } else if (b.stage == ShaderStage::Pixel) {
        EXPECT_NO_THROW(device().CreatePixelShader(b)) << rel;
      } else if (b.stage == ShaderStage::Compute) {
        EXPECT_NO_THROW(device().CreateComputeShader(b)) << rel;
      }
      ++compiled;
    }
  }
  EXPECT_GT(compiled, 0);
}

SP_INSTANTIATE_BACKEND_TESTS(BasicTechniqueTest);

// Both backends run on Mesa's shared rasterizer (llvmpipe/lavapipe), so the images must be
// identical: coverage, depth, comparisons and, since the toolchain lowers dot and matrix products
// to one fixed sequence of multiplies and adds (rhi/src/hlsl/spirv-arith.cpp), shading too. Other
// drivers may differ in sub-pixel precision and comparison-filter weights at shadow edges, so
// there up to 0.5% of pixels may differ.
TEST(BasicTechniqueCrossBackend, DefaultSceneRendersIdenticallyOnBothBackends) {
  const uint32_t W = 192, H = 108;
  CrossBackendFrame f = RenderOnBothBackends("basic", {{"resolution", "1024"}}, scene::MakeBuiltinScene("default"), W, H);
  size_t differing = CompareImages("default-basic", W, H, f.images[0].data(), f.images[1].data(), 0);
  if (f.mesa) {
    EXPECT_EQ(differing, 0u) << "Vulkan and GL images differ on Mesa; see the heat map in " << TestOutputDir();
  } else {
    EXPECT_LT(differing, size_t(W * H / 200)) << "more than 0.5% of pixels differ across backends";
  }
}

}  // namespace
}  // namespace sp::test
