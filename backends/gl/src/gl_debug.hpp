#pragma once
// KHR_debug output routed to loom's logger (source "gl").

namespace loom::gl {

/// Turns on synchronous debug output for the current context: API errors and high-severity
/// messages are logged at LogLevel::Error, medium at Warning, low at Info, notifications at
/// Debug; shader compiler messages at Info (compile and link errors are returned as values).
/// Does nothing when the context was not created with the debug flag.
void install_debug_output();

}  // namespace loom::gl
