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

namespace loom::test {
namespace {

class LayeredSamplingTest : public RenderTest {
protected:
    /// Renders a 6x1 RGBA32Float image whose pixel i is `fragment_body` evaluated with
    /// `int i = int(gl_FragCoord.x)` and the texture bound at set 0, binding 0.
    Result<rhi::Image> render_six(rhi::TextureHandle texture, const std::string& declaration, const std::string& body) {
        auto vs = make_shader(device(), rhi::ShaderStage::Vertex, "fullscreen.vert", kFullscreenVert);
        if (!vs.ok()) return vs.take_error();
        auto fs = make_shader(device(), rhi::ShaderStage::Fragment, "layered.frag",
                              "#version 450\n" + declaration +
                                  "\nlayout(location = 0) out vec4 frag_color;\n"
                                  "void main() {\n    int i = int(gl_FragCoord.x);\n" +
                                  body + "\n}\n");
        if (!fs.ok()) return fs.take_error();
        rhi::GraphicsPipelineDesc pd;
        pd.name = "layered";
        pd.vertex = *vs;
        pd.fragment = *fs;
        pd.color_formats = {rhi::Format::RGBA32Float};
        auto pipeline = device().create_graphics_pipeline(pd);
        if (!pipeline.ok()) return pipeline.take_error();
        rhi::SamplerDesc sd;
        sd.min_filter = sd.mag_filter = rhi::Filter::Nearest;
        auto sampler = device().create_sampler(sd);
        if (!sampler.ok()) return sampler.take_error();
        auto target = make_target(device(), "six", rhi::Format::RGBA32Float, 6, 1);
        if (!target.ok()) return target.take_error();
        LOOM_TRY(run_frame(device(), [&](rhi::CommandList& list) {
            list.begin_render_pass(clear_pass("layered", *target, {-1, -1, -1, -1}));
            list.set_pipeline(*pipeline);
            list.set_bind_group(0, rhi::BindGroup{}.texture(0, texture, *sampler));
            list.draw(3);
            list.end_render_pass();
        }));
        return device().read_texture(*target);
    }

    /// A texture of 2x2 texels per layer/face/slice, every texel of layer k = (k, 10 + k, 0, 1).
    Result<rhi::TextureHandle> make_layered(rhi::TextureDimension dimension, uint32_t layers) {
        rhi::TextureDesc desc;
        desc.name = "layered";
        desc.dimension = dimension;
        desc.format = rhi::Format::RGBA16Float;
        desc.width = desc.height = 2;
        desc.depth_or_layers = layers;
        desc.usage = rhi::TextureUsage::Sampled | rhi::TextureUsage::CopyDst;
        auto texture = device().create_texture(desc);
        if (!texture.ok()) return texture;
        for (uint32_t k = 0; k < layers; ++k) {
            rhi::Image image(2, 2, rhi::Format::RGBA16Float);
            for (uint32_t i = 0; i < 4; ++i) image.store(i % 2, i / 2, {double(k), 10.0 + k, 0, 1});
            rhi::TextureRegion region;
            if (dimension == rhi::TextureDimension::Tex3D) {
                region.origin.z = k;
                region.extent = {2, 2, 1};
            } else {
                region.layer = k;
            }
            LOOM_TRY(device().write_texture(*texture, region, image.pixels));
        }
        return texture;
    }
};

TEST_P(LayeredSamplingTest, CubeFacesFollowDirection) {
    // Faces in the order +X, -X, +Y, -Y, +Z, -Z: the direction along an axis samples its face.
    LOOM_ASSIGN_OR_FAIL(auto cube, make_layered(rhi::TextureDimension::Cube, 6));
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, render_six(cube, "layout(set = 0, binding = 0) uniform samplerCube tex;", R"(
    vec3 dirs[6] = vec3[](vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0), vec3(0, 0, 1), vec3(0, 0, -1));
    frag_color = texture(tex, dirs[i]);)"));
    for (uint32_t face = 0; face < 6; ++face) {
        EXPECT_EQ(image.load(face, 0)[0], double(face)) << "direction " << face;
        EXPECT_EQ(image.load(face, 0)[1], 10.0 + face) << "direction " << face;
    }
}

TEST_P(LayeredSamplingTest, ArrayLayersAndVolumeSlices) {
    LOOM_ASSIGN_OR_FAIL(auto array, make_layered(rhi::TextureDimension::Tex2DArray, 6));
    LOOM_ASSIGN_OR_FAIL(rhi::Image layers, render_six(array, "layout(set = 0, binding = 0) uniform sampler2DArray tex;",
                                                      "    frag_color = texture(tex, vec3(0.5, 0.5, float(5 - i)));"));
    for (uint32_t i = 0; i < 6; ++i) EXPECT_EQ(layers.load(i, 0)[0], double(5 - i)) << "layer " << 5 - i;
    // A 3D texture of 6 slices: slice k is sampled at w = (k + 0.5) / 6.
    LOOM_ASSIGN_OR_FAIL(auto volume, make_layered(rhi::TextureDimension::Tex3D, 6));
    LOOM_ASSIGN_OR_FAIL(rhi::Image slices, render_six(volume, "layout(set = 0, binding = 0) uniform sampler3D tex;",
                                                      "    frag_color = texture(tex, vec3(0.5, 0.5, (float(i) + 0.5) / 6.0));"));
    for (uint32_t i = 0; i < 6; ++i) EXPECT_EQ(slices.load(i, 0)[0], double(i)) << "slice " << i;
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(LayeredSamplingTest);

}  // namespace loom::test
