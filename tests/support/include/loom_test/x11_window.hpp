#pragma once
// Acts on a top-level X11 window by title from outside the program that owns it, as a user or
// window manager would: resizes it, presses a key in it, clicks in it. Kept apart from gtest:
// Xlib's macros clash with its names.

namespace loom::test {

/// False when there is no display or no window with that title.
bool resize_x11_window(const char* title, unsigned width, unsigned height);

/// Sends a press and a release of the key `keysym` (an X keysym, e.g. 0xffbe for F1) to the
/// window. False when there is no display, no such window or no key for the keysym.
bool press_x11_key(const char* title, unsigned long keysym);

/// Moves the pointer to (x, y) in the window's coordinates and sends a press and a release of
/// the left button there. False when there is no display or no such window.
bool click_x11_window(const char* title, int x, int y);

}  // namespace loom::test
