// The GL backend's caches: framebuffer objects by attachment set, vertex arrays by vertex
// layout, and the state cache that keeps redundant binds from reaching GL.
#include <cstdio>

#include "gl_test_util.hpp"
#include "render_helpers.hpp"

namespace loom::test {
namespace {

class GlCacheTest : public GlTest {};

TEST_F(GlCacheTest, FramebuffersAreCachedByAttachmentSetAndDroppedWithTheirTextures) {
    LOOM_ASSIGN_OR_FAIL(auto a, make_target(device(), "a", rhi::Format::RGBA8Unorm, 8, 8));
    LOOM_ASSIGN_OR_FAIL(auto b, make_target(device(), "b", rhi::Format::RGBA8Unorm, 8, 8));
    LOOM_ASSIGN_OR_FAIL(auto depth, make_target(device(), "depth", rhi::Format::Depth32F, 8, 8));
    EXPECT_EQ(caches().framebuffers, 0u);
    for (int frame = 0; frame < 3; ++frame) {
        LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
            list.begin_render_pass(clear_pass("a", a, {0, 0, 0, 1}));
            list.end_render_pass();
            list.begin_render_pass(clear_pass("a again", a, {0, 0, 0, 1}));
            list.end_render_pass();
        }));
    }
    EXPECT_EQ(caches().framebuffers, 1u) << "the same attachment set must reuse its framebuffer";
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("b", b, {0, 0, 0, 1}));
        list.end_render_pass();
        list.begin_render_pass(clear_pass("a with depth", a, {0, 0, 0, 1}, depth));
        list.end_render_pass();
    }));
    EXPECT_EQ(caches().framebuffers, 3u);
    LOOM_ASSERT_OK(device().destroy(a));  // drops "a" and "a with depth"
    EXPECT_EQ(caches().framebuffers, 1u);
    // Destroyed while a frame is recorded: the framebuffer goes once the frame has run.
    rhi::CommandList& list = device().begin_frame();
    list.begin_render_pass(clear_pass("b", b, {0, 0, 0, 1}));
    list.end_render_pass();
    LOOM_ASSERT_OK(device().destroy(b));
    EXPECT_EQ(caches().framebuffers, 1u);
    LOOM_ASSERT_OK(device().end_frame());
    EXPECT_EQ(caches().framebuffers, 0u);
    LOOM_ASSERT_OK(device().destroy(depth));
}

TEST_F(GlCacheTest, VertexArraysAreCachedByVertexLayout) {
    LOOM_ASSIGN_OR_FAIL(auto p1, make_solid_pipeline(device(), rhi::Format::RGBA8Unorm));
    LOOM_ASSIGN_OR_FAIL(auto p2, make_solid_pipeline(device(), rhi::Format::RGBA16Float));
    EXPECT_EQ(caches().vertex_arrays, 1u) << "same vertex layout, same vertex array";
    LOOM_ASSIGN_OR_FAIL(auto vs, make_shader(device(), rhi::ShaderStage::Vertex, "position.vert", kPositionVert));
    LOOM_ASSIGN_OR_FAIL(auto fs, make_shader(device(), rhi::ShaderStage::Fragment, "push_color.frag", kPushColorFrag));
    rhi::GraphicsPipelineDesc pd;
    pd.name = "strided";
    pd.vertex = vs;
    pd.fragment = fs;
    pd.vertex_buffers = {rhi::VertexBufferLayout{24, rhi::VertexStepMode::PerVertex, {{0, rhi::VertexFormat::Float3, 12}}}};
    pd.color_formats = {rhi::Format::RGBA8Unorm};
    LOOM_ASSIGN_OR_FAIL(auto p3, device().create_graphics_pipeline(pd));
    EXPECT_EQ(caches().vertex_arrays, 2u);
    LOOM_ASSERT_OK(device().destroy(p1));
    EXPECT_EQ(caches().vertex_arrays, 2u) << "p2 still uses the first vertex array";
    LOOM_ASSERT_OK(device().destroy(p2));
    LOOM_ASSERT_OK(device().destroy(p3));
    EXPECT_EQ(caches().vertex_arrays, 0u);
}

TEST_F(GlCacheTest, RedundantBindsAreFiltered) {
    LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "target", rhi::Format::RGBA8Unorm, 8, 8));
    LOOM_ASSIGN_OR_FAIL(auto vs, make_shader(device(), rhi::ShaderStage::Vertex, "position.vert", kPositionVert));
    LOOM_ASSIGN_OR_FAIL(auto fs, make_shader(device(), rhi::ShaderStage::Fragment, "textured.frag", R"(#version 450
layout(set = 0, binding = 0) uniform sampler2D tex;
layout(set = 0, binding = 1) uniform Tint { vec4 tint; } tint;
layout(location = 0) out vec4 frag_color;
void main() { frag_color = texture(tex, vec2(0.5)) * tint.tint; }
)"));
    rhi::GraphicsPipelineDesc pd;
    pd.name = "textured";
    pd.vertex = vs;
    pd.fragment = fs;
    pd.vertex_buffers = {rhi::VertexBufferLayout{12, rhi::VertexStepMode::PerVertex, {{0, rhi::VertexFormat::Float3, 0}}}};
    pd.color_formats = {rhi::Format::RGBA8Unorm};
    LOOM_ASSIGN_OR_FAIL(auto pipeline, device().create_graphics_pipeline(pd));
    std::vector<rhi::TextureHandle> textures;
    for (int i = 0; i < 2; ++i) {
        rhi::TextureDesc td;
        td.name = "texture " + std::to_string(i);
        td.usage = rhi::TextureUsage::Sampled;
        LOOM_ASSIGN_OR_FAIL(auto t, device().create_texture(td));
        LOOM_ASSERT_OK(device().write_texture(t, {}, std::vector<std::byte>(4, std::byte{255})));
        textures.push_back(t);
    }
    LOOM_ASSIGN_OR_FAIL(auto sampler, device().create_sampler(rhi::SamplerDesc{}));
    LOOM_ASSIGN_OR_FAIL(auto tint, make_buffer_of(device(), "tint", rhi::BufferUsage::Uniform, std::vector<float>{1, 1, 1, 1}));
    const std::vector<float> vertices = {-1, -1, 0, 3, -1, 0, -1, 3, 0};
    LOOM_ASSIGN_OR_FAIL(auto vb, make_buffer_of(device(), "vertices", rhi::BufferUsage::Vertex, vertices));

    auto record = [&](bool alternate) {
        return run_frame(device(), [&](rhi::CommandList& list) {
            list.begin_render_pass(clear_pass("binds", target, {0, 0, 0, 1}));
            for (int i = 0; i < 10; ++i) {
                // Everything is set again before every draw, as a naive renderer would.
                list.set_pipeline(pipeline);
                list.set_vertex_buffer(0, vb);
                const rhi::TextureHandle t = textures[alternate ? i % 2 : 0];
                list.set_bind_group(0, rhi::BindGroup{}.texture(0, t, sampler).buffer(1, tint));
                list.draw(3);
            }
            list.end_render_pass();
        });
    };
    LOOM_ASSERT_OK(record(false));
    rhi::FrameStats same = device().last_frame_stats();
    EXPECT_EQ(same.draw_calls, 10u);
    EXPECT_EQ(same.pipeline_binds, 1u);
    EXPECT_EQ(same.texture_binds, 1u);
    EXPECT_EQ(same.buffer_binds, 2u);  // the vertex buffer and the uniform buffer, once each

    LOOM_ASSERT_OK(record(true));
    rhi::FrameStats alternating = device().last_frame_stats();
    EXPECT_EQ(alternating.pipeline_binds, 1u);
    EXPECT_EQ(alternating.texture_binds, 10u) << "every change of texture is a real bind";
    EXPECT_EQ(alternating.buffer_binds, 2u);
    EXPECT_GT(alternating.api_calls, same.api_calls);
    std::printf("10 draws, same state: %llu GL calls; alternating textures: %llu GL calls\n",
                static_cast<unsigned long long>(same.api_calls), static_cast<unsigned long long>(alternating.api_calls));
}

}  // namespace
}  // namespace loom::test
