// DeviceDesc::validation off skips loom's checks of recorded commands, not their effect: the
// same frame, with the per-draw paths (vertex and index buffers rebound per draw, push
// constants, set_uniforms_of, a bind group, a pipeline change), renders the same pixels on a
// device that validates and on one that does not, and the API's own debug output (on for both)
// reports nothing.
#include "loom_test/render_fixture.hpp"
#include "render_helpers.hpp"

namespace loom::test {
namespace {

class ValidationOffTest : public RenderTest {
protected:
    static constexpr uint32_t kColumns = 8;  ///< of render_frame's target, 4 pixels wide

    Result<std::unique_ptr<rhi::Device>> unvalidated_device() {
        rhi::DeviceDesc desc;
        desc.backend = backend();
        desc.debug = true;
        desc.validation = false;
        return rhi::create_device(desc);
    }
};

// Positions as given; colour = the uniform block at set 0 binding 0 + the one at set 1 binding 0.
const char* const kPositionVert = R"(#version 450
layout(location = 0) in vec3 position;
void main() { gl_Position = vec4(position, 1.0); })";
const char* const kTwoBlocksFrag = R"(#version 450
layout(set = 0, binding = 0) uniform Base { vec4 color; } base;
layout(set = 1, binding = 0) uniform PerDraw { vec4 color; } per_draw;
layout(location = 0) out vec4 frag_color;
void main() { frag_color = base.color + per_draw.color; }
)";

/// Renders the frame on `device` and reads the target back. Each of the 8 columns is two
/// quads: the top one drawn by the solid pipeline (its colour a push constant), the bottom one
/// by the two-block pipeline (a bind group and per-draw uniforms). Consecutive draws change only
/// what is per draw (the quad's offset in its vertex buffer, which of two vertex and two index
/// buffers, the constants), the paths on which the backends skip most of their work.
Result<rhi::Image> render_frame(rhi::Device& device) {
    constexpr uint32_t kColumns = 8;
    auto solid = make_solid_pipeline(device, rhi::Format::RGBA32Float);
    if (!solid.ok()) return solid.take_error();
    auto vs = make_shader(device, rhi::ShaderStage::Vertex, "position.vert", kPositionVert);
    if (!vs.ok()) return vs.take_error();
    auto fs = make_shader(device, rhi::ShaderStage::Fragment, "two_blocks.frag", kTwoBlocksFrag);
    if (!fs.ok()) return fs.take_error();
    rhi::GraphicsPipelineDesc pd;
    pd.name = "two blocks";
    pd.vertex = *vs;
    pd.fragment = *fs;
    pd.vertex_buffers = {rhi::VertexBufferLayout{12, rhi::VertexStepMode::PerVertex, {{0, rhi::VertexFormat::Float3, 0}}}};
    pd.color_formats = {rhi::Format::RGBA32Float};
    auto blocks = device.create_graphics_pipeline(pd);
    if (!blocks.ok()) return blocks.take_error();

    // Quad q (4 vertices): column q % 8, the top half of the target for q < 8, else the bottom.
    std::vector<float> quads;
    for (uint32_t q = 0; q < 2 * kColumns; ++q) {
        const float x0 = -1.0f + 0.25f * static_cast<float>(q % kColumns);
        const float y0 = q < kColumns ? 0.0f : -1.0f;
        for (const auto& [dx, dy] : {std::pair{0.0f, 0.0f}, {0.25f, 0.0f}, {0.0f, 1.0f}, {0.25f, 1.0f}}) {
            quads.insert(quads.end(), {x0 + dx, y0 + dy, 0.0f});
        }
    }
    constexpr uint64_t kQuadBytes = 4 * 3 * sizeof(float);
    std::array<rhi::BufferHandle, 2> vertices;  // two copies: draws alternate between them
    for (auto& vb : vertices) {
        auto made = make_buffer_of(device, "quads", rhi::BufferUsage::Vertex, quads);
        if (!made.ok()) return made.take_error();
        vb = *made;
    }
    auto indices16 = make_buffer_of(device, "indices16", rhi::BufferUsage::Index, std::vector<uint16_t>{0, 1, 2, 2, 1, 3});
    if (!indices16.ok()) return indices16.take_error();
    auto indices32 = make_buffer_of(device, "indices32", rhi::BufferUsage::Index, std::vector<uint32_t>{0, 1, 2, 2, 1, 3});
    if (!indices32.ok()) return indices32.take_error();
    const std::array<float, 4> base{0.0f, 0.0f, 0.25f, 1.0f};
    auto base_ubo = make_buffer(device, "base", rhi::BufferUsage::Uniform, bytes_of(base));
    if (!base_ubo.ok()) return base_ubo.take_error();
    auto target = make_target(device, "columns", rhi::Format::RGBA32Float, kColumns * 4, 8);
    if (!target.ok()) return target.take_error();

    const auto bind_quad = [&](rhi::CommandList& list, uint32_t q) {
        list.set_vertex_buffer(0, vertices[q % 2], q * kQuadBytes);
        if (q % 2 == 0) {
            list.set_index_buffer(*indices16, rhi::IndexType::Uint16);
        } else {
            list.set_index_buffer(*indices32, rhi::IndexType::Uint32);
        }
    };
    LOOM_TRY(run_frame(device, [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("columns", *target, {-1, -1, -1, -1}));
        list.set_pipeline(*solid);
        for (uint32_t i = 0; i < kColumns; ++i) {
            bind_quad(list, i);
            list.push_constants_of(std::array<float, 4>{static_cast<float>(i), 1.0f, 0.0f, 1.0f});
            list.draw_indexed(6);
        }
        list.set_pipeline(*blocks);
        list.set_bind_group(0, rhi::BindGroup{}.buffer(0, *base_ubo));
        for (uint32_t i = 0; i < kColumns; ++i) {
            bind_quad(list, kColumns + i);
            list.set_uniforms_of(1, 0, std::array<float, 4>{static_cast<float>(i), 2.0f, 0.0f, 0.0f});
            list.draw_indexed(6);
        }
        list.end_render_pass();
    }));
    return device.read_texture(*target);
}

TEST_P(ValidationOffTest, TheSameFrameRendersTheSamePixels) {
    LOOM_ASSIGN_OR_FAIL(auto unchecked, unvalidated_device());
    LOOM_ASSIGN_OR_FAIL(rhi::Image validated_image, render_frame(device()));
    LOOM_ASSIGN_OR_FAIL(rhi::Image unvalidated_image, render_frame(*unchecked));
    for (uint32_t i = 0; i < kColumns; ++i) {
        const uint32_t x = i * 4 + 1;
        const auto column = static_cast<double>(i);
        EXPECT_EQ(validated_image.load(x, 1), (std::array<double, 4>{column, 1.0, 0.0, 1.0})) << "column " << i;
        EXPECT_EQ(validated_image.load(x, 6), (std::array<double, 4>{column, 2.0, 0.25, 1.0})) << "column " << i;
    }
    ASSERT_EQ(unvalidated_image.width, validated_image.width);
    ASSERT_EQ(unvalidated_image.height, validated_image.height);
    for (uint32_t y = 0; y < validated_image.height; ++y) {
        for (uint32_t x = 0; x < validated_image.width; ++x) {
            ASSERT_EQ(unvalidated_image.load(x, y), validated_image.load(x, y)) << "pixel " << x << "," << y;
        }
    }
    auto status = unchecked->wait_idle();
    EXPECT_TRUE(status.ok()) << status.error().to_string();
}

// What validation refuses, a device without it records unchecked: here a pipeline for other
// attachments than the pass has, set but not drawn with (no API rule is broken until a draw),
// which the validating device reports.
TEST_P(ValidationOffTest, AMisuseIsReportedOnlyWhenValidating) {
    LOOM_ASSIGN_OR_FAIL(auto unchecked, unvalidated_device());
    for (rhi::Device* d : {&device(), unchecked.get()}) {
        LOOM_ASSIGN_OR_FAIL(auto pipeline, make_solid_pipeline(*d, rhi::Format::RGBA32Float));
        LOOM_ASSIGN_OR_FAIL(auto target, make_target(*d, "target", rhi::Format::RGBA8Unorm, 4, 4));
        const Status status = run_frame(*d, [&](rhi::CommandList& list) {
            list.begin_render_pass(clear_pass("pass", target, {0, 0, 0, 1}));
            list.set_pipeline(pipeline);
            list.end_render_pass();
        });
        if (d == &device()) {
            ASSERT_FALSE(status.ok()) << "the validating device accepted the pipeline";
            EXPECT_NE(status.error().message.find("set_pipeline"), std::string::npos) << status.error().message;
        } else {
            EXPECT_TRUE(status.ok()) << status.error().to_string();
        }
    }
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(ValidationOffTest);

}  // namespace loom::test
