// All six cube faces in one pass (SceneDrawer::DrawDepthLayered, cube faces_pass=single) against
// the six per-face passes: the same depth bits in every face of the cube room, the same images,
// the same triangle count; and the refusals (no capability, storage=radial). Both backends, and
// the single-pass image identical across them.
#include "backend-test.h"
#include "technique-renderer.h"
#include "cross-backend.h"
#include "cube-room.h"
#include "cube/cube-faces.h"
#include <sp/tech/renderer.h>

namespace sp::test {
namespace {

class CubeLayeredTest : public BackendTest {
 public:
  std::unique_ptr<tech::Renderer> MakeRenderer(const scene::Scene& s, uint32_t w, uint32_t h, const std::map<std::string, std::string>& params) {
    return MakeTechniqueRenderer(device(), "cube", s, w, h, params);
  }
};

// The scene drawer on its own: the six faces of the room's light drawn face by face (DrawDepth
// into one slice DSV each) and in one layered pass, with the cube technique's rasterizer state;
// every texel of every face must hold the same float.
TEST_P(CubeLayeredTest, OneLayeredPassWritesTheSameDepthBitsAsSixFacePasses) {
  if (!device().Info().vsRenderTargetArrayIndex) GTEST_SKIP() << "device lacks vsRenderTargetArrayIndex";
  const uint32_t N = 128;
  CubeRoom room = MakeCubeRoom();
  scene::GpuScene gpu(device(), room.scene);
  tech::SceneDrawer drawer(device(), gpu);
  const scene::PointLight& pl = room.scene.pointLights[0];
  const float nearZ = 0.05f;
  glm::mat4 viewProj[6];
  for (int f = 0; f < 6; ++f) viewProj[f] = tech::cube::FaceViewProj(f, pl.position, nearZ, pl.range);
  // The six walls (instances 0-5) in every face, a sphere only in the face of its centre: not
  // the technique's culling, but a different instance list per layer, which is what matters.
  auto keep = [&](uint32_t i, uint32_t f) {
    const scene::Bounds& b = room.scene.instances[i].worldBounds;
    return i < 6 || tech::cube::FaceOf((b.min + b.max) * 0.5f - pl.position) == int(f);
  };

  Ref<Texture2D> perFace, layered;
  for (Ref<Texture2D>* t : {&perFace, &layered})
    *t = MakeTexture2D(device(), N, N, FORMAT_R32_TYPELESS, BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE, nullptr, 1, 6, 1, RESOURCE_MISC_TEXTURECUBE);
  RASTERIZER_DESC rd;
  rd.CullMode = CULL_NONE;
  rd.FrontCounterClockwise = true;
  rd.DepthBias = 200;
  rd.SlopeScaledDepthBias = 2.0f;
  Ref<RasterizerState> rs = device().CreateRasterizerState(rd);
  VIEWPORT vp{0, 0, float(N), float(N), 0, 1};
  ctx().RSSetViewports(1, &vp);
  ctx().RSSetState(rs.get());

  std::vector<Ref<DepthStencilView>> faces = tech::MakeSliceDepthViews(device(), perFace.get());
  uint64_t trianglesPerFace = 0;
  for (uint32_t f = 0; f < 6; ++f) {
    ctx().OMSetRenderTargets(0, nullptr, faces[f].get());
    ctx().ClearDepthStencilView(faces[f].get(), CLEAR_DEPTH, 1.0f, 0);
    trianglesPerFace += drawer.DrawDepth(ctx(), viewProj[f], [&](uint32_t i) { return keep(i, f); });
  }
  DEPTH_STENCIL_VIEW_DESC dv;
  dv.Format = FORMAT_D32_FLOAT;
  dv.ViewDimension = DSV_DIMENSION_TEXTURE2DARRAY;
  dv.Texture2DArray = {0, 0, 6};
  Ref<DepthStencilView> all = device().CreateDepthStencilView(layered.get(), &dv);
  ctx().OMSetRenderTargets(0, nullptr, all.get());
  ctx().ClearDepthStencilView(all.get(), CLEAR_DEPTH, 1.0f, 0);
  uint64_t trianglesLayered = drawer.DrawDepthLayered(ctx(), viewProj, 6, keep);
  ctx().OMSetRenderTargets(0, nullptr, nullptr);
  EXPECT_EQ(trianglesLayered, trianglesPerFace);

  size_t differing = 0, covered = 0;
  for (uint32_t f = 0; f < 6; ++f) {
    std::vector<uint32_t> a = ReadAs<uint32_t>(ReadTexture(device(), ctx(), perFace.get(), f));
    std::vector<uint32_t> b = ReadAs<uint32_t>(ReadTexture(device(), ctx(), layered.get(), f));
    ASSERT_EQ(a.size(), size_t(N) * N);
    ASSERT_EQ(b.size(), a.size());
    size_t faceDiff = 0, faceSpheres = 0;
    for (size_t i = 0; i < a.size(); ++i) {
      faceDiff += a[i] != b[i];
      // Texels nearer than the walls (the room is at least 2.4 from the light) hold a sphere.
      float d;
      std::memcpy(&d, &a[i], 4);
      faceSpheres += d < tech::cube::WindowZ({2.0f, 0, 0}, nearZ, pl.range);
      covered += d < 1.0f;
    }
    EXPECT_EQ(faceDiff, 0u) << "face " << f;
    EXPECT_GT(faceSpheres, 50u) << "face " << f << " should show its sphere";
    differing += faceDiff;
  }
  EXPECT_EQ(covered, size_t(6) * N * N) << "the walls cover every texel of every face";
  EXPECT_EQ(differing, 0u);
}

// The technique: images of the room from three cameras (all six faces sampled) identical with
// faces_pass=single and per_face, the same triangles submitted, with face culling on and off.
TEST_P(CubeLayeredTest, SinglePassCubeRendersTheSameImagesAsPerFacePasses) {
  if (!device().Info().vsRenderTargetArrayIndex) GTEST_SKIP() << "device lacks vsRenderTargetArrayIndex";
  const uint32_t W = 128, H = 96;
  CubeRoom room = MakeCubeRoom();
  for (const char* cull : {"1", "0"}) {
    std::unique_ptr<tech::Renderer> r[2] = {MakeRenderer(room.scene, W, H, {{"resolution", "256"}, {"cull_faces", cull}}),
                                            MakeRenderer(room.scene, W, H, {{"resolution", "256"}, {"cull_faces", cull}, {"faces_pass", "single"}})};
    for (const scene::Camera& cam : RoomCameras(room)) {
      std::vector<uint8_t> img[2];
      uint64_t triangles[2];
      for (int i = 0; i < 2; ++i) {
        r[i]->RenderFrame(cam, room.scene.light);
        img[i] = r[i]->ReadColor();
        triangles[i] = r[i]->technique().Stats().trianglesSubmitted;
      }
      EXPECT_EQ(triangles[1], triangles[0]) << "cull_faces=" << cull;
      EXPECT_EQ(CompareImages(std::string("faces-pass-cull") + cull, W, H, img[0].data(), img[1].data(), 0), 0u) << "cull_faces=" << cull;
      // And the picture is the room's exact shadows, not two equally wrong images.
      RoomCheck c = CheckRoomImage(room, cam, img[1], W, H);
      EXPECT_EQ(c.wrong, 0) << "of " << c.checked;
    }
  }
}

SP_INSTANTIATE_BACKEND_TESTS(CubeLayeredTest);

// Bad input refused by name, no pixels checked: these run on the null backend too.
class CubeLayeredValidationTest : public CubeLayeredTest {};

TEST_P(CubeLayeredValidationTest, SinglePassNeedsTheCapabilityAndDepthStorage) {
  ExpectConfigureRefused(device(), "cube", {{"faces_pass", "single"}, {"storage", "radial"}}, "faces_pass=single needs storage=depth");
  DeviceDesc dd;
  dd.backend = backend();
  dd.disableVsRenderTargetArrayIndex = true;
  Ref<Device> dev = CreateDevice(dd);
  ExpectConfigureRefused(*dev, "cube", {{"faces_pass", "single"}}, "vsRenderTargetArrayIndex");
  ExpectConfigureRefused(*dev, "cube", {{"faces_pass", "single"}}, BackendName(backend()));
  // per_face still works there, drawer included.
  CubeRoom room = MakeCubeRoom();
  tech::Renderer r(*dev, room.scene, MakeConfiguredTechnique(*dev, "cube", {{"resolution", "64"}}), 32, 32);
  EXPECT_NO_THROW(r.RenderFrame(room.scene.camera, room.scene.light));
  EXPECT_EQ(dev->ValidationErrorCount(), 0u) << dev->LastValidationError();
}

SP_INSTANTIATE_VALIDATION_TESTS(CubeLayeredValidationTest);

TEST(CubeLayeredCrossBackend, SinglePassRoomRendersIdenticallyOnBothBackends) {
  const uint32_t W = 160, H = 120;
  CubeRoom room = MakeCubeRoom();
  CrossBackendFrame f = RenderOnBothBackends("cube", {{"resolution", "256"}, {"faces_pass", "single"}}, room.scene, W, H);
  size_t differing = CompareImages("cube-room-single", W, H, f.images[0].data(), f.images[1].data(), 0);
  if (f.mesa) EXPECT_EQ(differing, 0u) << "Vulkan and GL images differ on Mesa; see the heat map in " << TestOutputDir();
  else EXPECT_LT(differing, size_t(W * H / 200)) << "more than 0.5% of pixels differ across backends";
}

}  // namespace
}  // namespace sp::test
