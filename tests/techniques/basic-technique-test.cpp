// The basic technique end to end: the shadow it draws matches an analytic shadow computed on the
// CPU, the default scene renders identically on both backends, and every lit-pass variant and
// every shader in shaders-hlsl/ compiles and links on both backends.
#include <filesystem>
#include <fstream>
#include <glm/ext/matrix_transform.hpp>
#include <regex>

#include "backend-test.h"
#include "renderer.h"

namespace sp::test {
namespace {

class BasicTechniqueTest : public BackendTest {
 protected:
  std::unique_ptr<tech::Renderer> MakeRenderer(const scene::Scene& s, uint32_t w, uint32_t h,
                                               const std::map<std::string, std::string>& params = {}) {
    std::unique_ptr<tech::Technique> t = tech::CreateTechnique("basic");
    t->Configure(device(), tech::ParamValues::Parse("basic", t->Params(), params));
    return std::make_unique<tech::Renderer>(device(), s, std::move(t), w, h);
  }
};

// A floor and a box floating above it, a light at 45 degrees, the camera looking straight down.
scene::Scene FloatingBoxScene() {
  scene::Scene s;
  s.name = "floating-box";
  uint32_t plane = s.addMesh(scene::MakePlane(1));
  uint32_t box = s.addMesh(scene::MakeBox());
  s.addInstance(plane, glm::scale(glm::mat4(1.0f), glm::vec3(20, 1, 20)), glm::vec3(0.8f));
  s.addInstance(box, glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(-2.0f, 3.0f, 0.0f)), glm::vec3(2.0f)), glm::vec3(0.8f));
  s.camera.position = {0.0f, 16.0f, 0.001f};
  s.camera.target = {0.0f, 0.0f, 0.0f};
  s.camera.up = {0.0f, 0.0f, -1.0f};
  s.camera.fovY = glm::radians(50.0f);
  s.camera.nearZ = 1.0f;
  s.camera.farZ = 40.0f;
  s.light.direction = glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f));
  s.light.ambient = 0.2f;
  s.finalize();
  return s;
}

// Slab test of a ray against an axis-aligned box; returns the entry distance or -1.
float RayBox(glm::vec3 o, glm::vec3 d, glm::vec3 bmin, glm::vec3 bmax) {
  float t0 = 0.0f, t1 = 1e30f;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-9f) {
      if (o[a] < bmin[a] || o[a] > bmax[a]) return -1.0f;
      continue;
    }
    float ta = (bmin[a] - o[a]) / d[a], tb = (bmax[a] - o[a]) / d[a];
    t0 = std::max(t0, std::min(ta, tb));
    t1 = std::min(t1, std::max(ta, tb));
  }
  return t0 <= t1 ? t0 : -1.0f;
}

TEST_P(BasicTechniqueTest, ShadowMatchesAnalyticShadowOfAFloatingBox) {
  const uint32_t W = 128, H = 128;
  scene::Scene s = FloatingBoxScene();
  std::unique_ptr<tech::Renderer> r = MakeRenderer(s, W, H, {{"resolution", "1024"}});
  r->RenderFrame(s.camera, s.light);
  std::vector<uint8_t> img = r->ReadColor();

  glm::mat4 invViewProj = glm::inverse(s.camera.projection(float(W) / H) * s.camera.view());
  glm::vec3 bmin(-3.0f, 2.0f, -1.0f), bmax(-1.0f, 4.0f, 1.0f);
  glm::vec3 toLight = s.light.towardsLight();
  // Classify each floor pixel on the CPU, then compare; pixels within 2 of a boundary may differ
  // (the 2x2 PCF and the map's texel grid soften the edge).
  std::vector<int> expected(W * H, -1);  // -1 not floor, 0 lit, 1 shadow
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      glm::vec4 ndcNear((x + 0.5f) / W * 2 - 1, 1 - (y + 0.5f) / H * 2, 0.0f, 1.0f), ndcFar = ndcNear;
      ndcFar.z = 1.0f;
      glm::vec4 a = invViewProj * ndcNear, b = invViewProj * ndcFar;
      glm::vec3 o = glm::vec3(a) / a.w, d = glm::normalize(glm::vec3(b) / b.w - o);
      float tFloor = -o.y / d.y;
      float tBox = RayBox(o, d, bmin, bmax);
      if (tBox >= 0 && tBox < tFloor) continue;
      glm::vec3 p = o + d * tFloor;
      if (std::abs(p.x) > 10 || std::abs(p.z) > 10) continue;
      expected[y * W + x] = RayBox(p + toLight * 1e-3f, toLight, bmin, bmax) >= 0 ? 1 : 0;
    }
  int checked = 0, wrong = 0, shadowPixels = 0;
  for (uint32_t y = 2; y < H - 2; ++y)
    for (uint32_t x = 2; x < W - 2; ++x) {
      int e = expected[y * W + x];
      if (e < 0) continue;
      bool nearEdge = false;
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) nearEdge |= expected[(y + dy) * W + (x + dx)] != e;
      if (nearEdge) continue;
      // Lit floor: 0.8 * (0.2 + 0.707) = 0.73 linear; shadowed: 0.16. Threshold halfway in sRGB.
      uint8_t v = img[(y * W + x) * 4 + 1];
      int got = v < 150 ? 1 : 0;
      ++checked;
      shadowPixels += e;
      if (got != e) ++wrong;
    }
  EXPECT_GT(checked, int(W * H / 2));
  EXPECT_GT(shadowPixels, 200) << "the test scene must contain a sizeable shadow";
  EXPECT_EQ(wrong, 0) << "pixels whose shadowing differs from the analytic answer";
  if (wrong) WritePng(TestOutputDir() / "floating-box.png", W, H, img.data());
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
  std::unique_ptr<tech::Technique> t = tech::CreateTechnique("basic");
  t->Configure(device(), tech::ParamValues::Parse("basic", t->Params(), {{"resolution", "512"}}));
  tech::RendererOptions ro;
  ro.lab = true;
  tech::Renderer r(device(), s, std::move(t), W, H, ro);
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
  std::vector<uint8_t> images[2];
  std::string renderer[2];
  const Backend backends[2] = {Backend::Vulkan, Backend::OpenGL};
  scene::Scene s = scene::MakeBuiltinScene("default");
  for (int i = 0; i < 2; ++i) {
    DeviceDesc dd;
    dd.backend = backends[i];
    Ref<Device> dev = CreateDevice(dd);
    renderer[i] = dev->Info().deviceName;
    std::unique_ptr<tech::Technique> t = tech::CreateTechnique("basic");
    t->Configure(*dev, tech::ParamValues::Parse("basic", t->Params(), {{"resolution", "1024"}}));
    tech::Renderer r(*dev, s, std::move(t), W, H);
    r.RenderFrame(s.camera, s.light);
    images[i] = r.ReadColor();
    EXPECT_EQ(dev->ValidationErrorCount(), 0u) << dev->LastValidationError();
  }
  bool mesa = renderer[0].find("llvmpipe") != std::string::npos && renderer[1].find("llvmpipe") != std::string::npos;
  size_t differing = CompareImages("default-basic", W, H, images[0].data(), images[1].data(), 0);
  if (mesa) {
    EXPECT_EQ(differing, 0u) << "Vulkan and GL images differ on Mesa; see the heat map in " << TestOutputDir();
  } else {
    EXPECT_LT(differing, size_t(W * H / 200)) << "more than 0.5% of pixels differ across backends";
  }
}

}  // namespace
}  // namespace sp::test
