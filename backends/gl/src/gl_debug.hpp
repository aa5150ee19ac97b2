#pragma once
// KHR_debug output routed to loom's logger (source "gl").

#include <epoxy/gl.h>

namespace loom::gl {

/// Turns on synchronous debug output for the current context: API errors and high-severity
/// messages are logged at LogLevel::Error, medium at Warning, low at Info, notifications at
/// Debug; shader compiler messages at Info (compile and link errors are returned as values).
/// Does nothing when the context was not created with the debug flag.
void install_debug_output();

/// The debug-output settings of an application's context: its callback and user pointer, and
/// whether GL_DEBUG_OUTPUT and GL_DEBUG_OUTPUT_SYNCHRONOUS were enabled.
struct SavedDebugOutput {
    GLDEBUGPROC callback = nullptr;
    const void* user = nullptr;
    bool enabled = false;
    bool synchronous = false;
};

/// On an application's context: installs loom's callback (levels as install_debug_output) and
/// enables synchronous debug output, without touching the message filter. Returns what was
/// there before, for restore_debug_output.
SavedDebugOutput take_over_debug_output();

/// Puts the application's debug-output settings back.
void restore_debug_output(const SavedDebugOutput& saved);

}  // namespace loom::gl
