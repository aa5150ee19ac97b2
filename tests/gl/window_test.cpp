// A windowed GL device: frames render into the offscreen back buffer, which end_frame() blits
// into the window right way up. Needs an X display: ctest runs it under xvfb-run when that is
// installed; run alone without a display it is skipped.
#include <cstdlib>

#include <epoxy/gl.h>

#include "loom/gl/gl_device.hpp"
#include "loom_test/test_support.hpp"
#include "render_helpers.hpp"

namespace loom::test {
namespace {

bool have_display() {
    const char* display = std::getenv("DISPLAY");
    return display && *display;
}

TEST(GlWindow, PresentsTheBackBufferRightWayUp) {
    if (!have_display()) GTEST_SKIP() << "no X display (ctest runs this under xvfb-run)";
    rhi::DeviceDesc desc;
    desc.headless = false;
    desc.window.title = "loom gl window test";
    desc.window.width = 64;
    desc.window.height = 48;
    desc.window.vsync = false;
    LOOM_ASSIGN_OR_FAIL(auto device, gl::create_gl_device(desc));
    EXPECT_EQ(device->window_size().width, 64u);
    EXPECT_EQ(device->window_size().height, 48u);
    EXPECT_TRUE(device->backbuffer().is_null()) << "no back buffer outside a frame";

    LOOM_ASSIGN_OR_FAIL(auto pipeline, make_solid_pipeline(*device, rhi::Format::RGBA8Unorm));
    // The top half of NDC (y > 0).
    const std::vector<float> top_half = {-1, 0, 0, 1, 0, 0, 1, 1, 0, -1, 0, 0, 1, 1, 0, -1, 1, 0};
    LOOM_ASSIGN_OR_FAIL(auto vb, make_buffer_of(*device, "top half", rhi::BufferUsage::Vertex, top_half));
    for (int frame = 0; frame < 3; ++frame) {
        EXPECT_TRUE(device->poll_window());
        rhi::CommandList& list = device->begin_frame();
        const rhi::TextureHandle backbuffer = device->backbuffer();
        ASSERT_FALSE(backbuffer.is_null());
        LOOM_ASSIGN_OR_FAIL(const rhi::TextureDesc bd, device->texture_desc(backbuffer));
        EXPECT_EQ(bd.width, 64u);
        EXPECT_EQ(bd.height, 48u);
        list.begin_render_pass(clear_pass("window", backbuffer, {0, 1, 0, 1}));
        list.set_pipeline(pipeline);
        list.set_vertex_buffer(0, vb);
        list.push_constants_of(std::array<float, 4>{1, 0, 0, 1});
        list.draw(6);
        list.end_render_pass();
        LOOM_ASSERT_OK(device->end_frame());
    }
    EXPECT_EQ(device->resource_stats().textures, 0u) << "the back buffer is not a user texture";

    // What the window shows: GL's default framebuffer has row 0 at the bottom, so the top of
    // the window (red) is its last row. The back buffer is read after the swap: GL leaves its
    // contents undefined, but Mesa's X11 software path (the one under xvfb-run) swaps by copy
    // and keeps them, while reading GL_FRONT there returns nothing.
    glFinish();
    glNamedFramebufferReadBuffer(0, GL_BACK);
    std::vector<uint8_t> pixels(64 * 48 * 4);
    glReadnPixels(0, 0, 64, 48, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(pixels.size()), pixels.data());
    auto at = [&](int x, int gl_row) {
        const uint8_t* p = &pixels[(static_cast<std::size_t>(gl_row) * 64 + static_cast<std::size_t>(x)) * 4];
        return std::array<int, 3>{p[0], p[1], p[2]};
    };
    EXPECT_EQ(at(32, 47), (std::array<int, 3>{255, 0, 0})) << "the top of the window is not red";
    EXPECT_EQ(at(32, 0), (std::array<int, 3>{0, 255, 0})) << "the bottom of the window is not green";
    glNamedFramebufferReadBuffer(0, GL_BACK);
    LOOM_ASSERT_OK(device->destroy(vb));
    LOOM_ASSERT_OK(device->destroy(pipeline));
    LOOM_ASSERT_OK(device->wait_idle());
}

}  // namespace
}  // namespace loom::test
