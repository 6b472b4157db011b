// What the core asks the X server about a swap chain's window, without linking libX11: the
// application that passes a Display* has libX11 loaded, so its entry points are looked up in the
// process (dlsym). The RHI thus depends on no windowing library, not even Xlib at link time.
#pragma once
#include <cstdint>

namespace sp::detail {

struct X11WindowState {
  bool queried = false;  // false: libX11 is not in the process, nothing could be asked
  bool exists = false;
  uint32_t width = 0, height = 0;
  unsigned long visualId = 0;
};

// Whether `window` still exists on `display`, its size and visual. A BadWindow error (the window
// was destroyed) is caught by a handler installed only for this query, so it neither reaches the
// application's handler nor ends the process.
X11WindowState QueryX11Window(void* display, unsigned long window);

}  // namespace sp::detail
