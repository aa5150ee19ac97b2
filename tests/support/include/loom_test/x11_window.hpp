#pragma once
// Resizes a top-level X11 window by title, from outside the program that owns it (as a user
// or window manager would). Kept apart from gtest: Xlib's macros clash with its names.

namespace loom::test {

/// False when there is no display or no window with that title.
bool resize_x11_window(const char* title, unsigned width, unsigned height);

}  // namespace loom::test
