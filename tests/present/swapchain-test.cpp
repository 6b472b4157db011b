// Swap chains on both backends, against a real X server (Xvfb in ctest): what the window shows
// is read back with XGetImage and compared with pixels computed here from the D3D11 rules (row 0
// at the top, sRGB encoded on write). Also resizing, and every refusal of sp::CreateSwapChain,
// Present and ResizeBuffers. Xlib is used directly: the RHI and its tests need no GLFW.
#include <cmath>
#include <cstdlib>
#include <unistd.h>

#include "../rhi/rhi-test-util.h"
// After gtest: Xlib's macros (None, Bool, Status) would break its headers.
#include <X11/Xlib.h>
#include <X11/Xutil.h>

namespace sp::test {
namespace {

// Xlib's default handler ends the process on any error; the tests provoke some (a destroyed
// window) and count them instead.
int gXErrors = 0;
int CountXError(Display*, XErrorEvent*) {
  ++gXErrors;
  return 0;
}

// Rectangles come from gpu::RectDrawer's vertex shader; this colours them.
const char* kColorPs = "cbuffer Color : register(b0) { float4 color; };\n"
                       "float4 PSColor(float4 p : SV_Position) : SV_Target { return color; }\n";

struct Rect {
  uint32_t x, y, w, h;
  float color[4];
};

class SwapChainTest : public BackendTest {
 protected:
  // One connection for the whole suite: opening one per test failed now and then on a loaded
  // machine (XOpenDisplay returning null mid-run with the server alive).
  static void TearDownTestSuite() {
    if (sDisplay) XCloseDisplay(sDisplay);
    sDisplay = nullptr;
  }
  void SetUp() override {
    if (!sDisplay) sDisplay = OpenDisplay();
    display_ = sDisplay;
    if (!display_) {
      // ctest runs the suite under xvfb-run and sets this: there a missing display is a failure.
      if (std::getenv("SHADOWPORT_REQUIRE_DISPLAY")) FAIL() << "cannot open the X display '" << (std::getenv("DISPLAY") ? std::getenv("DISPLAY") : "") << "'";
      GTEST_SKIP() << "no X display (DISPLAY unset or unreachable); ctest runs these under xvfb-run";
    }
    previousHandler_ = XSetErrorHandler(CountXError);
    gXErrors = 0;
    BackendTest::SetUp();
  }
  void TearDown() override {
    BackendTest::TearDown();
    if (display_) {
      for (Window w : std::vector<Window>(windows_)) DestroyWindow(w);
      XSync(display_, False);
      XSetErrorHandler(previousHandler_);
    }
  }
  // A few tries: a busy server can refuse a connection for a moment.
  static Display* OpenDisplay() {
    if (!std::getenv("DISPLAY")) return nullptr;
    for (int i = 0; i < 20; ++i) {
      if (Display* d = XOpenDisplay(nullptr)) return d;
      usleep(100000);
    }
    return nullptr;
  }
  void ConfigureDevice(DeviceDesc& desc) override { desc.x11Display = display_; }

  Window OpenWindow(uint32_t w, uint32_t h) {
    Window win = XCreateSimpleWindow(display_, DefaultRootWindow(display_), 0, 0, w, h, 0, 0, 0);
    XSelectInput(display_, win, StructureNotifyMask);
    XMapWindow(display_, win);
    XEvent e;
    do XWindowEvent(display_, win, StructureNotifyMask, &e);
    while (e.type != MapNotify);
    windows_.push_back(win);
    return win;
  }
  void DestroyWindow(Window w) {
    auto it = std::find(windows_.begin(), windows_.end(), w);
    if (it == windows_.end()) return;
    windows_.erase(it);
    XDestroyWindow(display_, w);
    XSync(display_, False);
  }
  void ResizeWindow(Window w, uint32_t width, uint32_t height) {
    XResizeWindow(display_, w, width, height);
    XSync(display_, False);
  }

  SwapChainDesc Desc(Window w, uint32_t width, uint32_t height, FORMAT format = FORMAT_R8G8B8A8_UNORM) {
    SwapChainDesc d;
    d.window = {display_, w};
    d.width = width;
    d.height = height;
    d.format = format;
    d.bufferCount = 2;
    d.syncInterval = 0;
    return d;
  }

  // The window's pixels, RGBA8 with alpha 255, row 0 at the top.
  std::vector<uint8_t> Screenshot(Window w, uint32_t width, uint32_t height) {
    XSync(display_, False);
    XImage* img = XGetImage(display_, w, 0, 0, width, height, AllPlanes, ZPixmap);
    if (!img) {
      ADD_FAILURE() << "XGetImage failed";
      return {};
    }
    auto channel = [](unsigned long pixel, unsigned long mask) {
      int shift = 0;
      while (mask && !(mask & 1)) mask >>= 1, ++shift;
      return uint8_t(((pixel >> shift) & mask) * 255 / (mask ? mask : 1));
    };
    std::vector<uint8_t> out(size_t(width) * height * 4);
    for (uint32_t y = 0; y < height; ++y)
      for (uint32_t x = 0; x < width; ++x) {
        unsigned long p = XGetPixel(img, int(x), int(y));
        uint8_t* o = &out[(size_t(y) * width + x) * 4];
        o[0] = channel(p, img->red_mask), o[1] = channel(p, img->green_mask), o[2] = channel(p, img->blue_mask), o[3] = 255;
      }
    XDestroyImage(img);
    return out;
  }

  // Draws each rectangle (in order, in pixels from the top left) into the swap chain's back buffer.
  void Render(SwapChain& sc, const std::vector<Rect>& rects) {
    Texture2D* buffer = sc.GetBuffer(0);
    const TEXTURE2D_DESC d = buffer->GetDesc();
    Ref<RenderTargetView> rtv = device().CreateRenderTargetView(buffer);
    RectDrawer rect(device());
    Ref<PixelShader> ps = device().CreatePixelShader(CompileHlsl(kColorPs, "ps_5_0", "PSColor"));
    Ref<Buffer> cb = MakeBuffer(device(), BIND_CONSTANT_BUFFER, nullptr, 16);
    RenderTargetView* rtvs[] = {rtv.get()};
    ctx().OMSetRenderTargets(1, rtvs, nullptr);
    SetViewport(ctx(), float(d.Width), float(d.Height));
    ctx().PSSetShader(ps.get());
    ctx().PSSetConstantBuffers(0, {cb.get()});
    for (const Rect& r : rects) {
      ctx().UpdateSubresource(cb.get(), 0, nullptr, r.color, 0, 0);
      rect.Draw(ctx(), float(r.x), float(r.y), float(r.x + r.w), float(r.y + r.h), float(d.Width), float(d.Height));
    }
    // DXGI requires the back buffer's views released before ResizeBuffers; the tests do so.
    ctx().ClearState();
  }

  static inline Display* sDisplay = nullptr;
  Display* display_ = nullptr;
  std::vector<Window> windows_;
  XErrorHandler previousHandler_ = nullptr;
};

double EncodeSrgb(double v) { return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055; }

// What D3D11 stores for the rectangles (later ones on top), RGBA8, row 0 at the top.
std::vector<uint8_t> Expected(uint32_t w, uint32_t h, const std::vector<Rect>& rects, bool srgb) {
  std::vector<uint8_t> px(size_t(w) * h * 4, 0);
  for (const Rect& r : rects)
    for (uint32_t y = r.y; y < r.y + r.h; ++y)
      for (uint32_t x = r.x; x < r.x + r.w; ++x)
        for (int c = 0; c < 3; ++c) px[(size_t(y) * w + x) * 4 + c] = uint8_t(std::lround((srgb ? EncodeSrgb(r.color[c]) : r.color[c]) * 255));
  for (size_t i = 3; i < px.size(); i += 4) px[i] = 255;
  return px;
}

// Four quadrants and a small marker near the top-left corner: a flipped or mirrored image, a
// swapped channel order or a missing sRGB encoding each change many pixels.
std::vector<Rect> Pattern(uint32_t w, uint32_t h) {
  return {{0, 0, w / 2, h / 2, {1, 0, 0, 1}},
          {w / 2, 0, w - w / 2, h / 2, {0, 1, 0, 1}},
          {0, h / 2, w / 2, h - h / 2, {0, 0, 1, 1}},
          {w / 2, h / 2, w - w / 2, h - h / 2, {0.25f, 0.5f, 0.75f, 1}},
          {3, 2, 6, 4, {1, 1, 1, 1}}};
}

// Pixels further apart than `tolerance` in any colour channel.
size_t Mismatches(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, int tolerance) {
  if (a.size() != b.size()) return std::max(a.size(), b.size()) / 4;
  size_t n = 0;
  for (size_t i = 0; i < a.size(); i += 4)
    for (int c = 0; c < 3; ++c)
      if (std::abs(int(a[i + c]) - int(b[i + c])) > tolerance) {
        ++n;
        break;
      }
  return n;
}

TEST_P(SwapChainTest, WindowShowsTheBackBufferTopRowFirst) {
  const uint32_t W = 64, H = 48;
  Window win = OpenWindow(W, H);
  std::unique_ptr<SwapChain> sc = CreateSwapChain(device(), Desc(win, W, H));
  Render(*sc, Pattern(W, H));
  sc->Present(0);
  std::vector<uint8_t> shot = Screenshot(win, W, H), expected = Expected(W, H, Pattern(W, H), false);
  EXPECT_EQ(CompareImages("window", W, H, shot.data(), expected.data()), 0u);
  EXPECT_EQ(gXErrors, 0);
}

// An sRGB back buffer stores encoded values (0.5 linear -> 188); the window shows those bytes.
// D3D11 allows the encoding 0.6 units of error, so the CPU encoding is compared within 1; the
// window must equal the back buffer's own bytes exactly.
TEST_P(SwapChainTest, SrgbBackBufferShowsEncodedBytes) {
  const uint32_t W = 40, H = 30;
  Window win = OpenWindow(W, H);
  std::unique_ptr<SwapChain> sc = CreateSwapChain(device(), Desc(win, W, H, FORMAT_R8G8B8A8_UNORM_SRGB));
  std::vector<Rect> rects = Pattern(W, H);
  rects.push_back({20, 15, 10, 10, {0.5f, 0.5f, 0.5f, 1}});
  Render(*sc, rects);
  std::vector<uint8_t> stored = ReadTexture(device(), ctx(), sc->GetBuffer(0));
  sc->Present(1);
  std::vector<uint8_t> shot = Screenshot(win, W, H);
  for (size_t i = 3; i < stored.size(); i += 4) stored[i] = 255;
  EXPECT_EQ(CompareImages("window-vs-buffer", W, H, shot.data(), stored.data()), 0u);
  EXPECT_EQ(Mismatches(shot, Expected(W, H, rects, true), 1), 0u);
  EXPECT_NEAR(shot[(size_t(20) * W + 25) * 4], 188, 1);  // 187.52: llvmpipe gives 187
}

TEST_P(SwapChainTest, BgraBackBufferKeepsChannels) {
  const uint32_t W = 32, H = 32;
  Window win = OpenWindow(W, H);
  std::unique_ptr<SwapChain> sc = CreateSwapChain(device(), Desc(win, W, H, FORMAT_B8G8R8A8_UNORM));
  Render(*sc, Pattern(W, H));
  sc->Present(0);
  std::vector<uint8_t> shot = Screenshot(win, W, H), expected = Expected(W, H, Pattern(W, H), false);
  EXPECT_EQ(CompareImages("window", W, H, shot.data(), expected.data()), 0u);
}

// ResizeBuffers after the window grew: a back buffer of the new size, presented 1:1, and no
// validation error on the way (the fixture fails the test on any).
TEST_P(SwapChainTest, ResizeBuffersFollowsTheWindow) {
  Window win = OpenWindow(48, 32);
  std::unique_ptr<SwapChain> sc = CreateSwapChain(device(), Desc(win, 48, 32));
  Render(*sc, Pattern(48, 32));
  sc->Present(0);
  const uint32_t W = 80, H = 60;
  ResizeWindow(win, W, H);
  sc->ResizeBuffers(0, W, H, FORMAT_UNKNOWN);
  TEXTURE2D_DESC d = sc->GetBuffer(0)->GetDesc();
  EXPECT_EQ(d.Width, W);
  EXPECT_EQ(d.Height, H);
  Render(*sc, Pattern(W, H));
  sc->Present(0);
  std::vector<uint8_t> shot = Screenshot(win, W, H), expected = Expected(W, H, Pattern(W, H), false);
  EXPECT_EQ(CompareImages("window", W, H, shot.data(), expected.data()), 0u);
  // And back down, twice in a row, presenting in between.
  for (uint32_t size : {40u, 24u}) {
    ResizeWindow(win, size, size);
    sc->ResizeBuffers(3, size, size, FORMAT_UNKNOWN);
    Render(*sc, Pattern(size, size));
    sc->Present(0);
    std::vector<uint8_t> s = Screenshot(win, size, size), e = Expected(size, size, Pattern(size, size), false);
    EXPECT_EQ(Mismatches(s, e, 0), 0u) << size;
  }
}

void ExpectError(ErrorId id, const std::string& call, const std::string& text, const std::function<void()>& f) {
  try {
    f();
    ADD_FAILURE() << "no error; expected " << ErrorIdName(id) << " from " << call;
  } catch (const Error& e) {
    EXPECT_EQ(e.id(), id) << e.what();
    EXPECT_EQ(e.call(), call) << e.what();
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
  }
}

TEST_P(SwapChainTest, CreateRefusesBadDescs) {
  Window win = OpenWindow(32, 32);
  SwapChainDesc d = Desc(win, 32, 32);
  auto create = [&](SwapChainDesc x) { return [this, x] { CreateSwapChain(device(), x); }; };
  SwapChainDesc x = d;
  x.window.x11Window = 0;
  ExpectError(ErrorId::INVALID_ARGUMENT, "CreateSwapChain", "null handle", create(x));
  x = d;
  x.window.x11Display = nullptr;
  ExpectError(ErrorId::INVALID_ARGUMENT, "CreateSwapChain", "null handle", create(x));
  x = d;
  x.width = 0;
  ExpectError(ErrorId::SIZE_OUT_OF_RANGE, "CreateSwapChain", "got 0x32", create(x));
  x = d;
  x.height = 0;
  ExpectError(ErrorId::SIZE_OUT_OF_RANGE, "CreateSwapChain", "got 32x0", create(x));
  x = d;
  x.bufferCount = 0;
  ExpectError(ErrorId::INVALID_ARGUMENT, "CreateSwapChain", "bufferCount must be in [1, 16] (got 0)", create(x));
  x.bufferCount = 17;
  ExpectError(ErrorId::INVALID_ARGUMENT, "CreateSwapChain", "bufferCount must be in [1, 16] (got 17)", create(x));
  x = d;
  x.syncInterval = 5;
  ExpectError(ErrorId::INVALID_ARGUMENT, "CreateSwapChain", "syncInterval must be in [0, 4] (got 5)", create(x));
  x = d;
  x.format = FORMAT_R32_FLOAT;
  ExpectError(ErrorId::FORMAT_UNSUPPORTED, "CreateSwapChain", "R32_FLOAT is not a swap-chain format", create(x));
  // A DXGI back-buffer format that this 24-bit window's surface does not offer on either backend.
  x.format = FORMAT_R16G16B16A16_FLOAT;
  ExpectError(ErrorId::FORMAT_UNSUPPORTED, "CreateSwapChain", "cannot show R16G16B16A16_FLOAT; it offers ", create(x));
  // Another display connection than the device's.
  Display* other = OpenDisplay();
  ASSERT_NE(other, nullptr);
  x = d;
  x.window.x11Display = other;
  ExpectError(ErrorId::INVALID_ARGUMENT, "CreateSwapChain", "set DeviceDesc::x11Display", create(x));
  XCloseDisplay(other);
  // A window that never existed.
  x = d;
  x.window.x11Window = win + 0x1000;
  ExpectError(ErrorId::INVALID_ARGUMENT, "CreateSwapChain", "no longer exists", create(x));
  EXPECT_EQ(gXErrors, 0) << "the RHI's window query must keep BadWindow from the application's handler";
}

TEST_P(SwapChainTest, PresentAfterTheWindowIsGoneFails) {
  Window win = OpenWindow(32, 32);
  std::unique_ptr<SwapChain> sc = CreateSwapChain(device(), Desc(win, 32, 32));
  Render(*sc, Pattern(32, 32));
  sc->Present(0);
  DestroyWindow(win);
  ExpectError(ErrorId::INVALID_ARGUMENT, "Present", "no longer exists", [&] { sc->Present(0); });
  ExpectError(ErrorId::INVALID_ARGUMENT, "ResizeBuffers", "no longer exists", [&] { sc->ResizeBuffers(0, 16, 16, FORMAT_UNKNOWN); });
  sc.reset();  // destroying it afterwards is fine
  XSync(display_, False);
}

TEST_P(SwapChainTest, ResizeAndPresentRefuseMisuse) {
  Window win = OpenWindow(32, 32);
  std::unique_ptr<SwapChain> sc = CreateSwapChain(device(), Desc(win, 32, 32));
  ExpectError(ErrorId::INVALID_ARGUMENT, "GetBuffer", "only buffer 0", [&] { sc->GetBuffer(1); });
  ExpectError(ErrorId::INVALID_ARGUMENT, "Present", "syncInterval must be in [0, 4] (got 7)", [&] { sc->Present(7); });
  {
    // DXGI refuses ResizeBuffers while views of the back buffer exist.
    Ref<RenderTargetView> rtv = device().CreateRenderTargetView(sc->GetBuffer(0));
    ExpectError(ErrorId::INVALID_ARGUMENT, "ResizeBuffers", "1 reference(s) to the back buffer are still held",
                [&] { sc->ResizeBuffers(0, 16, 16, FORMAT_UNKNOWN); });
  }
  ExpectError(ErrorId::SIZE_OUT_OF_RANGE, "ResizeBuffers", "got 0x16", [&] { sc->ResizeBuffers(0, 0, 16, FORMAT_UNKNOWN); });
  ExpectError(ErrorId::INVALID_ARGUMENT, "ResizeBuffers", "(got 17)", [&] { sc->ResizeBuffers(17, 16, 16, FORMAT_UNKNOWN); });
  ExpectError(ErrorId::FORMAT_UNSUPPORTED, "ResizeBuffers", "cannot show R16G16B16A16_FLOAT", [&] { sc->ResizeBuffers(0, 16, 16, FORMAT_R16G16B16A16_FLOAT); });
  // A refused resize leaves the swap chain as it was.
  EXPECT_EQ(sc->GetBuffer(0)->GetDesc().Width, 32u);
  sc->ResizeBuffers(0, 16, 16, FORMAT_R8G8B8A8_UNORM_SRGB);
  EXPECT_EQ(sc->GetBuffer(0)->GetDesc().Format, FORMAT_R8G8B8A8_UNORM_SRGB);
  sc->Present(0);
}

// A device made without the window's display cannot present to it.
TEST_P(SwapChainTest, HeadlessDeviceIsRefused) {
  Window win = OpenWindow(16, 16);
  DeviceDesc dd;
  dd.backend = GetParam();
  dd.shaderCacheDir = TestShaderCacheDir();
  Ref<Device> headless = CreateDevice(dd);
  ExpectError(ErrorId::INVALID_ARGUMENT, "CreateSwapChain", "set DeviceDesc::x11Display", [&] { CreateSwapChain(*headless, Desc(win, 16, 16)); });
}

SP_INSTANTIATE_BACKEND_TESTS(SwapChainTest);

// The null backend draws nothing and says so.
TEST(NullDevice, SwapChainIsRefused) {
  DeviceDesc dd;
  dd.backend = Backend::Null;
  Ref<Device> dev = CreateDevice(dd);
  SwapChainDesc d;
  d.window = {reinterpret_cast<void*>(1), 1};
  d.width = d.height = 16;
  try {
    CreateSwapChain(*dev, d);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.id(), ErrorId::NOT_SUPPORTED);
    EXPECT_NE(std::string(e.what()).find("cannot present"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sp::test
