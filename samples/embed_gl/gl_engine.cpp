#include "gl_engine.hpp"

#include <cstring>
#include <string>

#include <epoxy/egl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace loom::samples {

Result<std::unique_ptr<GlEngine>> GlEngine::create(bool window, uint32_t width, uint32_t height) {
    std::unique_ptr<GlEngine> engine(new GlEngine());
    if (window) {
        if (!glfwInit()) return Error{ErrorCode::Unsupported, "glfwInit failed: is there a display?"};
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
        glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
        glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
        glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, GLFW_TRUE);
        engine->window_ = glfwCreateWindow(static_cast<int>(width), static_cast<int>(height), "loom embedded in a GL engine",
                                           nullptr, nullptr);
        if (!engine->window_) {
            glfwTerminate();
            return Error{ErrorCode::Unsupported, "cannot open an OpenGL 4.5 window"};
        }
        glfwMakeContextCurrent(engine->window_);
        glfwSwapInterval(1);
        int w = 0, h = 0;
        glfwGetFramebufferSize(engine->window_, &w, &h);
        width = static_cast<uint32_t>(w);
        height = static_cast<uint32_t>(h);
    } else {
        EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        EGLint major = 0, minor = 0;
        if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor) || !eglBindAPI(EGL_OPENGL_API)) {
            return Error{ErrorCode::Unsupported, "no EGL surfaceless display"};
        }
        const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                     EGL_CONTEXT_FLAGS_KHR, EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR, EGL_NONE};
        EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
        if (context == EGL_NO_CONTEXT || !eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
            eglTerminate(display);
            return Error{ErrorCode::Unsupported, "cannot make an OpenGL 4.5 core context current (EGL)"};
        }
        engine->egl_display_ = display;
        engine->egl_context_ = context;
    }
    engine->create_target(width, height);
    return engine;
}

GlEngine::~GlEngine() {
    if (target_) glDeleteTextures(1, &target_);
    if (window_) {
        glfwDestroyWindow(window_);
        glfwTerminate();
    }
    if (egl_context_) {
        auto display = static_cast<EGLDisplay>(egl_display_);
        eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display, static_cast<EGLContext>(egl_context_));
        eglTerminate(display);
    }
}

void GlEngine::create_target(uint32_t width, uint32_t height) {
    if (target_) glDeleteTextures(1, &target_);
    glCreateTextures(GL_TEXTURE_2D, 1, &target_);
    glTextureStorage2D(target_, 1, GL_RGBA8, static_cast<GLsizei>(width), static_cast<GLsizei>(height));
    glObjectLabel(GL_TEXTURE, target_, -1, "engine target");
    width_ = width;
    height_ = height;
}

bool GlEngine::poll() {
    if (!window_) return true;
    glfwPollEvents();
    return !glfwWindowShouldClose(window_);
}

bool GlEngine::fit_target_to_window() {
    if (!window_) return false;
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    if (w <= 0 || h <= 0 || (static_cast<uint32_t>(w) == width_ && static_cast<uint32_t>(h) == height_)) return false;
    create_target(static_cast<uint32_t>(w), static_cast<uint32_t>(h));
    return true;
}

void GlEngine::clear_target() { glClearTexImage(target_, 0, GL_RGBA, GL_FLOAT, kClearColor.data()); }

void GlEngine::present() {
    if (window_) glfwSwapBuffers(window_);
}

rhi::Image GlEngine::read_target() const {
    rhi::Image image(width_, height_, rhi::Format::RGBA8Unorm);
    glGetTextureImage(target_, 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(image.pixels.size()), image.pixels.data());
    return image;
}

rhi::Image GlEngine::read_window() const {
    rhi::Image image(width_, height_, rhi::Format::RGBA8Unorm);
    std::vector<std::byte> rows(image.pixels.size());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, static_cast<GLsizei>(width_), static_cast<GLsizei>(height_), GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
    // GL counts window rows from the bottom.
    for (uint32_t y = 0; y < height_; ++y) {
        std::memcpy(image.pixels.data() + std::size_t{y} * image.row_bytes(),
                    rows.data() + std::size_t{height_ - 1 - y} * image.row_bytes(), image.row_bytes());
    }
    return image;
}

}  // namespace loom::samples
