// viewer: a window on a scene, rendered by a shadow technique through an sp::SwapChain.
//
//   viewer [--backend vulkan|gl] [--scene NAME|file.gltf] [--technique NAME] [--param k=v]...
//          [--size WxH] [--sync 0|1] [--validate] [--frames N --screenshot out.png] [--ui]
//          [--record FILE.json] [--replay FILE.json] [--overlay layers|density|error|shadowmap]
//          [--dump-lab PREFIX]
//
// Mouse: left drag looks around, right drag turns the sun. Keys: W A S D move, Q E down/up,
// Shift faster; 1-9 pick a technique; Tab picks a parameter, [ and ] step it; F1 shows or hides
// the panel; R starts or stops recording the camera path; C, T, M toggle the layer colours, the
// texel-density heat map, the shadow-map view; H traces the error heat map of this frame (slow)
// or hides it; F12 saves a screenshot; Esc quits. (Overlays: docs/viewer.md, overlay-view.h.)
// With --frames N the viewer renders the scene's own camera and light N times, saves what the
// window shows to --screenshot and exits: the same picture as `shadowport render` with the same
// scene, technique, parameters and size (the panel is off unless --ui asks for it).
#include <sp/rhi/rhi.h>
#include <sp/scene/scene.h>
#include <sp/tech/gpu-timer.h>
#include <sp/tech/renderer.h>
#include <sp/tech/technique.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "fly-camera.h"
#include "imgui-renderer.h"
#include "overlay-view.h"
#include "panel.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <X11/Xlib.h>
#include <X11/Xutil.h>
// GLFW's X11 handles. glfw3native.h declares them, but with GLFW_EXPOSE_NATIVE_X11 it also
// includes Xrandr's header (libxrandr-dev), which nothing here needs.
extern "C" {
Display* glfwGetX11Display(void);
Window glfwGetX11Window(GLFWwindow* window);
}
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

namespace {

constexpr double kFrameSeconds = 1.0 / 60.0;  // the clock of a --frames run

struct Options {
  sp::Backend backend = sp::Backend::Vulkan;
  std::string scene = "default", technique = "basic";
  std::map<std::string, std::string> params;
  uint32_t width = 1280, height = 720;
  uint32_t sync = 1;
  bool validate = false;
  int frames = 0;  // > 0: non-interactive
  std::string screenshot;
  bool ui = false;      // the panel in --frames mode (interactively it is on anyway)
  std::string record;   // where a recorded path goes (default viewer-path-<N>.json)
  std::string replay;   // a recorded path to fly instead of the fly camera
  sp::viewer::Overlay overlay = sp::viewer::Overlay::Off;
  std::string dumpLab;  // with --frames: the last frame's lab colour and layers as PNGs (tests)
};

[[noreturn]] void Usage(const std::string& why) {
  throw std::invalid_argument(why + "\nusage: viewer [--backend vulkan|gl] [--scene NAME|file.gltf] [--technique NAME] [--param k=v]... "
                                    "[--size WxH] [--sync 0|1] [--validate] [--frames N --screenshot out.png] [--ui] "
                                    "[--record FILE.json] [--replay FILE.json] [--overlay layers|density|error|shadowmap] [--dump-lab PREFIX]");
}

Options ParseOptions(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) Usage(a + " needs a value");
      return argv[++i];
    };
    if (a == "--backend") {
      std::string b = value();
      if (!sp::ParseBackend(b, &o.backend) || o.backend == sp::Backend::Null) Usage("--backend '" + b + "': vulkan or gl");
    } else if (a == "--scene") {
      o.scene = value();
    } else if (a == "--technique") {
      o.technique = value();
    } else if (a == "--param") {
      std::string p = value();
      size_t eq = p.find('=');
      if (eq == std::string::npos || eq == 0) Usage("--param '" + p + "' is not name=value");
      o.params[p.substr(0, eq)] = p.substr(eq + 1);
    } else if (a == "--size") {
      std::string s = value();
      if (std::sscanf(s.c_str(), "%ux%u", &o.width, &o.height) != 2 || !o.width || !o.height) Usage("--size '" + s + "': WxH");
    } else if (a == "--sync") {
      o.sync = uint32_t(std::stoul(value()));
    } else if (a == "--validate") {
      o.validate = true;
    } else if (a == "--frames") {
      o.frames = std::stoi(value());
      if (o.frames <= 0) Usage("--frames must be at least 1");
    } else if (a == "--screenshot") {
      o.screenshot = value();
    } else if (a == "--ui") {
      o.ui = true;
    } else if (a == "--record") {
      o.record = value();
    } else if (a == "--replay") {
      o.replay = value();
    } else if (a == "--overlay") {
      std::string v = value();
      if (!sp::viewer::ParseOverlay(v, &o.overlay)) Usage("--overlay '" + v + "': none, layers, density, error or shadowmap");
    } else if (a == "--dump-lab") {
      o.dumpLab = value();
    } else {
      Usage("unknown option " + a);
    }
  }
  if (o.frames > 0 && o.screenshot.empty()) Usage("--frames needs --screenshot out.png");
  if (!o.dumpLab.empty() && (o.frames == 0 || (o.overlay != sp::viewer::Overlay::Layers && o.overlay != sp::viewer::Overlay::Density &&
                                                o.overlay != sp::viewer::Overlay::Error)))
    Usage("--dump-lab needs --frames and --overlay layers, density or error (the overlays that read the lab's buffers)");
  return o;
}

// What the window shows, read from the X server (RGBA8, top row first): the pixels on screen,
// not the back buffer, so the test of the viewer covers Present too.
std::vector<uint8_t> WindowPixels(Display* display, Window window, uint32_t w, uint32_t h) {
  XSync(display, False);
  XImage* img = XGetImage(display, window, 0, 0, w, h, AllPlanes, ZPixmap);
  if (!img) throw std::runtime_error("XGetImage of the viewer's window failed");
  auto channel = [](unsigned long pixel, unsigned long mask) {
    int shift = 0;
    while (mask && !(mask & 1)) mask >>= 1, ++shift;
    return uint8_t(((pixel >> shift) & mask) * 255 / (mask ? mask : 1));
  };
  std::vector<uint8_t> out(size_t(w) * h * 4);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      unsigned long p = XGetPixel(img, int(x), int(y));
      uint8_t* o = &out[(size_t(y) * w + x) * 4];
      o[0] = channel(p, img->red_mask), o[1] = channel(p, img->green_mask), o[2] = channel(p, img->blue_mask), o[3] = 255;
    }
  XDestroyImage(img);
  return out;
}

void WritePng(const std::string& path, uint32_t w, uint32_t h, const std::vector<uint8_t>& rgba) {
  std::filesystem::path p(path);
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
  if (!stbi_write_png(path.c_str(), int(w), int(h), 4, rgba.data(), int(w * 4))) throw std::runtime_error("cannot write " + path);
}

class Viewer {
 public:
  Viewer(const Options& o, GLFWwindow* window) : opt_(o), window_(window), techniques_(sp::tech::TechniqueNames()) {
    sp::DeviceDesc dd;
    dd.backend = o.backend;
    dd.debug = o.validate;
    dd.x11Display = glfwGetX11Display();
    device_ = sp::CreateDevice(dd);
    scene_ = sp::scene::LoadScene(o.scene);
    camera_ = std::make_unique<viewer::FlyCamera>(scene_.camera);
    light_ = scene_.light;
    technique_ = o.technique;
    params_ = o.params;
    glfwGetFramebufferSize(window_, &width_, &height_);
    sp::SwapChainDesc sd;
    sd.window = {glfwGetX11Display(), glfwGetX11Window(window_)};
    sd.width = uint32_t(width_);
    sd.height = uint32_t(height_);
    // The renderer's colour target is sRGB; a back buffer of the same format takes it by CopyResource.
    sd.format = sp::FORMAT_R8G8B8A8_UNORM_SRGB;
    sd.bufferCount = 2;
    sd.syncInterval = o.sync;
    swapChain_ = sp::CreateSwapChain(*device_, sd);
    if (!o.replay.empty()) replay_ = sp::scene::LoadCameraPath(o.replay);
    overlays_ = std::make_unique<sp::viewer::OverlayView>(*device_, scene_);
    overlays_->Set(o.overlay);
    Rebuild();
  }

  ~Viewer() {
    if (ImGui::GetCurrentContext()) {
      ui_.reset();
      ImGui_ImplGlfw_Shutdown();
      ImGui::DestroyContext();
    }
    renderer_.reset();
    overlays_.reset();
    swapChain_.reset();  // before the device, as DXGI wants its swap chain released first
  }

  // The panel: ImGui gets GLFW's input (it chains the callbacks set before, so call this after
  // them) and draws through ImGuiRenderer into the back buffer. Without this call (--frames
  // without --ui) no ImGui context exists and the window is exactly `shadowport render`'s picture.
  void StartUi() {
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // a run leaves no imgui.ini behind
    ImGui_ImplGlfw_InitForOther(window_, true);
    ui_ = std::make_unique<sp::viewer::ImGuiRenderer>(*device_, sp::FORMAT_R8G8B8A8_UNORM_SRGB);
    timer_ = std::make_unique<sp::tech::GpuTimer>(*device_);
    renderer_->SetGpuTimer(timer_.get());
    showUi_ = true;
  }

  // seconds: the clock that times recorded keys and moves a replayed path.
  void Frame(double seconds) {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    if (w == 0 || h == 0) return;  // minimised: nothing to show
    if (w != width_ || h != height_) {
      width_ = w, height_ = h;
      swapChain_->ResizeBuffers(0, uint32_t(w), uint32_t(h), sp::FORMAT_UNKNOWN);
      Rebuild();
    }
    if (replay_) Replay(seconds);
    if (recording_) recorder_.add(seconds, camera_->camera(), light_.direction);
    renderer_->RenderFrame(camera_->camera(), light_, overlays_->NeedsLabPass() ? sp::tech::LitPass::Lab : sp::tech::LitPass::Normal);
    sp::DeviceContext* ctx = device_->GetImmediateContext();
    ctx->CopyResource(swapChain_->GetBuffer(0), renderer_->colorTarget());
    try {
      overlays_->Draw(*ctx, *renderer_, swapChain_->GetBuffer(0), light_, ViewKey());
    } catch (const std::exception& e) {
      // An overlay that cannot be made (a scene the tracer refuses, ...) is reported and turned
      // off; the viewer goes on with the plain frame.
      std::fprintf(stderr, "viewer: the %s overlay failed: %s\n", sp::viewer::OverlayName(overlays_->overlay()), e.what());
      overlays_->Set(sp::viewer::Overlay::Off);
      ctx->CopyResource(swapChain_->GetBuffer(0), renderer_->colorTarget());
    }
    if (ui_) DrawUi(*ctx);
    swapChain_->Present(opt_.sync);
  }

  void ToggleRecording() {
    if (!recording_) {
      recorder_.clear();
      recording_ = true;
      std::printf("recording the camera path (R stops)\n");
      return;
    }
    recording_ = false;
    if (recorder_.size() < 2) {
      std::printf("recording stopped: %zu key(s), a path needs 2; nothing saved\n", recorder_.size());
      return;
    }
    std::string file = opt_.record.empty() ? "viewer-path-" + std::to_string(++paths_) + ".json" : opt_.record;
    recorder_.save(file);
    std::printf("saved %zu keys (%.2f s) to %s; replay it in the lab with:\n  shadowport bench --scene %s --technique %s --backend %s --path %s\n",
                recorder_.size(), recorder_.durationSeconds(), file.c_str(), opt_.scene.c_str(), technique_.c_str(),
                sp::BackendName(opt_.backend), file.c_str());
    std::fflush(stdout);
  }
  bool Recording() const { return recording_; }

  // C, T, M, H and the panel: one overlay at a time; the renderer gets the lab's lit pass the
  // first time an overlay needs it (and keeps it: its normal pass is unchanged by it).
  void SetOverlay(sp::viewer::Overlay o) {
    overlays_->Set(o);
    if (overlays_->NeedsLabRenderer() && !labRenderer_) Rebuild();
  }
  // H while a heat map shows hides it; once it was dropped (the view changed) H traces again.
  void ToggleOverlay(sp::viewer::Overlay o) { SetOverlay(overlays_->overlay() == o ? sp::viewer::Overlay::Off : o); }

  // The last frame's lab buffers as PNGs (colour, and layer + 1 as grey, 0 where no map was read),
  // so a checker can compute the layer colours the window must show from them.
  void DumpLab(const std::string& prefix) {
    const sp::tech::LabBuffers* lab = overlays_->lastLab();
    if (!lab) throw std::runtime_error("--dump-lab: no frame read the lab's buffers");
    std::vector<uint8_t> layers(lab->size() * 4, 255);
    for (size_t i = 0; i < lab->size(); ++i) layers[i * 4] = layers[i * 4 + 1] = layers[i * 4 + 2] = uint8_t(sp::viewer::LayerOf(*lab, i) + 1);
    WritePng(prefix + "-color.png", lab->width, lab->height, lab->color);
    WritePng(prefix + "-layer.png", lab->width, lab->height, layers);
  }

  void Screenshot(const std::string& path) {
    WritePng(path, uint32_t(width_), uint32_t(height_),
             WindowPixels(glfwGetX11Display(), glfwGetX11Window(window_), uint32_t(width_), uint32_t(height_)));
    std::printf("screenshot: %s (%dx%d)\n", path.c_str(), width_, height_);
  }

  // Interactive controls (GLFW callbacks forward here).
  void OnKey(int key, int action) {
    if (action != GLFW_PRESS) return;
    if (key == GLFW_KEY_F1 && ui_) showUi_ = !showUi_;
    // Typing into the panel's text field is not a command to the viewer.
    if (ui_ && showUi_ && ImGui::GetIO().WantCaptureKeyboard) return;
    if (key == GLFW_KEY_R) ToggleRecording();
    if (key == GLFW_KEY_C) ToggleOverlay(sp::viewer::Overlay::Layers);
    if (key == GLFW_KEY_T) ToggleOverlay(sp::viewer::Overlay::Density);
    if (key == GLFW_KEY_M) ToggleOverlay(sp::viewer::Overlay::ShadowMap);
    if (key == GLFW_KEY_H) ToggleOverlay(sp::viewer::Overlay::Error);
    if (key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(window_, GLFW_TRUE);
    if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9 && size_t(key - GLFW_KEY_1) < techniques_.size()) {
      technique_ = techniques_[size_t(key - GLFW_KEY_1)];
      params_.clear();
      param_ = 0;
      Rebuild();
    }
    if (key == GLFW_KEY_TAB && !specs_.empty()) {
      param_ = (param_ + 1) % specs_.size();
      Describe();
    }
    if ((key == GLFW_KEY_LEFT_BRACKET || key == GLFW_KEY_RIGHT_BRACKET) && !specs_.empty()) Step(key == GLFW_KEY_RIGHT_BRACKET ? 1 : -1);
    if (key == GLFW_KEY_F12) Screenshot("viewer-" + std::to_string(++screenshots_) + ".png");
  }

  void OnMouse(double x, double y) {
    double dx = x - mouseX_, dy = y - mouseY_;
    mouseX_ = x, mouseY_ = y;
    // A drag that started on the panel moves its widgets, not the camera or the sun.
    if (ui_ && showUi_ && ImGui::GetIO().WantCaptureMouse) return;
    if (glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS) camera_->Look(dx, dy);
    if (glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS) viewer::DragLight(light_, dx, dy);
  }

  void Move(double seconds) {
    float speed = float(seconds) * (glfwGetKey(window_, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ? 20.0f : 5.0f);
    auto down = [&](int k) { return glfwGetKey(window_, k) == GLFW_PRESS ? 1.0f : 0.0f; };
    camera_->Move((down(GLFW_KEY_D) - down(GLFW_KEY_A)) * speed, (down(GLFW_KEY_E) - down(GLFW_KEY_Q)) * speed,
                  (down(GLFW_KEY_W) - down(GLFW_KEY_S)) * speed);
  }

  uint64_t ValidationErrors() const { return device_->ValidationErrorCount(); }

 private:
  // Interactively a recorded path loops every kReplaySeconds (the file keeps the keys' order and
  // spacing, not their seconds); with --frames N its N frames span it from start to end.
  static constexpr double kReplaySeconds = 10.0;
  void Replay(double seconds) {
    double t = opt_.frames > 1 ? seconds / ((opt_.frames - 1) * kFrameSeconds) : std::fmod(seconds / kReplaySeconds, 1.0);
    camera_ = std::make_unique<viewer::FlyCamera>(replay_->at(t));
    if (std::optional<glm::vec3> sun = replay_->lightAt(t)) light_.direction = *sun;
  }

  void DrawUi(sp::DeviceContext& ctx) {
    if (timer_)
      for (const sp::tech::FrameTimes& f : timer_->Collect(ctx, false)) gpuMs_.assign(f.begin(), f.end());
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    if (showUi_) {
      sp::viewer::PanelState st;
      st.techniques = techniques_;
      st.technique = int(std::find(techniques_.begin(), techniques_.end(), technique_) - techniques_.begin());
      st.params = specs_;
      st.values = params_;
      for (const auto& [name, value] : pending_) st.values[name] = value;
      st.gpuMs = gpuMs_;
      st.offerOverlays = true;
      st.noShadowMap = sp::viewer::OverlayView::NoShadowMap(renderer_->technique());
      st.noHeatMaps = sp::viewer::OverlayView::NoHeatMaps();
      st.cascadeColours = overlays_->overlay() == sp::viewer::Overlay::Layers;
      st.texelDensity = overlays_->overlay() == sp::viewer::Overlay::Density;
      st.showShadowMap = overlays_->overlay() == sp::viewer::Overlay::ShadowMap;
      st.errorHeatMap = overlays_->overlay() == sp::viewer::Overlay::Error;
      st.overlayNote = overlays_->note();
      st.recordingPath = recording_;
      st.recordedKeys = recorder_.size();
      Apply(sp::viewer::DrawPanel(st));
    }
    ImGui::Render();
    // A view per frame, released before the next ResizeBuffers (which refuses live references).
    sp::Ref<sp::RenderTargetView> rtv = device_->CreateRenderTargetView(swapChain_->GetBuffer(0));
    ui_->Render(ctx, rtv.get(), ImGui::GetDrawData());
  }

  void Apply(const sp::viewer::PanelChanges& c) {
    if (c.technique && size_t(*c.technique) < techniques_.size()) {
      technique_ = techniques_[size_t(*c.technique)];
      params_.clear(), pending_.clear();
      param_ = 0;
      Rebuild();
      return;
    }
    if (c.recordingPath && *c.recordingPath != recording_) ToggleRecording();
    using sp::viewer::Overlay;
    for (auto [flag, o] : {std::pair{c.cascadeColours, Overlay::Layers}, std::pair{c.texelDensity, Overlay::Density},
                           std::pair{c.showShadowMap, Overlay::ShadowMap}, std::pair{c.errorHeatMap, Overlay::Error}})
      if (flag) SetOverlay(*flag ? o : Overlay::Off);
    if (c.savePath && recording_) ToggleRecording();
    for (const auto& [name, value] : c.params) pending_[name] = value;
    // A slider reports every step of a drag; reconfiguring (new shadow maps, new shaders) on each
    // would stall the drag, so changes wait for the button's release or kApplyEvery frames.
    ++framesPending_;
    if (pending_.empty() || (ImGui::IsMouseDown(ImGuiMouseButton_Left) && framesPending_ < kApplyEvery)) return;
    std::map<std::string, std::string> before = params_;
    for (const auto& [name, value] : pending_) params_[name] = value;
    pending_.clear();
    framesPending_ = 0;
    try {
      Rebuild();
    } catch (const std::exception& e) {
      std::fprintf(stderr, "viewer: %s\n", e.what());
      params_ = before;
      Rebuild();
    }
  }
  static constexpr int kApplyEvery = 15;

  // A new technique (or new parameters, or a new size): the renderer is made again, as
  // `shadowport render` makes it, so a frame of the viewer is a frame of `render`.
  void Rebuild() {
    pending_.clear();  // panel edits meant for the technique being replaced
    renderer_.reset();
    std::unique_ptr<sp::tech::Technique> t = sp::tech::CreateTechnique(technique_);
    specs_ = t->Params();
    sp::tech::ParamValues values = sp::tech::ParamValues::Parse(technique_, specs_, params_);
    params_ = values.all();
    t->Configure(*device_, values);
    sp::tech::RendererOptions ro;
    ro.lab = labRenderer_ = labRenderer_ || overlays_->NeedsLabRenderer();
    renderer_ = std::make_unique<sp::tech::Renderer>(*device_, scene_, std::move(t), uint32_t(width_), uint32_t(height_), ro);
    renderer_->SetGpuTimer(timer_.get());
    Describe();
  }

  // Everything an error heat map depends on: it is dropped when any of it changes.
  std::string ViewKey() const {
    const sp::scene::Camera& c = camera_->camera();
    char text[256];
    std::snprintf(text, sizeof text, "%a %a %a|%a %a %a|%a %a %a|%a|%a %a %a|%dx%d|", c.position.x, c.position.y, c.position.z, c.target.x,
                  c.target.y, c.target.z, c.up.x, c.up.y, c.up.z, c.fovY, light_.direction.x, light_.direction.y, light_.direction.z,
                  width_, height_);
    std::string key = text + technique_;
    for (const auto& [name, value] : params_) key += "|" + name + "=" + value;
    return key;
  }

  void Step(int direction) {
    const sp::tech::ParamSpec& s = specs_[param_];
    std::string& v = params_[s.name];
    switch (s.kind) {
      case sp::tech::ParamSpec::Choice: {
        auto it = std::find(s.choices.begin(), s.choices.end(), v);
        size_t i = it == s.choices.end() ? 0 : size_t(it - s.choices.begin());
        v = s.choices[(i + s.choices.size() + size_t(direction)) % s.choices.size()];
        break;
      }
      case sp::tech::ParamSpec::Int: v = std::to_string(std::clamp(std::stoi(v) + direction, int(s.min), int(s.max))); break;
      case sp::tech::ParamSpec::Float: {
        double step = (s.max - s.min) / 20.0;
        v = std::to_string(std::clamp(std::stod(v) + direction * step, s.min, s.max));
        break;
      }
      case sp::tech::ParamSpec::Text: return;  // free text: set it with --param
    }
    try {
      Rebuild();
    } catch (const std::exception& e) {
      std::fprintf(stderr, "viewer: %s\n", e.what());
    }
  }

  void Describe() {
    std::string title = "ShadowPort viewer - " + std::string(sp::BackendName(opt_.backend)) + " - " + technique_;
    for (size_t i = 0; i < specs_.size(); ++i)
      title += (i == param_ ? "  [" : "  ") + specs_[i].name + "=" + params_[specs_[i].name] + (i == param_ ? "]" : "");
    glfwSetWindowTitle(window_, title.c_str());
    if (opt_.frames == 0) std::printf("%s\n", title.c_str());
  }

  Options opt_;
  GLFWwindow* window_;
  std::vector<std::string> techniques_;
  sp::Ref<sp::Device> device_;
  sp::scene::Scene scene_;
  std::unique_ptr<viewer::FlyCamera> camera_;
  sp::scene::DirectionalLight light_;
  std::string technique_;
  std::map<std::string, std::string> params_;
  std::vector<sp::tech::ParamSpec> specs_;
  size_t param_ = 0;
  std::unique_ptr<sp::SwapChain> swapChain_;
  std::unique_ptr<sp::tech::Renderer> renderer_;
  std::unique_ptr<sp::viewer::OverlayView> overlays_;
  bool labRenderer_ = false;  // renderer_ was built with RendererOptions::lab
  int width_ = 0, height_ = 0;
  double mouseX_ = 0, mouseY_ = 0;
  int screenshots_ = 0;
  std::unique_ptr<sp::viewer::ImGuiRenderer> ui_;
  std::unique_ptr<sp::tech::GpuTimer> timer_;
  bool showUi_ = false;
  std::vector<std::pair<std::string, double>> gpuMs_;
  std::map<std::string, std::string> pending_;  // parameter changes not applied yet
  int framesPending_ = 0;
  std::optional<sp::scene::CameraPath> replay_;
  sp::scene::CameraPathRecorder recorder_;
  bool recording_ = false;
  int paths_ = 0;
};

int Run(const Options& o) {
  if (!glfwInit()) throw std::runtime_error("glfwInit failed (no X display? set DISPLAY, or run under xvfb-run)");
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);  // the RHI owns the API; GLFW only makes the window
  // A fixed-size window for screenshot runs: the picture must have exactly --size.
  glfwWindowHint(GLFW_RESIZABLE, o.frames > 0 ? GLFW_FALSE : GLFW_TRUE);
  GLFWwindow* window = glfwCreateWindow(int(o.width), int(o.height), "ShadowPort viewer", nullptr, nullptr);
  if (!window) {
    glfwTerminate();
    throw std::runtime_error("glfwCreateWindow failed");
  }
  int rc = 0;
  {
    Viewer v(o, window);
    glfwSetWindowUserPointer(window, &v);
    glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int) { static_cast<Viewer*>(glfwGetWindowUserPointer(w))->OnKey(key, action); });
    glfwSetCursorPosCallback(window, [](GLFWwindow* w, double x, double y) { static_cast<Viewer*>(glfwGetWindowUserPointer(w))->OnMouse(x, y); });
    if (o.frames == 0 || o.ui) v.StartUi();
    if (o.frames > 0) {
      // A fixed clock, so a recording made here is the same on every run.
      if (!o.record.empty()) v.ToggleRecording();
      for (int i = 0; i < o.frames; ++i) {
        glfwPollEvents();
        v.Frame(i * kFrameSeconds);
      }
      if (v.Recording()) v.ToggleRecording();
      v.Screenshot(o.screenshot);
      if (!o.dumpLab.empty()) v.DumpLab(o.dumpLab);
    } else {
      auto start = std::chrono::steady_clock::now(), last = start;
      while (!glfwWindowShouldClose(window)) {
        glfwPollEvents();
        auto now = std::chrono::steady_clock::now();
        v.Move(std::chrono::duration<double>(now - last).count());
        last = now;
        v.Frame(std::chrono::duration<double>(now - start).count());
      }
      if (v.Recording()) v.ToggleRecording();  // quitting while recording keeps the path
    }
    if (v.ValidationErrors()) {
      std::fprintf(stderr, "viewer: %llu validation error(s)\n", static_cast<unsigned long long>(v.ValidationErrors()));
      rc = 1;
    }
  }
  glfwDestroyWindow(window);
  glfwTerminate();
  return rc;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Run(ParseOptions(argc, argv));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "viewer: %s\n", e.what());
    return 2;
  }
}
