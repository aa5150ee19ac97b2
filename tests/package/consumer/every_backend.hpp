#pragma once
// What the consumer programs that render share: loom's logged errors (GL debug output, Vulkan
// validation; DeviceDesc::debug is on) are counted so that any of them fails the run, and a
// check runs on a device of every backend loom was built with.
#include <cstdio>
#include <functional>
#include <string>
#include <string_view>

#include "loom/rhi/device.hpp"
#include "loom/rhi/log.hpp"

namespace consumer {

/// Prints loom's warnings and errors to stderr and counts the errors, from construction on.
class LoggedErrors {
public:
    LoggedErrors() {
        loom::set_log_sink([this](loom::LogLevel level, std::string_view source, std::string_view message) {
            if (level < loom::LogLevel::Warning) return;
            std::fprintf(stderr, "[%s] %.*s\n", std::string(source).c_str(), static_cast<int>(message.size()),
                         message.data());
            if (level == loom::LogLevel::Error) ++count_;
        });
    }
    LoggedErrors(const LoggedErrors&) = delete;
    LoggedErrors& operator=(const LoggedErrors&) = delete;

    [[nodiscard]] int count() const { return count_; }

private:
    int count_ = 0;
};

/// Runs `check` on a new device of each compiled-in backend and prints one line per backend,
/// "<program>: <backend>: <success or the error>". Returns how many failed, or -1 (after saying
/// so) when loom was built without a backend.
inline int on_every_backend(const char* program, const char* success,
                            const std::function<loom::Status(loom::rhi::Device&)>& check) {
    int failures = 0;
    int backends = 0;
    for (loom::rhi::Backend backend : loom::rhi::compiled_backends()) {
        ++backends;
        loom::rhi::DeviceDesc desc;
        desc.backend = backend;
        auto device = loom::rhi::create_device(desc);
        const loom::Status status = device ? check(**device) : loom::Status(device.error());
        std::printf("%s: %s: %s\n", program, std::string(loom::rhi::backend_name(backend)).c_str(),
                    status ? success : status.error().to_string().c_str());
        if (!status) ++failures;
    }
    if (backends == 0) {
        std::fprintf(stderr, "%s: loom has no backend\n", program);
        return -1;
    }
    return failures;
}

}  // namespace consumer
