// Errors a user can cause come back as typed errors naming the object at fault: stale,
// foreign and null handles, invalid descriptions, and misuse inside a command list (reported
// by end_frame, with the offending command skipped).
#include "loom_test/render_fixture.hpp"
#include "render_helpers.hpp"

namespace loom::test {
namespace {

class ErrorsTest : public RenderTest {
protected:
    static bool mentions(const Error& e, const std::string& text) { return e.message.find(text) != std::string::npos; }
};

TEST_P(ErrorsTest, StaleAndNullHandlesAreInvalidHandle) {
    LOOM_ASSIGN_OR_FAIL(auto texture, make_target(device(), "short-lived", rhi::Format::RGBA8Unorm, 4, 4));
    LOOM_ASSERT_OK(device().destroy(texture));
    auto again = device().destroy(texture);
    ASSERT_FALSE(again.ok());
    EXPECT_EQ(again.error().code, ErrorCode::InvalidHandle);
    EXPECT_TRUE(mentions(again.error(), "stale")) << again.error().message;
    auto read = device().read_texture(texture);
    ASSERT_FALSE(read.ok());
    EXPECT_EQ(read.error().code, ErrorCode::InvalidHandle);
    auto desc = device().texture_desc(texture);
    ASSERT_FALSE(desc.ok());
    EXPECT_EQ(desc.error().code, ErrorCode::InvalidHandle);
    // A new texture reusing the slot does not revive the old handle.
    LOOM_ASSIGN_OR_FAIL(auto replacement, make_target(device(), "replacement", rhi::Format::RGBA8Unorm, 4, 4));
    EXPECT_NE(replacement, texture);
    EXPECT_EQ(device().destroy(texture).error().code, ErrorCode::InvalidHandle);

    EXPECT_EQ(device().destroy(rhi::BufferHandle{}).error().code, ErrorCode::InvalidHandle);
    EXPECT_EQ(device().destroy(rhi::SamplerHandle{}).error().code, ErrorCode::InvalidHandle);
    EXPECT_EQ(device().destroy(rhi::PipelineHandle{}).error().code, ErrorCode::InvalidHandle);
    EXPECT_EQ(device().destroy(rhi::ShaderHandle{}).error().code, ErrorCode::InvalidHandle);
    EXPECT_EQ(device().write_buffer(rhi::BufferHandle{}, 0, {}).error().code, ErrorCode::InvalidHandle);
}

TEST_P(ErrorsTest, ForeignHandlesAreInvalidHandle) {
    rhi::DeviceDesc desc;
    desc.backend = backend();
    LOOM_ASSIGN_OR_FAIL(auto other, rhi::create_device(desc));
    LOOM_ASSIGN_OR_FAIL(auto foreign, make_target(*other, "other device's", rhi::Format::RGBA8Unorm, 4, 4));
    LOOM_ASSIGN_OR_FAIL(auto ours, make_target(device(), "ours", rhi::Format::RGBA8Unorm, 4, 4));
    auto destroyed = device().destroy(foreign);
    ASSERT_FALSE(destroyed.ok());
    EXPECT_EQ(destroyed.error().code, ErrorCode::InvalidHandle);
    EXPECT_TRUE(mentions(destroyed.error(), "belongs to device")) << destroyed.error().message;
    EXPECT_EQ(device().read_texture(foreign).error().code, ErrorCode::InvalidHandle);
    // Using the foreign texture in a render pass is recorded and reported by end_frame.
    auto frame = run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("foreign", foreign, {0, 0, 0, 1}));
        list.end_render_pass();
    });
    ASSERT_FALSE(frame.ok());
    EXPECT_EQ(frame.error().code, ErrorCode::InvalidHandle);
    // Both devices still work.
    LOOM_ASSERT_OK(other->destroy(foreign));
    LOOM_ASSERT_OK(device().destroy(ours));
    LOOM_ASSERT_OK(other->wait_idle());
}

TEST_P(ErrorsTest, InvalidDescriptionsNameTheObjectAndField) {
    rhi::TextureDesc zero;
    zero.name = "empty texture";
    zero.width = 0;
    auto t = device().create_texture(zero);
    ASSERT_FALSE(t.ok());
    EXPECT_EQ(t.error().code, ErrorCode::InvalidArgument);
    EXPECT_TRUE(mentions(t.error(), "empty texture")) << t.error().message;

    rhi::TextureDesc undefined;
    undefined.name = "no format";
    undefined.format = rhi::Format::Undefined;
    EXPECT_EQ(device().create_texture(undefined).error().code, ErrorCode::InvalidArgument);

    rhi::TextureDesc depth_as_color;
    depth_as_color.name = "depth as colour";
    depth_as_color.format = rhi::Format::Depth32F;
    depth_as_color.usage = rhi::TextureUsage::ColorAttachment;
    auto dc = device().create_texture(depth_as_color);
    ASSERT_FALSE(dc.ok());
    EXPECT_EQ(dc.error().code, ErrorCode::InvalidArgument);
    EXPECT_TRUE(mentions(dc.error(), "depth as colour")) << dc.error().message;

    rhi::TextureDesc too_many_mips;
    too_many_mips.name = "mips";
    too_many_mips.width = too_many_mips.height = 4;
    too_many_mips.mip_levels = 4;
    EXPECT_EQ(device().create_texture(too_many_mips).error().code, ErrorCode::InvalidArgument);

    auto b = device().create_buffer(rhi::BufferDesc{"empty buffer", 0, rhi::BufferUsage::Vertex});
    ASSERT_FALSE(b.ok());
    EXPECT_EQ(b.error().code, ErrorCode::InvalidArgument);
    EXPECT_TRUE(mentions(b.error(), "empty buffer")) << b.error().message;

    LOOM_ASSIGN_OR_FAIL(auto small, device().create_buffer(rhi::BufferDesc{"small", 16, rhi::BufferUsage::Uniform}));
    const std::vector<std::byte> too_much(17);
    auto w = device().write_buffer(small, 0, too_much);
    ASSERT_FALSE(w.ok());
    EXPECT_EQ(w.error().code, ErrorCode::InvalidArgument);
    EXPECT_TRUE(mentions(w.error(), "small")) << w.error().message;
    // Offsets near 2^64: offset + size wraps into range unless the check avoids computing it.
    const std::vector<std::byte> eight(8);
    auto wrapped = device().write_buffer(small, UINT64_MAX - 3, eight);
    ASSERT_FALSE(wrapped.ok());
    EXPECT_EQ(wrapped.error().code, ErrorCode::InvalidArgument);
    EXPECT_TRUE(mentions(wrapped.error(), "small")) << wrapped.error().message;
    auto read_wrapped = device().read_buffer(small, UINT64_MAX - 3, 8);
    ASSERT_FALSE(read_wrapped.ok());
    EXPECT_EQ(read_wrapped.error().code, ErrorCode::InvalidArgument);

    LOOM_ASSIGN_OR_FAIL(auto texture, make_target(device(), "upload target", rhi::Format::RGBA8Unorm, 4, 4));
    const std::vector<std::byte> wrong_size(4 * 4 * 4 - 1);
    auto wt = device().write_texture(texture, {}, wrong_size);
    ASSERT_FALSE(wt.ok());
    EXPECT_EQ(wt.error().code, ErrorCode::InvalidArgument);

    // A pipeline whose vertex input is not fed by any vertex buffer.
    LOOM_ASSIGN_OR_FAIL(auto vs, make_shader(device(), rhi::ShaderStage::Vertex, "position.vert", kPositionVert));
    LOOM_ASSIGN_OR_FAIL(auto fs, make_shader(device(), rhi::ShaderStage::Fragment, "push_color.frag", kPushColorFrag));
    rhi::GraphicsPipelineDesc pd;
    pd.name = "unfed";
    pd.vertex = vs;
    pd.fragment = fs;
    pd.color_formats = {rhi::Format::RGBA8Unorm};
    auto p = device().create_graphics_pipeline(pd);
    ASSERT_FALSE(p.ok());
    EXPECT_EQ(p.error().code, ErrorCode::InvalidArgument);
    EXPECT_TRUE(mentions(p.error(), "unfed") && mentions(p.error(), "position")) << p.error().message;
    // Stages swapped.
    pd.name = "swapped";
    pd.vertex = fs;
    pd.fragment = vs;
    EXPECT_EQ(device().create_graphics_pipeline(pd).error().code, ErrorCode::InvalidArgument);
}

TEST_P(ErrorsTest, AttachmentsOfDifferentSizesAreRejected) {
    LOOM_ASSIGN_OR_FAIL(auto a, make_target(device(), "big", rhi::Format::RGBA8Unorm, 8, 8));
    LOOM_ASSIGN_OR_FAIL(auto b, make_target(device(), "small", rhi::Format::RGBA8Unorm, 4, 4));
    rhi::RenderPassDesc pass = clear_pass("mismatched", a, {0, 0, 0, 1});
    rhi::ColorAttachment second;
    second.texture = b;
    pass.colors.push_back(second);
    auto status = run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(pass);
        list.end_render_pass();
    });
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.error().code, ErrorCode::InvalidArgument);
    EXPECT_TRUE(mentions(status.error(), "mismatched") && mentions(status.error(), "small")) << status.error().message;
}

TEST_P(ErrorsTest, MisuseInCommandListIsReportedByEndFrame) {
    LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "misuse target", rhi::Format::RGBA8Unorm, 8, 8));
    LOOM_ASSIGN_OR_FAIL(auto pipeline, make_solid_pipeline(device(), rhi::Format::RGBA8Unorm));
    const std::vector<float> vertices = {-1, -1, 0, 3, -1, 0, -1, 3, 0};
    LOOM_ASSIGN_OR_FAIL(auto vb, make_buffer_of(device(), "vertices", rhi::BufferUsage::Vertex, vertices));

    // A draw outside a render pass.
    auto outside = run_frame(device(), [&](rhi::CommandList& list) {
        list.set_pipeline(pipeline);
        list.set_vertex_buffer(0, vb);
        list.draw(3);
    });
    ASSERT_FALSE(outside.ok());
    EXPECT_EQ(outside.error().code, ErrorCode::InvalidState);

    // A draw without a pipeline, then a correct frame: the error does not stick.
    auto no_pipeline = run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("no pipeline", target, {0, 0, 0, 1}));
        list.draw(3);
        list.end_render_pass();
    });
    ASSERT_FALSE(no_pipeline.ok());
    EXPECT_EQ(no_pipeline.error().code, ErrorCode::InvalidState);
    EXPECT_TRUE(mentions(no_pipeline.error(), "no pipeline")) << no_pipeline.error().message;

    // A stale vertex buffer: the draw is skipped, the rest of the frame runs (the clear).
    LOOM_ASSIGN_OR_FAIL(auto doomed, make_buffer_of(device(), "doomed", rhi::BufferUsage::Vertex, vertices));
    LOOM_ASSERT_OK(device().destroy(doomed));
    auto stale = run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("stale", target, {0, 0, 1, 1}));
        list.set_pipeline(pipeline);
        list.set_vertex_buffer(0, doomed);
        list.push_constants_of(std::array<float, 4>{1, 0, 0, 1});
        list.draw(3);
        list.end_render_pass();
    });
    ASSERT_FALSE(stale.ok());
    EXPECT_EQ(stale.error().code, ErrorCode::InvalidHandle);
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target));
    EXPECT_EQ(rgba8_at(image, 4, 4), (std::array<int, 4>{0, 0, 255, 255})) << "the skipped draw ran, or the clear did not";

    // A render pass left open is closed by end_frame, with an error.
    auto open = run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("left open", target, {0, 0, 0, 1}));
    });
    ASSERT_FALSE(open.ok());
    EXPECT_TRUE(mentions(open.error(), "left open")) << open.error().message;

    // A pipeline whose colour format does not match the pass.
    LOOM_ASSIGN_OR_FAIL(auto float_pipeline, make_solid_pipeline(device(), rhi::Format::RGBA16Float));
    auto mismatch = run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("rgba8 pass", target, {0, 0, 0, 1}));
        list.set_pipeline(float_pipeline);
        list.end_render_pass();
    });
    ASSERT_FALSE(mismatch.ok());
    EXPECT_EQ(mismatch.error().code, ErrorCode::InvalidArgument);
    EXPECT_TRUE(mentions(mismatch.error(), "RGBA16Float")) << mismatch.error().message;

    // end_frame without begin_frame.
    EXPECT_EQ(device().end_frame().error().code, ErrorCode::InvalidState);

    // A good frame afterwards succeeds.
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("fine", target, {0, 0, 0, 1}));
        list.set_pipeline(pipeline);
        list.set_vertex_buffer(0, vb);
        list.push_constants_of(std::array<float, 4>{1, 0, 0, 1});
        list.draw(3);
        list.end_render_pass();
    }));
}

TEST_P(ErrorsTest, IndexRangesPastTheIndexBufferAreRefused) {
    LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "index target", rhi::Format::RGBA8Unorm, 8, 8));
    LOOM_ASSIGN_OR_FAIL(auto pipeline, make_solid_pipeline(device(), rhi::Format::RGBA8Unorm));
    const std::vector<float> vertices = {-1, -1, 0, 3, -1, 0, -1, 3, 0};
    LOOM_ASSIGN_OR_FAIL(auto vb, make_buffer_of(device(), "vertices", rhi::BufferUsage::Vertex, vertices));
    LOOM_ASSIGN_OR_FAIL(auto ib, make_buffer_of(device(), "three indices", rhi::BufferUsage::Index,
                                                 std::vector<uint32_t>{0, 1, 2}));
    auto draw = [&](uint32_t count, uint32_t first, std::array<double, 4> clear) {
        return run_frame(device(), [&](rhi::CommandList& list) {
            list.begin_render_pass(clear_pass("indexed", target, clear));
            list.set_pipeline(pipeline);
            list.set_vertex_buffer(0, vb);
            list.set_index_buffer(ib, rhi::IndexType::Uint32);
            list.push_constants_of(std::array<float, 4>{1, 0, 0, 1});
            list.draw_indexed(count, 1, first, 0, 0);
            list.end_render_pass();
        });
    };
    // One index too many, and a count whose byte size passes 2^32: refused, the draw skipped.
    for (auto [count, first] : {std::pair<uint32_t, uint32_t>{3, 1}, {0xFFFFFFFFu, 0}}) {
        auto status = draw(count, first, {0, 0, 1, 1});
        ASSERT_FALSE(status.ok()) << count << " from " << first;
        EXPECT_EQ(status.error().code, ErrorCode::InvalidArgument);
        EXPECT_TRUE(mentions(status.error(), "run past the end of index buffer") && mentions(status.error(), "three indices"))
            << status.error().message;
        LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target));
        EXPECT_EQ(rgba8_at(image, 1, 1), (std::array<int, 4>{0, 0, 255, 255})) << "the refused draw ran";
    }
    // An index buffer bound at its end: refused at the bind.
    auto at_end = run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("indexed", target, {0, 0, 1, 1}));
        list.set_pipeline(pipeline);
        list.set_vertex_buffer(0, vb);
        list.set_index_buffer(ib, rhi::IndexType::Uint32, 12);
        list.push_constants_of(std::array<float, 4>{1, 0, 0, 1});
        list.draw_indexed(1, 1, 0, 0, 0);
        list.end_render_pass();
    });
    ASSERT_FALSE(at_end.ok());
    EXPECT_EQ(at_end.error().code, ErrorCode::InvalidArgument);
    EXPECT_TRUE(mentions(at_end.error(), "three indices")) << at_end.error().message;
    // The three indices themselves draw.
    LOOM_ASSERT_OK(draw(3, 0, {0, 0, 0, 1}));
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target));
    EXPECT_EQ(rgba8_at(image, 1, 1), (std::array<int, 4>{255, 0, 0, 255}));
}

TEST_P(ErrorsTest, SamplingATextureNotInShaderReadIsInvalidState) {
    LOOM_ASSIGN_OR_FAIL(auto rendered, make_target(device(), "rendered", rhi::Format::RGBA8Unorm, 8, 8, rhi::TextureUsage::Sampled));
    LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "sampling target", rhi::Format::RGBA8Unorm, 8, 8));
    LOOM_ASSIGN_OR_FAIL(auto vs, make_shader(device(), rhi::ShaderStage::Vertex, "fullscreen.vert", R"(#version 450
void main() {
    vec2 p = vec2(gl_VertexIndex == 1 ? 3.0 : -1.0, gl_VertexIndex == 2 ? 3.0 : -1.0);
    gl_Position = vec4(p, 0.0, 1.0);
})"));
    LOOM_ASSIGN_OR_FAIL(auto fs, make_shader(device(), rhi::ShaderStage::Fragment, "fetch.frag", R"(#version 450
layout(set = 0, binding = 0) uniform sampler2D tex;
layout(location = 0) out vec4 frag_color;
void main() { frag_color = texelFetch(tex, ivec2(gl_FragCoord.xy), 0); }
)"));
    rhi::GraphicsPipelineDesc pd;
    pd.name = "fetch";
    pd.vertex = vs;
    pd.fragment = fs;
    pd.color_formats = {rhi::Format::RGBA8Unorm};
    LOOM_ASSIGN_OR_FAIL(auto pipeline, device().create_graphics_pipeline(pd));
    LOOM_ASSIGN_OR_FAIL(auto sampler, device().create_sampler(rhi::SamplerDesc{}));
    auto record = [&](bool transition) {
        return run_frame(device(), [&](rhi::CommandList& list) {
            list.begin_render_pass(clear_pass("produce", rendered, {0, 1, 0, 1}));
            list.end_render_pass();
            if (transition) list.transition(rendered, rhi::ResourceState::ShaderRead);
            list.begin_render_pass(clear_pass("consume", target, {0, 0, 0, 1}));
            list.set_pipeline(pipeline);
            list.set_bind_group(0, rhi::BindGroup{}.texture(0, rendered, sampler));
            list.draw(3);
            list.end_render_pass();
        });
    };
    auto forgotten = record(false);
    ASSERT_FALSE(forgotten.ok());
    EXPECT_EQ(forgotten.error().code, ErrorCode::InvalidState);
    EXPECT_TRUE(mentions(forgotten.error(), "rendered") && mentions(forgotten.error(), "RenderTarget"))
        << forgotten.error().message;
    LOOM_ASSERT_OK(record(true));
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target));
    EXPECT_EQ(rgba8_at(image, 3, 3), (std::array<int, 4>{0, 255, 0, 255}));
}

TEST_P(ErrorsTest, MissingBindingIsReported) {
    LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "binding target", rhi::Format::RGBA8Unorm, 4, 4));
    LOOM_ASSIGN_OR_FAIL(auto vs, make_shader(device(), rhi::ShaderStage::Vertex, "fullscreen.vert", R"(#version 450
void main() {
    vec2 p = vec2(gl_VertexIndex == 1 ? 3.0 : -1.0, gl_VertexIndex == 2 ? 3.0 : -1.0);
    gl_Position = vec4(p, 0.0, 1.0);
})"));
    LOOM_ASSIGN_OR_FAIL(auto fs, make_shader(device(), rhi::ShaderStage::Fragment, "ubo.frag", R"(#version 450
layout(set = 2, binding = 3) uniform Params { vec4 color; } params;
layout(location = 0) out vec4 frag_color;
void main() { frag_color = params.color; }
)"));
    rhi::GraphicsPipelineDesc pd;
    pd.name = "needs params";
    pd.vertex = vs;
    pd.fragment = fs;
    pd.color_formats = {rhi::Format::RGBA8Unorm};
    LOOM_ASSIGN_OR_FAIL(auto pipeline, device().create_graphics_pipeline(pd));
    auto status = run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("unbound", target, {0, 0, 0, 1}));
        list.set_pipeline(pipeline);
        list.draw(3);
        list.end_render_pass();
    });
    ASSERT_FALSE(status.ok());
    EXPECT_TRUE(mentions(status.error(), "set 2 binding 3") && mentions(status.error(), "needs params"))
        << status.error().message;
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(ErrorsTest);

}  // namespace loom::test
