#pragma once
// The "engine" of loom-embed-gl: it owns the window and the OpenGL 4.5 context (GLFW), or a
// headless EGL context, and its own render target texture, cleared with its own GL calls. loom
// runs on this context and draws into the target (samples/embed_gl/main.cpp).

#include <array>
#include <cstdint>
#include <memory>

#include <epoxy/gl.h>

#include "loom/rhi/image.hpp"
#include "loom/rhi/result.hpp"

struct GLFWwindow;

namespace loom::samples {

class GlEngine {
public:
    /// The engine's clear colour, exact in 8-bit unorm: (51, 102, 153, 255).
    static constexpr std::array<float, 4> kClearColor{0.2f, 0.4f, 0.6f, 1.0f};

    /// A window of width x height with its context (`window`), or a surfaceless EGL context;
    /// the context is current afterwards. Unsupported when neither can be made.
    static Result<std::unique_ptr<GlEngine>> create(bool window, uint32_t width, uint32_t height);
    ~GlEngine();
    GlEngine(const GlEngine&) = delete;
    GlEngine& operator=(const GlEngine&) = delete;

    /// Processes window events; false once the window was closed (always true headless).
    bool poll();
    /// Makes the render target match the window's framebuffer; true when it was recreated.
    bool fit_target_to_window();
    /// The render target (RGBA8) loom draws into.
    [[nodiscard]] GLuint target() const { return target_; }
    [[nodiscard]] uint32_t width() const { return width_; }
    [[nodiscard]] uint32_t height() const { return height_; }
    [[nodiscard]] bool windowed() const { return window_ != nullptr; }

    /// The engine's own rendering before loom's: clears the target.
    void clear_target();
    /// Presents the window's back buffer.
    void present();
    /// The target's texels, rows top-first (as loom wrote them).
    [[nodiscard]] rhi::Image read_target() const;
    /// The window's back buffer, rows flipped to top-first.
    [[nodiscard]] rhi::Image read_window() const;

private:
    GlEngine() = default;
    void create_target(uint32_t width, uint32_t height);

    GLFWwindow* window_ = nullptr;
    void* egl_display_ = nullptr;
    void* egl_context_ = nullptr;
    GLuint target_ = 0;
    uint32_t width_ = 0;
    uint32_t height_ = 0;
};

}  // namespace loom::samples
