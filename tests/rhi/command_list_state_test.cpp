// The command-list state tracker without a device: pipelines and buffers live in handle pools
// here, as they do in the backends, so that stale handles read as they do there. The same rules
// on real devices of both backends: tests/render/misuse_table_test.cpp.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "loom/rhi/command_list_state.hpp"
#include "loom/rhi/handle_pool.hpp"

namespace loom::rhi {
namespace {

struct FakePipeline {
    std::string name;
    bool compute = false;
    std::vector<Format> color_formats;
    Format depth_format = Format::Undefined;
    uint32_t samples = 1;
    uint32_t vertex_buffers = 0;
};

void expect_error(const Status& status, ErrorCode code, const std::string& message) {
    ASSERT_FALSE(status.ok()) << "accepted, expected: " << message;
    EXPECT_EQ(error_code_name(status.error().code), error_code_name(code));
    EXPECT_EQ(status.error().message, message);
}

class CommandListStateTest : public ::testing::Test {
protected:
    CommandListStateTest()
        : state(
              [this](PipelineHandle h) -> Result<PipelineFacts> {
                  auto found = pipelines.get(h);
                  if (!found.ok()) return found.take_error();
                  const FakePipeline& p = **found;
                  return PipelineFacts{p.name, p.compute, p.color_formats, p.depth_format, p.samples, p.vertex_buffers};
              },
              [this](BufferHandle h) -> Result<const BufferDesc*> {
                  auto found = buffers.get(h);
                  if (!found.ok()) return found.take_error();
                  return *found;
              }) {}

    PipelineHandle graphics(const std::string& name, Format color = Format::RGBA8Unorm, uint32_t vertex_buffers = 0) {
        return pipelines.insert({name, false, {color}, Format::Undefined, 1, vertex_buffers});
    }
    PipelineHandle compute(const std::string& name) {
        return pipelines.insert({name, true, {}, Format::Undefined, 1, 0});
    }
    BufferHandle buffer(const std::string& name, uint64_t size, BufferUsage usage) {
        return buffers.insert({name, size, usage});
    }
    /// Opens render pass `label` with one RGBA8Unorm attachment.
    void open_pass(const std::string& label = "p") {
        ASSERT_TRUE(state.check_begin_render_pass(label).ok());
        state.render_pass_begun(label, validation::RenderPassShape{4, 4, 1, {Format::RGBA8Unorm}, Format::Undefined});
    }
    /// Begins a frame; a draw is refused without a render pass, then (in one) without a pipeline.
    void begin_frame_and_expect_a_pass_then_a_pipeline() {
        state.begin_frame();
        expect_error(state.check_draw("draw", false), ErrorCode::InvalidState,
                     "draw: no render pass is open; draws go inside a render pass");
        open_pass();
        expect_error(state.check_draw("draw", false), ErrorCode::InvalidState,
                     "draw: no pipeline is set; call set_pipeline first");
    }
    /// The InvalidHandle message of a destroyed pipeline / buffer, as the pool words it.
    std::string stale_message(PipelineHandle h) { return pipelines.get(h).error().message; }
    std::string stale_message(BufferHandle h) { return buffers.get(h).error().message; }

    HandlePool<PipelineTag, FakePipeline> pipelines{next_device_id()};
    HandlePool<BufferTag, BufferDesc> buffers{next_device_id()};
    CommandListState state;
};

TEST_F(CommandListStateTest, AFrameIsBegunOnceAndEndedOnce) {
    EXPECT_FALSE(state.recording());
    expect_error(state.check_recording("end_frame"), ErrorCode::InvalidState,
                 "end_frame: no frame is being recorded; call begin_frame first");
    expect_error(state.check_recording("transient_uniforms"), ErrorCode::InvalidState,
                 "transient_uniforms: no frame is being recorded; call begin_frame first");
    ASSERT_TRUE(state.check_begin_frame().ok());
    state.begin_frame();
    EXPECT_TRUE(state.recording());
    EXPECT_TRUE(state.check_recording("end_frame").ok());
    expect_error(state.check_begin_frame(), ErrorCode::InvalidState,
                 "begin_frame: the previous frame was not ended; call end_frame first");
    expect_error(state.check_begin_frame("begin_external_frame"), ErrorCode::InvalidState,
                 "begin_external_frame: the previous frame was not ended; call end_frame first");
    EXPECT_TRUE(state.check_nothing_open().ok());
    state.end_frame();
    EXPECT_FALSE(state.recording());
}

TEST_F(CommandListStateTest, EndFrameNamesWhatWasLeftOpenPassFirst) {
    state.begin_frame();
    state.push_debug_group();
    expect_error(state.check_nothing_open(), ErrorCode::InvalidState, "end_frame: 1 debug group was not popped");
    state.push_debug_group();
    expect_error(state.check_nothing_open(), ErrorCode::InvalidState, "end_frame: 2 debug groups were not popped");
    ASSERT_TRUE(state.begin_timer("t").ok());
    expect_error(state.check_nothing_open(), ErrorCode::InvalidState, "end_frame: timer 't' was not ended");
    open_pass("left open");
    expect_error(state.check_nothing_open(), ErrorCode::InvalidState,
                 "end_frame: render pass 'left open' was not ended");
    // The next frame starts with nothing open.
    state.end_frame();
    state.begin_frame();
    EXPECT_TRUE(state.check_nothing_open().ok());
    EXPECT_EQ(state.render_pass(), nullptr);
    EXPECT_FALSE(state.open_timer());
    EXPECT_EQ(state.debug_group_depth(), 0u);
}

TEST_F(CommandListStateTest, RenderPassesDoNotNest) {
    state.begin_frame();
    expect_error(state.end_render_pass(), ErrorCode::InvalidState, "end_render_pass: no render pass is open");
    open_pass("outer");
    const CommandListState::RenderPass* open = state.render_pass();
    ASSERT_NE(open, nullptr);
    EXPECT_EQ(open->label, "outer");
    expect_error(state.check_begin_render_pass("inner"), ErrorCode::InvalidState,
                 "begin_render_pass 'inner': render pass 'outer' is still open; render passes do not nest");
    EXPECT_TRUE(state.end_render_pass().ok());
    EXPECT_EQ(state.render_pass(), nullptr);
    EXPECT_TRUE(state.check_begin_render_pass("inner").ok());
}

TEST_F(CommandListStateTest, DispatchesCopiesTransitionsAndReadbacksGoOutsideRenderPasses) {
    state.begin_frame();
    for (const char* command : {"copy_buffer", "copy_texture", "transition", "read_texture of texture 't'"}) {
        EXPECT_TRUE(state.check_outside_render_pass(command).ok()) << command;
    }
    open_pass();
    expect_error(state.check_outside_render_pass("read_texture of texture 't'"), ErrorCode::InvalidState,
                 "read_texture of texture 't': render pass 'p' is open; dispatches, copies, transitions and readbacks "
                 "go outside "
                 "render passes");
    ASSERT_TRUE(state.set_pipeline(compute("c")).ok());
    expect_error(
        state.check_dispatch(), ErrorCode::InvalidState,
        "dispatch: render pass 'p' is open; dispatches, copies, transitions and readbacks go outside render passes");
    ASSERT_TRUE(state.end_render_pass().ok());
    EXPECT_TRUE(state.check_dispatch().ok());
}

TEST_F(CommandListStateTest, DrawsGoInsideARenderPassWithAGraphicsPipeline) {
    begin_frame_and_expect_a_pass_then_a_pipeline();
    ASSERT_TRUE(state.set_pipeline(compute("c")).ok());
    expect_error(state.check_draw("draw", false), ErrorCode::InvalidState,
                 "draw: pipeline 'c' is a compute pipeline; draws need a graphics pipeline");
    ASSERT_TRUE(state.set_pipeline(graphics("g")).ok());
    EXPECT_TRUE(state.check_draw("draw", false).ok());
    ASSERT_TRUE(state.end_render_pass().ok());
    expect_error(state.check_dispatch(), ErrorCode::InvalidState,
                 "dispatch: pipeline 'g' is a graphics pipeline; dispatches need a compute pipeline");
}

TEST_F(CommandListStateTest, APipelineMustTargetThePassAttachments) {
    state.begin_frame();
    const PipelineHandle wide = graphics("wide", Format::RGBA16Float);
    // Set before the pass: refused at the draw.
    ASSERT_TRUE(state.set_pipeline(wide).ok());
    open_pass();
    const std::string mismatch =
        "pipeline 'wide' targets [RGBA16Float] depth Undefined x1, render pass 'p' has [RGBA8Unorm] depth Undefined x1";
    expect_error(state.check_draw("draw", false), ErrorCode::InvalidArgument, "draw: " + mismatch);
    // Set inside the pass: refused at once, and nothing stays bound.
    expect_error(state.set_pipeline(wide), ErrorCode::InvalidArgument, "set_pipeline: " + mismatch);
    EXPECT_TRUE(state.pipeline().is_null());
    expect_error(state.check_draw("draw", false), ErrorCode::InvalidState,
                 "draw: no pipeline is set; call set_pipeline first");
    // Compute pipelines may be set inside a pass (and dispatched after it).
    EXPECT_TRUE(state.set_pipeline(compute("c")).ok());
}

TEST_F(CommandListStateTest, ADestroyedPipelineIsAnInvalidHandle) {
    state.begin_frame();
    open_pass();
    const PipelineHandle doomed = graphics("doomed");
    ASSERT_TRUE(state.set_pipeline(doomed).ok());
    ASSERT_TRUE(pipelines.remove(doomed).ok());
    expect_error(state.check_draw("draw", false), ErrorCode::InvalidHandle,
                 "draw: pipeline 'doomed': " + stale_message(doomed));
    expect_error(state.set_pipeline(doomed), ErrorCode::InvalidHandle, "set_pipeline: " + stale_message(doomed));
    expect_error(state.set_pipeline({}), ErrorCode::InvalidHandle, "set_pipeline: pipeline handle is null");
}

TEST_F(CommandListStateTest, EverySlotThePipelineReadsNeedsAVertexBuffer) {
    state.begin_frame();
    open_pass();
    ASSERT_TRUE(state.set_pipeline(graphics("g", Format::RGBA8Unorm, 2)).ok());
    const BufferHandle vertices = buffer("v", 64, BufferUsage::Vertex);
    ASSERT_TRUE(state.set_vertex_buffer(0, vertices, 16).ok());
    EXPECT_EQ(state.vertex_buffer(0).buffer, vertices);
    EXPECT_EQ(state.vertex_buffer(0).offset, 16u);
    expect_error(state.check_draw("draw", false), ErrorCode::InvalidState,
                 "draw: pipeline 'g' reads vertex buffer slot 1, but no vertex buffer is bound there");
    const BufferHandle doomed = buffer("doomed", 64, BufferUsage::Vertex);
    ASSERT_TRUE(state.set_vertex_buffer(1, doomed, 0).ok());
    EXPECT_TRUE(state.check_draw("draw", false).ok());
    ASSERT_TRUE(buffers.remove(doomed).ok());
    expect_error(state.check_draw("draw", false), ErrorCode::InvalidHandle,
                 "draw: vertex buffer slot 1: " + stale_message(doomed));
    // The binding's own rules are rhi::validation's.
    expect_error(state.set_vertex_buffer(16, vertices, 0), ErrorCode::InvalidArgument,
                 "set_vertex_buffer: slot 16 is beyond the 16 slots loom supports");
    expect_error(state.set_vertex_buffer(0, {}, 0), ErrorCode::InvalidHandle,
                 "set_vertex_buffer: buffer handle is null");
    expect_error(state.set_vertex_buffer(0, buffer("i", 64, BufferUsage::Index), 0), ErrorCode::InvalidArgument,
                 "set_vertex_buffer: slot 0: buffer 'i' lacks usage Vertex");
    EXPECT_EQ(state.vertex_buffer(0).buffer, vertices) << "a refused binding replaced the bound one";
}

TEST_F(CommandListStateTest, IndexedDrawsNeedAnIndexBufferThatHoldsTheirIndices) {
    state.begin_frame();
    open_pass();
    ASSERT_TRUE(state.set_pipeline(graphics("g")).ok());
    EXPECT_TRUE(state.check_draw("draw", false).ok());
    expect_error(state.check_draw("draw_indexed", true), ErrorCode::InvalidState,
                 "draw_indexed: no index buffer is bound; call set_index_buffer first");
    const BufferHandle indices = buffer("i", 12, BufferUsage::Index);
    ASSERT_TRUE(state.set_index_buffer(indices, IndexType::Uint16, 2).ok());
    EXPECT_TRUE(state.check_draw("draw_indexed_indirect", true).ok());
    EXPECT_TRUE(state.check_index_range(0, 5).ok());
    expect_error(state.check_index_range(1, 5), ErrorCode::InvalidArgument,
                 "draw_indexed: 5 indices from index 1 run past the end of index buffer 'i' (12 bytes from offset 2)");
    ASSERT_TRUE(buffers.remove(indices).ok());
    expect_error(state.check_draw("draw_indexed", true), ErrorCode::InvalidHandle,
                 "draw_indexed: index buffer: " + stale_message(indices));
}

TEST_F(CommandListStateTest, SignalsAreNumberedPerFrameAndWaitedOnceByTheOtherQueue) {
    state.begin_frame();
    EXPECT_EQ(state.queue(), QueueType::Graphics);
    auto first = state.signal_queue();
    ASSERT_TRUE(first.ok());
    EXPECT_EQ(*first, (QueueSignal{0, QueueType::Graphics}));
    ASSERT_TRUE(state.set_queue(QueueType::Compute).ok());
    auto second = state.signal_queue();
    ASSERT_TRUE(second.ok());
    EXPECT_EQ(*second, (QueueSignal{1, QueueType::Compute}));
    EXPECT_TRUE(state.wait_queue(*first).ok());
    expect_error(state.wait_queue(*first), ErrorCode::InvalidArgument,
                 "wait_queue(signal 0): already waited for; a signal is waited at most once");
    expect_error(state.wait_queue(*second), ErrorCode::InvalidArgument,
                 "wait_queue(signal 1): made on the compute queue, which is the queue recording; wait on the other one");
    // A signal of the wrong queue is not this frame's signal.
    expect_error(state.wait_queue(QueueSignal{1, QueueType::Graphics}), ErrorCode::InvalidArgument,
                 "wait_queue(signal 1): not a signal of this frame (2 made so far)");
    expect_error(state.check_begin_render_pass("p"), ErrorCode::InvalidState,
                 "begin_render_pass 'p': the commands go to the compute queue, which runs no render passes; "
                 "set_queue(QueueType::Graphics) first");
    EXPECT_EQ(state.signal_count(), 2u);
    state.end_frame();
    // The next frame starts on the graphics queue with no signals.
    state.begin_frame();
    EXPECT_EQ(state.queue(), QueueType::Graphics);
    EXPECT_EQ(state.signal_count(), 0u);
    expect_error(state.wait_queue(*second), ErrorCode::InvalidArgument,
                 "wait_queue(signal 1): not a signal of this frame (0 made so far)");
    state.end_frame();
    expect_error(state.set_queue(QueueType::Compute), ErrorCode::InvalidState,
                 "set_queue(compute): no frame is being recorded; call begin_frame first");
}

TEST_F(CommandListStateTest, TimersDoNotNestAndDebugGroupsBalance) {
    state.begin_frame();
    expect_error(state.end_timer(), ErrorCode::InvalidState, "end_timer: no timer is open");
    ASSERT_TRUE(state.begin_timer("outer").ok());
    expect_error(state.begin_timer("inner"), ErrorCode::InvalidState,
                 "begin_timer 'inner': timer 'outer' is still open; timers do not nest");
    EXPECT_EQ(state.open_timer(), "outer");
    EXPECT_TRUE(state.end_timer().ok());
    EXPECT_TRUE(state.begin_timer("inner").ok());

    expect_error(state.pop_debug_group(), ErrorCode::InvalidState, "pop_debug_group: no debug group is open");
    state.push_debug_group();
    state.push_debug_group();
    EXPECT_TRUE(state.pop_debug_group().ok());
    EXPECT_EQ(state.debug_group_depth(), 1u);
}

TEST_F(CommandListStateTest, BoundStateLastsForOneFrame) {
    state.begin_frame();
    const PipelineHandle pipeline = graphics("g");
    ASSERT_TRUE(state.set_pipeline(pipeline).ok());
    ASSERT_TRUE(state.set_bind_group(1, BindGroup{}.buffer(0, buffer("u", 256, BufferUsage::Uniform))).ok());
    expect_error(state.set_bind_group(4, {}), ErrorCode::InvalidArgument,
                 "set_bind_group: set 4 is beyond the 4 sets loom supports");
    const std::vector<std::byte> bytes(8, std::byte{7});
    ASSERT_TRUE(state.push_constants(bytes, 8).ok());
    expect_error(state.push_constants(bytes, 252), ErrorCode::InvalidArgument,
                 "push_constants: 8 bytes at offset 252 exceed the 256 bytes loom supports");
    ASSERT_TRUE(state.set_index_buffer(buffer("i", 12, BufferUsage::Index), IndexType::Uint32, 0).ok());
    EXPECT_EQ(state.pipeline(), pipeline);
    const BindGroup* group1 = state.bind_group(1);
    ASSERT_NE(group1, nullptr);
    EXPECT_EQ(group1->entries.size(), 1u);
    EXPECT_EQ(state.bind_group(0), nullptr);
    EXPECT_EQ(state.push_constant_size(), 16u);
    EXPECT_EQ(state.push_constant_data()[8], std::byte{7});
    EXPECT_EQ(state.push_constant_data()[7], std::byte{0});

    state.end_frame();
    state.begin_frame();
    EXPECT_TRUE(state.pipeline().is_null());
    EXPECT_EQ(state.bind_group(1), nullptr);
    EXPECT_EQ(state.push_constant_size(), 0u);
    EXPECT_EQ(state.push_constant_data()[8], std::byte{0});
    EXPECT_TRUE(state.index_buffer().buffer.is_null());
}

}  // namespace
}  // namespace loom::rhi

namespace loom::rhi {
namespace {

// set_buffer changes one binding of a set's group and keeps the others; the last entry of a
// binding is the one draws use, so that is the one replaced.
TEST_F(CommandListStateTest, SetBufferReplacesOneBindingOfTheGroup) {
    state.begin_frame();
    const BufferHandle ubo = buffer("ubo", 256, BufferUsage::Uniform);
    ASSERT_TRUE(state.set_buffer(2, 1, BufferBinding{ubo, 0, 16}).ok());
    const BindGroup* group2 = state.bind_group(2);
    ASSERT_NE(group2, nullptr);
    ASSERT_EQ(group2->entries.size(), 1u);

    BindGroup group;
    group.buffer(0, ubo, 0, 16).buffer(1, ubo, 0, 16).buffer(1, ubo, 32, 16);
    ASSERT_TRUE(state.set_bind_group(0, group).ok());
    ASSERT_TRUE(state.set_buffer(0, 1, BufferBinding{ubo, 64, 16}).ok());
    const BindGroup* group0 = state.bind_group(0);
    ASSERT_NE(group0, nullptr);
    const BindGroup& bound = *group0;
    ASSERT_EQ(bound.entries.size(), 3u);
    EXPECT_EQ(std::get<BufferBinding>(bound.entries[0].resource).offset, 0u);   // binding 0 kept
    EXPECT_EQ(std::get<BufferBinding>(bound.entries[1].resource).offset, 0u);   // hidden by the later one
    EXPECT_EQ(std::get<BufferBinding>(bound.entries[2].resource).offset, 64u);  // the one draws use
    ASSERT_TRUE(state.set_buffer(0, 5, BufferBinding{ubo, 128, 16}).ok());
    EXPECT_EQ(bound.entries.size(), 4u);  // the same group, one entry more

    expect_error(state.set_buffer(kMaxBindGroups, 0, BufferBinding{ubo, 0, 16}), ErrorCode::InvalidArgument,
                 "set_buffer: set " + std::to_string(kMaxBindGroups) + " binding 0 is beyond the " +
                     std::to_string(kMaxBindGroups) + " sets of " + std::to_string(kMaxBindingsPerGroup) +
                     " bindings loom supports");
    state.end_frame();
    EXPECT_EQ(state.bind_group(0), nullptr);
}

// DeviceDesc::validation off: what the draws use is accepted unchecked (a misuse is the
// user's), while the order of commands and the tracker's own slots are still checked.
TEST_F(CommandListStateTest, WithValidationOffResourcesAreTakenUncheckedButCommandOrderIsNot) {
    if (!validation::kCompiled) GTEST_SKIP() << "validation is compiled out of this build (LOOM_RHI_VALIDATION=OFF)";
    ASSERT_TRUE(state.validating()) << "validation is on by default";
    state.set_validation(false);
    EXPECT_FALSE(state.validating());
    begin_frame_and_expect_a_pass_then_a_pipeline();
    // A pipeline for other attachments, then destroyed: both refused when validating.
    const PipelineHandle other = graphics("float target", Format::RGBA32Float, 1);
    ASSERT_TRUE(pipelines.remove(other).ok());
    ASSERT_TRUE(state.set_pipeline(other).ok());
    EXPECT_EQ(state.pipeline(), other);
    // No vertex buffer in the slot it reads, an index buffer of the wrong usage and too small.
    EXPECT_TRUE(state.check_draw("draw", false).ok());
    const BufferHandle small = buffer("small", 4, BufferUsage::Vertex);
    const BufferDesc* small_desc = *buffers.get(small);
    ASSERT_TRUE(state.set_index_buffer(small, small_desc, IndexType::Uint32, 0).ok());
    EXPECT_TRUE(state.check_draw("draw_indexed", true).ok());
    EXPECT_TRUE(state.check_index_range(0, 1000).ok());
    ASSERT_TRUE(state.set_vertex_buffer(0, small, small_desc, 64).ok());
    EXPECT_FALSE(state.check_dispatch().ok()) << "dispatches go outside render passes either way";
    // The tracker's own slots are bounded either way.
    expect_error(state.set_vertex_buffer(16, small, small_desc, 0), ErrorCode::InvalidArgument,
                 "set_vertex_buffer: slot 16 is beyond the 16 slots loom supports");
    EXPECT_FALSE(state.set_buffer(kMaxBindGroups, 0, BufferBinding{small, 0, 4}).ok());
    EXPECT_FALSE(state.set_bind_group(kMaxBindGroups, BindGroup{}).ok());

    // The same commands validated are refused.
    state.set_validation(true);
    EXPECT_FALSE(state.set_index_buffer(small, small_desc, IndexType::Uint32, 0).ok());  // lacks usage Index
    EXPECT_FALSE(state.set_pipeline(other).ok());
    EXPECT_FALSE(state.check_index_range(0, 1000).ok());
}

}  // namespace
}  // namespace loom::rhi
