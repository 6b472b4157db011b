// The null backend (backends/null): a device without a driver that validates every call like the
// others and then does nothing. Checked here: it starts and works with every driver made
// unreachable and loads no shared object; it offers what Direct3D 11 feature level 11_0
// guarantees; Map hands out the subresource's memory; readbacks give zeros, never a picture;
// queries answer at once and empty; the core's own errors still reach the fixture; the CLI
// refuses it for rendering (tests/CMakeLists.txt).
#include <cstring>
#include <fstream>
#include <set>

#include "rhi-test-util.h"

namespace sp::test {
namespace {

// Every shared object mapped into this process.
std::set<std::string> MappedLibraries() {
  std::set<std::string> libs;
  std::ifstream maps("/proc/self/maps");
  std::string line;
  while (std::getline(maps, line)) {
    size_t slash = line.find('/');
    if (slash != std::string::npos && line.find(".so", slash) != std::string::npos) libs.insert(line.substr(slash));
  }
  return libs;
}

// Exercises a device the way the validation tests do: resources, views, shaders, a draw, a map.
void UseDevice(Device& dev) {
  DeviceContext& ctx = *dev.GetImmediateContext();
  Target t = MakeTarget(dev, 8, 8, FORMAT_R8G8B8A8_UNORM);
  const char* src = "float4 VS(uint id : SV_VertexID) : SV_Position { return float4(0, 0, 0, 1); }\n"
                    "float4 PS(float4 p : SV_Position) : SV_Target { return 1; }\n";
  Ref<VertexShader> vs = dev.CreateVertexShader(CompileHlsl(src, "vs_5_0", "VS"));
  Ref<PixelShader> ps = dev.CreatePixelShader(CompileHlsl(src, "ps_5_0", "PS"));
  RenderTargetView* rtvs[] = {t.rtv.get()};
  ctx.OMSetRenderTargets(1, rtvs, nullptr);
  SetViewport(ctx, 8, 8);
  ctx.IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  ctx.VSSetShader(vs.get());
  ctx.PSSetShader(ps.get());
  ctx.Draw(3, 0);
  ReadTexture(dev, ctx, t.texture.get());
  ctx.ClearState();
}

TEST(NullDevice, NeedsNoDriverAndLoadsNoLibrary) {
  // Nothing a Vulkan loader or libglvnd could find a driver with.
  ScopedEnv icd("VK_ICD_FILENAMES", "/nonexistent/icd.json"), drivers("VK_DRIVER_FILES", "/nonexistent/icd.json");
  ScopedEnv egl("EGL_PLATFORM", "bogus"), vendors("__EGL_VENDOR_LIBRARY_FILENAMES", "/nonexistent/egl.json");
  ScopedEnv dri("LIBGL_DRIVERS_PATH", "/nonexistent"), display("DISPLAY", std::nullopt), wayland("WAYLAND_DISPLAY", std::nullopt);
  const std::set<std::string> before = MappedLibraries();
  DeviceDesc dd;
  dd.backend = Backend::Null;
  std::vector<std::string> errors;
  dd.messageCallback = [&](MessageSeverity s, std::string_view t) {
    if (s == MessageSeverity::Error) errors.emplace_back(t);
  };
  Ref<Device> dev = CreateDevice(dd);
  UseDevice(*dev);
  dev.reset();
  for (const std::string& lib : MappedLibraries())
    EXPECT_TRUE(before.count(lib)) << "a null device loaded " << lib;
  EXPECT_TRUE(errors.empty()) << errors.front();
  // The environment above does keep a real driver from starting.
  dd.backend = Backend::Vulkan;
  try {
    CreateDevice(dd);
    ADD_FAILURE() << "a Vulkan device started with VK_ICD_FILENAMES pointing at nothing";
  } catch (const Error& e) {
    EXPECT_EQ(e.id(), ErrorId::DEVICE_CREATION_FAILED) << e.what();
  }
}

TEST(NullDevice, IsNamedNull) {
  Backend b = Backend::Vulkan;
  EXPECT_TRUE(ParseBackend("null", &b));
  EXPECT_EQ(b, Backend::Null);
  EXPECT_STREQ(BackendName(Backend::Null), "null");
}

// The limits come from D3D11's feature level 11_0 requirements, not from any driver.
TEST(NullDevice, OffersWhatFeatureLevel11Guarantees) {
  DeviceDesc dd;
  dd.backend = Backend::Null;
  Ref<Device> dev = CreateDevice(dd);
  const DeviceInfo& info = dev->Info();
  EXPECT_EQ(info.backend, Backend::Null);
  EXPECT_EQ(info.maxMsaaSamples, 8u);  // 8x for every render-target format up to 64 bits
  EXPECT_TRUE(info.depthBiasClamp);
  EXPECT_EQ(info.depthBiasScaleD16, 1.0f);  // nothing to calibrate: D3D11's own units
  EXPECT_EQ(info.depthBiasScaleD24, 1.0f);
  EXPECT_EQ(info.depthBiasScaleD32, 1.0f);
  const uint32_t rgba8 = dev->CheckFormatSupport(FORMAT_R8G8B8A8_UNORM);
  for (uint32_t bit : {FORMAT_SUPPORT_TEXTURE2D, FORMAT_SUPPORT_TEXTURE3D, FORMAT_SUPPORT_TEXTURECUBE, FORMAT_SUPPORT_RENDER_TARGET,
                       FORMAT_SUPPORT_BLENDABLE, FORMAT_SUPPORT_SHADER_SAMPLE, FORMAT_SUPPORT_TYPED_UNORDERED_ACCESS_VIEW,
                       FORMAT_SUPPORT_MULTISAMPLE_RENDERTARGET, FORMAT_SUPPORT_MULTISAMPLE_RESOLVE, FORMAT_SUPPORT_IA_VERTEX_BUFFER})
    EXPECT_TRUE(rgba8 & bit) << std::hex << bit;
  EXPECT_FALSE(rgba8 & FORMAT_SUPPORT_DEPTH_STENCIL);
  EXPECT_FALSE(rgba8 & FORMAT_SUPPORT_IA_INDEX_BUFFER);
  const uint32_t r32u = dev->CheckFormatSupport(FORMAT_R32_UINT);
  EXPECT_TRUE(r32u & FORMAT_SUPPORT_IA_INDEX_BUFFER);
  EXPECT_FALSE(r32u & FORMAT_SUPPORT_SHADER_SAMPLE);  // integers are loaded, not filtered
  EXPECT_FALSE(r32u & FORMAT_SUPPORT_BLENDABLE);
  const uint32_t d24 = dev->CheckFormatSupport(FORMAT_D24_UNORM_S8_UINT);
  EXPECT_TRUE(d24 & FORMAT_SUPPORT_DEPTH_STENCIL);
  EXPECT_FALSE(d24 & (FORMAT_SUPPORT_RENDER_TARGET | FORMAT_SUPPORT_TEXTURE3D));
  EXPECT_TRUE(dev->CheckFormatSupport(FORMAT_R24_UNORM_X8_TYPELESS) & FORMAT_SUPPORT_SHADER_SAMPLE_COMPARISON);
  EXPECT_FALSE(dev->CheckFormatSupport(FORMAT_R8G8B8A8_UNORM_SRGB) & FORMAT_SUPPORT_TYPED_UNORDERED_ACCESS_VIEW);
  EXPECT_FALSE(dev->CheckFormatSupport(FORMAT_B8G8R8A8_UNORM) & FORMAT_SUPPORT_TYPED_UNORDERED_ACCESS_VIEW);  // optional on 11_0
  EXPECT_FALSE(dev->CheckFormatSupport(FORMAT_R32G32B32_FLOAT) & FORMAT_SUPPORT_TEXTURE2D);  // ShadowPort's backends cannot
  EXPECT_EQ(dev->CheckMultisampleQualityLevels(FORMAT_R32G32B32A32_FLOAT, 4), 1u);
  EXPECT_EQ(dev->CheckMultisampleQualityLevels(FORMAT_R32G32B32A32_FLOAT, 8), 0u);  // 128-bit formats: 4x only
  EXPECT_EQ(dev->CheckMultisampleQualityLevels(FORMAT_D32_FLOAT, 8), 1u);
  EXPECT_EQ(dev->CheckMultisampleQualityLevels(FORMAT_R8G8B8A8_UNORM, 6), 0u);
  // The largest 11_0 texture costs nothing on a device that stores nothing.
  EXPECT_NO_THROW(MakeTexture2D(*dev, 16384, 16384, FORMAT_R32G32B32A32_FLOAT, BIND_RENDER_TARGET | BIND_SHADER_RESOURCE));
}

// Map hands out writable memory of the subresource's size in D3D11's tight layout, and keeps what
// the CPU wrote; GPU work never reaches it, so a readback of a cleared target is zeros.
TEST(NullDevice, MapGivesTheSubresourceAndReadbacksGiveZeros) {
  DeviceDesc dd;
  dd.backend = Backend::Null;
  Ref<Device> dev = CreateDevice(dd);
  DeviceContext& ctx = *dev->GetImmediateContext();
  TEXTURE3D_DESC td;
  td.Width = 5;
  td.Height = 3;
  td.Depth = 4;
  td.MipLevels = 2;
  td.Format = FORMAT_R16G16B16A16_FLOAT;
  td.Usage = USAGE_STAGING;
  td.CPUAccessFlags = CPU_ACCESS_READ | CPU_ACCESS_WRITE;
  Ref<Texture3D> vol = dev->CreateTexture3D(td);
  MAPPED_SUBRESOURCE m;
  ASSERT_TRUE(ctx.Map(vol.get(), 1, MAP_WRITE, 0, &m));  // mip 1: 2 x 1 x 2 texels of 8 bytes
  EXPECT_EQ(m.RowPitch, 16u);
  EXPECT_EQ(m.DepthPitch, 16u);
  std::memset(m.pData, 0xab, 32);
  ctx.Unmap(vol.get(), 1);
  ASSERT_TRUE(ctx.Map(vol.get(), 1, MAP_READ, MAP_FLAG_DO_NOT_WAIT, &m));
  EXPECT_EQ(static_cast<const uint8_t*>(m.pData)[31], 0xab);
  ctx.Unmap(vol.get(), 1);

  BUFFER_DESC bd;
  bd.ByteWidth = 100;
  bd.Usage = USAGE_DYNAMIC;
  bd.BindFlags = BIND_VERTEX_BUFFER;
  bd.CPUAccessFlags = CPU_ACCESS_WRITE;
  Ref<Buffer> vb = dev->CreateBuffer(bd);
  ASSERT_TRUE(ctx.Map(vb.get(), 0, MAP_WRITE_DISCARD, 0, &m));
  EXPECT_EQ(m.RowPitch, 100u);
  std::memset(m.pData, 1, 100);
  ctx.Unmap(vb.get(), 0);

  Target t = MakeTarget(*dev, 4, 4, FORMAT_R8G8B8A8_UNORM);
  const float white[4] = {1, 1, 1, 1};
  ctx.ClearRenderTargetView(t.rtv.get(), white);
  std::vector<uint8_t> px = ReadTexture(*dev, ctx, t.texture.get());
  ASSERT_EQ(px.size(), 4u * 4 * 4);
  for (uint8_t v : px) EXPECT_EQ(v, 0);
}

// Results are ready at once and empty: no samples, every timestamp 0, so every pass takes 0 ms.
TEST(NullDevice, QueriesAnswerAtOnceAndEmpty) {
  DeviceDesc dd;
  dd.backend = Backend::Null;
  Ref<Device> dev = CreateDevice(dd);
  DeviceContext& ctx = *dev->GetImmediateContext();
  auto make = [&](QUERY kind) {
    QUERY_DESC qd;
    qd.Query = kind;
    return dev->CreateQuery(qd);
  };
  Ref<Query> event = make(QUERY_EVENT), occlusion = make(QUERY_OCCLUSION), stamp = make(QUERY_TIMESTAMP), disjoint = make(QUERY_TIMESTAMP_DISJOINT);
  ctx.Begin(disjoint.get());
  ctx.Begin(occlusion.get());
  ctx.End(occlusion.get());
  ctx.End(stamp.get());
  ctx.End(disjoint.get());
  ctx.End(event.get());
  uint32_t done = 0;
  EXPECT_EQ(ctx.GetData(event.get(), &done, sizeof(done), 0), S_OK);
  EXPECT_EQ(done, 1u);
  uint64_t samples = 7, ticks = 7;
  EXPECT_EQ(ctx.GetData(occlusion.get(), &samples, sizeof(samples), 0), S_OK);
  EXPECT_EQ(samples, 0u);
  EXPECT_EQ(ctx.GetData(stamp.get(), &ticks, sizeof(ticks), 0), S_OK);
  EXPECT_EQ(ticks, 0u);
  QUERY_DATA_TIMESTAMP_DISJOINT dj;
  EXPECT_EQ(ctx.GetData(disjoint.get(), &dj, sizeof(dj), 0), S_OK);
  EXPECT_FALSE(dj.Disjoint);
  EXPECT_EQ(dj.Frequency, dev->Info().timestampFrequency);
}

// The fixture's hook: without driver messages, the core's own errors still reach
// validationMessages, which fail the test in TearDown.
class NullFixtureTest : public BackendTest {};

TEST_P(NullFixtureTest, CoreErrorsReachTheFixture) {
  TEXTURE2D_DESC td;
  td.Width = 0;
  td.Height = 4;
  td.Format = FORMAT_R8G8B8A8_UNORM;
  td.BindFlags = BIND_SHADER_RESOURCE;
  Texture2D* tex = nullptr;
  EXPECT_EQ(device().CreateTexture2D(&td, nullptr, &tex), E_INVALIDARG);
  ASSERT_EQ(validationMessages.size(), 1u);
  EXPECT_NE(validationMessages[0].find("CreateTexture2D"), std::string::npos) << validationMessages[0];
  validationMessages.clear();  // provoked on purpose
}

INSTANTIATE_TEST_SUITE_P(Backends, NullFixtureTest, ::testing::Values(Backend::Null), BackendParamName);

}  // namespace
}  // namespace sp::test
