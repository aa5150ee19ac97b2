#include "x11_window.hpp"

#include <cstring>

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

}  // namespace

bool resize_x11_window(const char* title, unsigned width, unsigned height) {
    Display* display = XOpenDisplay(nullptr);
    if (!display) return false;
    const ::Window window = find_window(display, DefaultRootWindow(display), title);
    if (window) {
        XResizeWindow(display, window, width, height);
        XSync(display, 0);
    }
    XCloseDisplay(display);
    return window != 0;
}

}  // namespace loom::test
