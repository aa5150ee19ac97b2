// gtest main for every loom test executable: any error logged through loom's logger (GL
// debug output, Vulkan validation messages, library errors) fails the running test, unless a
// ScopedLogCapture collects it on purpose. Tests with missing data are reported in the summary.
#include <mutex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "loom/rhi/log.hpp"
#include "loom_test/test_support.hpp"

namespace loom::test {
namespace {

struct CaptureState {
    std::mutex mutex;
    int depth = 0;
    std::vector<std::string> messages;
};

CaptureState& capture() {
    static CaptureState state;
    return state;
}

void test_sink(LogLevel level, std::string_view source, std::string_view message) {
    if (level < LogLevel::Warning) return;
    // Appended piece by piece: GCC 12 at -O3 warns (-Wrestrict, falsely) on "literal" + string.
    std::string line;
    line.reserve(source.size() + message.size() + 3);
    line.append("[").append(source).append("] ").append(message);
    {
        std::lock_guard lock(capture().mutex);
        if (capture().depth > 0) {
            capture().messages.push_back(line);
            return;
        }
    }
    if (level == LogLevel::Error) {
        ADD_FAILURE() << "error logged: " << line;
    } else {
        std::fprintf(stderr, "[warning] %s\n", line.c_str());
    }
}

}  // namespace

ScopedLogCapture::ScopedLogCapture() {
    std::lock_guard lock(capture().mutex);
    if (capture().depth++ == 0) capture().messages.clear();
}

ScopedLogCapture::~ScopedLogCapture() {
    std::lock_guard lock(capture().mutex);
    --capture().depth;
}

std::vector<std::string> ScopedLogCapture::messages() const {
    std::lock_guard lock(capture().mutex);
    return capture().messages;
}

}  // namespace loom::test

int main(int argc, char** argv) {
    ::testing::InitGoogleTest(&argc, argv);
    loom::set_log_sink(loom::test::test_sink);
    return RUN_ALL_TESTS();
}
