#pragma once
// The input of a GLFW window as rhi::WindowInput, shared by the GL and Vulkan backends' windows
// (header-only, so that each backend library stays self-contained). GLFW calls back from inside
// glfwPollEvents, which handles the events of every window of the process: events gather per
// window in `pending_` until that window's device polls and publishes them, so that two windowed
// devices polling in turn never drop each other's events.

#if !defined(GLFW_INCLUDE_VULKAN) && !defined(GLFW_INCLUDE_NONE)
#define GLFW_INCLUDE_NONE
#endif
#include <GLFW/glfw3.h>

#include <algorithm>
#include <optional>

#include "loom/rhi/window_input.hpp"

namespace loom::backends {

class GlfwWindowInput {
public:
    /// Starts listening to `window` (its GLFW user pointer is this object from now on).
    void attach(GLFWwindow* window) {
        window_ = window;
        glfwSetWindowUserPointer(window, this);
        glfwSetKeyCallback(window, &GlfwWindowInput::on_key);
        glfwSetCharCallback(window, &GlfwWindowInput::on_char);
        glfwSetMouseButtonCallback(window, &GlfwWindowInput::on_button);
        glfwSetScrollCallback(window, &GlfwWindowInput::on_scroll);
        glfwSetCursorPosCallback(window, &GlfwWindowInput::on_cursor);
        glfwSetCursorEnterCallback(window, &GlfwWindowInput::on_enter);
        double x = 0.0, y = 0.0;
        glfwGetCursorPos(window, &x, &y);
        cursor_x_ = x;
        cursor_y_ = y;
        int width = 0, height = 0;
        glfwGetWindowSize(window, &width, &height);
        inside_ = x >= 0.0 && y >= 0.0 && x < width && y < height;
    }

    /// After glfwPollEvents: the events gathered since the previous call become the input's,
    /// and the held state is read as it is now.
    void publish() {
        if (!window_) return;
        rhi::WindowInput& in = current_;
        in.buttons_pressed = pending_.buttons_pressed;
        in.scroll_x = pending_.scroll_x;
        in.scroll_y = pending_.scroll_y;
        in.key_presses.swap(pending_.key_presses);
        in.text.swap(pending_.text);
        pending_.buttons_pressed = {};
        pending_.scroll_x = pending_.scroll_y = 0.0f;
        pending_.key_presses.clear();
        pending_.text.clear();

        in.keys_down = keys_down_;
        in.buttons_down = buttons_down_;
        // GLFW reports the cursor in window coordinates; the back buffer may have more pixels.
        int width = 0, height = 0, fb_width = 0, fb_height = 0;
        glfwGetWindowSize(window_, &width, &height);
        glfwGetFramebufferSize(window_, &fb_width, &fb_height);
        const double sx = width > 0 ? static_cast<double>(fb_width) / width : 1.0;
        const double sy = height > 0 ? static_cast<double>(fb_height) / height : 1.0;
        in.cursor_x = static_cast<float>(cursor_x_ * sx);
        in.cursor_y = static_cast<float>(cursor_y_ * sy);
        in.cursor_inside = inside_;
        in.focused = glfwGetWindowAttrib(window_, GLFW_FOCUSED) == GLFW_TRUE;
        in.shift = held(GLFW_KEY_LEFT_SHIFT) || held(GLFW_KEY_RIGHT_SHIFT);
        in.ctrl = held(GLFW_KEY_LEFT_CONTROL) || held(GLFW_KEY_RIGHT_CONTROL);
        in.alt = held(GLFW_KEY_LEFT_ALT) || held(GLFW_KEY_RIGHT_ALT);
        in.super = held(GLFW_KEY_LEFT_SUPER) || held(GLFW_KEY_RIGHT_SUPER);
    }

    [[nodiscard]] const rhi::WindowInput& input() const { return current_; }

    /// The loom key of a GLFW key code; none for keys loom does not report.
    static std::optional<rhi::Key> key_of(int glfw_key) {
        using rhi::Key;
        if (glfw_key >= GLFW_KEY_F1 && glfw_key <= GLFW_KEY_F12) {
            return static_cast<Key>(static_cast<int>(Key::F1) + (glfw_key - GLFW_KEY_F1));
        }
        switch (glfw_key) {
        case GLFW_KEY_TAB: return Key::Tab;
        case GLFW_KEY_LEFT: return Key::Left;
        case GLFW_KEY_RIGHT: return Key::Right;
        case GLFW_KEY_UP: return Key::Up;
        case GLFW_KEY_DOWN: return Key::Down;
        case GLFW_KEY_PAGE_UP: return Key::PageUp;
        case GLFW_KEY_PAGE_DOWN: return Key::PageDown;
        case GLFW_KEY_HOME: return Key::Home;
        case GLFW_KEY_END: return Key::End;
        case GLFW_KEY_INSERT: return Key::Insert;
        case GLFW_KEY_DELETE: return Key::Delete;
        case GLFW_KEY_BACKSPACE: return Key::Backspace;
        case GLFW_KEY_SPACE: return Key::Space;
        case GLFW_KEY_ENTER:
        case GLFW_KEY_KP_ENTER: return Key::Enter;
        case GLFW_KEY_ESCAPE: return Key::Escape;
        case GLFW_KEY_A: return Key::A;
        case GLFW_KEY_C: return Key::C;
        case GLFW_KEY_V: return Key::V;
        case GLFW_KEY_X: return Key::X;
        case GLFW_KEY_Y: return Key::Y;
        case GLFW_KEY_Z: return Key::Z;
        default: return std::nullopt;
        }
    }

private:
    static GlfwWindowInput* of(GLFWwindow* window) { return static_cast<GlfwWindowInput*>(glfwGetWindowUserPointer(window)); }

    [[nodiscard]] bool held(int glfw_key) const { return glfwGetKey(window_, glfw_key) == GLFW_PRESS; }

    static void on_key(GLFWwindow* window, int key, int /*scancode*/, int action, int /*mods*/) {
        GlfwWindowInput* self = of(window);
        const std::optional<rhi::Key> k = key_of(key);
        if (!self || !k) return;
        const auto i = static_cast<std::size_t>(*k);
        if (action == GLFW_RELEASE) {
            self->keys_down_.reset(i);
        } else {
            self->keys_down_.set(i);
            self->pending_.key_presses.push_back(*k);
        }
    }
    static void on_char(GLFWwindow* window, unsigned int code_point) {
        if (GlfwWindowInput* self = of(window)) self->pending_.text.push_back(static_cast<char32_t>(code_point));
    }
    static void on_button(GLFWwindow* window, int button, int action, int /*mods*/) {
        GlfwWindowInput* self = of(window);
        // GLFW's left, right and middle are 0, 1 and 2, as rhi::MouseButton's.
        if (!self || button < 0 || button >= static_cast<int>(rhi::kMouseButtonCount)) return;
        const bool down = action == GLFW_PRESS;
        self->buttons_down_[static_cast<std::size_t>(button)] = down;
        if (down) self->pending_.buttons_pressed[static_cast<std::size_t>(button)] = true;
    }
    static void on_scroll(GLFWwindow* window, double x, double y) {
        if (GlfwWindowInput* self = of(window)) {
            self->pending_.scroll_x += static_cast<float>(x);
            self->pending_.scroll_y += static_cast<float>(y);
        }
    }
    static void on_cursor(GLFWwindow* window, double x, double y) {
        if (GlfwWindowInput* self = of(window)) {
            self->cursor_x_ = x;
            self->cursor_y_ = y;
            self->inside_ = true;
        }
    }
    static void on_enter(GLFWwindow* window, int entered) {
        if (GlfwWindowInput* self = of(window)) self->inside_ = entered == GLFW_TRUE;
    }

    GLFWwindow* window_ = nullptr;
    rhi::WindowInput current_;
    rhi::WindowInput pending_;  ///< only its event fields are used
    std::bitset<rhi::kKeyCount> keys_down_;
    std::array<bool, rhi::kMouseButtonCount> buttons_down_{};
    double cursor_x_ = 0.0;
    double cursor_y_ = 0.0;
    bool inside_ = false;
};

}  // namespace loom::backends
