// The frame overlay drawn through loom's RHI on every backend (headless): it draws only inside
// its window and leaves every other pixel as it was, shows text, draws nothing while hidden,
// F1 shows and hides it, and a click on a control changes the controls it returns.
#include <gtest/gtest.h>

#include "frame_overlay.hpp"
#include "loom_test/render_fixture.hpp"
#include "render_helpers.hpp"
#include "overlay_test_support.hpp"

namespace loom::test {
namespace {

constexpr uint32_t kWidth = 800;
constexpr uint32_t kHeight = 480;
constexpr std::array<double, 4> kClear{0.2, 0.4, 0.6, 1.0};

fg::Plan sample_plan() {
    fg::Plan plan;
    plan.allocator = "interval";
    plan.frame = {kWidth, kHeight};
    for (const char* name : {"shadow", "geometry", "deferred", "blur-h", "blur-v", "composite", "present"}) {
        fg::PlanPass pass;
        pass.name = name;
        plan.order.push_back(pass);
    }
    plan.culled = {"debug-view"};
    plan.summary.textures = 5;
    plan.summary.naive_textures = 8;
    plan.summary.lower_bound_textures = 5;
    plan.summary.bytes = 12u << 20;
    plan.summary.naive_bytes = 20u << 20;
    plan.summary.lower_bound_bytes = 10u << 20;
    return plan;
}

overlay::OverlayFrame sample_frame(const fg::Plan& plan) {
    overlay::OverlayFrame frame;
    frame.title = "test frame";
    frame.plan = &plan;
    for (const fg::PlanPass& pass : plan.order) frame.timings.push_back({pass.name, 0.25, 0.5});
    frame.device_bytes = 64u << 20;
    frame.frame_ms = 4.0;
    return frame;
}

overlay::OverlayControls sample_controls() {
    overlay::OverlayControls controls;
    controls.allocator = fg::AllocatorKind::Interval;
    controls.switches.push_back({"bloom", {"blur-h", "blur-v"}, true});
    controls.switches.push_back({"vsync", {}, true});
    return controls;
}

bool is_clear(const std::array<double, 4>& p) {
    // RGBA8: the clear colour comes back within half a step.
    for (int c = 0; c < 4; ++c) {
        if (std::abs(p[c] - kClear[c]) > 0.6 / 255.0) return false;
    }
    return true;
}

class FrameOverlayTest : public RenderTest {};

TEST_P(FrameOverlayTest, DrawsItsWindowAndNothingElse) {
    LOOM_ASSIGN_OR_FAIL(auto overlay, overlay::FrameOverlay::create(device(), rhi::Format::RGBA8Unorm));
    overlay->set_visible(true);
    const fg::Plan plan = sample_plan();
    const overlay::OverlayFrame frame = sample_frame(plan);
    const overlay::OverlayControls controls = sample_controls();
    // ImGui sizes an auto-resizing window in its first frame and shows it from the second.
    for (int i = 0; i < 2; ++i) {
        EXPECT_EQ(overlay->update(rhi::WindowInput{}, {kWidth, kHeight, 1}, 1.0 / 60.0, frame, controls), controls);
    }
    const auto window = overlay->control_rect("window");
    ASSERT_TRUE(window.has_value());
    EXPECT_GT(window->width, 200u);
    EXPECT_GT(window->height, 150u);
    EXPECT_LT(window->x + static_cast<int32_t>(window->width), static_cast<int32_t>(kWidth));
    for (const char* control : {"allocator:paper", "allocator:interval", "allocator:heap", "switch:bloom", "switch:vsync"}) {
        const auto rect = overlay->control_rect(control);
        ASSERT_TRUE(rect.has_value()) << control;
        EXPECT_GE(rect->x, window->x) << control;
        EXPECT_LE(rect->x + static_cast<int32_t>(rect->width), window->x + static_cast<int32_t>(window->width)) << control;
    }
    EXPECT_FALSE(overlay->control_rect("switch:nothing").has_value());

    LOOM_ASSIGN_OR_FAIL(rhi::TextureHandle target, cleared_target(device(), kWidth, kHeight, kClear));
    rhi::CommandList& commands = device().begin_frame();
    LOOM_ASSERT_OK(overlay->record(commands, target));
    LOOM_ASSERT_OK(device().end_frame());
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target));

    // Outside the window every pixel is the clear colour.
    const rhi::Rect right{window->x + static_cast<int32_t>(window->width) + 1, 0,
                          kWidth - static_cast<uint32_t>(window->x) - window->width - 1, kHeight};
    const rhi::Rect below{0, window->y + static_cast<int32_t>(window->height) + 1, kWidth,
                          kHeight - static_cast<uint32_t>(window->y) - window->height - 1};
    EXPECT_EQ(count_pixels(image, right, is_clear), right.width * right.height);
    EXPECT_EQ(count_pixels(image, below, is_clear), below.width * below.height);
    // Inside: the dark, nearly opaque background, and light text.
    const uint32_t area = window->width * window->height;
    const uint32_t dark = count_pixels(image, *window, [](const auto& p) { return p[0] < 0.15 && p[1] < 0.15 && p[2] < 0.2; });
    const uint32_t light = count_pixels(image, *window, [](const auto& p) { return p[0] > 0.7 && p[1] > 0.7 && p[2] > 0.7; });
    EXPECT_GT(dark, area / 3) << "dark background pixels " << dark << " of " << area;
    EXPECT_GT(light, 300u) << "light (text) pixels " << light;
    EXPECT_EQ(count_pixels(image, *window, is_clear), 0u) << "the window covers the target where it is";
    LOOM_ASSERT_OK(device().destroy(target));
}

TEST_P(FrameOverlayTest, HiddenDrawsNothingAndF1ShowsAndHides) {
    LOOM_ASSIGN_OR_FAIL(auto overlay, overlay::FrameOverlay::create(device(), rhi::Format::RGBA8Unorm));
    const fg::Plan plan = sample_plan();
    const overlay::OverlayFrame frame = sample_frame(plan);
    const overlay::OverlayControls controls = sample_controls();
    EXPECT_FALSE(overlay->visible());
    (void)overlay->update(rhi::WindowInput{}, {kWidth, kHeight, 1}, 0.016, frame, controls);
    EXPECT_FALSE(overlay->control_rect("window").has_value());

    LOOM_ASSIGN_OR_FAIL(rhi::TextureHandle target, cleared_target(device(), kWidth, kHeight, kClear));
    rhi::CommandList& commands = device().begin_frame();
    LOOM_ASSERT_OK(overlay->record(commands, target));
    LOOM_ASSERT_OK(device().end_frame());
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target));
    EXPECT_EQ(count_pixels(image, {0, 0, kWidth, kHeight}, is_clear), kWidth * kHeight);

    rhi::WindowInput f1;
    f1.key_presses = {rhi::Key::F1};
    (void)overlay->update(f1, {kWidth, kHeight, 1}, 0.016, frame, controls);
    EXPECT_TRUE(overlay->visible());
    (void)overlay->update(rhi::WindowInput{}, {kWidth, kHeight, 1}, 0.016, frame, controls);
    EXPECT_TRUE(overlay->visible()) << "F1 toggles on the press, not while nothing happens";
    (void)overlay->update(f1, {kWidth, kHeight, 1}, 0.016, frame, controls);
    EXPECT_FALSE(overlay->visible());
    LOOM_ASSERT_OK(device().destroy(target));
}

TEST_P(FrameOverlayTest, AClickChangesTheControls) {
    LOOM_ASSIGN_OR_FAIL(auto overlay, overlay::FrameOverlay::create(device(), rhi::Format::RGBA8Unorm));
    overlay->set_visible(true);
    const fg::Plan plan = sample_plan();
    const overlay::OverlayFrame frame = sample_frame(plan);
    overlay::OverlayControls controls = sample_controls();
    const rhi::Extent3D size{kWidth, kHeight, 1};
    for (int i = 0; i < 2; ++i) (void)overlay->update(rhi::WindowInput{}, size, 0.016, frame, controls);

    // A click: down in one update (a tap arrives pressed and released), up in the next. The
    // application takes the changed controls, and the overlay lays them out once more (as the
    // next frame would) before the next click.
    auto click = [&](const char* control) {
        const auto rect = overlay->control_rect(control);
        EXPECT_TRUE(rect.has_value()) << control;
        if (!rect) return;
        const auto [x, y] = centre(*rect);
        const overlay::OverlayControls down = overlay->update(tap_at(x, y), size, 0.016, frame, controls);
        EXPECT_EQ(down, controls) << "nothing changes before the button is released";
        controls = overlay->update(hover_at(x, y), size, 0.016, frame, controls);
        (void)overlay->update(hover_at(1, 1), size, 0.016, frame, controls);
    };
    click("switch:bloom");
    EXPECT_FALSE(controls.switches[0].on);
    EXPECT_TRUE(controls.switches[1].on);
    EXPECT_EQ(controls.allocator, fg::AllocatorKind::Interval);
    click("allocator:heap");
    EXPECT_EQ(controls.allocator, fg::AllocatorKind::Heap);
    EXPECT_FALSE(controls.switches[0].on);
    click("switch:bloom");
    EXPECT_TRUE(controls.switches[0].on);
    click("switch:vsync");
    EXPECT_FALSE(controls.switches[1].on);
    EXPECT_TRUE(controls.switches[0].on);
    // The pointer over the window is the overlay's; elsewhere it is the application's.
    (void)overlay->update(hover_at(centre(*overlay->control_rect("window")).first, 20), size, 0.016, frame, controls);
    EXPECT_TRUE(overlay->wants_pointer());
    (void)overlay->update(hover_at(kWidth - 2, kHeight - 2), size, 0.016, frame, controls);
    EXPECT_FALSE(overlay->wants_pointer());
}

LOOM_INSTANTIATE_RENDER_TEST(FrameOverlayTest);

}  // namespace
}  // namespace loom::test
