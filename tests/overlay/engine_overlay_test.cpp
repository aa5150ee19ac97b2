// loom-engine's frame under the frame overlay (headless, every backend): the async compute
// switch re-plans the frame onto one queue, the paper allocator is refused while async passes
// exist (the overlay shows why and keeps the frame as it was), and accepted once they are gone.
#include <algorithm>

#include <gtest/gtest.h>

#include "engine_controls.hpp"
#include "loom_test/render_fixture.hpp"
#include "overlay_test_support.hpp"
#include "render_helpers.hpp"

namespace loom::test {
namespace {

constexpr fg::Extent2D kFrame{160, 96};
constexpr rhi::Extent3D kOverlaySize{1280, 720, 1};

uint32_t async_passes(const fg::Plan& plan) {
    return static_cast<uint32_t>(std::count_if(plan.order.begin(), plan.order.end(), [](const fg::PlanPass& p) {
        return p.queue == fg::Queue::AsyncCompute;
    }));
}

class EngineOverlayTest : public RenderTest {};

TEST_P(EngineOverlayTest, AsyncSwitchAndAllocatorRePlanAndPaperIsRefusedWithAsyncPasses) {
    engine::SceneSettings scene_settings;
    scene_settings.lights = 16;
    LOOM_ASSIGN_OR_FAIL(const engine::EngineScene scene, engine::make_engine_scene(scene_settings));
    engine::FrameSettings settings;
    settings.shadow_size = 256;
    settings.capture = false;
    LOOM_ASSIGN_OR_FAIL(auto frame, engine::EngineFrame::create(device(), scene, settings));
    LOOM_ASSERT_OK(frame->render(kFrame));
    ASSERT_GT(async_passes(*frame->executor().plan()), 0u);
    EXPECT_EQ(frame->executor().plan()->allocator, "heap");

    engine::EngineFrameControls controls(*frame);
    LOOM_ASSIGN_OR_FAIL(auto live, overlay::LiveOverlay::create(device(), controls, rhi::Format::RGBA8Unorm));
    live->overlay().set_visible(true);
    for (int i = 0; i < 2; ++i) ASSERT_TRUE(live->update(rhi::WindowInput{}, kOverlaySize, 0.016, 1.0).ok());
    auto click = [&](const std::string& control) -> Result<bool> {
        const auto rect = live->overlay().control_rect(control);
        if (!rect) return make_error(ErrorCode::InvalidArgument, "no control " + control);
        const auto [x, y] = centre(*rect);
        if (auto down = live->update(tap_at(x, y), kOverlaySize, 0.016, 1.0); !down) return down.take_error();
        auto up = live->update(hover_at(x, y), kOverlaySize, 0.016, 1.0);
        if (auto settle = live->update(hover_at(1, 1), kOverlaySize, 0.016, 1.0); !settle) return settle.take_error();
        return up;
    };

    {
        // Refused: the frame, its settings and the controls stay; the overlay says why.
        ScopedLogCapture log;
        LOOM_ASSIGN_OR_FAIL(const bool replanned, click("allocator:paper"));
        EXPECT_FALSE(replanned);
        EXPECT_EQ(live->replans(), 0u);
        EXPECT_NE(live->message().find("async compute"), std::string::npos) << live->message();
        EXPECT_EQ(live->controls().allocator, fg::AllocatorKind::Heap);
        EXPECT_EQ(frame->settings().allocator, fg::AllocatorKind::Heap);
        EXPECT_TRUE(frame->settings().async_compute);
    }
    LOOM_ASSIGN_OR_FAIL(const bool async_off, click(std::string("switch:") + engine::kAsyncComputeSwitch));
    EXPECT_TRUE(async_off);
    EXPECT_TRUE(live->message().empty());
    LOOM_ASSERT_OK(frame->render(kFrame));
    EXPECT_EQ(async_passes(*frame->executor().plan()), 0u);

    LOOM_ASSIGN_OR_FAIL(const bool paper, click("allocator:paper"));
    EXPECT_TRUE(paper);
    LOOM_ASSERT_OK(frame->render(kFrame));
    EXPECT_EQ(frame->executor().plan()->allocator, "paper");
    EXPECT_EQ(live->replans(), 2u);
    LOOM_ASSERT_OK(device().wait_idle());
}

LOOM_INSTANTIATE_RENDER_TEST(EngineOverlayTest);

}  // namespace
}  // namespace loom::test
