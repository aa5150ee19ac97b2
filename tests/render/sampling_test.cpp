// Sampling with nearest and linear filtering at known texel values: the expectations are
// computed from the texel values and the sample positions.
#include <algorithm>

#include "loom_test/render_fixture.hpp"
#include "render_helpers.hpp"

namespace loom::test {
namespace {

class SamplingTest : public RenderTest {};

const char* const kFullscreenVert = R"(#version 450
void main() {
    vec2 p = vec2(gl_VertexIndex == 1 ? 3.0 : -1.0, gl_VertexIndex == 2 ? 3.0 : -1.0);
    gl_Position = vec4(p, 0.0, 1.0);
})";

TEST_P(SamplingTest, NearestAndLinearAtKnownPositions) {
    // A 2x1 texture: texel 0 = 0.0, texel 1 = 1.0 (in R; G holds 0.5 everywhere). Its texel
    // centres are at u = 0.25 and u = 0.75.
    rhi::TextureDesc desc;
    desc.name = "two texels";
    desc.format = rhi::Format::RGBA16Float;
    desc.width = 2;
    desc.height = 1;
    desc.usage = rhi::TextureUsage::Sampled | rhi::TextureUsage::CopyDst;
    LOOM_ASSIGN_OR_FAIL(auto texture, device().create_texture(desc));
    rhi::Image texels(2, 1, rhi::Format::RGBA16Float);
    const std::array<double, 2> value{0.0, 1.0};
    texels.store(0, 0, {value[0], 0.5, 0, 1});
    texels.store(1, 0, {value[1], 0.5, 0, 1});
    LOOM_ASSERT_OK(device().write_texture(texture, {}, texels.pixels));

    // Pixel x of a 4x1 target samples u = (x + 0.5) / 4: 0.125, 0.375, 0.625, 0.875.
    LOOM_ASSIGN_OR_FAIL(auto vs, make_shader(device(), rhi::ShaderStage::Vertex, "fullscreen.vert", kFullscreenVert));
    LOOM_ASSIGN_OR_FAIL(auto fs, make_shader(device(), rhi::ShaderStage::Fragment, "sample_u.frag", R"(#version 450
layout(set = 0, binding = 0) uniform sampler2D tex;
layout(location = 0) out vec4 frag_color;
void main() { frag_color = texture(tex, vec2(gl_FragCoord.x / 4.0, 0.5)); }
)"));
    rhi::GraphicsPipelineDesc pd;
    pd.name = "sample u";
    pd.vertex = vs;
    pd.fragment = fs;
    pd.color_formats = {rhi::Format::RGBA32Float};
    LOOM_ASSIGN_OR_FAIL(auto pipeline, device().create_graphics_pipeline(pd));

    for (rhi::Filter filter : {rhi::Filter::Nearest, rhi::Filter::Linear}) {
        const bool linear = filter == rhi::Filter::Linear;
        SCOPED_TRACE(linear ? "linear" : "nearest");
        rhi::SamplerDesc sd;
        sd.name = linear ? "linear" : "nearest";
        sd.min_filter = sd.mag_filter = filter;
        sd.address_u = sd.address_v = rhi::AddressMode::ClampToEdge;
        LOOM_ASSIGN_OR_FAIL(auto sampler, device().create_sampler(sd));
        LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "samples", rhi::Format::RGBA32Float, 4, 1));
        LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
            list.begin_render_pass(clear_pass("sample", target, {-1, -1, -1, -1}));
            list.set_pipeline(pipeline);
            list.set_bind_group(0, rhi::BindGroup{}.texture(0, texture, sampler));
            list.draw(3);
            list.end_render_pass();
        }));
        LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target));
        for (uint32_t x = 0; x < 4; ++x) {
            const double u = (x + 0.5) / 4.0;
            double expected;
            if (linear) {
                // Weight of texel 1 is frac(u * 2 - 0.5), clamped to the edge texels.
                const double t = std::clamp(u * 2.0 - 0.5, 0.0, 1.0);
                expected = value[0] * (1.0 - t) + value[1] * t;  // 0, 0.25, 0.75, 1
            } else {
                expected = value[u < 0.5 ? 0 : 1];
            }
            // Weights of 1/4 and 3/4 are exact in every filtering precision GL and Vulkan allow.
            EXPECT_EQ(image.load(x, 0)[0], expected) << "u = " << u;
            EXPECT_EQ(image.load(x, 0)[1], 0.5) << "u = " << u;
        }
        LOOM_ASSERT_OK(device().destroy(sampler));
        LOOM_ASSERT_OK(device().destroy(target));
    }
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(SamplingTest);

}  // namespace loom::test

namespace loom::test {
namespace {

class ShadowSamplingTest : public RenderTest {};

TEST_P(ShadowSamplingTest, CompareSamplerComparesAgainstDepth) {
    // A 4x1 depth texture with depths 0.2, 0.4, 0.6, 0.8, compared (Less: reference < stored)
    // against reference 0.5 with a nearest compare sampler: 0, 0, 1, 1.
    rhi::TextureDesc desc;
    desc.name = "shadow map";
    desc.format = rhi::Format::Depth32F;
    desc.width = 4;
    desc.height = 1;
    desc.usage = rhi::TextureUsage::Sampled | rhi::TextureUsage::DepthStencilAttachment | rhi::TextureUsage::CopyDst;
    LOOM_ASSIGN_OR_FAIL(auto depth, device().create_texture(desc));
    const std::vector<float> depths = {0.2f, 0.4f, 0.6f, 0.8f};
    LOOM_ASSERT_OK(device().write_texture(depth, {}, std::as_bytes(std::span(depths))));
    LOOM_ASSIGN_OR_FAIL(auto vs, make_shader(device(), rhi::ShaderStage::Vertex, "fullscreen.vert", kFullscreenVert));
    LOOM_ASSIGN_OR_FAIL(auto fs, make_shader(device(), rhi::ShaderStage::Fragment, "shadow.frag", R"(#version 450
layout(set = 0, binding = 0) uniform sampler2DShadow shadow_map;
layout(location = 0) out vec4 frag_color;
void main() { frag_color = vec4(texture(shadow_map, vec3(gl_FragCoord.x / 4.0, 0.5, 0.5))); }
)"));
    rhi::GraphicsPipelineDesc pd;
    pd.name = "shadow";
    pd.vertex = vs;
    pd.fragment = fs;
    pd.color_formats = {rhi::Format::RGBA32Float};
    LOOM_ASSIGN_OR_FAIL(auto pipeline, device().create_graphics_pipeline(pd));
    rhi::SamplerDesc sd;
    sd.name = "compare less";
    sd.min_filter = sd.mag_filter = rhi::Filter::Nearest;
    sd.compare = rhi::CompareOp::Less;
    LOOM_ASSIGN_OR_FAIL(auto sampler, device().create_sampler(sd));
    LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "comparisons", rhi::Format::RGBA32Float, 4, 1));
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("shadow", target, {-1, -1, -1, -1}));
        list.set_pipeline(pipeline);
        list.set_bind_group(0, rhi::BindGroup{}.texture(0, depth, sampler));
        list.draw(3);
        list.end_render_pass();
    }));
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target));
    const std::array<double, 4> expected{0.0, 0.0, 1.0, 1.0};
    for (uint32_t x = 0; x < 4; ++x) EXPECT_EQ(image.load(x, 0)[0], expected[x]) << "texel " << x;
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(ShadowSamplingTest);

}  // namespace loom::test
