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
    // Appended piece by piece: GCC 12 at -O3 warns falsely about "literal" + std::string
    // (-Wrestrict, GCC bug 105651), and warnings are errors.
    std::string line = "[";
    line += log_level_name(level);
    line += "] ";
    line += source;
    line += ": ";
    line += message;
    messages_->push_back(std::move(line));
}

}  // namespace loom::compare
