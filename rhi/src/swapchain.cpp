// SwapChain: DXGI's validation, once for every backend, and the back buffer as an ordinary
// Texture2D. Backends only copy that texture to the window (backends/*/…-swapchain.cpp).
#include <sp/rhi/context.h>
#include <sp/rhi/device.h>

#include <algorithm>
#include <cstdio>

#include "backend.h"
#include "validate.h"
#include "x11-window.h"

namespace sp {

namespace detail {
std::unique_ptr<SwapChainBackend> DeviceBackend::CreateSwapChainBackend(const SwapChainDesc&, unsigned long) {
  throw Error(ErrorId::NOT_SUPPORTED, "CreateSwapChain", BackendName(core_.GetBackend()), "this backend cannot present");
}
}  // namespace detail

namespace {

constexpr uint32_t kMaxBuffers = 16;     // DXGI_MAX_SWAP_CHAIN_BUFFERS
constexpr uint32_t kMaxSyncInterval = 4;  // IDXGISwapChain::Present

// What DXGI accepts as a back-buffer format (flip and blt model together).
bool IsDisplayFormat(FORMAT f) {
  switch (f) {
    case FORMAT_R8G8B8A8_UNORM:
    case FORMAT_R8G8B8A8_UNORM_SRGB:
    case FORMAT_B8G8R8A8_UNORM:
    case FORMAT_B8G8R8A8_UNORM_SRGB:
    case FORMAT_R10G10B10A2_UNORM:
    case FORMAT_R16G16B16A16_FLOAT: return true;
    default: return false;
  }
}

std::string FormatList(const std::vector<FORMAT>& formats) {
  std::string s;
  for (FORMAT f : formats) s += (s.empty() ? "" : ", ") + std::string(FormatName(f));
  return s.empty() ? "none" : s;
}

std::string WindowName(const NativeWindow& w) {
  char buf[48];
  std::snprintf(buf, sizeof(buf), "window 0x%lx", w.x11Window);
  return buf;
}

void ValidateSize(const char* call, const std::string& obj, uint32_t width, uint32_t height) {
  if (width == 0 || height == 0)
    Fail(ErrorId::SIZE_OUT_OF_RANGE, call, obj,
         "width and height must be at least 1 (got " + std::to_string(width) + "x" + std::to_string(height) +
             "); a minimised window has no size: skip Present until it has one");
  if (width > REQ_TEXTURE2D_U_OR_V_DIMENSION || height > REQ_TEXTURE2D_U_OR_V_DIMENSION)
    Fail(ErrorId::SIZE_OUT_OF_RANGE, call, obj, "width and height must be at most 16384");
}

void ValidateFormat(const char* call, const std::string& obj, FORMAT format) {
  if (!IsDisplayFormat(format))
    Fail(ErrorId::FORMAT_UNSUPPORTED, call, obj,
         "format " + std::string(FormatName(format)) +
             " is not a swap-chain format (DXGI allows R8G8B8A8_UNORM[_SRGB], B8G8R8A8_UNORM[_SRGB], R10G10B10A2_UNORM, "
             "R16G16B16A16_FLOAT)");
}

void ValidateBufferCount(const char* call, const std::string& obj, uint32_t count) {
  if (count == 0 || count > kMaxBuffers)
    Fail(ErrorId::INVALID_ARGUMENT, call, obj, "bufferCount must be in [1, 16] (got " + std::to_string(count) + ")");
}

void ValidateSyncInterval(const char* call, const std::string& obj, uint32_t interval) {
  if (interval > kMaxSyncInterval)
    Fail(ErrorId::INVALID_ARGUMENT, call, obj, "syncInterval must be in [0, 4] (got " + std::to_string(interval) + ")");
}

// Throws unless the window still exists; returns what the X server said of it.
detail::X11WindowState RequireWindow(const char* call, const std::string& obj, const NativeWindow& w) {
  detail::X11WindowState s = detail::QueryX11Window(w.x11Display, w.x11Window);
  if (s.queried && !s.exists)
    Fail(ErrorId::INVALID_ARGUMENT, call, obj,
         WindowName(w) + " no longer exists on its display (destroyed or closed); destroy the swap chain with its window");
  return s;
}

}  // namespace

SwapChain::SwapChain(Device& device, const SwapChainDesc& desc) : device_(device), desc_(desc) {}

SwapChain::~SwapChain() {
  // The back buffer's GPU work must be done before the backend releases what shows it.
  buffer_.reset();
  if (backend_) device_.GetImmediateContext()->Flush();
  backend_.reset();
}

std::string SwapChain::Describe() const {
  return "SwapChain (" + WindowName(desc_.window) + ", " + std::to_string(desc_.width) + "x" + std::to_string(desc_.height) + " " +
         std::string(FormatName(desc_.format)) + ")";
}

void SwapChain::CreateBackBuffer() {
  TEXTURE2D_DESC td{};
  td.Width = desc_.width;
  td.Height = desc_.height;
  td.MipLevels = 1;
  td.ArraySize = 1;
  td.Format = desc_.format;
  td.SampleDesc.Count = 1;
  td.Usage = USAGE_DEFAULT;
  // DXGI_USAGE_RENDER_TARGET_OUTPUT | DXGI_USAGE_SHADER_INPUT.
  td.BindFlags = BIND_RENDER_TARGET | BIND_SHADER_RESOURCE;
  buffer_ = device_.CreateTexture2D(td);
  buffer_->SetDebugName("swap chain back buffer");
}

Texture2D* SwapChain::GetBuffer(uint32_t index) {
  if (index != 0)
    Fail(ErrorId::INVALID_ARGUMENT, "GetBuffer", Describe(),
         "buffer " + std::to_string(index) + " is not accessible: as in DXGI's discard model, only buffer 0 is");
  return buffer_.get();
}

void SwapChain::Present(uint32_t syncInterval) {
  const char* call = "Present";
  if (syncInterval == UINT32_MAX) syncInterval = desc_.syncInterval;
  ValidateSyncInterval(call, Describe(), syncInterval);
  RequireWindow(call, Describe(), desc_.window);
  backend_->Present(*buffer_, syncInterval);
}

void SwapChain::ResizeBuffers(uint32_t bufferCount, uint32_t width, uint32_t height, FORMAT format) {
  const char* call = "ResizeBuffers";
  SwapChainDesc next = desc_;
  if (bufferCount != 0) next.bufferCount = bufferCount;
  if (format != FORMAT_UNKNOWN) next.format = format;
  next.width = width;
  next.height = height;
  ValidateBufferCount(call, Describe(), next.bufferCount);
  ValidateSize(call, Describe(), width, height);
  ValidateFormat(call, Describe(), next.format);
  if (std::find(formats_.begin(), formats_.end(), next.format) == formats_.end())
    Fail(ErrorId::FORMAT_UNSUPPORTED, call, Describe(),
         "the window cannot show " + std::string(FormatName(next.format)) + "; it offers " + FormatList(formats_));
  RequireWindow(call, Describe(), desc_.window);
  // Our own Ref is one; a view (which keeps its resource), a binding or an AddRef is another.
  if (buffer_.use_count() > 1)
    Fail(ErrorId::INVALID_ARGUMENT, call, Describe(),
         std::to_string(buffer_.use_count() - 1) +
             " reference(s) to the back buffer are still held (render-target or shader-resource views, bindings, Refs): "
             "DXGI requires releasing them, and unbinding them from the context, before ResizeBuffers");
  buffer_.reset();
  desc_ = next;
  backend_->Configure(desc_);
  CreateBackBuffer();
}

std::unique_ptr<SwapChain> CreateSwapChain(Device& device, const SwapChainDesc& desc) {
  const char* call = "CreateSwapChain";
  std::string obj = "SwapChain (" + WindowName(desc.window) + ")";
  if (device.GetBackend() == Backend::Null)
    Fail(ErrorId::NOT_SUPPORTED, call, obj, "the null backend draws nothing and cannot present; create the device on vulkan or gl");
  if (!desc.window.x11Display || !desc.window.x11Window)
    Fail(ErrorId::INVALID_ARGUMENT, call, obj, "desc.window needs an X11 Display* and Window (got a null handle)");
  if (desc.window.x11Display != detail::DeviceAccess::X11Display(device))
    Fail(ErrorId::INVALID_ARGUMENT, call, obj,
         "the device was not created for this window's display: set DeviceDesc::x11Display to the window's Display*");
  ValidateSize(call, obj, desc.width, desc.height);
  ValidateBufferCount(call, obj, desc.bufferCount);
  ValidateSyncInterval(call, obj, desc.syncInterval);
  ValidateFormat(call, obj, desc.format);
  detail::X11WindowState window = RequireWindow(call, obj, desc.window);

  std::unique_ptr<SwapChain> sc(new SwapChain(device, desc));
  sc->backend_ = detail::DeviceAccess::Backend(device).CreateSwapChainBackend(desc, window.visualId);
  sc->formats_ = sc->backend_->Formats();
  if (std::find(sc->formats_.begin(), sc->formats_.end(), desc.format) == sc->formats_.end())
    Fail(ErrorId::FORMAT_UNSUPPORTED, call, obj,
         "the window's surface cannot show " + std::string(FormatName(desc.format)) + "; it offers " + FormatList(sc->formats_));
  sc->backend_->Configure(desc);
  sc->CreateBackBuffer();
  return sc;
}

}  // namespace sp
