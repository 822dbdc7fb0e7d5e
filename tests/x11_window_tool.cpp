// A small X11 client for the view tests: finds a top-level window by (part of) its title and
// sends it what a window manager or a user would: a close request (WM_DELETE_WINDOW) or keys.
//   x11_window_tool close TITLE
//   x11_window_tool keys TITLE KEYSYM...     (X keysym names: space, Right, 2, Escape, ...)
// Exit status 0 when sent, 1 when no such window (or no display), 2 on bad usage.
#include <X11/Xlib.h>
#include <X11/Xutil.h>

#include <cstdio>
#include <cstring>
#include <string>

namespace {

Window findWindow(Display* display, Window parent, const char* title) {
    char* name = nullptr;
    if (XFetchName(display, parent, &name) && name) {
        const bool match = std::strstr(name, title) != nullptr;
        XFree(name);
        if (match) return parent;
    }
    Window root = 0, up = 0, *children = nullptr;
    unsigned count = 0;
    if (!XQueryTree(display, parent, &root, &up, &children, &count)) return 0;
    Window found = 0;
    for (unsigned i = 0; i < count && !found; ++i)
        found = findWindow(display, children[i], title);
    if (children) XFree(children);
    return found;
}

void sendKey(Display* display, Window window, KeyCode code, int type) {
    XEvent event{};
    event.xkey.type = type;
    event.xkey.display = display;
    event.xkey.window = window;
    event.xkey.root = DefaultRootWindow(display);
    event.xkey.subwindow = None;
    event.xkey.time = CurrentTime;
    event.xkey.x = event.xkey.y = 1;
    event.xkey.x_root = event.xkey.y_root = 1;
    event.xkey.same_screen = True;
    event.xkey.keycode = code;
    XSendEvent(display, window, True, type == KeyPress ? KeyPressMask : KeyReleaseMask, &event);
}

} // namespace

int main(int argc, char** argv) {
    if (argc < 3 || (std::strcmp(argv[1], "close") != 0 && std::strcmp(argv[1], "keys") != 0)) {
        std::fprintf(stderr, "usage: x11_window_tool close TITLE | keys TITLE KEYSYM...\n");
        return 2;
    }
    Display* display = XOpenDisplay(nullptr);
    if (!display) {
        std::fprintf(stderr, "x11_window_tool: cannot open the display\n");
        return 1;
    }
    const Window window = findWindow(display, DefaultRootWindow(display), argv[2]);
    if (!window) {
        std::fprintf(stderr, "x11_window_tool: no window titled \"%s\"\n", argv[2]);
        XCloseDisplay(display);
        return 1;
    }
    int status = 0;
    if (std::strcmp(argv[1], "close") == 0) {
        XEvent event{};
        event.xclient.type = ClientMessage;
        event.xclient.window = window;
        event.xclient.message_type = XInternAtom(display, "WM_PROTOCOLS", False);
        event.xclient.format = 32;
        event.xclient.data.l[0] = long(XInternAtom(display, "WM_DELETE_WINDOW", False));
        event.xclient.data.l[1] = CurrentTime;
        XSendEvent(display, window, False, NoEventMask, &event);
    } else {
        for (int i = 3; i < argc; ++i) {
            const KeySym symbol = XStringToKeysym(argv[i]);
            const KeyCode code = symbol == NoSymbol ? 0 : XKeysymToKeycode(display, symbol);
            if (code == 0) {
                std::fprintf(stderr, "x11_window_tool: no key \"%s\"\n", argv[i]);
                status = 2;
                break;
            }
            sendKey(display, window, code, KeyPress);
            sendKey(display, window, code, KeyRelease);
        }
    }
    XFlush(display);
    XCloseDisplay(display);
    return status;
}
