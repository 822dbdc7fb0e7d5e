// A small X11 client for the view tests: finds a top-level window by (part of) its title and
// sends it what a window manager or a user would: a close request (WM_DELETE_WINDOW), keys, a
// mouse drag or wheel steps.
//   x11_window_tool close TITLE
//   x11_window_tool keys TITLE KEYSYM...     (X keysym names: space, Right, 2, Escape, ...)
//   x11_window_tool drag TITLE BUTTON X0 Y0 X1 Y1 [shift]   (buttons 1 left, 2 middle, 3 right;
//                                            window pixels: the pointer moves to X0 Y0, the
//                                            button goes down, the pointer moves to X1 Y1 in four
//                                            steps, the button comes up)
//   x11_window_tool wheel TITLE STEPS        (positive: away from the user, X buttons 4; else 5)
// Exit status 0 when sent, 1 when no such window (or no display), 2 on bad usage.
#include <X11/Xlib.h>
#include <X11/Xutil.h>

#include <cstdio>
#include <cstdlib>
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

void sendPointer(Display* display, Window window, int type, int x, int y, unsigned state,
                 unsigned button) {
    XEvent event{};
    event.type = type;
    long mask = PointerMotionMask;
    if (type == MotionNotify) {
        event.xmotion.display = display;
        event.xmotion.window = window;
        event.xmotion.root = DefaultRootWindow(display);
        event.xmotion.time = CurrentTime;
        event.xmotion.x = event.xmotion.x_root = x;
        event.xmotion.y = event.xmotion.y_root = y;
        event.xmotion.state = state;
        event.xmotion.same_screen = True;
        if (state & (Button1Mask | Button2Mask | Button3Mask)) mask |= ButtonMotionMask;
    } else {
        event.xbutton.display = display;
        event.xbutton.window = window;
        event.xbutton.root = DefaultRootWindow(display);
        event.xbutton.time = CurrentTime;
        event.xbutton.x = event.xbutton.x_root = x;
        event.xbutton.y = event.xbutton.y_root = y;
        event.xbutton.state = state;
        event.xbutton.button = button;
        event.xbutton.same_screen = True;
        mask = type == ButtonPress ? ButtonPressMask : ButtonReleaseMask;
    }
    XSendEvent(display, window, True, mask, &event);
}

unsigned buttonMask(unsigned button) {
    return button == 1 ? Button1Mask : button == 2 ? Button2Mask : Button3Mask;
}

} // namespace

int main(int argc, char** argv) {
    const bool drag = argc >= 8 && std::strcmp(argv[1], "drag") == 0;
    const bool wheel = argc == 4 && std::strcmp(argv[1], "wheel") == 0;
    if (argc < 3 || (std::strcmp(argv[1], "close") != 0 && std::strcmp(argv[1], "keys") != 0 &&
                     !drag && !wheel)) {
        std::fprintf(stderr, "usage: x11_window_tool close TITLE | keys TITLE KEYSYM... | drag "
                             "TITLE BUTTON X0 Y0 X1 Y1 [shift] | wheel TITLE STEPS\n");
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
    } else if (drag) {
        const unsigned button = unsigned(std::atoi(argv[3]));
        const int x0 = std::atoi(argv[4]), y0 = std::atoi(argv[5]);
        const int x1 = std::atoi(argv[6]), y1 = std::atoi(argv[7]);
        const unsigned shift = argc > 8 && std::strcmp(argv[8], "shift") == 0 ? ShiftMask : 0;
        const unsigned held = shift | buttonMask(button);
        sendPointer(display, window, MotionNotify, x0, y0, shift, 0);
        sendPointer(display, window, ButtonPress, x0, y0, shift, button);
        for (int step = 1; step <= 4; ++step)
            sendPointer(display, window, MotionNotify, x0 + (x1 - x0) * step / 4,
                        y0 + (y1 - y0) * step / 4, held, 0);
        sendPointer(display, window, ButtonRelease, x1, y1, held, button);
    } else if (wheel) {
        const int steps = std::atoi(argv[3]);
        const unsigned button = steps > 0 ? 4 : 5;
        for (int i = 0; i < std::abs(steps); ++i) {
            sendPointer(display, window, ButtonPress, 10, 10, 0, button);
            sendPointer(display, window, ButtonRelease, 10, 10, 0, button);
        }
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
