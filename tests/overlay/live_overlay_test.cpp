// The flagship pipeline under the frame overlay (headless, every backend): clicks on the
// overlay's switches and allocator re-plan the frame, and the next plan has exactly the passes
// and the allocator the controls say.
#include <algorithm>

#include <gtest/gtest.h>

#include "deferred_controls.hpp"
#include "loom_test/render_fixture.hpp"
#include "overlay_test_support.hpp"
#include "procedural_scene.hpp"
#include "render_helpers.hpp"

namespace loom::test {
namespace {

constexpr fg::Extent2D kFrame{320, 180};
constexpr rhi::Extent3D kOverlaySize{1280, 720, 1};

std::vector<std::string> pass_names(const fg::Plan& plan) {
    std::vector<std::string> names;
    for (const fg::PlanPass& pass : plan.order) names.push_back(pass.name);
    return names;
}

bool has(const std::vector<std::string>& names, const char* name) {
    return std::find(names.begin(), names.end(), name) != names.end();
}

class LiveOverlayTest : public RenderTest {};

TEST_P(LiveOverlayTest, ClicksRePlanThePipeline) {
    renderer::PipelineSettings settings;
    settings.capture = false;
    LOOM_ASSIGN_OR_FAIL(auto pipeline, deferred::create_procedural_pipeline(device(), deferred::procedural_scene(), settings));
    LOOM_ASSERT_OK(pipeline->render(kFrame));
    const std::vector<std::string> before = pass_names(*pipeline->executor().plan());
    ASSERT_TRUE(has(before, "blur-h") && has(before, "blur-v") && has(before, "geometry") && has(before, "deferred"));
    EXPECT_EQ(pipeline->executor().plan()->allocator, "interval");

    deferred::DeferredFrameControls controls(*pipeline);
    LOOM_ASSIGN_OR_FAIL(auto live, overlay::LiveOverlay::create(device(), controls, rhi::Format::RGBA8Unorm));
    // The procedural scene has no blended objects: no transparent switch.
    ASSERT_EQ(live->controls().switches.size(), 2u);
    live->overlay().set_visible(true);
    for (int i = 0; i < 2; ++i) {
        LOOM_ASSIGN_OR_FAIL(const bool replanned, live->update(rhi::WindowInput{}, kOverlaySize, 0.016, 1.0));
        EXPECT_FALSE(replanned);
    }
    // Every pass of the plan has a row; the switches' checkboxes sit on their first pass's.
    auto click = [&](const std::string& control) -> bool {
        const auto rect = live->overlay().control_rect(control);
        EXPECT_TRUE(rect.has_value()) << control;
        if (!rect) return false;
        const auto [x, y] = centre(*rect);
        auto down = live->update(tap_at(x, y), kOverlaySize, 0.016, 1.0);
        auto up = live->update(hover_at(x, y), kOverlaySize, 0.016, 1.0);
        EXPECT_TRUE(down.ok() && up.ok());
        return down.ok() && up.ok() && !*down && *up;
    };

    EXPECT_TRUE(click(std::string("switch:") + deferred::kBloomSwitch));
    EXPECT_EQ(live->replans(), 1u);
    EXPECT_FALSE(pipeline->settings().bloom);
    LOOM_ASSERT_OK(pipeline->render(kFrame));
    std::vector<std::string> now = pass_names(*pipeline->executor().plan());
    EXPECT_EQ(now.size(), before.size() - 2);
    EXPECT_FALSE(has(now, "blur-h"));
    EXPECT_FALSE(has(now, "blur-v"));
    EXPECT_EQ(pipeline->blur_radius(), 0u);

    // The overlay lays out the new plan before the next click.
    (void)live->update(rhi::WindowInput{}, kOverlaySize, 0.016, 1.0);
    EXPECT_TRUE(click("allocator:heap"));
    LOOM_ASSERT_OK(pipeline->render(kFrame));
    EXPECT_EQ(pipeline->executor().plan()->allocator, "heap");

    (void)live->update(rhi::WindowInput{}, kOverlaySize, 0.016, 1.0);
    EXPECT_TRUE(click(std::string("switch:") + deferred::kDeferredSwitch));
    LOOM_ASSERT_OK(pipeline->render(kFrame));
    now = pass_names(*pipeline->executor().plan());
    EXPECT_TRUE(has(now, "forward"));
    EXPECT_FALSE(has(now, "geometry"));
    EXPECT_FALSE(has(now, "deferred"));

    // Bloom back on: the blur passes return (their checkbox is on the row listing them as off).
    (void)live->update(rhi::WindowInput{}, kOverlaySize, 0.016, 1.0);
    EXPECT_TRUE(click(std::string("switch:") + deferred::kBloomSwitch));
    LOOM_ASSERT_OK(pipeline->render(kFrame));
    now = pass_names(*pipeline->executor().plan());
    EXPECT_TRUE(has(now, "blur-h"));
    EXPECT_TRUE(has(now, "blur-v"));
    EXPECT_EQ(live->replans(), 4u);
}

TEST_P(LiveOverlayTest, BloomOffMatchesBloomStrengthZero) {
    // Without the blur passes the composite weighs the bloom input by 0: the picture is the one
    // the full graph makes with no bloom.
    renderer::PipelineSettings settings;
    settings.capture = false;
    settings.bloom_strength = 0.0f;
    LOOM_ASSIGN_OR_FAIL(auto with_blur, deferred::create_procedural_pipeline(device(), deferred::procedural_scene(), settings));
    LOOM_ASSERT_OK(with_blur->render(kFrame));
    LOOM_ASSIGN_OR_FAIL(rhi::Image expected, device().read_texture(with_blur->final_texture()));
    settings.bloom = false;
    settings.bloom_strength = 0.8f;
    LOOM_ASSIGN_OR_FAIL(auto without, deferred::create_procedural_pipeline(device(), deferred::procedural_scene(), settings));
    LOOM_ASSERT_OK(without->render(kFrame));
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(without->final_texture()));
    EXPECT_EQ(image.pixels, expected.pixels);
    EXPECT_EQ(without->executor().plan()->order.size() + 2, with_blur->executor().plan()->order.size());
}

LOOM_INSTANTIATE_RENDER_TEST(LiveOverlayTest);

}  // namespace
}  // namespace loom::test
