#include "gl_context.hpp"

#include <cstdio>
#include <mutex>
#include <string>

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "glfw_window_input.hpp"

namespace loom::gl {
namespace {

// The EGL display and GLFW are process-wide; they are initialised by the first device that
// needs them and shut down with the last one.
std::mutex g_platform_mutex;
int g_egl_users = 0;
int g_glfw_users = 0;

std::string egl_error_string() {
    char buf[32];
    std::snprintf(buf, sizeof buf, "0x%04X", static_cast<unsigned>(eglGetError()));
    return buf;
}

std::string glfw_error_string() {
    const char* description = nullptr;
    const int code = glfwGetError(&description);
    if (code == GLFW_NO_ERROR) return "unknown GLFW error";
    return description ? description : "GLFW error " + std::to_string(code);
}

}  // namespace

Result<std::unique_ptr<GlContext>> GlContext::create_headless(bool debug) {
    std::lock_guard lock(g_platform_mutex);
    const char* client_extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!client_extensions || std::string(client_extensions).find("EGL_MESA_platform_surfaceless") == std::string::npos) {
        return Error{ErrorCode::Unsupported, "EGL has no surfaceless platform (EGL_MESA_platform_surfaceless missing)"};
    }
    EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display == EGL_NO_DISPLAY) {
        return Error{ErrorCode::Unsupported, "eglGetPlatformDisplayEXT(surfaceless) failed: " + egl_error_string()};
    }
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) {
        return Error{ErrorCode::Unsupported, "eglInitialize failed: " + egl_error_string()};
    }
    ++g_egl_users;
    auto fail = [&](std::string message) -> Error {
        if (--g_egl_users == 0) eglTerminate(display);
        return Error{ErrorCode::Unsupported, std::move(message)};
    };
    const std::string extensions = eglQueryString(display, EGL_EXTENSIONS);
    if (extensions.find("EGL_KHR_no_config_context") == std::string::npos ||
        extensions.find("EGL_KHR_surfaceless_context") == std::string::npos) {
        return fail("EGL lacks EGL_KHR_no_config_context / EGL_KHR_surfaceless_context");
    }
    if (!eglBindAPI(EGL_OPENGL_API)) return fail("eglBindAPI(EGL_OPENGL_API) failed: " + egl_error_string());
    const EGLint attributes[] = {
        EGL_CONTEXT_MAJOR_VERSION, 4,
        EGL_CONTEXT_MINOR_VERSION, 5,
        EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
        EGL_CONTEXT_FLAGS_KHR, debug ? EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR : 0,
        EGL_NONE,
    };
    EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
    if (context == EGL_NO_CONTEXT) {
        return fail("eglCreateContext(OpenGL 4.5 core) failed: " + egl_error_string());
    }
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
        eglDestroyContext(display, context);
        return fail("eglMakeCurrent(surfaceless) failed: " + egl_error_string());
    }
    std::unique_ptr<GlContext> out(new GlContext());
    out->egl_display_ = display;
    out->egl_context_ = context;
    return out;
}

Result<std::unique_ptr<GlContext>> GlContext::create_windowed(const rhi::WindowDesc& window, bool debug) {
    std::lock_guard lock(g_platform_mutex);
    if (g_glfw_users == 0 && !glfwInit()) {
        return Error{ErrorCode::Unsupported, "cannot open a window: glfwInit failed (" + glfw_error_string() +
                                                 "); is a display available (DISPLAY / WAYLAND_DISPLAY)?"};
    }
    ++g_glfw_users;
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, debug ? GLFW_TRUE : GLFW_FALSE);
    glfwWindowHint(GLFW_RESIZABLE, window.resizable ? GLFW_TRUE : GLFW_FALSE);
    // The back buffer is an offscreen texture; the window's own framebuffer needs no depth.
    glfwWindowHint(GLFW_DEPTH_BITS, 0);
    glfwWindowHint(GLFW_STENCIL_BITS, 0);
    GLFWwindow* handle = glfwCreateWindow(static_cast<int>(window.width), static_cast<int>(window.height),
                                          window.title.c_str(), nullptr, nullptr);
    if (!handle) {
        std::string reason = glfw_error_string();
        if (--g_glfw_users == 0) glfwTerminate();
        return Error{ErrorCode::Unsupported, "cannot open a " + std::to_string(window.width) + "x" +
                                                 std::to_string(window.height) + " OpenGL 4.5 window: " + reason};
    }
    glfwMakeContextCurrent(handle);
    glfwSwapInterval(window.vsync ? 1 : 0);
    std::unique_ptr<GlContext> out(new GlContext());
    out->window_ = handle;
    out->input_ = std::make_unique<backends::GlfwWindowInput>();
    out->input_->attach(handle);
    return out;
}

Result<std::unique_ptr<GlContext>> GlContext::adopt_current() {
    // Without a current context GL returns no strings (the calls reach no driver).
    if (glGetString(GL_VERSION) == nullptr) {
        return Error{ErrorCode::Unsupported, "no OpenGL context is current on this thread: make the application's context "
                                             "current before creating the device"};
    }
    std::unique_ptr<GlContext> out(new GlContext());
    out->adopted_ = true;
    return out;
}

GlContext::~GlContext() {
    std::lock_guard lock(g_platform_mutex);
    if (window_) {
        glfwDestroyWindow(window_);
        if (--g_glfw_users == 0) glfwTerminate();
    }
    if (egl_context_) {
        auto display = static_cast<EGLDisplay>(egl_display_);
        if (eglGetCurrentContext() == static_cast<EGLContext>(egl_context_)) {
            eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        }
        eglDestroyContext(display, static_cast<EGLContext>(egl_context_));
        if (--g_egl_users == 0) {
            eglTerminate(display);
            eglReleaseThread();
        }
    }
}

void GlContext::make_current() {
    if (adopted_) return;  // the application keeps its context current while it calls loom
    if (window_) {
        if (glfwGetCurrentContext() != window_) glfwMakeContextCurrent(window_);
        return;
    }
    auto context = static_cast<EGLContext>(egl_context_);
    if (eglGetCurrentContext() != context) {
        eglMakeCurrent(static_cast<EGLDisplay>(egl_display_), EGL_NO_SURFACE, EGL_NO_SURFACE, context);
    }
}

bool GlContext::poll_events() {
    if (!window_) return false;
    glfwPollEvents();
    input_->publish();
    return !glfwWindowShouldClose(window_);
}

const rhi::WindowInput* GlContext::input() const { return input_ ? &input_->input() : nullptr; }

rhi::Extent3D GlContext::framebuffer_size() const {
    if (!window_) return {0, 0, 0};
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return {static_cast<uint32_t>(w), static_cast<uint32_t>(h), 1};
}

void GlContext::swap_buffers() {
    if (window_) glfwSwapBuffers(window_);
}

}  // namespace loom::gl
