#pragma once
// The project's logger. Backends route API debug output here (KHR_debug, the Vulkan
// validation layer); tests install a sink that fails the test on any error message.

#include <functional>
#include <string>
#include <string_view>

namespace loom {

/// Severity of a log message.
enum class LogLevel : uint8_t { Debug, Info, Warning, Error };

/// "debug", "info", "warning" or "error".
std::string_view log_level_name(LogLevel level);

/// Receives every message at or above the minimum level. `source` names the origin
/// ("gl", "vulkan", "framegraph", ...).
using LogSink = std::function<void(LogLevel level, std::string_view source, std::string_view message)>;

/// Replaces the sink (the default prints Warning and above to stderr); returns the old one.
/// Pass an empty function to restore the default.
LogSink set_log_sink(LogSink sink);

/// Messages below this level are dropped before reaching the sink (default Info).
void set_log_level(LogLevel min_level);

/// Sends a message to the sink (when at or above the minimum level).
void log(LogLevel level, std::string_view source, std::string_view message);

/// log() at LogLevel::Debug.
inline void log_debug(std::string_view source, std::string_view message) { log(LogLevel::Debug, source, message); }
/// log() at LogLevel::Info.
inline void log_info(std::string_view source, std::string_view message) { log(LogLevel::Info, source, message); }
/// log() at LogLevel::Warning.
inline void log_warning(std::string_view source, std::string_view message) { log(LogLevel::Warning, source, message); }
/// log() at LogLevel::Error.
inline void log_error(std::string_view source, std::string_view message) { log(LogLevel::Error, source, message); }

}  // namespace loom
