// Multiple render targets of different formats written in one draw.
#include "loom_test/render_fixture.hpp"
#include "render_helpers.hpp"

namespace loom::test {
namespace {

class MrtTest : public RenderTest {};

TEST_P(MrtTest, FourTargetsOfDifferentFormats) {
    constexpr uint32_t kSize = 8;
    const std::array<rhi::Format, 4> formats{rhi::Format::RGBA8Unorm, rhi::Format::RGBA16Float, rhi::Format::R32Uint,
                                             rhi::Format::RG32Float};
    std::vector<rhi::TextureHandle> targets;
    rhi::RenderPassDesc pass;
    pass.label = "mrt";
    for (rhi::Format f : formats) {
        LOOM_ASSIGN_OR_FAIL(auto t, make_target(device(), "mrt " + std::string(rhi::format_name(f)), f, kSize, kSize));
        targets.push_back(t);
        rhi::ColorAttachment a;
        a.texture = t;
        a.clear = {0, 0, 0, 0};
        pass.colors.push_back(a);
    }
    LOOM_ASSIGN_OR_FAIL(auto vs, make_shader(device(), rhi::ShaderStage::Vertex, "position.vert", kPositionVert));
    LOOM_ASSIGN_OR_FAIL(auto fs, make_shader(device(), rhi::ShaderStage::Fragment, "mrt.frag", R"(#version 450
layout(location = 0) out vec4 out0;
layout(location = 1) out vec4 out1;
layout(location = 2) out uint out2;
layout(location = 3) out vec2 out3;
void main() {
    out0 = vec4(0.2, 0.4, 0.6, 0.8);
    out1 = vec4(-1.5, 2.25, 100.0, 0.5);
    out2 = 3000000000u;
    out3 = vec2(1.0e-3, -12345.5);
})"));
    rhi::GraphicsPipelineDesc pd;
    pd.name = "mrt";
    pd.vertex = vs;
    pd.fragment = fs;
    pd.vertex_buffers = {rhi::VertexBufferLayout{12, rhi::VertexStepMode::PerVertex, {{0, rhi::VertexFormat::Float3, 0}}}};
    pd.color_formats.assign(formats.begin(), formats.end());
    LOOM_ASSIGN_OR_FAIL(auto pipeline, device().create_graphics_pipeline(pd));
    const std::vector<float> vertices = {-1, -1, 0, 3, -1, 0, -1, 3, 0};
    LOOM_ASSIGN_OR_FAIL(auto vb, make_buffer_of(device(), "mrt vertices", rhi::BufferUsage::Vertex, vertices));
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(pass);
        list.set_pipeline(pipeline);
        list.set_vertex_buffer(0, vb);
        list.draw(3);
        list.end_render_pass();
    }));
    const std::array<std::array<double, 4>, 4> expected{{
        {51 / 255.0, 102 / 255.0, 153 / 255.0, 204 / 255.0},
        {-1.5, 2.25, 100.0, 0.5},
        {3000000000.0, 0, 0, 1},
        {static_cast<double>(1.0e-3f), -12345.5, 0, 1},
    }};
    for (std::size_t i = 0; i < 4; ++i) {
        SCOPED_TRACE(std::string(rhi::format_name(formats[i])));
        LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(targets[i]));
        for (uint32_t y = 0; y < kSize; ++y) {
            for (uint32_t x = 0; x < kSize; ++x) ASSERT_EQ(image.load(x, y), expected[i]) << "pixel " << x << "," << y;
        }
    }
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(MrtTest);

}  // namespace loom::test
