// SDSM GPU-driven caster culling (techniques/sdsm/caster-culling.h) on both backends: the
// indirect-draw records and visible lists the compute pass writes for partition bounds given in
// the results layout, the image DrawIndexedInstancedIndirect then renders (exactly the expected
// instances, two meshes so base vertex and start index vary), and the whole chain from a rendered
// camera depth buffer through the analysis to the culling with no CPU readback in between.
#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <set>

#include "backend-test.h"
#include <sp/scene/scene.h>
#include "sdsm/caster-culling.h"
#include "sdsm/depth-analysis.h"
#include <sp/tech/technique.h>

namespace sp::test {
namespace {

using namespace tech::sdsm;

// A 6 x 6 grid of 1.6-unit boxes and spheres (every third one a sphere) on y = 0, 4 units apart.
scene::Scene Grid(bool withGround) {
  scene::Scene s;
  s.name = "sdsm-cull-grid";
  uint32_t box = s.addMesh(scene::MakeBox());
  uint32_t sphere = s.addMesh(scene::MakeSphere(12, 8));
  uint32_t plane = withGround ? s.addMesh(scene::MakePlane(1)) : 0;
  for (int gz = 0; gz < 6; ++gz)
    for (int gx = 0; gx < 6; ++gx) {
      int k = gz * 6 + gx;
      glm::mat4 t = glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(-10.0f + 4 * gx, 0.0f, -10.0f + 4 * gz)), glm::vec3(1.6f));
      s.addInstance(k % 3 == 0 ? sphere : box, t, glm::vec3(0.7f));
    }
  if (withGround) s.addInstance(plane, glm::translate(glm::scale(glm::mat4(1.0f), glm::vec3(40, 1, 40)), glm::vec3(0, -0.8f, 0)), glm::vec3(0.7f));
  s.camera.position = {0.0f, 9.0f, 16.0f};
  s.camera.target = {0.0f, 0.0f, -2.0f};
  s.camera.nearZ = 1.0f;
  s.camera.farZ = 60.0f;
  s.light.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
  s.finalize();
  return s;
}

LightBounds Box(glm::vec3 lo, glm::vec3 hi, uint32_t samples = 100) { return {lo, hi, samples}; }

// The culling rule of casters.hlsl, on the CPU.
bool Survives(const scene::Instance& inst, const glm::mat4& lightView, const LightBounds& b, float dilation) {
  if (b.empty()) return false;
  glm::vec3 c = glm::vec3(lightView * glm::vec4(inst.worldBounds.center(), 1.0f));
  glm::mat3 r(lightView);
  for (int i = 0; i < 3; ++i) r[i] = glm::abs(r[i]);
  glm::vec3 e = r * (inst.worldBounds.extent() * 0.5f);
  glm::vec3 lo = b.min - dilation, hi = b.max + dilation;
  return c.x + e.x >= lo.x && c.y + e.y >= lo.y && c.x - e.x <= hi.x && c.y - e.y <= hi.y && c.z + e.z >= lo.z;
}

class SdsmCullingTest : public BackendTest {
 protected:
  Ref<Buffer> ResultsBuffer(const AnalysisResults& r, Ref<ShaderResourceView>* srv) {
    std::vector<uint32_t> words = EncodeResults(r);
    Ref<Buffer> b = MakeBuffer(device(), BIND_SHADER_RESOURCE, words.data(), kResultBytes, RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS);
    SHADER_RESOURCE_VIEW_DESC d;
    d.Format = FORMAT_R32_TYPELESS;
    d.ViewDimension = SRV_DIMENSION_BUFFEREX;
    d.BufferEx = {0, kResultWords, BUFFEREX_SRV_FLAG_RAW};
    *srv = device().CreateShaderResourceView(b.get(), &d);
    return b;
  }

  // Checks the records and visible lists of every partition against the CPU rule; returns the
  // expected survivors (caster indices) per partition.
  std::vector<std::set<uint32_t>> CheckRecords(const CasterCuller& culler, const scene::Scene& s, const glm::mat4& lightView,
                                               const std::vector<LightBounds>& bounds, float dilation) {
    const uint32_t K = uint32_t(bounds.size()), B = uint32_t(culler.batches().size()), n = culler.casterCount();
    std::vector<uint32_t> args = ReadAs<uint32_t>(ReadBuffer(device(), ctx(), culler.args()));
    std::vector<uint32_t> visible = ReadAs<uint32_t>(ReadBuffer(device(), ctx(), culler.visible()));
    std::vector<std::set<uint32_t>> expected(K);
    for (uint32_t p = 0; p < K; ++p)
      for (uint32_t b = 0; b < B; ++b) {
        const CasterCuller::Batch& batch = culler.batches()[b];
        std::set<uint32_t> expect;
        for (uint32_t c : batch.casters)
          if (Survives(s.instances[culler.sceneInstance(c)], lightView, bounds[p], dilation)) expect.insert(c);
        const uint32_t* rec = &args[(p * B + b) * 5];
        EXPECT_EQ(rec[0], batch.indexCount);
        EXPECT_EQ(rec[1], expect.size()) << "InstanceCount of partition " << p << " batch " << b;
        EXPECT_EQ(rec[2], batch.firstIndex);
        EXPECT_EQ(int32_t(rec[3]), batch.baseVertex);
        EXPECT_EQ(rec[4], 0u);
        std::set<uint32_t> got(visible.begin() + p * n + batch.listOffset, visible.begin() + p * n + batch.listOffset + std::min<size_t>(rec[1], batch.casters.size()));
        EXPECT_EQ(got, expect) << "visible list of partition " << p << " batch " << b;
        expected[p].insert(expect.begin(), expect.end());
      }
    return expected;
  }
};

const char* kIdPixelShader = R"(
struct CasterIdOut { float4 position : SV_Position; nointerpolation uint instance : INSTANCE; };
uint PSId(CasterIdOut v) : SV_Target { return v.instance + 1; }
)";

TEST_P(SdsmCullingTest, CulledInstancesGetNoInstancesAndIndirectDrawsRenderExactlyTheSurvivors) {
  scene::Scene s = Grid(false);
  scene::GpuScene gpu(device(), s);
  CasterCuller culler(device(), gpu);
  ASSERT_EQ(culler.batches().size(), 2u);
  // Instance 0 is a sphere, whose vertices and indices follow the box's in the scene buffers.
  EXPECT_NE(culler.batches()[0].baseVertex, 0);
  EXPECT_NE(culler.batches()[0].firstIndex, 0u);
  // Light straight down: light x = -world z, y = -world x, z = world y - 20.
  glm::mat4 lightView = MakeLightView({0, 20, 0}, {0, 0, -1}, {0, 1, 0}, {0, -1, 0});
  std::vector<LightBounds> bounds = {
      Box({-6.0f, -4.5f, -21.0f}, {2.2f, 8.0f, -19.0f}),  // a 3 x 3 block of instances
      Box({-20, -20, -30}, {20, 20, -25}),                 // receivers below everything: all cast
      Box({-20, -20, -10}, {20, 20, -9}),                  // receivers above everything: none cast
      Box({-20, -20, -30}, {20, 20, 0}, 0),                // no receiver at all
      Box({-1, -1, -21}, {1, 1, -19}),                     // between four instances: only dilation reaches them
  };
  AnalysisResults r;
  r.partitionCount = uint32_t(bounds.size());
  r.bounds = bounds;
  Ref<ShaderResourceView> srv;
  Ref<Buffer> results = ResultsBuffer(r, &srv);

  const std::vector<size_t> expectCounts[2] = {{9, 36, 0, 0, 0}, {9, 36, 0, 0, 4}};
  const float dilations[2] = {0.0f, 0.5f};
  for (int run = 0; run < 2; ++run) {
    SCOPED_TRACE("dilation " + std::to_string(dilations[run]));
    culler.Cull(ctx(), srv.get(), lightView, uint32_t(bounds.size()), dilations[run]);
    std::vector<std::set<uint32_t>> expected = CheckRecords(culler, s, lightView, bounds, dilations[run]);
    for (size_t p = 0; p < bounds.size(); ++p) EXPECT_EQ(expected[p].size(), expectCounts[run][p]) << "partition " << p;

    // Draw each partition over the whole grid and look at which instances appear.
    const uint32_t S = 64;
    Ref<Texture2D> target = MakeTexture2D(device(), S, S, FORMAT_R32_UINT, BIND_RENDER_TARGET);
    Ref<RenderTargetView> rtv = device().CreateRenderTargetView(target.get());
    Ref<PixelShader> ps = device().CreatePixelShader(CompileHlsl(kIdPixelShader, "ps_5_0", "PSId"));
    RASTERIZER_DESC rd;
    rd.CullMode = CULL_NONE;
    Ref<RasterizerState> rs = device().CreateRasterizerState(rd);
    glm::mat4 viewProj = PartitionProjection(Box({-12, -12, -22}, {12, 12, -18}), 0.0f) * lightView;
    for (uint32_t p = 0; p < bounds.size(); ++p) {
      const float zero[4] = {0, 0, 0, 0};
      ctx().ClearRenderTargetView(rtv.get(), zero);
      ctx().OMSetRenderTargets(1, std::vector<RenderTargetView*>{rtv.get()}.data(), nullptr);
      VIEWPORT vp{0, 0, float(S), float(S), 0, 1};
      ctx().RSSetViewports(1, &vp);
      ctx().RSSetState(rs.get());
      ctx().PSSetShader(ps.get());
      EXPECT_EQ(culler.DrawPartition(ctx(), p, viewProj, CasterCuller::Shader::InstanceId), 2u);
      ctx().OMSetRenderTargets(0, nullptr, nullptr);
      std::vector<uint32_t> px = ReadAs<uint32_t>(ReadTexture(device(), ctx(), target.get()));
      std::set<uint32_t> seen;
      for (uint32_t v : px)
        if (v) seen.insert(v - 1);
      EXPECT_EQ(seen, expected[p]) << "instances drawn for partition " << p;
      for (uint32_t c : expected[p]) {
        glm::vec4 clip = viewProj * glm::vec4(s.instances[culler.sceneInstance(c)].worldBounds.center(), 1.0f);
        uint32_t x = uint32_t((clip.x + 1) * 0.5f * S), y = uint32_t((1 - clip.y) * 0.5f * S);
        EXPECT_EQ(px[y * S + x], c + 1) << "centre of caster " << c << " in partition " << p;
      }
    }
  }
}

// The GPU-driven chain: camera depth rendered by the scene drawer, analysed, and culled from the
// analysis results on the GPU; the records match the CPU rule applied to the results read after.
TEST_P(SdsmCullingTest, CullsFromTheAnalysisOfARenderedDepthBufferWithoutReadback) {
  scene::Scene s = Grid(true);
  scene::GpuScene gpu(device(), s);
  tech::SceneDrawer drawer(device(), gpu);
  const uint32_t W = 160, H = 96;
  Ref<Texture2D> depth = MakeTexture2D(device(), W, H, FORMAT_R32_TYPELESS, BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE);
  DEPTH_STENCIL_VIEW_DESC dd;
  dd.Format = FORMAT_D32_FLOAT;
  dd.ViewDimension = DSV_DIMENSION_TEXTURE2D;
  Ref<DepthStencilView> dsv = device().CreateDepthStencilView(depth.get(), &dd);
  SHADER_RESOURCE_VIEW_DESC sd;
  sd.Format = FORMAT_R32_FLOAT;
  sd.ViewDimension = SRV_DIMENSION_TEXTURE2D;
  sd.Texture2D = {0, 1};
  Ref<ShaderResourceView> depthSrv = device().CreateShaderResourceView(depth.get(), &sd);
  RASTERIZER_DESC rd;
  rd.CullMode = CULL_NONE;
  Ref<RasterizerState> rs = device().CreateRasterizerState(rd);

  glm::mat4 view = s.camera.view(), proj = s.camera.projection(float(W) / H);
  ctx().ClearDepthStencilView(dsv.get(), CLEAR_DEPTH, 1.0f, 0);
  ctx().OMSetRenderTargets(0, nullptr, dsv.get());
  VIEWPORT vp{0, 0, float(W), float(H), 0, 1};
  ctx().RSSetViewports(1, &vp);
  ctx().RSSetState(rs.get());
  drawer.DrawDepth(ctx(), proj * view);
  ctx().OMSetRenderTargets(0, nullptr, nullptr);

  glm::mat4 lightView = MakeLightView(s.camera.position, s.camera.forward(), s.camera.up, s.light.direction);
  AnalysisFrame frame = AnalysisFrame::Make(view, proj, lightView, W, H);
  DepthAnalysis analysis(device());
  CasterCuller culler(device(), gpu);
  const uint32_t K = 4;
  analysis.Run(ctx(), depthSrv.get(), frame, {ReduceMode::Atomic, {PartitionScheme::AdaptiveLog, K}});
  culler.Cull(ctx(), analysis.resultsSrv(), lightView, K, 0.25f);

  AnalysisResults r = DecodeResults(ReadAs<uint32_t>(ReadBuffer(device(), ctx(), analysis.results())).data());
  ASSERT_TRUE(r.covered());
  ASSERT_EQ(r.bounds.size(), K);
  std::vector<std::set<uint32_t>> expected = CheckRecords(culler, s, lightView, r.bounds, 0.25f);
  // The camera sees part of the grid: near partitions keep some casters, and not every one.
  size_t kept = 0;
  for (const auto& e : expected) kept += e.size();
  EXPECT_GT(kept, 0u);
  EXPECT_LT(expected[0].size(), culler.casterCount());
}

SP_INSTANTIATE_BACKEND_TESTS(SdsmCullingTest);

}  // namespace
}  // namespace sp::test
