#include <cstdlib>
#include <string_view>

#include "loom_test/test_support.hpp"

namespace loom::test {

std::optional<std::filesystem::path> data_dir() {
    const std::filesystem::path dir = LOOM_TEST_DATA_DIR;
    std::error_code ec;
    if (std::filesystem::is_directory(dir, ec)) return std::filesystem::weakly_canonical(dir, ec);
    return std::nullopt;
}

bool running_in_ci() {
    const char* ci = std::getenv("CI");
    return ci != nullptr && std::string_view(ci) == "true";
}

std::filesystem::path output_dir() {
    const char* dir = std::getenv("LOOM_TEST_OUTPUT_DIR");
    std::filesystem::path path = dir && *dir ? dir : "test-output";
    std::error_code ec;
    std::filesystem::create_directories(path, ec);
    return path;
}

}  // namespace loom::test
