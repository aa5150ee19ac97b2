// Indirect multi-draws (CommandList::draw_indexed_indirect): every command of the range is
// drawn with its own index range, base vertex, instance count and first instance (which offsets
// per-instance attributes); the offset skips earlier commands; no commands draw nothing; misuse
// (a buffer without Indirect usage, commands past its end, an unaligned offset) fails the frame
// with an InvalidArgument error (naming the buffer at fault; nothing is logged).
#include "loom_test/render_fixture.hpp"
#include "render_helpers.hpp"

namespace loom::test {
namespace {

class IndirectDrawTest : public RenderTest {
protected:
    static constexpr uint32_t kSize = 32;

    void SetUp() override {
        RenderTest::SetUp();
        if (HasFatalFailure()) return;
        ASSERT_TRUE(device().capabilities().draw_indirect);
        LOOM_ASSIGN_OR_FAIL(auto vs, make_shader(device(), rhi::ShaderStage::Vertex, "indirect.vert", R"(#version 450
layout(location = 0) in vec2 corner;
layout(location = 1) in vec2 offset;
layout(location = 2) in float red;
layout(location = 0) out vec4 v_color;
void main() {
    v_color = vec4(red, 1.0, 0.0, 1.0);
    gl_Position = vec4(corner + offset, 0.0, 1.0);
})"));
        LOOM_ASSIGN_OR_FAIL(auto fs, make_shader(device(), rhi::ShaderStage::Fragment, "color.frag", R"(#version 450
layout(location = 0) in vec4 v_color;
layout(location = 0) out vec4 frag_color;
void main() { frag_color = v_color; }
)"));
        rhi::GraphicsPipelineDesc pd;
        pd.name = "indirect";
        pd.vertex = vs;
        pd.fragment = fs;
        pd.vertex_buffers = {
            rhi::VertexBufferLayout{8, rhi::VertexStepMode::PerVertex, {{0, rhi::VertexFormat::Float2, 0}}},
            rhi::VertexBufferLayout{12, rhi::VertexStepMode::PerInstance,
                                    {{1, rhi::VertexFormat::Float2, 0}, {2, rhi::VertexFormat::Float, 8}}},
        };
        pd.color_formats = {rhi::Format::RGBA32Float};
        LOOM_ASSIGN_OR_FAIL(pipeline_, device().create_graphics_pipeline(pd));
        // Two quads: vertices 0..3 cover the top-left 8x8 cell, 4..7 the cell below it.
        const std::vector<float> corners = {-1, 0.5f, -0.5f, 0.5f, -0.5f, 1,    -1, 1,
                                            -1, 0,    -0.5f, 0,    -0.5f, 0.5f, -1, 0.5f};
        // Indices of a quad (two triangles), then one triangle of it (first index 6).
        const std::vector<uint32_t> indices = {0, 1, 2, 0, 2, 3, 0, 1, 2};
        // Per instance: an offset (in 8-pixel cells: 0.5 NDC) and a red value.
        const std::vector<float> instances = {
            0.0f, 0.0f, 0.125f,   // 0
            0.5f, 0.0f, 0.25f,    // 1
            1.0f, 0.0f, 0.375f,   // 2
            1.5f, -1.0f, 0.5f,    // 3
            1.0f, -1.0f, 0.625f,  // 4 (never drawn)
        };
        LOOM_ASSIGN_OR_FAIL(corners_, make_buffer_of(device(), "corners", rhi::BufferUsage::Vertex, corners));
        LOOM_ASSIGN_OR_FAIL(indices_, make_buffer_of(device(), "indices", rhi::BufferUsage::Index, indices));
        LOOM_ASSIGN_OR_FAIL(instances_, make_buffer_of(device(), "instances", rhi::BufferUsage::Vertex, instances));
        LOOM_ASSIGN_OR_FAIL(target_, make_target(device(), "indirect", rhi::Format::RGBA32Float, kSize, kSize));
    }

    void record(rhi::CommandList& list, rhi::BufferHandle arguments, uint64_t offset, uint32_t count) {
        list.begin_render_pass(clear_pass("indirect", target_, {-1, 0, 0, 0}));
        list.set_pipeline(pipeline_);
        list.set_vertex_buffer(0, corners_);
        list.set_vertex_buffer(1, instances_);
        list.set_index_buffer(indices_, rhi::IndexType::Uint32);
        list.draw_indexed_indirect(arguments, offset, count);
        list.end_render_pass();
    }

    rhi::PipelineHandle pipeline_;
    rhi::BufferHandle corners_, indices_, instances_;
    rhi::TextureHandle target_;
};

TEST_P(IndirectDrawTest, EveryCommandDrawsItsRangeWithItsInstances) {
    const std::vector<rhi::DrawIndexedIndirectCommand> commands = {
        {6, 1, 0, 0, 4},  // skipped by the offset: instance 4 would mark cell (2, 2)
        {6, 2, 0, 0, 0},  // the top quad, instances 0 and 1: cells (0, 0) and (1, 0)
        {6, 1, 0, 4, 2},  // base vertex 4, the lower quad, instance 2: cell (2, 1)
        {3, 1, 6, 0, 3},  // first index 6, one triangle of the top quad, instance 3: cell (3, 2)
    };
    LOOM_ASSIGN_OR_FAIL(auto arguments, make_buffer_of(device(), "arguments", rhi::BufferUsage::Indirect, commands));
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        record(list, arguments, sizeof(rhi::DrawIndexedIndirectCommand), 3);
    }));
    EXPECT_EQ(device().last_frame_stats().draw_calls, 1u);
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target_));
    auto cell = [&](uint32_t cx, uint32_t cy) { return image.load(cx * 8 + 4, cy * 8 + 4); };
    EXPECT_EQ(cell(0, 0), (std::array<double, 4>{0.125, 1, 0, 1}));
    EXPECT_EQ(cell(1, 0), (std::array<double, 4>{0.25, 1, 0, 1}));
    EXPECT_EQ(cell(2, 1), (std::array<double, 4>{0.375, 1, 0, 1}));
    // The triangle (0, 1, 2) covers the cell's lower-right half.
    EXPECT_EQ(image.load(3 * 8 + 6, 2 * 8 + 6), (std::array<double, 4>{0.5, 1, 0, 1}));
    EXPECT_EQ(image.load(3 * 8 + 1, 2 * 8 + 1), (std::array<double, 4>{-1, 0, 0, 0}));
    EXPECT_EQ(cell(2, 2), (std::array<double, 4>{-1, 0, 0, 0})) << "the skipped command drew";
    EXPECT_EQ(cell(0, 1), (std::array<double, 4>{-1, 0, 0, 0}));
    save_picture(image, "indirect_draw_" + std::string(rhi::backend_name(backend())));
}

TEST_P(IndirectDrawTest, ZeroCommandsDrawNothing) {
    const std::vector<rhi::DrawIndexedIndirectCommand> commands = {{6, 1, 0, 0, 0}};
    LOOM_ASSIGN_OR_FAIL(auto arguments, make_buffer_of(device(), "arguments", rhi::BufferUsage::Indirect, commands));
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) { record(list, arguments, 0, 0); }));
    EXPECT_EQ(device().last_frame_stats().draw_calls, 0u);
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target_));
    for (uint32_t y = 0; y < kSize; y += 4) {
        for (uint32_t x = 0; x < kSize; x += 4) {
            ASSERT_EQ(image.load(x, y), (std::array<double, 4>{-1, 0, 0, 0})) << "at " << x << ", " << y;
        }
    }
}

TEST_P(IndirectDrawTest, MisuseFailsTheFrameNamingTheBuffer) {
    const std::vector<rhi::DrawIndexedIndirectCommand> commands = {{6, 1, 0, 0, 0}, {6, 1, 0, 0, 1}};
    LOOM_ASSIGN_OR_FAIL(auto not_indirect, make_buffer_of(device(), "plain vertices", rhi::BufferUsage::Vertex, commands));
    auto status = run_frame(device(), [&](rhi::CommandList& list) { record(list, not_indirect, 0, 2); });
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.error().code, ErrorCode::InvalidArgument);
    EXPECT_NE(status.error().message.find("plain vertices"), std::string::npos) << status.error().message;

    LOOM_ASSIGN_OR_FAIL(auto arguments, make_buffer_of(device(), "two commands", rhi::BufferUsage::Indirect, commands));
    status = run_frame(device(), [&](rhi::CommandList& list) { record(list, arguments, 20, 2); });
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.error().code, ErrorCode::InvalidArgument);
    EXPECT_NE(status.error().message.find("two commands"), std::string::npos) << status.error().message;

    // Commands are read as 32-bit words: an offset that is not a multiple of 4 is refused.
    status = run_frame(device(), [&](rhi::CommandList& list) { record(list, arguments, 2, 1); });
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.error().code, ErrorCode::InvalidArgument);
    EXPECT_NE(status.error().message.find("multiples of 4"), std::string::npos) << status.error().message;
}

TEST_P(IndirectDrawTest, TheInstanceIndexCountsFromTheCommandsFirstInstance) {
    // gl_InstanceIndex counts from each command's first instance. GL reads it as gl_InstanceID +
    // gl_BaseInstanceARB (ARB_shader_draw_parameters, which llvmpipe has); without that
    // extension SPIR-V Cross emulates the base with a uniform set per draw call, which one
    // multi-draw cannot set per command, and the GL backend refuses the draw (Unsupported).
    LOOM_ASSIGN_OR_FAIL(auto vs, make_shader(device(), rhi::ShaderStage::Vertex, "instance_index.vert", R"(#version 450
layout(location = 0) in vec2 corner;
layout(location = 0) out vec4 v_color;
void main() {
    v_color = vec4(float(gl_InstanceIndex) * 0.25, 1.0, 0.0, 1.0);
    gl_Position = vec4(corner + vec2(0.5 * float(gl_InstanceIndex), 0.0), 0.0, 1.0);
})"));
    LOOM_ASSIGN_OR_FAIL(auto fs, make_shader(device(), rhi::ShaderStage::Fragment, "color.frag", R"(#version 450
layout(location = 0) in vec4 v_color;
layout(location = 0) out vec4 frag_color;
void main() { frag_color = v_color; }
)"));
    rhi::GraphicsPipelineDesc pd;
    pd.name = "instance index";
    pd.vertex = vs;
    pd.fragment = fs;
    pd.vertex_buffers = {rhi::VertexBufferLayout{8, rhi::VertexStepMode::PerVertex, {{0, rhi::VertexFormat::Float2, 0}}}};
    pd.color_formats = {rhi::Format::RGBA32Float};
    LOOM_ASSIGN_OR_FAIL(auto pipeline, device().create_graphics_pipeline(pd));
    const std::vector<rhi::DrawIndexedIndirectCommand> commands = {{6, 1, 0, 0, 2}};
    LOOM_ASSIGN_OR_FAIL(auto arguments, make_buffer_of(device(), "arguments", rhi::BufferUsage::Indirect, commands));
    auto status = run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("indirect", target_, {-1, 0, 0, 0}));
        list.set_pipeline(pipeline);
        list.set_vertex_buffer(0, corners_);
        list.set_index_buffer(indices_, rhi::IndexType::Uint32);
        list.draw_indexed_indirect(arguments, 0, 1);
        list.end_render_pass();
    });
    if (backend() == rhi::Backend::OpenGL && !status.ok() && status.error().code == ErrorCode::Unsupported) {
        EXPECT_NE(status.error().message.find("instance index"), std::string::npos) << status.error().message;
        GTEST_SKIP() << "GL without ARB_shader_draw_parameters: " << status.error().message;
    }
    LOOM_ASSERT_OK(status);
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target_));
    EXPECT_EQ(image.load(2 * 8 + 4, 4), (std::array<double, 4>{0.5, 1, 0, 1})) << "instance 2 moves two cells right";
    EXPECT_EQ(image.load(4, 4), (std::array<double, 4>{-1, 0, 0, 0}));
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(IndirectDrawTest);

}  // namespace loom::test
