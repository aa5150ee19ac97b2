// Subresources in shaders and barriers: sampling a TextureRange (a mip of a chain, a layer of an
// array) while another subresource of the same texture is written, transitions of ranges,
// storage buffers written twice and then read as vertices, indirect arguments and uniforms.
// Every test runs on each backend; Vulkan's validation layer (synchronisation included) and GL's
// debug output fail a test on any message.
#include <array>
#include <cmath>
#include <cstring>
#include <vector>

#include "loom_test/render_fixture.hpp"
#include "render_helpers.hpp"

namespace loom::test {
namespace {

using rhi::ResourceState;
using rhi::TextureRange;

class SubresourceTest : public RenderTest {};

constexpr uint32_t kChainSize = 16;
constexpr uint32_t kChainLevels = 4;

// Texel (x, y) of mip 0 of the chain: integers 0..255, so that every 2x2 average down the chain
// is a multiple of 1/4^k, exact in 32-bit floats whatever the order of the additions.
float chain_texel(uint32_t x, uint32_t y) { return static_cast<float>((x * 37 + y * 91 + x * y * 13) % 256); }

// The CPU reference: mip k of the box-filter chain (k = 0: the uploaded texels).
std::vector<std::vector<float>> chain_reference() {
    std::vector<std::vector<float>> mips(kChainLevels);
    mips[0].resize(kChainSize * kChainSize);
    for (uint32_t y = 0; y < kChainSize; ++y) {
        for (uint32_t x = 0; x < kChainSize; ++x) mips[0][y * kChainSize + x] = chain_texel(x, y);
    }
    for (uint32_t k = 1; k < kChainLevels; ++k) {
        const uint32_t size = kChainSize >> k, above = size * 2;
        mips[k].resize(size * size);
        const std::vector<float>& src = mips[k - 1];
        for (uint32_t y = 0; y < size; ++y) {
            for (uint32_t x = 0; x < size; ++x) {
                const float sum = src[(2 * y) * above + 2 * x] + src[(2 * y) * above + 2 * x + 1] + src[(2 * y + 1) * above + 2 * x] +
                                  src[(2 * y + 1) * above + 2 * x + 1];
                mips[k][y * size + x] = sum * 0.25f;
            }
        }
    }
    return mips;
}

// A 16x16 R32Float texture of 4 mips, mip 0 uploaded (and so in ShaderRead).
Result<rhi::TextureHandle> make_chain(rhi::Device& device, rhi::TextureUsage usage) {
    rhi::TextureDesc desc;
    desc.name = "chain";
    desc.format = rhi::Format::R32Float;
    desc.width = desc.height = kChainSize;
    desc.mip_levels = kChainLevels;
    desc.usage = usage | rhi::TextureUsage::Sampled | rhi::TextureUsage::CopySrc;
    auto texture = device.create_texture(desc);
    if (!texture.ok()) return texture;
    std::vector<float> texels = chain_reference()[0];
    LOOM_TRY(device.write_texture(*texture, {}, std::as_bytes(std::span<const float>(texels))));
    return texture;
}

// Compares mips 1.. of the chain with the CPU reference, exactly.
void expect_chain(rhi::Device& device, rhi::TextureHandle chain) {
    const auto reference = chain_reference();
    for (uint32_t k = 1; k < kChainLevels; ++k) {
        LOOM_ASSIGN_OR_FAIL(rhi::Image image, device.read_texture(chain, k));
        const uint32_t size = kChainSize >> k;
        ASSERT_EQ(image.width, size);
        for (uint32_t y = 0; y < size; ++y) {
            for (uint32_t x = 0; x < size; ++x) {
                ASSERT_EQ(image.load(x, y)[0], reference[k][y * size + x]) << "mip " << k << " texel " << x << "," << y;
            }
        }
    }
}

// A nearest sampler: texelFetch ignores filtering, but Vulkan refuses linear samplers on formats
// that cannot be filtered (R32Float on some devices) at draw time.
Result<rhi::SamplerHandle> nearest_sampler(rhi::Device& device) {
    rhi::SamplerDesc desc;
    desc.name = "nearest";
    desc.min_filter = desc.mag_filter = rhi::Filter::Nearest;
    return device.create_sampler(desc);
}

constexpr const char* kFullscreenVert = R"(#version 450
void main() {
    vec2 p = vec2(gl_VertexIndex == 1 ? 3.0 : -1.0, gl_VertexIndex == 2 ? 3.0 : -1.0);
    gl_Position = vec4(p, 0.0, 1.0);
})";

TEST_P(SubresourceTest, ComputeDownsampleChainSamplesMipAboveThroughARange) {
    // Each dispatch writes mip k as a storage image while it samples mip k-1 through a one-mip
    // view: the two are one texture, in Storage and ShaderRead at once.
    LOOM_ASSIGN_OR_FAIL(auto cs, make_shader(device(), rhi::ShaderStage::Compute, "downsample.comp", R"(#version 450
layout(local_size_x = 4, local_size_y = 4) in;
layout(set = 0, binding = 0) uniform sampler2D above;       // level 0 of the view: mip k-1
layout(set = 0, binding = 1, r32f) uniform writeonly image2D level;  // mip k
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(level)))) return;
    float sum = texelFetch(above, 2 * p, 0).r + texelFetch(above, 2 * p + ivec2(1, 0), 0).r +
                texelFetch(above, 2 * p + ivec2(0, 1), 0).r + texelFetch(above, 2 * p + ivec2(1, 1), 0).r;
    imageStore(level, p, vec4(sum * 0.25));
})"));
    LOOM_ASSIGN_OR_FAIL(auto pipeline, device().create_compute_pipeline({"downsample", cs}));
    LOOM_ASSIGN_OR_FAIL(auto chain, make_chain(device(), rhi::TextureUsage::Storage));
    LOOM_ASSIGN_OR_FAIL(auto sampler, nearest_sampler(device()));
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        list.set_pipeline(pipeline);
        for (uint32_t k = 1; k < kChainLevels; ++k) {
            list.transition(chain, ResourceState::Storage, TextureRange{.base_mip = k, .mip_count = 1});
            list.set_bind_group(0, rhi::BindGroup{}
                                       .texture(0, chain, sampler, TextureRange{.base_mip = k - 1, .mip_count = 1})
                                       .storage_texture(1, chain, k));
            const uint32_t groups = std::max(1u, (kChainSize >> k) / 4);
            list.dispatch(groups, groups);
            // The next dispatch samples what this one wrote.
            list.transition(chain, ResourceState::ShaderRead, TextureRange{.base_mip = k, .mip_count = 1});
        }
    }));
    expect_chain(device(), chain);
}

TEST_P(SubresourceTest, RenderPassDownsampleChainRendersIntoMipWhileSamplingTheOneAbove) {
    // The same chain with render passes: mip k is the colour attachment (ColorAttachment::mip)
    // while a one-mip view of mip k-1 is sampled.
    LOOM_ASSIGN_OR_FAIL(auto vs, make_shader(device(), rhi::ShaderStage::Vertex, "fullscreen.vert", kFullscreenVert));
    LOOM_ASSIGN_OR_FAIL(auto fs, make_shader(device(), rhi::ShaderStage::Fragment, "downsample.frag", R"(#version 450
layout(set = 0, binding = 0) uniform sampler2D above;
layout(location = 0) out vec4 frag_color;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    float sum = texelFetch(above, 2 * p, 0).r + texelFetch(above, 2 * p + ivec2(1, 0), 0).r +
                texelFetch(above, 2 * p + ivec2(0, 1), 0).r + texelFetch(above, 2 * p + ivec2(1, 1), 0).r;
    frag_color = vec4(sum * 0.25, 0.0, 0.0, 1.0);
})"));
    rhi::GraphicsPipelineDesc pd;
    pd.name = "downsample";
    pd.vertex = vs;
    pd.fragment = fs;
    pd.color_formats = {rhi::Format::R32Float};
    LOOM_ASSIGN_OR_FAIL(auto pipeline, device().create_graphics_pipeline(pd));
    LOOM_ASSIGN_OR_FAIL(auto chain, make_chain(device(), rhi::TextureUsage::ColorAttachment));
    LOOM_ASSIGN_OR_FAIL(auto sampler, nearest_sampler(device()));
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        for (uint32_t k = 1; k < kChainLevels; ++k) {
            rhi::RenderPassDesc pass;
            pass.label = "mip " + std::to_string(k);
            pass.colors.push_back({.texture = chain, .mip = k, .load = rhi::LoadOp::DontCare});
            list.begin_render_pass(pass);
            list.set_pipeline(pipeline);
            list.set_bind_group(0, rhi::BindGroup{}.texture(0, chain, sampler, TextureRange{.base_mip = k - 1, .mip_count = 1}));
            list.draw(3);
            list.end_render_pass();
            list.transition(chain, ResourceState::ShaderRead, TextureRange{.base_mip = k, .mip_count = 1});
        }
    }));
    expect_chain(device(), chain);
}

TEST_P(SubresourceTest, LayersRenderedOneByOneAndSampledAsOneLayerOrTheArray) {
    constexpr uint32_t kLayers = 3;
    const std::array<std::array<double, 4>, kLayers> colors{{{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}}};
    rhi::TextureDesc desc;
    desc.name = "layers";
    desc.dimension = rhi::TextureDimension::Tex2DArray;
    desc.width = desc.height = 8;
    desc.depth_or_layers = kLayers;
    desc.usage = rhi::TextureUsage::ColorAttachment | rhi::TextureUsage::Sampled;
    LOOM_ASSIGN_OR_FAIL(auto layers, device().create_texture(desc));
    LOOM_ASSIGN_OR_FAIL(auto solid, make_solid_pipeline(device(), rhi::Format::RGBA8Unorm));
    // A triangle over the whole of each layer (cleared grey first), in the layer's colour.
    const std::vector<float> triangle{-1, -1, 0, 3, -1, 0, -1, 3, 0};
    LOOM_ASSIGN_OR_FAIL(auto vertices, make_buffer_of(device(), "triangle", rhi::BufferUsage::Vertex, triangle));

    LOOM_ASSIGN_OR_FAIL(auto vs, make_shader(device(), rhi::ShaderStage::Vertex, "fullscreen.vert", kFullscreenVert));
    LOOM_ASSIGN_OR_FAIL(auto one_fs, make_shader(device(), rhi::ShaderStage::Fragment, "one_layer.frag", R"(#version 450
layout(set = 0, binding = 0) uniform sampler2D layer;
layout(location = 0) out vec4 frag_color;
void main() { frag_color = texelFetch(layer, ivec2(gl_FragCoord.xy), 0); })"));
    // Column c (4 pixels wide) shows layer c.
    LOOM_ASSIGN_OR_FAIL(auto array_fs, make_shader(device(), rhi::ShaderStage::Fragment, "array.frag", R"(#version 450
layout(set = 0, binding = 0) uniform sampler2DArray layers;
layout(location = 0) out vec4 frag_color;
void main() { frag_color = texelFetch(layers, ivec3(0, 0, int(gl_FragCoord.x) / 4), 0); })"));
    rhi::GraphicsPipelineDesc pd;
    pd.name = "one layer";
    pd.vertex = vs;
    pd.fragment = one_fs;
    pd.color_formats = {rhi::Format::RGBA8Unorm};
    LOOM_ASSIGN_OR_FAIL(auto one_pipeline, device().create_graphics_pipeline(pd));
    pd.name = "array";
    pd.fragment = array_fs;
    LOOM_ASSIGN_OR_FAIL(auto array_pipeline, device().create_graphics_pipeline(pd));
    LOOM_ASSIGN_OR_FAIL(auto sampler, nearest_sampler(device()));
    LOOM_ASSIGN_OR_FAIL(auto one_target, make_target(device(), "one layer", rhi::Format::RGBA8Unorm, 8, 8));
    LOOM_ASSIGN_OR_FAIL(auto array_target, make_target(device(), "array", rhi::Format::RGBA8Unorm, 4 * kLayers, 4));

    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        for (uint32_t i = 0; i < kLayers; ++i) {
            rhi::RenderPassDesc pass;
            pass.label = "layer " + std::to_string(i);
            pass.colors.push_back({.texture = layers, .layer = i, .clear = {0.5, 0.5, 0.5, 1}});
            list.begin_render_pass(pass);
            list.set_pipeline(solid);
            list.set_vertex_buffer(0, vertices);
            const std::array<float, 4> c{static_cast<float>(colors[i][0]), static_cast<float>(colors[i][1]),
                                         static_cast<float>(colors[i][2]), 1.0f};
            list.push_constants_of(c);
            list.draw(3);
            list.end_render_pass();
        }
        // Only layer 1 moves to ShaderRead; 0 and 2 stay render targets while it is sampled.
        list.transition(layers, ResourceState::ShaderRead, TextureRange{.base_layer = 1, .layer_count = 1});
        list.begin_render_pass(clear_pass("one layer", one_target, {0, 0, 0, 1}));
        list.set_pipeline(one_pipeline);
        list.set_bind_group(0, rhi::BindGroup{}.texture(0, layers, sampler, TextureRange{.base_layer = 1, .layer_count = 1}));
        list.draw(3);
        list.end_render_pass();
        list.transition(layers, ResourceState::ShaderRead);
        list.begin_render_pass(clear_pass("array", array_target, {0, 0, 0, 1}));
        list.set_pipeline(array_pipeline);
        list.set_bind_group(0, rhi::BindGroup{}.texture(0, layers, sampler));
        list.draw(3);
        list.end_render_pass();
    }));
    // The triangle (-1,-1), (3,-1), (-1,3) covers the whole layer: every texel has the colour.
    LOOM_ASSIGN_OR_FAIL(rhi::Image one, device().read_texture(one_target));
    EXPECT_EQ(rgba8_at(one, 0, 0), (std::array<int, 4>{0, 255, 0, 255}));
    EXPECT_EQ(rgba8_at(one, 7, 7), (std::array<int, 4>{0, 255, 0, 255}));
    LOOM_ASSIGN_OR_FAIL(rhi::Image array, device().read_texture(array_target));
    for (uint32_t i = 0; i < kLayers; ++i) {
        const std::array<int, 4> want{static_cast<int>(colors[i][0] * 255), static_cast<int>(colors[i][1] * 255),
                                      static_cast<int>(colors[i][2] * 255), 255};
        EXPECT_EQ(rgba8_at(array, 4 * i + 1, 1), want) << "layer " << i;
        EXPECT_EQ(rgba8_at(array, 4 * i + 3, 3), want) << "layer " << i;
    }
}

TEST_P(SubresourceTest, BindingSeveralLayersToASampler2DIsRefused) {
    rhi::TextureDesc desc;
    desc.name = "layers";
    desc.dimension = rhi::TextureDimension::Tex2DArray;
    desc.width = desc.height = 4;
    desc.depth_or_layers = 2;
    desc.usage = rhi::TextureUsage::Sampled;
    LOOM_ASSIGN_OR_FAIL(auto layers, device().create_texture(desc));
    LOOM_ASSIGN_OR_FAIL(auto cs, make_shader(device(), rhi::ShaderStage::Compute, "read.comp", R"(#version 450
layout(local_size_x = 1) in;
layout(set = 0, binding = 0) uniform sampler2D tex;
layout(set = 0, binding = 1) buffer Out { vec4 value; } result;
void main() { result.value = texelFetch(tex, ivec2(0), 0); })"));
    LOOM_ASSIGN_OR_FAIL(auto pipeline, device().create_compute_pipeline({"read", cs}));
    LOOM_ASSIGN_OR_FAIL(auto sampler, nearest_sampler(device()));
    LOOM_ASSIGN_OR_FAIL(auto out, make_buffer_of(device(), "out", rhi::BufferUsage::Storage, std::vector<float>(4)));
    const Status status = run_frame(device(), [&](rhi::CommandList& list) {
        list.transition(layers, ResourceState::ShaderRead);
        list.transition(out, ResourceState::Storage);
        list.set_pipeline(pipeline);
        list.set_bind_group(0, rhi::BindGroup{}.texture(0, layers, sampler).buffer(1, out));
        list.dispatch(1);
    });
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.error().code, ErrorCode::InvalidArgument);
    EXPECT_EQ(status.error().message,
              "dispatch: pipeline 'read' set 0 binding 0 ('tex'): texture 'layers' (Tex2DArray, 2 layers bound) does not fit the "
              "shader's Tex2D declaration; a 2D declaration sees one layer: bind one (layer_count 1) or declare an array");
}

TEST_P(SubresourceTest, StorageBufferWrittenTwiceThenReadAsVerticesIndirectArgumentsAndUniforms) {
    // Dispatch 1 writes half-size triangle positions, zero instances and a colour; dispatch 2
    // reads and rewrites all three (positions doubled, one instance, the colour's blue set).
    // Without a barrier between the two (Storage to Storage) or before the draw, the triangle
    // would be small, missing or of the wrong colour.
    LOOM_ASSIGN_OR_FAIL(auto first_cs, make_shader(device(), rhi::ShaderStage::Compute, "first.comp", R"(#version 450
layout(local_size_x = 1) in;
layout(set = 0, binding = 0) buffer Positions { vec4 p[3]; } positions;
layout(set = 0, binding = 1) buffer Args { uint index_count; uint instance_count; uint first_index; int base_vertex; uint first_instance; } args;
layout(set = 0, binding = 2) buffer Color { vec4 value; } color;
void main() {
    positions.p[0] = vec4(-0.5, -0.5, 0.0, 1.0);
    positions.p[1] = vec4(1.5, -0.5, 0.0, 1.0);
    positions.p[2] = vec4(-0.5, 1.5, 0.0, 1.0);
    args.index_count = 3u;
    args.instance_count = 0u;
    args.first_index = 0u;
    args.base_vertex = 0;
    args.first_instance = 0u;
    color.value = vec4(1.0, 0.0, 0.0, 1.0);
})"));
    LOOM_ASSIGN_OR_FAIL(auto second_cs, make_shader(device(), rhi::ShaderStage::Compute, "second.comp", R"(#version 450
layout(local_size_x = 1) in;
layout(set = 0, binding = 0) buffer Positions { vec4 p[3]; } positions;
layout(set = 0, binding = 1) buffer Args { uint index_count; uint instance_count; uint first_index; int base_vertex; uint first_instance; } args;
layout(set = 0, binding = 2) buffer Color { vec4 value; } color;
void main() {
    for (int i = 0; i < 3; ++i) positions.p[i] = vec4(positions.p[i].xy * 2.0, 0.0, 1.0);
    args.instance_count = args.instance_count + 1u;
    color.value = vec4(color.value.r, 0.0, 1.0, 1.0);
})"));
    LOOM_ASSIGN_OR_FAIL(auto first, device().create_compute_pipeline({"first", first_cs}));
    LOOM_ASSIGN_OR_FAIL(auto second, device().create_compute_pipeline({"second", second_cs}));
    LOOM_ASSIGN_OR_FAIL(auto vs, make_shader(device(), rhi::ShaderStage::Vertex, "position4.vert", R"(#version 450
layout(location = 0) in vec4 position;
void main() { gl_Position = position; })"));
    LOOM_ASSIGN_OR_FAIL(auto fs, make_shader(device(), rhi::ShaderStage::Fragment, "uniform_color.frag", R"(#version 450
layout(set = 0, binding = 0) uniform Color { vec4 value; } color;
layout(location = 0) out vec4 frag_color;
void main() { frag_color = color.value; })"));
    rhi::GraphicsPipelineDesc pd;
    pd.name = "draw";
    pd.vertex = vs;
    pd.fragment = fs;
    pd.color_formats = {rhi::Format::RGBA8Unorm};
    pd.vertex_buffers = {rhi::VertexBufferLayout{16, rhi::VertexStepMode::PerVertex, {{0, rhi::VertexFormat::Float4, 0}}}};
    LOOM_ASSIGN_OR_FAIL(auto draw, device().create_graphics_pipeline(pd));

    LOOM_ASSIGN_OR_FAIL(auto positions, device().create_buffer({"positions", 48, rhi::BufferUsage::Storage | rhi::BufferUsage::Vertex}));
    LOOM_ASSIGN_OR_FAIL(auto args, device().create_buffer({"args", 20, rhi::BufferUsage::Storage | rhi::BufferUsage::Indirect}));
    LOOM_ASSIGN_OR_FAIL(auto color, device().create_buffer({"color", 16, rhi::BufferUsage::Storage | rhi::BufferUsage::Uniform}));
    LOOM_ASSIGN_OR_FAIL(auto indices, make_buffer_of(device(), "indices", rhi::BufferUsage::Index, std::vector<uint32_t>{0, 1, 2}));
    LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "target", rhi::Format::RGBA8Unorm, 8, 8));
    const auto group = rhi::BindGroup{}.buffer(0, positions).buffer(1, args).buffer(2, color);
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        for (rhi::BufferHandle b : {positions, args, color}) list.transition(b, ResourceState::Storage);
        list.set_pipeline(first);
        list.set_bind_group(0, group);
        list.dispatch(1);
        // Storage to Storage: the second dispatch reads what the first wrote.
        for (rhi::BufferHandle b : {positions, args, color}) list.transition(b, ResourceState::Storage);
        list.set_pipeline(second);
        list.dispatch(1);
        list.transition(positions, ResourceState::VertexBuffer);
        list.transition(args, ResourceState::IndirectArgument);
        list.transition(color, ResourceState::ShaderRead);
        list.begin_render_pass(clear_pass("draw", target, {0, 0, 0, 1}));
        list.set_pipeline(draw);
        list.set_bind_group(0, rhi::BindGroup{}.buffer(0, color));
        list.set_vertex_buffer(0, positions);
        list.set_index_buffer(indices, rhi::IndexType::Uint32);
        list.draw_indexed_indirect(args, 0, 1);
        list.end_render_pass();
    }));
    // The doubled triangle (-1,-1), (3,-1), (-1,3) covers the whole target; the half-size one
    // that the first dispatch wrote leaves the left column (x < -0.5 in NDC) black.
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target));
    EXPECT_EQ(rgba8_at(image, 0, 0), (std::array<int, 4>{255, 0, 255, 255}));
    EXPECT_EQ(rgba8_at(image, 0, 7), (std::array<int, 4>{255, 0, 255, 255}));
    EXPECT_EQ(rgba8_at(image, 7, 7), (std::array<int, 4>{255, 0, 255, 255}));
}

// ---- buffers placed in heaps -------------------------------------------------------------------

TEST_P(SubresourceTest, BufferMemoryRequirementsAndPlacementWithoutPlacedResources) {
    LOOM_ASSIGN_OR_FAIL(auto req, device().buffer_memory_requirements({"b", 100, rhi::BufferUsage::Storage}));
    EXPECT_GE(req.size, 100u);
    EXPECT_GE(req.alignment, 1u);
    EXPECT_EQ(req.alignment & (req.alignment - 1), 0u) << "a power of two";
    if (device().capabilities().placed_resources) GTEST_SKIP() << "this device places buffers";
    EXPECT_EQ(req.size, 256u) << "GL rounds up to 256 bytes";
    EXPECT_EQ(req.alignment, 256u);
    rhi::BufferDesc desc{"placed", 64, rhi::BufferUsage::Storage};
    desc.placement = rhi::BufferPlacement{};
    auto made = device().create_buffer(desc);
    ASSERT_FALSE(made.ok());
    EXPECT_EQ(made.error().code, ErrorCode::Unsupported);
    EXPECT_EQ(made.error().message, "buffer 'placed': placement in a heap needs placed resources, which this device lacks");
}

TEST_P(SubresourceTest, PlacedBuffersAndATextureShareHeapBytesInOneFrame) {
    if (!device().capabilities().placed_resources) GTEST_SKIP() << "no placed resources (GL): see BufferMemoryRequirementsAndPlacementWithoutPlacedResources";
    const rhi::BufferDesc vertices_desc{"vertices", 48, rhi::BufferUsage::Storage | rhi::BufferUsage::Vertex};
    const rhi::BufferDesc values_desc{"values", 64, rhi::BufferUsage::Storage | rhi::BufferUsage::CopySrc};
    rhi::TextureDesc image_desc;
    image_desc.name = "image";
    image_desc.width = image_desc.height = 8;
    image_desc.usage = rhi::TextureUsage::ColorAttachment | rhi::TextureUsage::Sampled;
    LOOM_ASSIGN_OR_FAIL(auto vreq, device().buffer_memory_requirements(vertices_desc));
    LOOM_ASSIGN_OR_FAIL(auto breq, device().buffer_memory_requirements(values_desc));
    LOOM_ASSIGN_OR_FAIL(auto treq, device().texture_memory_requirements(image_desc));
    const uint64_t heap_size = std::max({vreq.size, breq.size, treq.size});
    const rhi::ResourceStats before = device().resource_stats();
    LOOM_ASSIGN_OR_FAIL(auto heap, device().create_heap({"transients", heap_size}));
    // All three at offset 0: the same bytes, used one after the other.
    auto placed = [&](rhi::BufferDesc d) {
        d.placement = rhi::BufferPlacement{heap, 0};
        return d;
    };
    LOOM_ASSIGN_OR_FAIL(auto vertices, device().create_buffer(placed(vertices_desc)));
    LOOM_ASSIGN_OR_FAIL(auto values, device().create_buffer(placed(values_desc)));
    image_desc.placement = rhi::TexturePlacement{heap, 0};
    LOOM_ASSIGN_OR_FAIL(auto image, device().create_texture(image_desc));
    const rhi::ResourceStats stats = device().resource_stats();
    EXPECT_EQ(stats.buffers, before.buffers + 2) << "placed buffers count as buffers";
    EXPECT_EQ(stats.buffer_bytes, before.buffer_bytes) << "their bytes are the heap's";
    EXPECT_EQ(stats.heap_bytes, before.heap_bytes + heap_size);

    LOOM_ASSIGN_OR_FAIL(auto vertices_cs, make_shader(device(), rhi::ShaderStage::Compute, "vertices.comp", R"(#version 450
layout(local_size_x = 1) in;
layout(set = 0, binding = 0) buffer Positions { vec4 p[3]; } positions;
void main() {
    positions.p[0] = vec4(-1.0, -1.0, 0.0, 1.0);
    positions.p[1] = vec4(3.0, -1.0, 0.0, 1.0);
    positions.p[2] = vec4(-1.0, 3.0, 0.0, 1.0);
})"));
    LOOM_ASSIGN_OR_FAIL(auto values_cs, make_shader(device(), rhi::ShaderStage::Compute, "values.comp", R"(#version 450
layout(local_size_x = 16) in;
layout(set = 0, binding = 0) buffer Values { uint v[16]; } values;
void main() { values.v[gl_LocalInvocationID.x] = gl_LocalInvocationID.x * 3u + 1u; })"));
    LOOM_ASSIGN_OR_FAIL(auto write_vertices, device().create_compute_pipeline({"write vertices", vertices_cs}));
    LOOM_ASSIGN_OR_FAIL(auto write_values, device().create_compute_pipeline({"write values", values_cs}));
    LOOM_ASSIGN_OR_FAIL(auto vs, make_shader(device(), rhi::ShaderStage::Vertex, "position4.vert", R"(#version 450
layout(location = 0) in vec4 position;
void main() { gl_Position = position; })"));
    LOOM_ASSIGN_OR_FAIL(auto color_fs, make_shader(device(), rhi::ShaderStage::Fragment, "push.frag", kPushColorFrag));
    rhi::GraphicsPipelineDesc pd;
    pd.name = "from placed vertices";
    pd.vertex = vs;
    pd.fragment = color_fs;
    pd.color_formats = {rhi::Format::RGBA8Unorm};
    pd.vertex_buffers = {rhi::VertexBufferLayout{16, rhi::VertexStepMode::PerVertex, {{0, rhi::VertexFormat::Float4, 0}}}};
    LOOM_ASSIGN_OR_FAIL(auto draw, device().create_graphics_pipeline(pd));
    LOOM_ASSIGN_OR_FAIL(auto fvs, make_shader(device(), rhi::ShaderStage::Vertex, "fullscreen.vert", kFullscreenVert));
    LOOM_ASSIGN_OR_FAIL(auto copy_fs, make_shader(device(), rhi::ShaderStage::Fragment, "copy.frag", R"(#version 450
layout(set = 0, binding = 0) uniform sampler2D source;
layout(location = 0) out vec4 frag_color;
void main() { frag_color = texelFetch(source, ivec2(gl_FragCoord.xy), 0); })"));
    pd.name = "copy";
    pd.vertex = fvs;
    pd.fragment = copy_fs;
    pd.vertex_buffers.clear();
    LOOM_ASSIGN_OR_FAIL(auto copy, device().create_graphics_pipeline(pd));
    LOOM_ASSIGN_OR_FAIL(auto sampler, nearest_sampler(device()));
    LOOM_ASSIGN_OR_FAIL(auto drawn, make_target(device(), "drawn", rhi::Format::RGBA8Unorm, 8, 8));
    LOOM_ASSIGN_OR_FAIL(auto copied, make_target(device(), "copied", rhi::Format::RGBA8Unorm, 8, 8));

    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        // 1. 'vertices' owns the bytes: written by compute, read as vertices.
        list.transition(vertices, ResourceState::Storage);
        list.set_pipeline(write_vertices);
        list.set_bind_group(0, rhi::BindGroup{}.buffer(0, vertices));
        list.dispatch(1);
        list.transition(vertices, ResourceState::VertexBuffer);
        list.begin_render_pass(clear_pass("draw", drawn, {0, 0, 0, 1}));
        list.set_pipeline(draw);
        list.set_vertex_buffer(0, vertices);
        list.push_constants_of(std::array<float, 4>{1.0f, 1.0f, 0.0f, 1.0f});
        list.draw(3);
        list.end_render_pass();
        // 2. 'image' takes them over: cleared (its old contents are not needed), sampled.
        rhi::RenderPassDesc fill;
        fill.label = "fill image";
        fill.colors.push_back({.texture = image, .clear = {0, 1, 1, 1}});
        list.begin_render_pass(fill);
        list.end_render_pass();
        list.transition(image, ResourceState::ShaderRead);
        list.begin_render_pass(clear_pass("copy", copied, {0, 0, 0, 1}));
        list.set_pipeline(copy);
        list.set_bind_group(0, rhi::BindGroup{}.texture(0, image, sampler));
        list.draw(3);
        list.end_render_pass();
        // 3. 'values' takes them over from the image: written by compute, read back below.
        list.transition(values, ResourceState::Storage);
        list.set_pipeline(write_values);
        list.set_bind_group(0, rhi::BindGroup{}.buffer(0, values));
        list.dispatch(1);
        list.transition(values, ResourceState::CopySrc);
    }));
    LOOM_ASSIGN_OR_FAIL(rhi::Image drawn_image, device().read_texture(drawn));
    EXPECT_EQ(rgba8_at(drawn_image, 0, 0), (std::array<int, 4>{255, 255, 0, 255}));
    EXPECT_EQ(rgba8_at(drawn_image, 7, 7), (std::array<int, 4>{255, 255, 0, 255}));
    LOOM_ASSIGN_OR_FAIL(rhi::Image copied_image, device().read_texture(copied));
    EXPECT_EQ(rgba8_at(copied_image, 3, 4), (std::array<int, 4>{0, 255, 255, 255}));
    LOOM_ASSIGN_OR_FAIL(auto bytes, device().read_buffer(values, 0, 64));
    std::array<uint32_t, 16> read{};
    std::memcpy(read.data(), bytes.data(), bytes.size());
    for (uint32_t i = 0; i < 16; ++i) EXPECT_EQ(read[i], i * 3 + 1) << "value " << i;

    // Sampling the image now would read bytes 'values' overwrote: refused, naming the buffer.
    const Status stale = run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("stale", copied, {0, 0, 0, 1}));
        list.set_pipeline(copy);
        list.set_bind_group(0, rhi::BindGroup{}.texture(0, image, sampler));
        list.draw(3);
        list.end_render_pass();
    });
    ASSERT_FALSE(stale.ok());
    EXPECT_EQ(stale.error().code, ErrorCode::InvalidState);
    EXPECT_NE(stale.error().message.find("shares heap memory with buffer 'values'"), std::string::npos) << stale.error().message;

    // The heap goes only after what is placed in it.
    LOOM_ASSERT_OK(device().destroy(image));
    const Status early = device().destroy(heap);
    ASSERT_FALSE(early.ok());
    EXPECT_EQ(early.error().code, ErrorCode::InvalidState);
    EXPECT_EQ(early.error().message, "heap 'transients' still holds 2 placed buffer(s); destroy them first");
    LOOM_ASSERT_OK(device().destroy(vertices));
    LOOM_ASSERT_OK(device().destroy(values));
    LOOM_ASSERT_OK(device().destroy(heap));
}

TEST_P(SubresourceTest, PlacedBufferOutsideItsHeapIsRefused) {
    if (!device().capabilities().placed_resources) GTEST_SKIP() << "no placed resources";
    rhi::BufferDesc desc{"b", 256, rhi::BufferUsage::Storage};
    LOOM_ASSIGN_OR_FAIL(auto req, device().buffer_memory_requirements(desc));
    LOOM_ASSIGN_OR_FAIL(auto heap, device().create_heap({"h", req.size}));
    desc.placement = rhi::BufferPlacement{heap, req.alignment};
    auto made = device().create_buffer(desc);
    ASSERT_FALSE(made.ok());
    EXPECT_EQ(made.error().code, ErrorCode::InvalidArgument);
    EXPECT_EQ(made.error().message, "buffer 'b' placed in heap 'h': range " + std::to_string(req.alignment) + "+" +
                                        std::to_string(req.size) + " exceeds the heap size " + std::to_string(req.size));
    LOOM_ASSERT_OK(device().destroy(heap));
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(SubresourceTest);

}  // namespace loom::test
