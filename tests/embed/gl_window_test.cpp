// What a window shows is what loom stored: presenting (a GL device's own window, or
// gl::blit_to_framebuffer into an application's window) copies the back buffer's values
// without encoding them again for an sRGB-capable window framebuffer, as Vulkan presents
// them. Needs an X display: ctest runs it under xvfb-run; without a display it is skipped.
#include <cstdlib>

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include "embed_test_support.hpp"
#include "loom/gl/gl_device.hpp"

namespace loom::test {
namespace {

TEST(GlWindowColour, StoredValuesReachTheWindow) {
    if (std::getenv("DISPLAY") == nullptr) GTEST_SKIP() << "no X display (ctest runs this under xvfb-run)";
    rhi::DeviceDesc desc;
    desc.headless = false;
    desc.window.title = "loom window colour test";
    desc.window.width = 32;
    desc.window.height = 24;
    desc.window.vsync = false;
    LOOM_EMBED_ASSIGN(auto device, gl::create_gl_device(desc));
    for (int frame = 0; frame < 2; ++frame) {
        ASSERT_TRUE(device->poll_window());
        rhi::CommandList& list = device->begin_frame();
        rhi::RenderPassDesc pass;
        pass.label = "clear";
        pass.colors.push_back({device->backbuffer(), 0, 0, rhi::LoadOp::Clear, rhi::StoreOp::Store, kEngineClear});
        list.begin_render_pass(pass);
        list.end_render_pass();
        LOOM_EMBED_OK(device->end_frame());
    }
    // Mesa's X11 software path (the one under xvfb-run) keeps the back buffer after the swap.
    glFinish();
    glNamedFramebufferReadBuffer(0, GL_BACK);
    std::vector<uint8_t> pixels(32 * 24 * 4);
    glReadnPixels(0, 0, 32, 24, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(pixels.size()), pixels.data());
    EXPECT_EQ((Rgba8{pixels[0], pixels[1], pixels[2], pixels[3]}), kEngineClearBytes)
        << "the window shows (" << int(pixels[0]) << ", " << int(pixels[1]) << ", " << int(pixels[2]) << ")";
    LOOM_EMBED_OK(device->wait_idle());
}

}  // namespace
}  // namespace loom::test
