#include "x11-window.h"

#include <X11/Xlib.h>
#include <dlfcn.h>

#include <mutex>

namespace sp::detail {
namespace {

using SyncFn = int (*)(Display*, Bool);
using SetErrorHandlerFn = XErrorHandler (*)(XErrorHandler);
using GetWindowAttributesFn = Status (*)(Display*, Window, XWindowAttributes*);

// Xlib's error handler is process-wide: queries are serialised so the flag is theirs.
std::mutex gQueryMutex;
int gLastError = 0;

int RecordError(Display*, XErrorEvent* e) {
  gLastError = e->error_code;
  return 0;
}

template <class F>
F Lookup(const char* name) {
  return reinterpret_cast<F>(dlsym(RTLD_DEFAULT, name));
}

}  // namespace

X11WindowState QueryX11Window(void* display, unsigned long window) {
  X11WindowState s;
  static const auto sync = Lookup<SyncFn>("XSync");
  static const auto setHandler = Lookup<SetErrorHandlerFn>("XSetErrorHandler");
  static const auto getAttributes = Lookup<GetWindowAttributesFn>("XGetWindowAttributes");
  if (!sync || !setHandler || !getAttributes || !display) return s;
  auto* dpy = static_cast<Display*>(display);
  std::lock_guard lock(gQueryMutex);
  // Errors of the application's earlier requests go to its own handler, not to this query.
  sync(dpy, False);
  XErrorHandler previous = setHandler(RecordError);
  gLastError = 0;
  XWindowAttributes a{};
  Status ok = getAttributes(dpy, Window(window), &a);
  sync(dpy, False);
  setHandler(previous);
  s.queried = true;
  s.exists = ok != 0 && gLastError == 0;
  if (s.exists) {
    s.width = uint32_t(a.width);
    s.height = uint32_t(a.height);
    s.visualId = a.visual ? a.visual->visualid : 0;
  }
  return s;
}

}  // namespace sp::detail
