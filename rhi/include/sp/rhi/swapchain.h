// IDXGISwapChain mirror: a window's back buffer as an ordinary Texture2D, shown by Present.
//
// Porting: `factory->CreateSwapChain(device, &desc, &swapChain)` -> `sp::CreateSwapChain(*device,
// desc)`; `swapChain->GetBuffer(0, __uuidof(ID3D11Texture2D), (void**)&tex)` ->
// `swapChain->GetBuffer(0)` (no COM reference: the swap chain owns it); Present and
// ResizeBuffers keep their shapes. The window is given by its native handles, so the RHI does not
// depend on a windowing library. The device that presents must be created with the window's
// display (DeviceDesc::x11Display); see docs/viewer.md for what Present does on each backend.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include <sp/rhi/common.h>
#include <sp/rhi/format.h>

namespace sp {

class Device;
class Texture2D;

namespace detail {
class SwapChainBackend;
}

// Xlib handles (GLFW: glfwGetX11Display / glfwGetX11Window with GLFW_EXPOSE_NATIVE_X11).
struct NativeWindow {
  void* x11Display = nullptr;    // Display*
  unsigned long x11Window = 0;   // Window
};

// DXGI_SWAP_CHAIN_DESC, reduced to what a windowed blt-model swap chain uses.
struct SwapChainDesc {
  NativeWindow window;
  uint32_t width = 0, height = 0;  // of the back buffer; unlike DXGI, 0 is refused (not "the window's size")
  FORMAT format = FORMAT_R8G8B8A8_UNORM;
  uint32_t bufferCount = 2;  // [1, 16] as DXGI; the presentation queue's length (the app sees buffer 0 only)
  uint32_t syncInterval = 1;  // what Present uses when it is given UINT32_MAX; [0, 4]
};

class SwapChain {
 public:
  ~SwapChain();
  SwapChain(const SwapChain&) = delete;
  SwapChain& operator=(const SwapChain&) = delete;

  // Buffer 0, as in DXGI's discard model: render into it (through an RTV), then Present. It keeps
  // every D3D11 rule of a texture: row 0 is the window's top row, sRGB formats encode on write.
  Texture2D* GetBuffer(uint32_t index);
  // Shows the back buffer in the window. syncInterval 0: no wait for vertical blank (tearing
  // allowed); 1-4: wait (FIFO; 2-4 are presented as 1). A back buffer of another size than the
  // window is stretched, as DXGI_SCALING_STRETCH does. Throws when the window is gone.
  void Present(uint32_t syncInterval);
  // DXGI's ResizeBuffers: bufferCount 0 and FORMAT_UNKNOWN keep the current ones. Refused while
  // the application still holds references to the back buffer (its views, a Ref), as DXGI
  // refuses: release them, and unbind them from the context, first.
  void ResizeBuffers(uint32_t bufferCount, uint32_t width, uint32_t height, FORMAT format);

  const SwapChainDesc& GetDesc() const { return desc_; }
  // The formats this window can show, as found when the swap chain was created.
  const std::vector<FORMAT>& PresentableFormats() const { return formats_; }

 private:
  friend std::unique_ptr<SwapChain> CreateSwapChain(Device& device, const SwapChainDesc& desc);
  SwapChain(Device& device, const SwapChainDesc& desc);
  void CreateBackBuffer();
  std::string Describe() const;

  Device& device_;
  SwapChainDesc desc_;
  std::unique_ptr<detail::SwapChainBackend> backend_;
  std::vector<FORMAT> formats_;
  Ref<Texture2D> buffer_;
};

// Creates a swap chain for the window on `device`, which must outlive it and must have been
// created with the window's display. Throws sp::Error naming the field at fault: a null window,
// a zero size, a bufferCount or syncInterval out of range, a format the window cannot show (the
// message lists those it can), a window that no longer exists, the null backend (it cannot present).
std::unique_ptr<SwapChain> CreateSwapChain(Device& device, const SwapChainDesc& desc);

}  // namespace sp
