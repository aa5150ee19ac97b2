#include "loom/rhi/log.hpp"

#include <atomic>
#include <cstdio>
#include <mutex>

namespace loom {
namespace {

void default_sink(LogLevel level, std::string_view source, std::string_view message) {
    if (level < LogLevel::Warning) return;
    std::fprintf(stderr, "[%.*s] %.*s: %.*s\n", static_cast<int>(log_level_name(level).size()),
                 log_level_name(level).data(), static_cast<int>(source.size()), source.data(),
                 static_cast<int>(message.size()), message.data());
}

// The logger is process-wide: API debug callbacks arrive on driver threads with no context.
struct Logger {
    std::mutex mutex;
    LogSink sink;
    std::atomic<LogLevel> min_level{LogLevel::Info};
};

Logger& logger() {
    static Logger instance;
    return instance;
}

}  // namespace

std::string_view log_level_name(LogLevel level) {
    switch (level) {
        case LogLevel::Debug: return "debug";
        case LogLevel::Info: return "info";
        case LogLevel::Warning: return "warning";
        case LogLevel::Error: return "error";
    }
    return "?";
}

LogSink set_log_sink(LogSink sink) {
    Logger& l = logger();
    std::lock_guard lock(l.mutex);
    LogSink old = std::move(l.sink);
    l.sink = std::move(sink);
    return old;
}

void set_log_level(LogLevel min_level) { logger().min_level = min_level; }

void log(LogLevel level, std::string_view source, std::string_view message) {
    Logger& l = logger();
    if (level < l.min_level.load()) return;
    std::lock_guard lock(l.mutex);
    if (l.sink) {
        l.sink(level, source, message);
    } else {
        default_sink(level, source, message);
    }
}

}  // namespace loom
