// Render pass load/store operations, blending and debug groups.
#include "loom_test/render_fixture.hpp"
#include "render_helpers.hpp"

namespace loom::test {
namespace {

class PassTest : public RenderTest {
protected:
    static constexpr uint32_t kSize = 16;
    const std::vector<float> left_half_{-1, -1, 0, 0, -1, 0, 0, 1, 0, -1, -1, 0, 0, 1, 0, -1, 1, 0};
};

TEST_P(PassTest, LoadKeepsEarlierContents) {
    LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "load target", rhi::Format::RGBA8Unorm, kSize, kSize));
    LOOM_ASSIGN_OR_FAIL(auto pipeline, make_solid_pipeline(device(), rhi::Format::RGBA8Unorm));
    LOOM_ASSIGN_OR_FAIL(auto vb, make_buffer_of(device(), "left half", rhi::BufferUsage::Vertex, left_half_));
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("clear red", target, {1, 0, 0, 1}));
        list.end_render_pass();
        rhi::RenderPassDesc load = clear_pass("load and draw", target, {0, 0, 0, 0});
        load.colors[0].load = rhi::LoadOp::Load;
        list.begin_render_pass(load);
        list.set_pipeline(pipeline);
        list.set_vertex_buffer(0, vb);
        list.push_constants_of(std::array<float, 4>{0, 0, 1, 1});
        list.draw(6);
        list.end_render_pass();
    }));
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target));
    EXPECT_EQ(rgba8_at(image, 2, 8), (std::array<int, 4>{0, 0, 255, 255}));
    EXPECT_EQ(rgba8_at(image, 13, 8), (std::array<int, 4>{255, 0, 0, 255})) << "Load lost the earlier clear";
}

TEST_P(PassTest, ContentsSurviveAcrossFrames) {
    LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "persistent", rhi::Format::RGBA8Unorm, kSize, kSize));
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("clear green", target, {0, 1, 0, 1}));
        list.end_render_pass();
    }));
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        rhi::RenderPassDesc load = clear_pass("load only", target, {0, 0, 0, 0});
        load.colors[0].load = rhi::LoadOp::Load;
        list.begin_render_pass(load);
        list.end_render_pass();
    }));
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target));
    EXPECT_EQ(rgba8_at(image, 7, 7), (std::array<int, 4>{0, 255, 0, 255}));
}

TEST_P(PassTest, AlphaBlendingComputesExactValues) {
    LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "blend target", rhi::Format::RGBA16Float, kSize, kSize));
    LOOM_ASSIGN_OR_FAIL(auto vs, make_shader(device(), rhi::ShaderStage::Vertex, "position.vert", kPositionVert));
    LOOM_ASSIGN_OR_FAIL(auto fs, make_shader(device(), rhi::ShaderStage::Fragment, "push_color.frag", kPushColorFrag));
    rhi::GraphicsPipelineDesc pd;
    pd.name = "blend";
    pd.vertex = vs;
    pd.fragment = fs;
    pd.vertex_buffers = {rhi::VertexBufferLayout{12, rhi::VertexStepMode::PerVertex, {{0, rhi::VertexFormat::Float3, 0}}}};
    pd.color_formats = {rhi::Format::RGBA16Float};
    rhi::BlendState blend;
    blend.enabled = true;
    blend.src_color = rhi::BlendFactor::SrcAlpha;
    blend.dst_color = rhi::BlendFactor::OneMinusSrcAlpha;
    blend.src_alpha = rhi::BlendFactor::One;
    blend.dst_alpha = rhi::BlendFactor::Zero;
    blend.write_mask = rhi::ColorMask::R | rhi::ColorMask::G | rhi::ColorMask::A;  // blue stays as cleared
    pd.blend = {blend};
    LOOM_ASSIGN_OR_FAIL(auto pipeline, device().create_graphics_pipeline(pd));
    LOOM_ASSIGN_OR_FAIL(auto vb, make_buffer_of(device(), "left half", rhi::BufferUsage::Vertex, left_half_));
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("blend", target, {1.0, 0.5, 0.25, 1.0}));
        list.set_pipeline(pipeline);
        list.set_vertex_buffer(0, vb);
        list.push_constants_of(std::array<float, 4>{0.0f, 1.0f, 1.0f, 0.25f});
        list.draw(6);
        list.end_render_pass();
    }));
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target));
    // src * 0.25 + dst * 0.75: r = 0.75, g = 0.25 + 0.375 = 0.625; blue masked; alpha = src.
    EXPECT_EQ(image.load(2, 8), (std::array<double, 4>{0.75, 0.625, 0.25, 0.25}));
    EXPECT_EQ(image.load(13, 8), (std::array<double, 4>{1.0, 0.5, 0.25, 1.0}));
}

TEST_P(PassTest, DebugGroupsMustBalance) {
    LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "grouped", rhi::Format::RGBA8Unorm, 4, 4));
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        list.push_debug_group("outer");
        list.push_debug_group("inner");
        list.begin_render_pass(clear_pass("grouped", target, {0, 0, 0, 1}));
        list.end_render_pass();
        list.pop_debug_group();
        list.pop_debug_group();
    }));
    auto extra_pop = run_frame(device(), [](rhi::CommandList& list) { list.pop_debug_group(); });
    ASSERT_FALSE(extra_pop.ok());
    EXPECT_EQ(extra_pop.error().code, ErrorCode::InvalidState);
    auto left_open = run_frame(device(), [](rhi::CommandList& list) { list.push_debug_group("never popped"); });
    ASSERT_FALSE(left_open.ok());
    EXPECT_EQ(left_open.error().code, ErrorCode::InvalidState);
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(PassTest);

}  // namespace loom::test
