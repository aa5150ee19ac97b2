#include "loom/rhi/window_input.hpp"

#include "loom/rhi/device.hpp"

namespace loom::rhi {

std::string_view key_name(Key key) {
    static constexpr std::array<std::string_view, kKeyCount> kNames = {
        "Tab", "Left", "Right", "Up", "Down", "PageUp", "PageDown", "Home", "End", "Insert", "Delete",
        "Backspace", "Space", "Enter", "Escape", "A", "C", "V", "X", "Y", "Z",
        "F1", "F2", "F3", "F4", "F5", "F6", "F7", "F8", "F9", "F10", "F11", "F12",
    };
    const auto i = static_cast<std::size_t>(key);
    return i < kNames.size() ? kNames[i] : std::string_view("unknown key");
}

const WindowInput& Device::window_input() const {
    // Nothing ever changes it: devices without a window of their own share it.
    static const WindowInput kNoInput;
    return kNoInput;
}

}  // namespace loom::rhi
