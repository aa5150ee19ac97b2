#include "log_router.hpp"

#include <cstdio>

namespace loom::compare {

LogRouter::LogRouter() {
    previous_ = set_log_sink([this](LogLevel level, std::string_view source, std::string_view message) {
        receive(level, source, message);
    });
}

LogRouter::~LogRouter() { set_log_sink(std::move(previous_)); }

void LogRouter::route(std::vector<std::string>* messages) {
    std::lock_guard lock(mutex_);
    messages_ = messages;
}

void LogRouter::receive(LogLevel level, std::string_view source, std::string_view message) {
    std::lock_guard lock(mutex_);
    const bool problem = level == LogLevel::Error || (level == LogLevel::Warning && source != "gltf");
    if (messages_ == nullptr) {
        if (previous_) {
            previous_(level, source, message);
        } else if (level >= LogLevel::Warning) {
            std::fprintf(stderr, "[%s] %s: %s\n", std::string(log_level_name(level)).c_str(), std::string(source).c_str(),
                         std::string(message).c_str());
        }
        return;
    }
    if (!problem) return;
    messages_->push_back("[" + std::string(log_level_name(level)) + "] " + std::string(source) + ": " +
                         std::string(message));
}

}  // namespace loom::compare
