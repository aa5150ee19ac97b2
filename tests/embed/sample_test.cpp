// The embedding samples run as a user would run them: headless (several frames, so that the
// Vulkan engine's frames in flight and loom's reuse of frame resources take turns) and, under
// a virtual X server, in a window (EmbedSampleWindow.*: the engine reads its presented back
// buffer / swapchain image). Their pictures are checked texel by texel.
#include <cstdlib>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "embed_test_support.hpp"
#include "loom/image_io/image_io.hpp"
#include "loom/rhi/image.hpp"
#include "loom_test/test_support.hpp"

namespace loom::test {
namespace {

/// Runs `exe` with `arguments` writing `name`.png under output_dir()/embed and returns the
/// picture it wrote.
Result<rhi::Image> run_sample(const std::string& exe, const std::string& arguments, const std::string& name) {
    const std::filesystem::path png = output_dir() / "embed" / (name + ".png");
    std::filesystem::remove(png);
    const std::string command = "\"" + exe + "\" " + arguments + " --out \"" + png.string() + "\"";
    if (const int status = std::system(command.c_str()); status != 0) {
        return Error{ErrorCode::Backend, command + " exited with status " + std::to_string(status)};
    }
    return image_io::read_png(png);
}

void expect_overlay(const Result<rhi::Image>& picture, uint32_t width, uint32_t height, const std::string& name) {
    ASSERT_TRUE(picture.ok()) << picture.error().to_string();
    ASSERT_EQ(picture->width, width);
    ASSERT_EQ(picture->height, height);
    EXPECT_TRUE(matches_overlay(*picture, name + ".checked"));
}

bool has_display() { return std::getenv("DISPLAY") != nullptr || std::getenv("WAYLAND_DISPLAY") != nullptr; }

#if defined(LOOM_EMBED_GL_EXE)
TEST(EmbedSample, GlHeadless) {
    expect_overlay(run_sample(LOOM_EMBED_GL_EXE, "--size 96x64", "sample_gl"), 96, 64, "sample_gl");
}

TEST(EmbedSampleWindow, Gl) {
    if (!has_display()) GTEST_SKIP() << "no display (ctest runs this under xvfb-run)";
    expect_overlay(run_sample(LOOM_EMBED_GL_EXE, "--window --frames 3 --size 96x64", "sample_gl_window"), 96, 64,
                   "sample_gl_window");
}
#endif

#if defined(LOOM_EMBED_VULKAN_EXE)
TEST(EmbedSample, VulkanHeadless) {
    expect_overlay(run_sample(LOOM_EMBED_VULKAN_EXE, "--size 96x64 --frames 4", "sample_vulkan"), 96, 64, "sample_vulkan");
}

TEST(EmbedSampleWindow, Vulkan) {
    if (!has_display()) GTEST_SKIP() << "no display (ctest runs this under xvfb-run)";
    expect_overlay(run_sample(LOOM_EMBED_VULKAN_EXE, "--window --frames 4 --size 96x64", "sample_vulkan_window"), 96, 64,
                   "sample_vulkan_window");
}
#endif

}  // namespace
}  // namespace loom::test
