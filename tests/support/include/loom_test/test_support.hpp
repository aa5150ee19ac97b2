#pragma once
// Helpers shared by loom's tests.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace loom::test {

/// The real test data directory (the LOOM_DATA_DIR cache variable), if it exists.
std::optional<std::filesystem::path> data_dir();

/// True when the CI environment variable is "true" (missing test data then fails tests).
bool running_in_ci();

/// Where tests write pictures they produce (diff heat maps on failure, sample output):
/// $LOOM_TEST_OUTPUT_DIR or ./test-output.
std::filesystem::path output_dir();

/// While alive, errors logged through loom's logger are collected here instead of failing
/// the current test (for tests that provoke errors on purpose).
class ScopedLogCapture {
public:
    ScopedLogCapture();
    ~ScopedLogCapture();
    ScopedLogCapture(const ScopedLogCapture&) = delete;
    ScopedLogCapture& operator=(const ScopedLogCapture&) = delete;
    /// Every message at Warning or above seen so far, as "[source] message".
    [[nodiscard]] std::vector<std::string> messages() const;
};

}  // namespace loom::test

/// Skips the test (with a visible message) when the test data directory is missing, or fails
/// it when running in CI, where the data must be present.
#define LOOM_REQUIRE_DATA_DIR(var)                                                              \
    auto var##_optional = ::loom::test::data_dir();                                            \
    if (!var##_optional) {                                                                     \
        if (::loom::test::running_in_ci()) {                                                   \
            FAIL() << "test data directory missing (LOOM_DATA_DIR) and CI=true";               \
        }                                                                                      \
        GTEST_SKIP() << "test data directory missing (set LOOM_DATA_DIR); skipping";          \
    }                                                                                          \
    const std::filesystem::path var = *var##_optional
