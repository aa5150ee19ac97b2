#pragma once
// What the user did to a windowed device's window: the cursor, mouse buttons, scrolling, keys
// and typed text, as seen by the latest Device::poll_window(). Enough to drive an immediate-mode
// UI (the windowed samples' frame overlay, samples/overlay) without reaching past the RHI for
// the window system's handle; headless devices report no input.

#include <array>
#include <bitset>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

namespace loom::rhi {

/// The keys a device reports: those a UI navigates and edits with, and the function keys
/// applications bind (the overlay's F1). Other keys are not reported.
enum class Key : uint8_t {
    Tab, Left, Right, Up, Down, PageUp, PageDown, Home, End, Insert, Delete, Backspace, Space, Enter,
    Escape, A, C, V, X, Y, Z,
    F1, F2, F3, F4, F5, F6, F7, F8, F9, F10, F11, F12,
};
/// How many Key values there are.
inline constexpr std::size_t kKeyCount = static_cast<std::size_t>(Key::F12) + 1;

/// "Tab", "F1", ... (for messages and tests).
std::string_view key_name(Key key);

/// The mouse buttons a device reports.
enum class MouseButton : uint8_t { Left, Right, Middle };
inline constexpr std::size_t kMouseButtonCount = 3;

/// The window's input as of the latest poll_window(). Held state (cursor, buttons and keys
/// down, modifiers) is what it was when the poll returned; events (presses, scrolling, text)
/// are those that arrived since the poll before, so a click or a key tap shorter than a frame
/// is not lost even though the button or key is up again by the time the poll returns.
struct WindowInput {
    /// The cursor in framebuffer pixels from the top-left corner (the back buffer's texels,
    /// also on displays that scale windows); meaningful only while `cursor_inside`.
    float cursor_x = 0.0f;
    float cursor_y = 0.0f;
    bool cursor_inside = false;
    /// The window has the keyboard focus.
    bool focused = false;
    std::array<bool, kMouseButtonCount> buttons_down{};
    /// A button went down since the previous poll (it may be up again already).
    std::array<bool, kMouseButtonCount> buttons_pressed{};
    /// Wheel or touchpad scrolling since the previous poll, in lines; +y scrolls up.
    float scroll_x = 0.0f;
    float scroll_y = 0.0f;
    std::bitset<kKeyCount> keys_down;
    /// Keys that went down (or repeated) since the previous poll, in order.
    std::vector<Key> key_presses;
    /// Unicode code points typed since the previous poll, in order.
    std::vector<char32_t> text;
    bool shift = false;
    bool ctrl = false;
    bool alt = false;
    bool super = false;

    [[nodiscard]] bool down(Key key) const { return keys_down.test(static_cast<std::size_t>(key)); }
    [[nodiscard]] bool down(MouseButton button) const { return buttons_down[static_cast<std::size_t>(button)]; }
    [[nodiscard]] bool pressed(MouseButton button) const { return buttons_pressed[static_cast<std::size_t>(button)]; }
    /// True when `key` went down since the previous poll.
    [[nodiscard]] bool pressed(Key key) const {
        for (Key k : key_presses) {
            if (k == key) return true;
        }
        return false;
    }
};

}  // namespace loom::rhi
