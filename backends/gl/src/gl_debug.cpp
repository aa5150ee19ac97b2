#include "gl_debug.hpp"

#include <string>

#include "loom/rhi/log.hpp"

namespace loom::gl {
namespace {

const char* source_name(GLenum source) {
    switch (source) {
        case GL_DEBUG_SOURCE_API: return "api";
        case GL_DEBUG_SOURCE_WINDOW_SYSTEM: return "window system";
        case GL_DEBUG_SOURCE_SHADER_COMPILER: return "shader compiler";
        case GL_DEBUG_SOURCE_THIRD_PARTY: return "third party";
        case GL_DEBUG_SOURCE_APPLICATION: return "application";
        default: return "other";
    }
}

const char* type_name(GLenum type) {
    switch (type) {
        case GL_DEBUG_TYPE_ERROR: return "error";
        case GL_DEBUG_TYPE_DEPRECATED_BEHAVIOR: return "deprecated";
        case GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR: return "undefined behaviour";
        case GL_DEBUG_TYPE_PORTABILITY: return "portability";
        case GL_DEBUG_TYPE_PERFORMANCE: return "performance";
        case GL_DEBUG_TYPE_MARKER: return "marker";
        case GL_DEBUG_TYPE_PUSH_GROUP: return "push group";
        case GL_DEBUG_TYPE_POP_GROUP: return "pop group";
        default: return "other";
    }
}

LogLevel level_of(GLenum source, GLenum type, GLenum severity) {
    // Compile and link failures come back from create_shader / create_*_pipeline as errors
    // with the full info log; logging them as errors too would report them twice.
    if (source == GL_DEBUG_SOURCE_SHADER_COMPILER) return LogLevel::Info;
    if (type == GL_DEBUG_TYPE_ERROR || severity == GL_DEBUG_SEVERITY_HIGH) return LogLevel::Error;
    switch (severity) {
        case GL_DEBUG_SEVERITY_MEDIUM: return LogLevel::Warning;
        case GL_DEBUG_SEVERITY_LOW: return LogLevel::Info;
        default: return LogLevel::Debug;
    }
}

void GLAPIENTRY on_debug_message(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                                 const GLchar* message, const void* /*user*/) {
    std::string text = std::string(type_name(type)) + " (" + source_name(source) + ", id " + std::to_string(id) + "): ";
    text.append(message, length >= 0 ? static_cast<std::size_t>(length) : std::char_traits<char>::length(message));
    log(level_of(source, type, severity), "gl", text);
}

}  // namespace

void install_debug_output() {
    GLint flags = 0;
    glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
    if ((flags & GL_CONTEXT_FLAG_DEBUG_BIT) == 0) return;
    glEnable(GL_DEBUG_OUTPUT);
    // Synchronous, so that an error is logged while the call that caused it is on the stack.
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(on_debug_message, nullptr);
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
}

SavedDebugOutput take_over_debug_output() {
    SavedDebugOutput saved;
    void* callback = nullptr;
    void* user = nullptr;
    glGetPointerv(GL_DEBUG_CALLBACK_FUNCTION, &callback);
    glGetPointerv(GL_DEBUG_CALLBACK_USER_PARAM, &user);
    // A function pointer comes back as a data pointer; GL stored the one it was given.
    saved.callback = reinterpret_cast<GLDEBUGPROC>(callback);
    saved.user = user;
    saved.enabled = glIsEnabled(GL_DEBUG_OUTPUT) == GL_TRUE;
    saved.synchronous = glIsEnabled(GL_DEBUG_OUTPUT_SYNCHRONOUS) == GL_TRUE;
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(on_debug_message, nullptr);
    return saved;
}

void restore_debug_output(const SavedDebugOutput& saved) {
    glDebugMessageCallback(saved.callback, saved.user);
    if (saved.synchronous) {
        glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    } else {
        glDisable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    }
    if (saved.enabled) {
        glEnable(GL_DEBUG_OUTPUT);
    } else {
        glDisable(GL_DEBUG_OUTPUT);
    }
}

}  // namespace loom::gl
