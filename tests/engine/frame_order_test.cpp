// The flagship (Figure 2) and the engine frame planned in memory order (fg::PassOrder::Memory)
// on every backend: the executor runs the passes in the plan's order, which differs from the
// declared one in these settings, and the final pictures are byte for byte those of the declared
// order; the peak of live bytes is never higher.
#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine_frame.hpp"
#include "loom_test/render_fixture.hpp"
#include "procedural_scene.hpp"
#include "render_helpers.hpp"

namespace loom::test {
namespace {

std::vector<std::string> order_of(const fg::Plan& plan) {
    std::vector<std::string> names;
    for (const fg::PlanPass& pass : plan.order) names.push_back(pass.name);
    return names;
}

std::string joined(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& name : names) out += (out.empty() ? "" : " ") + name;
    return out;
}

/// What one frame in one order gave: the plan's order, its peak, the final picture.
struct OrderedFrame {
    std::vector<std::string> order;
    uint64_t peak = 0;
    fg::PassOrder planned = fg::PassOrder::Declared;
    rhi::Image picture;
};

/// The frame `executor` ran last, its final picture `final` read back.
Result<OrderedFrame> ordered_frame(rhi::Device& device, const fg::Executor& executor, rhi::TextureHandle final) {
    OrderedFrame frame;
    const auto plan = executor.plan();
    frame.order = order_of(*plan);
    frame.peak = plan->summary.lower_bound_bytes;
    frame.planned = plan->pass_order;
    auto picture = device.read_texture(final);
    if (!picture) return picture.take_error();
    frame.picture = std::move(*picture);
    return frame;
}

/// What both frames must show: planned in memory order, a peak no higher, another order of the
/// passes, and the same bytes.
void expect_same_picture_in_another_order(const std::vector<OrderedFrame>& frames) {
    ASSERT_EQ(frames.size(), 2u);
    EXPECT_EQ(frames[1].planned, fg::PassOrder::Memory);
    EXPECT_LE(frames[1].peak, frames[0].peak);
    EXPECT_NE(frames[1].order, frames[0].order) << joined(frames[1].order);
    ::testing::Test::RecordProperty("declared", joined(frames[0].order));
    ::testing::Test::RecordProperty("memory", joined(frames[1].order));
    EXPECT_EQ(frames[1].picture.pixels, frames[0].picture.pixels);
}

class FrameOrderTest : public RenderTest {};

TEST_P(FrameOrderTest, FlagshipPicturesAreTheSameInMemoryOrder) {
    std::vector<OrderedFrame> frames;
    for (fg::PassOrder order : {fg::PassOrder::Declared, fg::PassOrder::Memory}) {
        renderer::PipelineSettings settings;
        settings.capture = false;
        settings.order = order;
        LOOM_ASSIGN_OR_FAIL(auto pipeline, deferred::create_procedural_pipeline(device(), deferred::procedural_scene(), settings));
        LOOM_ASSERT_OK(pipeline->render({320, 180}));
        LOOM_ASSIGN_OR_FAIL(OrderedFrame frame, ordered_frame(device(), pipeline->executor(), pipeline->final_texture()));
        frames.push_back(std::move(frame));
    }
    // With a 2048² shadow map the memory order draws it after the G-buffer, not first.
    expect_same_picture_in_another_order(frames);
    std::vector<std::string> sorted_declared = frames[0].order, sorted_memory = frames[1].order;
    std::sort(sorted_declared.begin(), sorted_declared.end());
    std::sort(sorted_memory.begin(), sorted_memory.end());
    EXPECT_EQ(sorted_declared, sorted_memory);
}

TEST_P(FrameOrderTest, EnginePicturesAreTheSameInMemoryOrder) {
    engine::SceneSettings scene_settings;
    scene_settings.lights = 32;
    LOOM_ASSIGN_OR_FAIL(const engine::EngineScene scene, engine::make_engine_scene(scene_settings));
    std::vector<OrderedFrame> frames;
    for (fg::PassOrder order : {fg::PassOrder::Declared, fg::PassOrder::Memory}) {
        engine::FrameSettings settings;
        settings.shadow_size = 256;
        // One queue: the memory order keeps async passes where they are declared.
        settings.async_compute = false;
        settings.capture = false;
        settings.order = order;
        LOOM_ASSIGN_OR_FAIL(auto frame, engine::EngineFrame::create(device(), scene, settings));
        LOOM_ASSERT_OK(frame->render({192, 108}));
        LOOM_ASSIGN_OR_FAIL(OrderedFrame result, ordered_frame(device(), frame->executor(), frame->final_texture()));
        frames.push_back(std::move(result));
        LOOM_ASSERT_OK(device().wait_idle());
    }
    EXPECT_EQ(frames[1].order.size(), frames[0].order.size());
    expect_same_picture_in_another_order(frames);
}

LOOM_INSTANTIATE_RENDER_TEST(FrameOrderTest);

}  // namespace
}  // namespace loom::test
