// The viewer's ImGui renderer on both backends (validation on), 256x256 offscreen: a frame of known
// primitives comes out as a CPU rasterisation of the same primitives says (D3D11's top-left rule,
// SrcAlpha / InvSrcAlpha blending with UNORM rounding, the sRGB encode of an _SRGB target):
//  - opaque rectangles, coloured through the font atlas's white texel, one of them cut by a clip
//    rectangle (the scissor);
//  - a half-transparent rectangle over them and the background;
//  - a 2x2 picture passed as an ImTextureID (a ShaderResourceView), its texel centres on pixel
//    centres, so a flipped or mirrored picture fails;
//  - an asymmetric triangle, so a flipped image fails;
//  - 20480 one-pixel rectangles of distinct colours in a second draw list: more than 65536 vertices,
//    so ImGui splits them with VtxOffset, and the second list checks the global offsets.
// Both backends draw the same image (an extra check).
#include "backend-test.h"

#include <cmath>
#include <functional>

#include "imgui-renderer.h"
#include "imgui-test-context.h"

namespace sp::test {
namespace {

constexpr int kSize = 256;
constexpr uint8_t kClear[4] = {10, 20, 30, 255};
constexpr uint8_t kPicture[4][4] = {{250, 0, 0, 255}, {0, 250, 0, 255}, {0, 0, 250, 255}, {250, 250, 250, 255}};  // 2x2, row-major

struct Image {
  std::vector<uint8_t> rgba = std::vector<uint8_t>(size_t(kSize) * kSize * 4);
  std::vector<int> tolerance = std::vector<int>(size_t(kSize) * kSize, 0);  // per pixel
  uint8_t* at(int x, int y) { return &rgba[(size_t(y) * kSize + size_t(x)) * 4]; }
};

double Decode(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }
double Encode(double l) { return l <= 0.0031308 ? l * 12.92 : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055; }
uint8_t Unorm(double v) { return uint8_t(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); }

// SrcAlpha / InvSrcAlpha for colour, One / InvSrcAlpha for alpha (imgui-renderer.cpp); on an sRGB
// target the shader's colour and the destination are linear values and the result is encoded.
void Blend(Image& img, int x, int y, const double src[4], bool srgb, int tolerance) {
  uint8_t* d = img.at(x, y);
  double a = src[3];
  for (int c = 0; c < 3; ++c) {
    double s = srgb ? Decode(src[c]) : src[c], dst = srgb ? Decode(d[c] / 255.0) : d[c] / 255.0;
    double v = s * a + dst * (1.0 - a);
    d[c] = Unorm(srgb ? Encode(v) : v);
  }
  d[3] = Unorm(a + d[3] / 255.0 * (1.0 - a));
  img.tolerance[size_t(y) * kSize + size_t(x)] = tolerance;
}

void Color(ImU32 c, double out[4]) {
  for (int i = 0; i < 4; ++i) out[i] = double((c >> (8 * i)) & 0xff) / 255.0;
}

// Pixels whose centre lies in the triangle by D3D11's top-left rule (y down the screen).
void RasterizeTriangle(ImVec2 a, ImVec2 b, ImVec2 c, const std::function<void(int, int)>& pixel) {
  auto cross = [](ImVec2 p, ImVec2 q, ImVec2 r) { return double(q.x - p.x) * (r.y - p.y) - double(q.y - p.y) * (r.x - p.x); };
  if (cross(a, b, c) < 0) std::swap(b, c);  // clockwise on screen
  const ImVec2 v[3] = {a, b, c};
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      ImVec2 p(float(x) + 0.5f, float(y) + 0.5f);
      bool inside = true;
      for (int e = 0; e < 3 && inside; ++e) {
        ImVec2 s = v[e], t = v[(e + 1) % 3];
        double dx = t.x - s.x, dy = t.y - s.y;
        double w = (p.y - s.y) * dx - (p.x - s.x) * dy;
        bool topLeft = (dy == 0 && dx > 0) || dy < 0;
        inside = w > 0 || (w == 0 && topLeft);
      }
      if (inside) pixel(x, y);
    }
}

// Draws the test frame into a fresh target of `format`; returns its pixels and fills `expected`.
std::vector<uint8_t> DrawFrame(Device& device, FORMAT format, Image* expected) {
  DeviceContext& ctx = *device.GetImmediateContext();
  viewer::ImGuiRenderer renderer(device, format);
  Ref<Texture2D> pictureTexture = MakeTexture2D(device, 2, 2, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE, kPicture);
  Ref<ShaderResourceView> picture = device.CreateShaderResourceView(pictureTexture.get());
  const bool srgb = GetFormatInfo(format).kind == FormatKind::UNormSRGB;
  Image& img = *expected;
  for (int i = 0; i < kSize * kSize; ++i) std::memcpy(&img.rgba[size_t(i) * 4], kClear, 4);

  ImGui::NewFrame();
  ImDrawList* back = ImGui::GetBackgroundDrawList();
  ImDrawList* front = ImGui::GetForegroundDrawList();
  auto rect = [&](ImVec2 lo, ImVec2 hi, ImU32 col, ImVec2 clipLo, ImVec2 clipHi, int tol) {
    double c[4];
    Color(col, c);
    for (int y = int(std::max(lo.y, clipLo.y)); y < int(std::min(hi.y, clipHi.y)); ++y)
      for (int x = int(std::max(lo.x, clipLo.x)); x < int(std::min(hi.x, clipHi.x)); ++x) Blend(img, x, y, c, srgb, tol);
  };
  const ImVec2 all(0, 0), allHi(kSize, kSize);
  back->AddRectFilled({16, 16}, {80, 64}, IM_COL32(255, 0, 0, 255));
  rect({16, 16}, {80, 64}, IM_COL32(255, 0, 0, 255), all, allHi, srgb ? 1 : 0);
  back->PushClipRect({100, 16}, {140, 60});
  back->AddRectFilled({90, 10}, {160, 80}, IM_COL32(0, 200, 0, 255));
  back->PopClipRect();
  rect({90, 10}, {160, 80}, IM_COL32(0, 200, 0, 255), {100, 16}, {140, 60}, srgb ? 1 : 0);
  // Blending rounds once in the driver and once here: one step apart at most.
  back->AddRectFilled({40, 40}, {120, 100}, IM_COL32(0, 0, 255, 128));
  rect({40, 40}, {120, 100}, IM_COL32(0, 0, 255, 128), all, allHi, 1);
  // 66 pixels across 2 texels: pixels 16 and 49 of the quad sample the texel centres exactly
  // (u = 16.5 / 66 = 0.25, 49.5 / 66 = 0.75); the others blend neighbours and are not checked.
  const ImVec2 pic(150, 10);
  back->AddImage(viewer::ImGuiRenderer::TextureId(picture.get()), pic, {pic.x + 66, pic.y + 66});
  for (int y = 0; y < 66; ++y)
    for (int x = 0; x < 66; ++x) img.tolerance[size_t(pic.y + y) * kSize + size_t(pic.x + x)] = 255;
  for (int ty = 0; ty < 2; ++ty)
    for (int tx = 0; tx < 2; ++tx) {
      double c[4];
      for (int i = 0; i < 4; ++i) c[i] = kPicture[ty * 2 + tx][i] / 255.0;
      Blend(img, int(pic.x) + (tx ? 49 : 16), int(pic.y) + (ty ? 49 : 16), c, srgb, 1);
    }
  const ImVec2 ta(140, 90), tb(250, 100), tc(160, 170);
  back->AddTriangleFilled(ta, tb, tc, IM_COL32(255, 255, 0, 255));
  RasterizeTriangle(ta, tb, tc, [&](int x, int y) {
    double c[4];
    Color(IM_COL32(255, 255, 0, 255), c);
    Blend(img, x, y, c, srgb, srgb ? 1 : 0);
  });
  for (int y = 176; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      ImU32 col = IM_COL32(x, y, (x * 7 + y * 3) & 255, 255);
      front->AddRectFilled({float(x), float(y)}, {float(x + 1), float(y + 1)}, col);
      rect({float(x), float(y)}, {float(x + 1), float(y + 1)}, col, all, allHi, srgb ? 1 : 0);
    }
  ImGui::Render();
  ImDrawData* dd = ImGui::GetDrawData();
  EXPECT_GT(dd->TotalVtxCount, 65536) << "the frame must need VtxOffset";
  int offsetCmds = 0;
  for (int n = 0; n < dd->CmdListsCount; ++n)
    for (const ImDrawCmd& c : dd->CmdLists[n]->CmdBuffer) offsetCmds += c.VtxOffset > 0;
  EXPECT_GT(offsetCmds, 0) << "no draw command used VtxOffset";

  Ref<Texture2D> target = MakeTexture2D(device, kSize, kSize, format, BIND_RENDER_TARGET);
  Ref<RenderTargetView> rtv = device.CreateRenderTargetView(target.get());
  const float clear[4] = {float(srgb ? Decode(kClear[0] / 255.0) : kClear[0] / 255.0), float(srgb ? Decode(kClear[1] / 255.0) : kClear[1] / 255.0),
                          float(srgb ? Decode(kClear[2] / 255.0) : kClear[2] / 255.0), 1.0f};
  ctx.ClearRenderTargetView(rtv.get(), clear);
  renderer.Render(ctx, rtv.get(), dd);
  EXPECT_GE(renderer.VertexCapacity(), uint32_t(dd->TotalVtxCount));
  std::vector<uint8_t> got = ReadTexture(device, ctx, target.get());
  // A second frame through the same (now large enough) buffers draws the same.
  ctx.ClearRenderTargetView(rtv.get(), clear);
  renderer.Render(ctx, rtv.get(), dd);
  EXPECT_EQ(ReadTexture(device, ctx, target.get()), got) << "second frame";
  return got;
}

// Pixels outside their tolerance; writes the images for a look on failure.
size_t Check(const std::string& name, Backend backend, const std::vector<uint8_t>& got, const Image& want) {
  size_t bad = 0, checked = 0;
  int worst = 0;
  for (size_t i = 0; i < size_t(kSize) * kSize; ++i) {
    if (want.tolerance[i] >= 255) continue;
    ++checked;
    int d = 0;
    for (int c = 0; c < 4; ++c) d = std::max(d, std::abs(int(got[i * 4 + c]) - int(want.rgba[i * 4 + c])));
    worst = std::max(worst, d);
    if (d > want.tolerance[i]) {
      if (bad < 5)
        ADD_FAILURE() << name << ": pixel (" << i % kSize << ", " << i / kSize << ") is " << int(got[i * 4]) << "," << int(got[i * 4 + 1]) << ","
                      << int(got[i * 4 + 2]) << "," << int(got[i * 4 + 3]) << ", expected " << int(want.rgba[i * 4]) << "," << int(want.rgba[i * 4 + 1])
                      << "," << int(want.rgba[i * 4 + 2]) << "," << int(want.rgba[i * 4 + 3]);
      ++bad;
    }
  }
  std::printf("[ imgui ] %s on %s: %zu of %zu pixels checked differ beyond their tolerance (largest difference %d)\n", name.c_str(),
              BackendTestName(backend).c_str(), bad, checked, worst);
  if (bad) {
    WritePng(TestOutputDir() / (name + "-got.png"), kSize, kSize, got.data());
    WritePng(TestOutputDir() / (name + "-expected.png"), kSize, kSize, want.rgba.data());
  }
  return bad;
}

class ImGuiRendererTest : public BackendTest {
 protected:
  ImGuiTestContext imgui_{kSize, kSize};
};

TEST_P(ImGuiRendererTest, DrawsKnownPrimitivesAsTheCpuRasterisesThem) {
  Image want;
  std::vector<uint8_t> got = DrawFrame(device(), FORMAT_R8G8B8A8_UNORM, &want);
  EXPECT_EQ(Check("unorm", backend(), got, want), 0u);
}

TEST_P(ImGuiRendererTest, KeepsImGuiColoursOnAnSrgbTarget) {
  Image want;
  std::vector<uint8_t> got = DrawFrame(device(), FORMAT_R8G8B8A8_UNORM_SRGB, &want);
  EXPECT_EQ(Check("srgb", backend(), got, want), 0u);
  // The red rectangle's interior holds ImGui's bytes, not their sRGB encoding.
  EXPECT_EQ(got[(size_t(30) * kSize + 30) * 4 + 0], 255);
  EXPECT_EQ(got[(size_t(30) * kSize + 100) * 4 + 1], 200) << "the green rectangle";
}

TEST_P(ImGuiRendererTest, RefusesAViewOfAnotherFormat) {
  viewer::ImGuiRenderer renderer(device(), FORMAT_R8G8B8A8_UNORM);
  Ref<Texture2D> target = MakeTexture2D(device(), 16, 16, FORMAT_R8G8B8A8_UNORM_SRGB, BIND_RENDER_TARGET);
  Ref<RenderTargetView> rtv = device().CreateRenderTargetView(target.get());
  ImGui::NewFrame();
  ImGui::GetBackgroundDrawList()->AddRectFilled({0, 0}, {4, 4}, IM_COL32_WHITE);
  ImGui::Render();
  try {
    renderer.Render(ctx(), rtv.get(), ImGui::GetDrawData());
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("R8G8B8A8_UNORM_SRGB but the renderer was made for R8G8B8A8_UNORM"), std::string::npos) << e.what();
  }
  EXPECT_THROW(viewer::ImGuiRenderer(device(), FORMAT_R32_FLOAT), std::invalid_argument);
}

SP_INSTANTIATE_BACKEND_TESTS(ImGuiRendererTest);

// Both backends draw the frame to the same bytes.
TEST(ImGuiRendererCrossBackend, BothBackendsDrawTheSameImage) {
  std::vector<uint8_t> images[2];
  const Backend backends[2] = {Backend::Vulkan, Backend::OpenGL};
  for (int b = 0; b < 2; ++b) {
    DeviceDesc dd;
    dd.backend = backends[b];
    dd.debug = true;
    dd.shaderCacheDir = TestShaderCacheDir();
    std::vector<std::string> errors;
    dd.messageCallback = [&](MessageSeverity s, std::string_view text) {
      if (s == MessageSeverity::Error) errors.emplace_back(text);
    };
    Ref<Device> device = CreateDevice(dd);
    {
      ImGuiTestContext imgui(kSize, kSize);
      Image want;
      images[b] = DrawFrame(*device, FORMAT_R8G8B8A8_UNORM, &want);
    }
    device->GetImmediateContext()->ClearState();
    device->GetImmediateContext()->WaitIdle();
    device.reset();
    for (const std::string& e : errors) ADD_FAILURE() << BackendName(backends[b]) << ": validation error: " << e;
  }
  EXPECT_EQ(CompareImages("vulkan-vs-gl", kSize, kSize, images[0].data(), images[1].data(), 0), 0u);
}

}  // namespace
}  // namespace sp::test
