// loom-triangle writes the same PNG with --backend gl and --backend vulkan.
#include <cstdlib>
#include <filesystem>
#include <string>

#include "cross_backend.hpp"
#include "loom_test/test_support.hpp"

#include "loom/image_io/image_io.hpp"

namespace loom::test {
namespace {

TEST(CrossBackendSample, TrianglePngIsIdenticalOnBothBackends) {
    std::string why_not;
    if (!both_backends_available(why_not)) GTEST_SKIP() << why_not;
    const std::filesystem::path dir = output_dir() / "cross_backend";
    std::filesystem::create_directories(dir);
    rhi::Image images[2];
    int i = 0;
    for (const char* backend : {"gl", "vulkan"}) {
        const std::filesystem::path png = dir / (std::string("triangle_") + backend + ".png");
        std::filesystem::remove(png);
        const std::string command = std::string("\"") + LOOM_TRIANGLE_EXE + "\" --backend " + backend +
                                    " --size 203x151 --out \"" + png.string() + "\" > /dev/null";
        ASSERT_EQ(std::system(command.c_str()), 0) << command;
        auto image = image_io::read_png(png);
        ASSERT_TRUE(image.ok()) << image.error().to_string();
        images[i++] = std::move(*image);
    }
    auto comparison = image_io::compare_and_report(images[0], images[1], dir, "triangle_sample");
    ASSERT_TRUE(comparison.ok()) << comparison.error().to_string();
    EXPECT_TRUE(comparison->equal()) << "gl vs vulkan: " << comparison->summary();
}

}  // namespace
}  // namespace loom::test
