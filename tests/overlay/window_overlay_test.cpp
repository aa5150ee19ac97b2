// The frame overlay in a real window on every backend (run under Xvfb by ctest; skipped without
// a display): an F1 key press sent to the window through X11 shows it, a click on its bloom
// switch re-plans the frame, and the back buffer, read back, holds the overlay over the scene.
// The last back buffer of each backend is written to the test output (overlay-<backend>.png).
#include <chrono>
#include <cstdlib>
#include <functional>
#include <thread>

#include <gtest/gtest.h>

#include "deferred_controls.hpp"
#include "loom/image_io/image_io.hpp"
#include "loom_test/render_fixture.hpp"
#include "loom_test/x11_window.hpp"
#include "overlay_test_support.hpp"
#include "procedural_scene.hpp"
#include "render_helpers.hpp"

namespace loom::test {
namespace {

constexpr unsigned long kKeysymF1 = 0xffbe;  // XK_F1 (X11/keysymdef.h)

/// A windowed device showing the flagship pipeline under the overlay, a frame at a time.
struct WindowedFrame {
    std::unique_ptr<rhi::Device> device;
    std::unique_ptr<renderer::DeferredPipeline> pipeline;
    std::unique_ptr<deferred::DeferredFrameControls> controls;
    std::unique_ptr<overlay::LiveOverlay> live;

    /// One frame: input, overlay update (re-planning on a change), pipeline, overlay; `read`
    /// gets the back buffer before it is presented.
    Status run(const std::function<void(rhi::Image&)>& read = {}) {
        if (!device->poll_window()) return make_error(ErrorCode::InvalidState, "the window closed");
        const rhi::Extent3D size = device->window_size();
        auto updated = live->update(device->window_input(), size, 0.016, 1.0);
        if (!updated) return updated.take_error();
        rhi::CommandList& commands = device->begin_frame();
        const rhi::TextureHandle backbuffer = device->backbuffer();
        Status recorded = pipeline->record(commands, backbuffer, {size.width, size.height}, rhi::ResourceState::RenderTarget);
        if (recorded) recorded = live->record(commands, backbuffer);
        if (recorded && read) {
            auto image = device->read_texture(backbuffer);
            if (image) read(*image);
            else recorded = image.take_error();
        }
        Status ended = device->end_frame();
        LOOM_TRY(recorded);
        return ended;
    }

    /// Runs frames until `done` holds (at most `frames`), giving the X server time to deliver.
    bool run_until(const std::function<bool()>& done, int frames = 100) {
        for (int i = 0; i < frames; ++i) {
            if (Status status = run(); !status) {
                ADD_FAILURE() << status.error().to_string();
                return false;
            }
            if (done()) return true;
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        return false;
    }
};

TEST(WindowOverlay, F1ShowsItAClickRePlansAndTheBackBufferShowsIt) {
    if (!std::getenv("DISPLAY")) GTEST_SKIP() << "no X display (run under xvfb-run)";
    for (rhi::Backend backend : backends_under_test()) {
        const std::string name(rhi::backend_name(backend));
        SCOPED_TRACE(name);
        const std::string title = "loom overlay test " + name;
        rhi::DeviceDesc desc;
        desc.backend = backend;
        desc.headless = false;
        desc.window.title = title;
        desc.window.width = 800;
        desc.window.height = 480;
        desc.window.vsync = false;
        desc.window.resizable = false;
        WindowedFrame frame;
        LOOM_ASSIGN_OR_FAIL(frame.device, rhi::create_device(desc));
        rhi::Device& device = *frame.device;
        // The back buffer's format decides the present pass's and the overlay's target format.
        (void)device.poll_window();
        (void)device.begin_frame();
        LOOM_ASSIGN_OR_FAIL(const rhi::TextureDesc backbuffer, device.texture_desc(device.backbuffer()));
        LOOM_ASSERT_OK(device.end_frame());
        renderer::PipelineSettings settings;
        settings.capture = false;
        settings.target_format = backbuffer.format;
        LOOM_ASSIGN_OR_FAIL(frame.pipeline, deferred::create_procedural_pipeline(device, deferred::procedural_scene(), settings));
        frame.controls = std::make_unique<deferred::DeferredFrameControls>(*frame.pipeline);
        LOOM_ASSIGN_OR_FAIL(frame.live, overlay::LiveOverlay::create(device, *frame.controls, backbuffer.format));
        overlay::LiveOverlay& live = *frame.live;
        ASSERT_TRUE(frame.run_until([] { return true; }, 1));
        EXPECT_FALSE(live.overlay().visible());

        ASSERT_TRUE(press_x11_key(title.c_str(), kKeysymF1)) << "window '" << title << "' not found";
        ASSERT_TRUE(frame.run_until([&] { return live.overlay().visible(); })) << "F1 never reached the overlay";
        // Two more frames: ImGui sizes the new window, then shows it.
        ASSERT_TRUE(frame.run_until([] { return false; }, 2) || true);

        const auto rect = live.overlay().control_rect(std::string("switch:") + deferred::kBloomSwitch);
        ASSERT_TRUE(rect.has_value());
        const auto [x, y] = centre(*rect);
        ASSERT_TRUE(click_x11_window(title.c_str(), static_cast<int>(x), static_cast<int>(y)));
        ASSERT_TRUE(frame.run_until([&] { return live.replans() == 1; })) << "the click never re-planned";
        EXPECT_FALSE(frame.pipeline->settings().bloom);
        const rhi::WindowInput& input = device.window_input();
        EXPECT_TRUE(input.cursor_inside);
        EXPECT_NEAR(input.cursor_x, x, 1.5);
        EXPECT_NEAR(input.cursor_y, y, 1.5);

        rhi::Image shot;
        ASSERT_TRUE(frame.run_until([] { return false; }, 2) || true);
        LOOM_ASSERT_OK(frame.run([&](rhi::Image& image) { shot = std::move(image); }));
        const auto plan = frame.pipeline->executor().plan();
        for (const fg::PlanPass& pass : plan->order) EXPECT_NE(pass.name, "blur-h");
        const auto window = live.overlay().control_rect("window");
        ASSERT_TRUE(window.has_value());
        ASSERT_EQ(shot.width, backbuffer.width);
        // The overlay's nearly opaque dark background over the scene, and its light text.
        const uint32_t area = window->width * window->height;
        const uint32_t dark = count_pixels(shot, *window, [](const auto& p) { return p[0] < 0.2 && p[1] < 0.2 && p[2] < 0.2; });
        const uint32_t light = count_pixels(shot, *window, [](const auto& p) { return p[0] > 0.7 && p[1] > 0.7 && p[2] > 0.7; });
        EXPECT_GT(dark, area / 3) << "dark pixels " << dark << " of " << area;
        EXPECT_GT(light, 300u);
        // Right of the overlay is the scene, not the overlay's background.
        const rhi::Rect scene{window->x + static_cast<int32_t>(window->width) + 8, 0,
                              backbuffer.width - static_cast<uint32_t>(window->x) - window->width - 8, backbuffer.height};
        const uint32_t scene_dark = count_pixels(shot, scene, [](const auto& p) { return p[0] < 0.2 && p[1] < 0.2 && p[2] < 0.2; });
        EXPECT_LT(scene_dark, scene.width * scene.height / 2);
        const auto png = output_dir() / ("overlay-" + name + ".png");
        std::filesystem::create_directories(output_dir());
        LOOM_ASSERT_OK(image_io::write_png(shot, png));
        LOOM_ASSERT_OK(device.wait_idle());
    }
}

}  // namespace
}  // namespace loom::test
