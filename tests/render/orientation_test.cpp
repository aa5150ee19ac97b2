// loom's conventions on every backend: NDC y is up, row 0 of framebuffers, uploads and
// readbacks is the top row, counter-clockwise (in NDC) is front-facing, viewports are
// top-left-origin pixel rectangles.
#include "loom_test/render_fixture.hpp"
#include "render_helpers.hpp"

namespace loom::test {
namespace {

class OrientationTest : public RenderTest {
protected:
    static constexpr uint32_t kSize = 32;
    const std::array<int, 4> red_{255, 0, 0, 255};
    const std::array<int, 4> black_{0, 0, 0, 255};
};

TEST_P(OrientationTest, NdcUpperLeftPointLandsInTopLeftQuadrant) {
    LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "orientation target", rhi::Format::RGBA8Unorm, kSize, kSize));
    LOOM_ASSIGN_OR_FAIL(auto pipeline, make_solid_pipeline(device(), rhi::Format::RGBA8Unorm));
    // A small triangle around NDC (-0.5, +0.5).
    const std::vector<float> vertices = {-0.6f, 0.4f, 0.0f, -0.4f, 0.4f, 0.0f, -0.5f, 0.6f, 0.0f};
    LOOM_ASSIGN_OR_FAIL(auto vb, make_buffer_of(device(), "point vertices", rhi::BufferUsage::Vertex, vertices));
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("point", target, {0, 0, 0, 1}));
        list.set_pipeline(pipeline);
        list.set_vertex_buffer(0, vb);
        list.push_constants_of(std::array<float, 4>{1, 0, 0, 1});
        list.draw(3);
        list.end_render_pass();
    }));
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target));
    save_picture(image, "orientation_point_" + std::string(rhi::backend_name(backend())));
    // NDC (-0.5, +0.5) is pixel (8, 8) counted from the top-left.
    EXPECT_EQ(rgba8_at(image, 8, 8), red_);
    EXPECT_EQ(rgba8_at(image, 8, kSize - 1 - 8), black_);  // the vertical mirror image
    EXPECT_EQ(rgba8_at(image, kSize - 1 - 8, 8), black_);  // the horizontal mirror image
}

TEST_P(OrientationTest, UploadedTopRowIsRowZeroAndSampledAtVZero) {
    // A 4x4 texture: top row red, the rest green.
    rhi::Image source(4, 4, rhi::Format::RGBA8Unorm);
    for (uint32_t y = 0; y < 4; ++y) {
        for (uint32_t x = 0; x < 4; ++x) source.store(x, y, y == 0 ? std::array<double, 4>{1, 0, 0, 1} : std::array<double, 4>{0, 1, 0, 1});
    }
    rhi::TextureDesc desc;
    desc.name = "red top row";
    desc.width = desc.height = 4;
    desc.usage = rhi::TextureUsage::Sampled | rhi::TextureUsage::CopyDst;
    LOOM_ASSIGN_OR_FAIL(auto texture, device().create_texture(desc));
    LOOM_ASSERT_OK(device().write_texture(texture, {}, source.pixels));

    // Read straight back: row 0 is the row uploaded first.
    LOOM_ASSIGN_OR_FAIL(rhi::Image back, device().read_texture(texture));
    EXPECT_EQ(back.pixels, source.pixels);

    // Sampled at v = 0 (top) and v = 1 (bottom) with a nearest sampler: left half of the
    // target samples v = 1/8 (row 0), right half v = 7/8 (row 3).
    LOOM_ASSIGN_OR_FAIL(auto vs, make_shader(device(), rhi::ShaderStage::Vertex, "fullscreen.vert", R"(#version 450
void main() {
    vec2 p = vec2(gl_VertexIndex == 1 ? 3.0 : -1.0, gl_VertexIndex == 2 ? 3.0 : -1.0);
    gl_Position = vec4(p, 0.0, 1.0);
})"));
    LOOM_ASSIGN_OR_FAIL(auto fs, make_shader(device(), rhi::ShaderStage::Fragment, "sample_v.frag", R"(#version 450
layout(set = 0, binding = 0) uniform sampler2D tex;
layout(location = 0) out vec4 frag_color;
void main() {
    float v = gl_FragCoord.x < 16.0 ? 0.125 : 0.875;
    frag_color = texture(tex, vec2(0.5, v));
})"));
    rhi::GraphicsPipelineDesc pd;
    pd.name = "sample v";
    pd.vertex = vs;
    pd.fragment = fs;
    pd.color_formats = {rhi::Format::RGBA8Unorm};
    LOOM_ASSIGN_OR_FAIL(auto pipeline, device().create_graphics_pipeline(pd));
    rhi::SamplerDesc sd;
    sd.min_filter = sd.mag_filter = rhi::Filter::Nearest;
    LOOM_ASSIGN_OR_FAIL(auto sampler, device().create_sampler(sd));
    LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "sampled", rhi::Format::RGBA8Unorm, kSize, kSize));
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("sample", target, {0, 0, 0, 1}));
        list.set_pipeline(pipeline);
        list.set_bind_group(0, rhi::BindGroup{}.texture(0, texture, sampler));
        list.draw(3);
        list.end_render_pass();
    }));
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target));
    EXPECT_EQ(rgba8_at(image, 4, 4), red_);
    EXPECT_EQ(rgba8_at(image, 4, 28), red_);
    EXPECT_EQ(rgba8_at(image, 28, 4), (std::array<int, 4>{0, 255, 0, 255}));
}

TEST_P(OrientationTest, CounterClockwiseSurvivesBackFaceCulling) {
    LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "culling target", rhi::Format::RGBA8Unorm, kSize, kSize));
    SolidPipelineOptions cull_back;
    cull_back.cull = rhi::CullMode::Back;
    LOOM_ASSIGN_OR_FAIL(auto culling, make_solid_pipeline(device(), rhi::Format::RGBA8Unorm, cull_back));
    LOOM_ASSIGN_OR_FAIL(auto no_culling, make_solid_pipeline(device(), rhi::Format::RGBA8Unorm));
    // Left: counter-clockwise in NDC (y up). Right: its mirror image, clockwise.
    const std::vector<float> vertices = {
        -0.9f, -0.5f, 0.0f, -0.1f, -0.5f, 0.0f, -0.5f, 0.5f, 0.0f,  // CCW
        0.9f,  -0.5f, 0.0f, 0.1f,  -0.5f, 0.0f, 0.5f,  0.5f, 0.0f,  // CW
    };
    LOOM_ASSIGN_OR_FAIL(auto vb, make_buffer_of(device(), "culling vertices", rhi::BufferUsage::Vertex, vertices));
    auto render = [&](rhi::PipelineHandle pipeline) -> Result<rhi::Image> {
        LOOM_TRY(run_frame(device(), [&](rhi::CommandList& list) {
            list.begin_render_pass(clear_pass("culling", target, {0, 0, 0, 1}));
            list.set_pipeline(pipeline);
            list.set_vertex_buffer(0, vb);
            list.push_constants_of(std::array<float, 4>{1, 0, 0, 1});
            list.draw(6);
            list.end_render_pass();
        }));
        return device().read_texture(target);
    };
    LOOM_ASSIGN_OR_FAIL(rhi::Image culled, render(culling));
    save_picture(culled, "orientation_culling_" + std::string(rhi::backend_name(backend())));
    EXPECT_EQ(rgba8_at(culled, 8, 16), red_) << "the counter-clockwise triangle was culled";
    EXPECT_EQ(rgba8_at(culled, 24, 16), black_) << "the clockwise triangle survived back-face culling";
    // Without culling both are drawn, so the geometry itself is fine.
    LOOM_ASSIGN_OR_FAIL(rhi::Image all, render(no_culling));
    EXPECT_EQ(rgba8_at(all, 8, 16), red_);
    EXPECT_EQ(rgba8_at(all, 24, 16), red_);
}

TEST_P(OrientationTest, ViewportIsTopLeftOrigin) {
    LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "viewport target", rhi::Format::RGBA8Unorm, kSize, kSize));
    LOOM_ASSIGN_OR_FAIL(auto pipeline, make_solid_pipeline(device(), rhi::Format::RGBA8Unorm));
    // Two triangles covering all of NDC.
    const std::vector<float> vertices = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, -1, 0, 1, 1, 0, -1, 1, 0};
    LOOM_ASSIGN_OR_FAIL(auto vb, make_buffer_of(device(), "quad vertices", rhi::BufferUsage::Vertex, vertices));
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("viewport", target, {0, 0, 0, 1}));
        list.set_pipeline(pipeline);
        list.set_viewport(rhi::Viewport{0, 0, kSize / 2, kSize / 2, 0, 1});
        list.set_vertex_buffer(0, vb);
        list.push_constants_of(std::array<float, 4>{1, 0, 0, 1});
        list.draw(6);
        list.end_render_pass();
    }));
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target));
    save_picture(image, "orientation_viewport_" + std::string(rhi::backend_name(backend())));
    for (uint32_t y = 0; y < kSize; ++y) {
        for (uint32_t x = 0; x < kSize; ++x) {
            const bool top_left = x < kSize / 2 && y < kSize / 2;
            ASSERT_EQ(rgba8_at(image, x, y), top_left ? red_ : black_) << "pixel " << x << "," << y;
        }
    }
}

TEST_P(OrientationTest, ScissorIsTopLeftOrigin) {
    LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "scissor target", rhi::Format::RGBA8Unorm, kSize, kSize));
    LOOM_ASSIGN_OR_FAIL(auto pipeline, make_solid_pipeline(device(), rhi::Format::RGBA8Unorm));
    const std::vector<float> vertices = {-1, -1, 0, 3, -1, 0, -1, 3, 0};
    LOOM_ASSIGN_OR_FAIL(auto vb, make_buffer_of(device(), "fullscreen vertices", rhi::BufferUsage::Vertex, vertices));
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("scissor", target, {0, 0, 0, 1}));
        list.set_pipeline(pipeline);
        list.set_scissor(rhi::Rect{4, 2, 8, 6});
        list.set_vertex_buffer(0, vb);
        list.push_constants_of(std::array<float, 4>{1, 0, 0, 1});
        list.draw(3);
        list.end_render_pass();
    }));
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target));
    for (uint32_t y = 0; y < kSize; ++y) {
        for (uint32_t x = 0; x < kSize; ++x) {
            const bool inside = x >= 4 && x < 12 && y >= 2 && y < 8;
            ASSERT_EQ(rgba8_at(image, x, y), inside ? red_ : black_) << "pixel " << x << "," << y;
        }
    }
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(OrientationTest);

}  // namespace loom::test
