#include "loom_test/x11_window.hpp"

#include <cstring>
#include <initializer_list>

#include <X11/Xlib.h>

namespace loom::test {
namespace {

::Window find_window(Display* display, ::Window root, const char* title) {
    char* name = nullptr;
    if (XFetchName(display, root, &name) && name) {
        const bool match = std::strcmp(name, title) == 0;
        XFree(name);
        if (match) return root;
    }
    ::Window parent = 0, root_return = 0;
    ::Window* children = nullptr;
    unsigned int count = 0;
    ::Window found = 0;
    if (XQueryTree(display, root, &root_return, &parent, &children, &count)) {
        for (unsigned int i = 0; i < count && !found; ++i) found = find_window(display, children[i], title);
        if (children) XFree(children);
    }
    return found;
}

/// Runs `act(display, window)` on the window titled `title`; false without one.
template <class Act>
bool with_window(const char* title, Act act) {
    Display* display = XOpenDisplay(nullptr);
    if (!display) return false;
    const ::Window window = find_window(display, DefaultRootWindow(display), title);
    bool done = false;
    if (window) {
        done = act(display, window);
        XSync(display, 0);
    }
    XCloseDisplay(display);
    return done;
}

}  // namespace

bool resize_x11_window(const char* title, unsigned width, unsigned height) {
    return with_window(title, [&](Display* display, ::Window window) {
        XResizeWindow(display, window, width, height);
        return true;
    });
}

bool press_x11_key(const char* title, unsigned long keysym) {
    return with_window(title, [&](Display* display, ::Window window) {
        const KeyCode code = XKeysymToKeycode(display, static_cast<KeySym>(keysym));
        if (code == 0) return false;
        for (int type : {KeyPress, KeyRelease}) {
            XEvent event{};
            event.xkey.type = type;
            event.xkey.display = display;
            event.xkey.window = window;
            event.xkey.root = DefaultRootWindow(display);
            event.xkey.subwindow = 0;
            event.xkey.time = CurrentTime;
            event.xkey.x = event.xkey.y = event.xkey.x_root = event.xkey.y_root = 1;
            event.xkey.keycode = code;
            event.xkey.same_screen = True;
            XSendEvent(display, window, True, type == KeyPress ? KeyPressMask : KeyReleaseMask, &event);
        }
        return true;
    });
}

bool click_x11_window(const char* title, int x, int y) {
    return with_window(title, [&](Display* display, ::Window window) {
        // A real pointer move: the server sends the window its enter and motion events.
        XWarpPointer(display, 0, window, 0, 0, 0, 0, x, y);
        XSync(display, 0);
        for (int type : {ButtonPress, ButtonRelease}) {
            XEvent event{};
            event.xbutton.type = type;
            event.xbutton.display = display;
            event.xbutton.window = window;
            event.xbutton.root = DefaultRootWindow(display);
            event.xbutton.time = CurrentTime;
            event.xbutton.x = x;
            event.xbutton.y = y;
            event.xbutton.button = Button1;
            event.xbutton.same_screen = True;
            XSendEvent(display, window, True, type == ButtonPress ? ButtonPressMask : ButtonReleaseMask, &event);
        }
        return true;
    });
}

}  // namespace loom::test
