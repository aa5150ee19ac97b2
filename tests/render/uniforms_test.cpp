// Uniform blocks, push constants and transient uniforms reach the shader: the colour written
// comes out of them.
#include "loom_test/render_fixture.hpp"
#include "render_helpers.hpp"

namespace loom::test {
namespace {

class UniformsTest : public RenderTest {};

const char* const kFullscreenVert = R"(#version 450
void main() {
    vec2 p = vec2(gl_VertexIndex == 1 ? 3.0 : -1.0, gl_VertexIndex == 2 ? 3.0 : -1.0);
    gl_Position = vec4(p, 0.0, 1.0);
})";

// Colour = the uniform block's `base` + the push constants' `offset`, scaled by `scale`.
const char* const kUniformFrag = R"(#version 450
layout(set = 0, binding = 0) uniform Material { vec4 base; float scale; } material;
layout(set = 1, binding = 2) uniform Extra { vec4 add; } extra;
layout(push_constant) uniform Push { vec4 offset; } pc;
layout(location = 0) out vec4 frag_color;
void main() { frag_color = (material.base + pc.offset) * material.scale + extra.add; }
)";

struct Material {
    std::array<float, 4> base;
    float scale;
    float pad[3];
};

/// The pipeline of these tests: a fullscreen triangle shaded by kUniformFrag into RGBA32Float.
Result<rhi::PipelineHandle> uniform_pipeline(rhi::Device& device, const std::string& name,
                                             std::vector<rhi::BlendState> blend = {}) {
    auto vs = make_shader(device, rhi::ShaderStage::Vertex, "fullscreen.vert", kFullscreenVert);
    if (!vs.ok()) return vs.take_error();
    auto fs = make_shader(device, rhi::ShaderStage::Fragment, "uniform.frag", kUniformFrag);
    if (!fs.ok()) return fs.take_error();
    rhi::GraphicsPipelineDesc pd;
    pd.name = name;
    pd.vertex = *vs;
    pd.fragment = *fs;
    pd.color_formats = {rhi::Format::RGBA32Float};
    pd.blend = std::move(blend);
    return device.create_graphics_pipeline(pd);
}

TEST_P(UniformsTest, UniformBlocksAndPushConstantsReachTheShader) {
    constexpr uint32_t kSize = 8;
    LOOM_ASSIGN_OR_FAIL(auto pipeline, uniform_pipeline(device(), "uniforms"));
    const Material material{{0.25f, 0.5f, 0.0f, 1.0f}, 2.0f, {}};
    LOOM_ASSIGN_OR_FAIL(auto ubo, make_buffer(device(), "material", rhi::BufferUsage::Uniform, bytes_of(material)));
    LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "uniform target", rhi::Format::RGBA32Float, kSize, kSize));

    const std::array<float, 4> extra_left{0.0f, 0.0f, 1.0f, 0.0f};
    const std::array<float, 4> extra_right{0.0f, 0.0f, 3.0f, 0.0f};
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("uniforms", target, {0, 0, 0, 0}));
        list.set_pipeline(pipeline);
        // Left half: push constants (0.5, 0, 0, 0), transient uniforms add blue 1.
        list.set_scissor(rhi::Rect{0, 0, kSize / 2, kSize});
        list.set_bind_group(0, rhi::BindGroup{}.buffer(0, ubo));
        list.set_bind_group(1, rhi::BindGroup{}.buffer(2, list.transient_uniforms_of(extra_left)));
        list.push_constants_of(std::array<float, 4>{0.5f, 0.0f, 0.0f, 0.0f});
        list.draw(3);
        // Right half: new push constants and new transient uniforms; each draw sees its own.
        list.set_scissor(rhi::Rect{kSize / 2, 0, kSize / 2, kSize});
        list.set_bind_group(1, rhi::BindGroup{}.buffer(2, list.transient_uniforms_of(extra_right)));
        list.push_constants_of(std::array<float, 4>{0.0f, 1.0f, 0.0f, 0.0f});
        list.draw(3);
        list.end_render_pass();
    }));
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target));
    // ((0.25, 0.5, 0, 1) + (0.5, 0, 0, 0)) * 2 + (0, 0, 1, 0)
    EXPECT_EQ(image.load(1, 1), (std::array<double, 4>{1.5, 1.0, 1.0, 2.0}));
    // ((0.25, 0.5, 0, 1) + (0, 1, 0, 0)) * 2 + (0, 0, 3, 0)
    EXPECT_EQ(image.load(6, 6), (std::array<double, 4>{0.5, 3.0, 3.0, 2.0}));
}

TEST_P(UniformsTest, UniformRangeAtAlignedOffset) {
    // Two materials in one buffer, the second at the device's uniform offset alignment.
    const uint64_t alignment = device().capabilities().uniform_buffer_offset_alignment;
    std::vector<std::byte> data(alignment + sizeof(Material));
    const Material first{{9.0f, 9.0f, 9.0f, 9.0f}, 1.0f, {}};
    const Material second{{0.125f, 0.25f, 0.375f, 0.5f}, 4.0f, {}};
    std::memcpy(data.data(), &first, sizeof first);
    std::memcpy(data.data() + alignment, &second, sizeof second);
    LOOM_ASSIGN_OR_FAIL(auto ubo, make_buffer(device(), "materials", rhi::BufferUsage::Uniform, data));
    LOOM_ASSIGN_OR_FAIL(auto pipeline, uniform_pipeline(device(), "uniform range"));
    LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "range target", rhi::Format::RGBA32Float, 4, 4));
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("range", target, {0, 0, 0, 0}));
        list.set_pipeline(pipeline);
        list.set_bind_group(0, rhi::BindGroup{}.buffer(0, ubo, alignment, sizeof(Material)));
        list.set_bind_group(1, rhi::BindGroup{}.buffer(2, list.transient_uniforms_of(std::array<float, 4>{})));
        list.push_constants_of(std::array<float, 4>{});
        list.draw(3);
        list.end_render_pass();
    }));
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target));
    EXPECT_EQ(image.load(2, 2), (std::array<double, 4>{0.5, 1.0, 1.5, 2.0}));
}

// Per-draw uniform data without bind groups: 16 draws, each into its own column with its own
// `extra` block (set 1 binding 2) from set_uniforms_of, while set 0 keeps the group given whole.
// After the first draw only the offset of `extra` changes: Vulkan binds the set it wrote with
// another dynamic offset, GL binds another range. Every column shows its own draw's value.
TEST_P(UniformsTest, PerDrawUniformsBySetBuffer) {
    constexpr uint32_t kColumns = 16;
    LOOM_ASSIGN_OR_FAIL(auto pipeline, uniform_pipeline(device(), "per-draw uniforms"));
    const Material material{{0.0f, 0.0f, 0.0f, 1.0f}, 1.0f, {}};
    LOOM_ASSIGN_OR_FAIL(auto ubo, make_buffer(device(), "material", rhi::BufferUsage::Uniform, bytes_of(material)));
    LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "per-draw target", rhi::Format::RGBA32Float, kColumns, 2));
    for (int frame = 0; frame < 2; ++frame) {  // the second frame reuses the first one's memory
        LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
            list.begin_render_pass(clear_pass("per-draw", target, {0, 0, 0, 0}));
            list.set_pipeline(pipeline);
            list.set_bind_group(0, rhi::BindGroup{}.buffer(0, ubo));
            list.push_constants_of(std::array<float, 4>{});
            for (uint32_t i = 0; i < kColumns; ++i) {
                list.set_scissor(rhi::Rect{static_cast<int32_t>(i), 0, 1, 2});
                list.set_uniforms_of(1, 2, std::array<float, 4>{static_cast<float>(i), static_cast<float>(frame), 0.5f, 0.0f});
                list.draw(3);
            }
            list.end_render_pass();
        }));
        LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target));
        for (uint32_t i = 0; i < kColumns; ++i) {
            EXPECT_EQ(image.load(i, 1), (std::array<double, 4>{static_cast<double>(i), static_cast<double>(frame), 0.5, 1.0}))
                << "column " << i << ", frame " << frame;
        }
    }
}

// Per-draw uniform data between draws with nothing else recorded between them (the path on
// which GL moves the offset of the range it resolved instead of resolving the bindings again):
// eight draws add their own `extra` into one pixel. A draw that saw a later draw's offset, the
// value set and then replaced before a draw, or a set_buffer on a binding the pipeline does not
// read changing anything, would change the sum.
TEST_P(UniformsTest, PerDrawUniformsBetweenConsecutiveDraws) {
    if (!device().capabilities().format(rhi::Format::RGBA32Float).blendable) GTEST_SKIP() << "RGBA32Float does not blend here";
    const rhi::BlendState add{.enabled = true, .dst_color = rhi::BlendFactor::One, .dst_alpha = rhi::BlendFactor::One};
    LOOM_ASSIGN_OR_FAIL(auto pipeline, uniform_pipeline(device(), "summed uniforms", {add}));
    const Material material{{0.0f, 0.0f, 0.0f, 1.0f}, 1.0f, {}};
    LOOM_ASSIGN_OR_FAIL(auto ubo, make_buffer(device(), "material", rhi::BufferUsage::Uniform, bytes_of(material)));
    LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "sum target", rhi::Format::RGBA32Float, 1, 1));
    for (int frame = 0; frame < 2; ++frame) {
        LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
            list.begin_render_pass(clear_pass("sum", target, {0, 0, 0, 0}));
            list.set_pipeline(pipeline);
            list.set_bind_group(0, rhi::BindGroup{}.buffer(0, ubo));
            list.push_constants_of(std::array<float, 4>{});
            for (uint32_t i = 0; i < 8; ++i) {
                if (i == 3) list.set_uniforms_of(1, 2, std::array<float, 4>{100.0f, 0.0f, 0.0f, 0.0f});  // replaced below
                if (i == 5) list.set_uniforms_of(1, 7, std::array<float, 4>{1000.0f, 0.0f, 0.0f, 0.0f});  // not read
                list.set_uniforms_of(1, 2, std::array<float, 4>{static_cast<float>(i), 1.0f, static_cast<float>(frame), 0.0f});
                list.draw(3);
            }
            list.end_render_pass();
        }));
        LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target));
        // 0 + 1 + ... + 7, one per draw, the frame's number per draw, the material's alpha per draw.
        EXPECT_EQ(image.load(0, 0), (std::array<double, 4>{28.0, 8.0, 8.0 * frame, 8.0})) << "frame " << frame;
    }
}

// Two per-draw uniform blocks changing between consecutive draws (set 0's `material` and set
// 1's `extra`): GL rebinds one range per draw without copying its bindings, and copies them
// when a second range changes too. Each draw must see both of its own blocks.
TEST_P(UniformsTest, TwoPerDrawUniformBlocksBetweenConsecutiveDraws) {
    if (!device().capabilities().format(rhi::Format::RGBA32Float).blendable) GTEST_SKIP() << "RGBA32Float does not blend here";
    const rhi::BlendState add{.enabled = true, .dst_color = rhi::BlendFactor::One, .dst_alpha = rhi::BlendFactor::One};
    LOOM_ASSIGN_OR_FAIL(auto pipeline, uniform_pipeline(device(), "two summed uniforms", {add}));
    LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "two-block sum target", rhi::Format::RGBA32Float, 1, 1));
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("two-block sum", target, {0, 0, 0, 0}));
        list.set_pipeline(pipeline);
        list.push_constants_of(std::array<float, 4>{});
        for (uint32_t i = 0; i < 8; ++i) {
            // Draws 0-3 change both blocks, 4-7 only `extra` (after draw 3's material).
            if (i < 4) list.set_uniforms_of(0, 0, Material{{0.0f, 0.0f, 0.0f, static_cast<float>(i + 1)}, 1.0f, {}});
            list.set_uniforms_of(1, 2, std::array<float, 4>{static_cast<float>(i), 1.0f, 0.0f, 0.0f});
            list.draw(3);
        }
        list.end_render_pass();
    }));
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target));
    // x: 0 + 1 + ... + 7; y: one per draw; w: the material's alpha, 1 + 2 + 3 + 4 and then 4 four times.
    EXPECT_EQ(image.load(0, 0), (std::array<double, 4>{28.0, 8.0, 0.0, 26.0}));
}

// set_buffer is checked like a bind group at the draw: a destroyed buffer is a stale handle,
// and a range past the buffer's end is refused although the set was bound before with a good one.
TEST_P(UniformsTest, SetBufferIsCheckedAtTheDraw) {
    LOOM_ASSIGN_OR_FAIL(auto pipeline, uniform_pipeline(device(), "checked uniforms"));
    const uint64_t alignment = device().capabilities().uniform_buffer_offset_alignment;
    std::vector<std::byte> data(alignment * 2);
    LOOM_ASSIGN_OR_FAIL(auto ubo, make_buffer(device(), "two blocks", rhi::BufferUsage::Uniform, data));
    LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "checked target", rhi::Format::RGBA32Float, 4, 4));
    auto frame = [&](uint64_t second_offset) {
        return run_frame(device(), [&](rhi::CommandList& list) {
            list.begin_render_pass(clear_pass("checked", target, {0, 0, 0, 0}));
            list.set_pipeline(pipeline);
            list.set_bind_group(0, rhi::BindGroup{}.buffer(0, ubo, 0, sizeof(Material)));
            list.set_buffer(1, 2, rhi::BufferBinding{ubo, 0, 16});
            list.push_constants_of(std::array<float, 4>{});
            list.draw(3);
            list.set_buffer(1, 2, rhi::BufferBinding{ubo, second_offset, 16});
            list.draw(3);
            list.end_render_pass();
        });
    };
    LOOM_ASSERT_OK(frame(alignment));
    const Status past_the_end = frame(alignment * 2);
    ASSERT_FALSE(past_the_end.ok());
    EXPECT_EQ(past_the_end.error().code, ErrorCode::InvalidArgument);
    EXPECT_NE(past_the_end.error().message.find("binding 2"), std::string::npos) << past_the_end.error().message;
    EXPECT_NE(past_the_end.error().message.find("'two blocks'"), std::string::npos) << past_the_end.error().message;

    const Status beyond = run_frame(device(), [&](rhi::CommandList& list) {
        list.set_buffer(rhi::kMaxBindGroups, 0, rhi::BufferBinding{ubo, 0, 16});
    });
    ASSERT_FALSE(beyond.ok());
    EXPECT_NE(beyond.error().message.find("set_buffer: set " + std::to_string(rhi::kMaxBindGroups)), std::string::npos)
        << beyond.error().message;
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(UniformsTest);

}  // namespace loom::test
