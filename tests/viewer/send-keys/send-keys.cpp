// send-keys (tests/viewer/send-keys/): types keys into the viewer's window on an X display, for the test of its interactive
// keys (tests/CMakeLists.txt, samples.viewer_overlay_keys_*). No XTest here: key events are sent
// to the window with XSendEvent, which GLFW handles as typed keys.
//
//   send-keys TITLE-PREFIX KEY[:SECONDS]...
//
// Waits (up to 60 s) for a top-level window whose name starts with TITLE-PREFIX, then presses
// and releases each KEY (an X keysym name: c, m, h, F12, Escape) and waits SECONDS after it
// (default 1), so the viewer draws frames between keys.
#include <X11/Xlib.h>
#include <X11/Xutil.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>

namespace {

Window FindWindow(Display* d, Window w, const char* prefix) {
  char* name = nullptr;
  if (XFetchName(d, w, &name) && name) {
    bool match = std::strncmp(name, prefix, std::strlen(prefix)) == 0;
    XFree(name);
    if (match) return w;
  }
  Window root, parent, *children = nullptr;
  unsigned n = 0;
  Window found = 0;
  if (XQueryTree(d, w, &root, &parent, &children, &n)) {
    for (unsigned i = 0; i < n && !found; ++i) found = FindWindow(d, children[i], prefix);
    if (children) XFree(children);
  }
  return found;
}

void Send(Display* d, Window w, KeySym sym, bool press) {
  XKeyEvent e{};
  e.type = press ? KeyPress : KeyRelease;
  e.display = d;
  e.window = w;
  e.root = DefaultRootWindow(d);
  e.time = CurrentTime;
  e.same_screen = True;
  e.keycode = XKeysymToKeycode(d, sym);
  XSendEvent(d, w, True, press ? KeyPressMask : KeyReleaseMask, reinterpret_cast<XEvent*>(&e));
  XFlush(d);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: send-keys TITLE-PREFIX KEY[:SECONDS]...\n");
    return 2;
  }
  Display* d = XOpenDisplay(nullptr);
  if (!d) {
    std::fprintf(stderr, "send-keys: cannot open the X display (DISPLAY unset?)\n");
    return 2;
  }
  Window w = 0;
  for (int i = 0; i < 600 && !w; ++i) {
    w = FindWindow(d, DefaultRootWindow(d), argv[1]);
    if (!w) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  if (!w) {
    std::fprintf(stderr, "send-keys: no window named '%s...' within 60 s\n", argv[1]);
    return 1;
  }
  std::this_thread::sleep_for(std::chrono::seconds(1));  // its first frames
  for (int i = 2; i < argc; ++i) {
    std::string arg = argv[i], key = arg.substr(0, arg.find(':'));
    double seconds = arg.find(':') == std::string::npos ? 1.0 : std::atof(arg.c_str() + arg.find(':') + 1);
    KeySym sym = XStringToKeysym(key.c_str());
    if (sym == NoSymbol) {
      std::fprintf(stderr, "send-keys: '%s' is no X keysym name\n", key.c_str());
      return 2;
    }
    Send(d, w, sym, true);
    Send(d, w, sym, false);
    std::printf("send-keys: %s\n", key.c_str());
    std::fflush(stdout);
    std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
  }
  XCloseDisplay(d);
  return 0;
}
