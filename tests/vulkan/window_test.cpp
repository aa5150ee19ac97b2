// A windowed Vulkan device: frames acquire and present the swapchain's back buffer, a
// readback in the middle of a frame works on it, and the swapchain follows window resizes.
// Needs an X display (ctest runs it under xvfb-run when that is installed); skipped without.
#include <chrono>
#include <cstdlib>
#include <thread>

#include <gtest/gtest.h>

#include "loom/rhi/device.hpp"
#include "loom_test/test_support.hpp"
#include "vulkan_test_support.hpp"
#include "loom_test/x11_window.hpp"

namespace loom::test {
namespace {

constexpr const char* kTitle = "loom vulkan window test";

void clear_backbuffer(rhi::CommandList& list, rhi::TextureHandle backbuffer, std::array<double, 4> color) {
    rhi::RenderPassDesc pass;
    pass.label = "clear back buffer";
    rhi::ColorAttachment a;
    a.texture = backbuffer;
    a.clear = color;
    pass.colors.push_back(a);
    list.begin_render_pass(pass);
    list.end_render_pass();
}

TEST(VulkanWindow, PresentsReadsBackAndFollowsResizes) {
    if (!std::getenv("DISPLAY")) GTEST_SKIP() << "no X display (run under xvfb-run)";
    rhi::DeviceDesc desc;
    desc.backend = rhi::Backend::Vulkan;
    desc.headless = false;
    desc.window.title = kTitle;
    desc.window.width = 160;
    desc.window.height = 120;
    auto created = rhi::create_device(desc);
    ASSERT_TRUE(created.ok()) << created.error().to_string();
    rhi::Device& device = **created;

    for (int frame = 0; frame < 4; ++frame) {
        EXPECT_TRUE(device.poll_window());
        rhi::CommandList& list = device.begin_frame();
        const rhi::TextureHandle backbuffer = device.backbuffer();
        ASSERT_FALSE(backbuffer.is_null());
        LOOM_VK_ASSIGN(const rhi::TextureDesc bd, device.texture_desc(backbuffer));
        EXPECT_EQ(bd.width, device.window_size().width);
        EXPECT_EQ(bd.height, device.window_size().height);
        clear_backbuffer(list, backbuffer, {0.0, 1.0, 0.0, 1.0});
        if (frame == 2) {
            // The frame is split here; the acquire wait goes with its first part.
            LOOM_VK_ASSIGN(rhi::Image image, device.read_texture(backbuffer));
            const auto green = image.load(bd.width / 2, bd.height / 2);
            EXPECT_EQ(green[0], 0.0);
            EXPECT_EQ(green[1], 1.0);
        }
        LOOM_VK_OK(device.end_frame());
    }
    EXPECT_EQ(device.resource_stats().textures, 0u) << "back buffers are not user textures";

    ASSERT_TRUE(resize_x11_window(kTitle, 320, 200)) << "window '" << kTitle << "' not found";

    bool resized = false;
    for (int frame = 0; frame < 100 && !resized; ++frame) {
        device.poll_window();
        rhi::CommandList& list = device.begin_frame();
        const rhi::TextureHandle backbuffer = device.backbuffer();
        if (!backbuffer.is_null()) {
            clear_backbuffer(list, backbuffer, {0.0, 0.0, 1.0, 1.0});
            LOOM_VK_ASSIGN(const rhi::TextureDesc bd, device.texture_desc(backbuffer));
            resized = bd.width == 320 && bd.height == 200;
        }
        LOOM_VK_OK(device.end_frame());
        if (!resized) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    EXPECT_TRUE(resized) << "the back buffer never became 320x200; window is " << device.window_size().width << "x"
                         << device.window_size().height;
    LOOM_VK_OK(device.wait_idle());
}

}  // namespace
}  // namespace loom::test
