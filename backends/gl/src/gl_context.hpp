#pragma once
// The GL context a device draws with: EGL surfaceless (headless) or a GLFW window.

#include <memory>

#include "loom/rhi/device.hpp"
#include "loom/rhi/result.hpp"

struct GLFWwindow;
namespace loom::backends {
class GlfwWindowInput;
}

namespace loom::gl {

/// Owns one OpenGL 4.5 core context (and its window, if any). Several devices may live in one
/// process, each with its own context; make_current() switches to this one when needed.
class GlContext {
public:
    /// A surfaceless EGL context on the Mesa surfaceless platform (no window system needed).
    static Result<std::unique_ptr<GlContext>> create_headless(bool debug);
    /// A GLFW window with a 4.5 core context; Unsupported when there is no display.
    static Result<std::unique_ptr<GlContext>> create_windowed(const rhi::WindowDesc& window, bool debug);
    /// The context current on the calling thread, owned by the application: never made current
    /// by loom, never destroyed, no window. Unsupported when no context is current.
    static Result<std::unique_ptr<GlContext>> adopt_current();

    ~GlContext();
    GlContext(const GlContext&) = delete;
    GlContext& operator=(const GlContext&) = delete;

    /// Makes this context current on the calling thread if it is not already.
    void make_current();
    [[nodiscard]] bool windowed() const { return window_ != nullptr; }
    /// True for a context adopted from the application (adopt_current).
    [[nodiscard]] bool adopted() const { return adopted_; }
    /// Processes window events; false once the window should close (always false headless).
    bool poll_events();
    /// The window's input as of the latest poll_events(); null without a window.
    [[nodiscard]] const rhi::WindowInput* input() const;
    /// The window's framebuffer size in pixels (0x0 headless).
    [[nodiscard]] rhi::Extent3D framebuffer_size() const;
    /// Presents the default framebuffer (windowed only).
    void swap_buffers();

private:
    GlContext() = default;

    // EGL objects are kept as void* so that this header does not pull in EGL.
    void* egl_display_ = nullptr;
    void* egl_context_ = nullptr;
    GLFWwindow* window_ = nullptr;
    std::unique_ptr<backends::GlfwWindowInput> input_;
    bool adopted_ = false;
};

}  // namespace loom::gl
