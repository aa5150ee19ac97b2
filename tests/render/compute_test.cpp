// Compute dispatches writing a storage buffer and a storage image.
#include "loom_test/render_fixture.hpp"
#include "render_helpers.hpp"

namespace loom::test {
namespace {

class ComputeTest : public RenderTest {};

TEST_P(ComputeTest, DispatchWritesStorageBuffer) {
    LOOM_ASSIGN_OR_FAIL(auto cs, make_shader(device(), rhi::ShaderStage::Compute, "squares.comp", R"(#version 450
layout(local_size_x = 8) in;
layout(set = 0, binding = 1) buffer Values { uint count; uint values[]; } data;
layout(push_constant) uniform Push { uint add; } pc;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i < data.count) data.values[i] = i * i + pc.add;
})"));
    LOOM_ASSIGN_OR_FAIL(auto pipeline, device().create_compute_pipeline(rhi::ComputePipelineDesc{"squares", cs}));
    constexpr uint32_t kCount = 37;  // not a multiple of the workgroup size
    std::vector<uint32_t> initial(kCount + 1 + 3, 0xDEADBEEFu);
    initial[0] = kCount;
    LOOM_ASSIGN_OR_FAIL(auto buffer, make_buffer_of(device(), "squares", rhi::BufferUsage::Storage, initial));
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        list.transition(buffer, rhi::ResourceState::Storage);
        list.set_pipeline(pipeline);
        list.set_bind_group(0, rhi::BindGroup{}.buffer(1, buffer));
        list.push_constants_of(uint32_t{7});
        list.dispatch((kCount + 7) / 8);
        list.transition(buffer, rhi::ResourceState::CopySrc);
    }));
    LOOM_ASSIGN_OR_FAIL(auto bytes, device().read_buffer(buffer, 0, initial.size() * 4));
    std::vector<uint32_t> result(initial.size());
    std::memcpy(result.data(), bytes.data(), bytes.size());
    EXPECT_EQ(result[0], kCount);
    for (uint32_t i = 0; i < kCount; ++i) EXPECT_EQ(result[1 + i], i * i + 7) << "value " << i;
    for (uint32_t i = kCount + 1; i < result.size(); ++i) EXPECT_EQ(result[i], 0xDEADBEEFu) << "past the end " << i;
}

// The compute queue: a dispatch recorded there fills a buffer, the graphics queue waits for its
// signal and copies the buffer; three frames in a row (every frame slot's semaphores are used
// and reused). A graphics signal nobody waits for and a compute batch nobody joins are joined
// by end_frame. Where the device has no second queue (GL, lavapipe) the commands run in
// recording order and the results are the same.
TEST_P(ComputeTest, ComputeQueueDispatchIsWaitedForByTheGraphicsQueue) {
    LOOM_ASSIGN_OR_FAIL(auto cs, make_shader(device(), rhi::ShaderStage::Compute, "frame_values.comp", R"(#version 450
layout(local_size_x = 16) in;
layout(set = 0, binding = 0) buffer Values { uint values[]; } data;
layout(push_constant) uniform Push { uint frame; } pc;
void main() { data.values[gl_GlobalInvocationID.x] = gl_GlobalInvocationID.x + 1000u * pc.frame; })"));
    LOOM_ASSIGN_OR_FAIL(auto pipeline, device().create_compute_pipeline(rhi::ComputePipelineDesc{"frame values", cs}));
    LOOM_ASSIGN_OR_FAIL(auto values, make_buffer_of(device(), "values", rhi::BufferUsage::Storage | rhi::BufferUsage::CopySrc,
                                                    std::vector<uint32_t>(16, 0)));
    LOOM_ASSIGN_OR_FAIL(auto copy, make_buffer_of(device(), "copy", rhi::BufferUsage::CopyDst | rhi::BufferUsage::Storage,
                                                  std::vector<uint32_t>(16, 0)));
    for (uint32_t frame = 1; frame <= 3; ++frame) {
        LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
            const rhi::QueueSignal start = list.signal_queue();  // graphics: nothing before it yet
            list.set_queue(rhi::QueueType::Compute);
            list.wait_queue(start);
            list.transition(values, rhi::ResourceState::Storage);
            list.set_pipeline(pipeline);
            list.set_bind_group(0, rhi::BindGroup{}.buffer(0, values));
            list.push_constants_of(frame);
            list.dispatch(1);
            list.transition(values, rhi::ResourceState::CopySrc);
            const rhi::QueueSignal filled = list.signal_queue();
            list.set_queue(rhi::QueueType::Graphics);
            list.wait_queue(filled);
            list.transition(copy, rhi::ResourceState::CopyDst);
            list.copy_buffer(values, 0, copy, 0, 16 * 4);
            list.transition(copy, rhi::ResourceState::CopySrc);
            (void)list.signal_queue();  // never waited: end_frame joins it
            list.set_queue(rhi::QueueType::Compute);  // an empty compute batch left open
        }));
        LOOM_ASSIGN_OR_FAIL(auto bytes, device().read_buffer(copy, 0, 16 * 4));
        std::vector<uint32_t> result(16);
        std::memcpy(result.data(), bytes.data(), bytes.size());
        for (uint32_t i = 0; i < 16; ++i) EXPECT_EQ(result[i], i + 1000 * frame) << "frame " << frame << " value " << i;
    }
    LOOM_ASSERT_OK(device().destroy(copy));
    LOOM_ASSERT_OK(device().destroy(values));
    LOOM_ASSERT_OK(device().destroy(pipeline));
    LOOM_ASSERT_OK(device().destroy(cs));
}

TEST_P(ComputeTest, DispatchWritesStorageImage) {
    LOOM_ASSIGN_OR_FAIL(auto cs, make_shader(device(), rhi::ShaderStage::Compute, "pattern.comp", R"(#version 450
layout(local_size_x = 4, local_size_y = 4) in;
layout(set = 0, binding = 0, r32ui) uniform writeonly uimage2D image;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    imageStore(image, p, uvec4(uint(p.x) + 100u * uint(p.y)));
})"));
    LOOM_ASSIGN_OR_FAIL(auto pipeline, device().create_compute_pipeline(rhi::ComputePipelineDesc{"pattern", cs}));
    rhi::TextureDesc desc;
    desc.name = "pattern";
    desc.format = rhi::Format::R32Uint;
    desc.width = 12;
    desc.height = 8;
    desc.usage = rhi::TextureUsage::Storage | rhi::TextureUsage::CopySrc;
    LOOM_ASSIGN_OR_FAIL(auto image, device().create_texture(desc));
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        list.transition(image, rhi::ResourceState::Storage);
        list.set_pipeline(pipeline);
        list.set_bind_group(0, rhi::BindGroup{}.storage_texture(0, image));
        list.dispatch(3, 2);
        list.transition(image, rhi::ResourceState::CopySrc);
    }));
    LOOM_ASSIGN_OR_FAIL(rhi::Image result, device().read_texture(image));
    // Row 0 of the readback is image row y = 0: storage images are not flipped either.
    for (uint32_t y = 0; y < 8; ++y) {
        for (uint32_t x = 0; x < 12; ++x) ASSERT_EQ(result.load(x, y)[0], x + 100.0 * y) << "texel " << x << "," << y;
    }
}

TEST_P(ComputeTest, StorageImageThenSampled) {
    // A compute pass writes an image, a render pass samples it: the transition between them
    // is what makes the writes visible.
    LOOM_ASSIGN_OR_FAIL(auto cs, make_shader(device(), rhi::ShaderStage::Compute, "fill.comp", R"(#version 450
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0, rgba8) uniform writeonly image2D image;
void main() { imageStore(image, ivec2(gl_GlobalInvocationID.xy), vec4(0.0, 1.0, 0.0, 1.0)); }
)"));
    LOOM_ASSIGN_OR_FAIL(auto fill, device().create_compute_pipeline(rhi::ComputePipelineDesc{"fill", cs}));
    rhi::TextureDesc desc;
    desc.name = "filled";
    desc.width = desc.height = 8;
    desc.usage = rhi::TextureUsage::Storage | rhi::TextureUsage::Sampled;
    LOOM_ASSIGN_OR_FAIL(auto image, device().create_texture(desc));
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
    LOOM_ASSIGN_OR_FAIL(auto draw, device().create_graphics_pipeline(pd));
    LOOM_ASSIGN_OR_FAIL(auto sampler, device().create_sampler(rhi::SamplerDesc{}));
    LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "fetched", rhi::Format::RGBA8Unorm, 8, 8));
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        list.transition(image, rhi::ResourceState::Storage);
        list.set_pipeline(fill);
        list.set_bind_group(0, rhi::BindGroup{}.storage_texture(0, image));
        list.dispatch(1, 1);
        list.transition(image, rhi::ResourceState::ShaderRead);
        list.begin_render_pass(clear_pass("fetch", target, {1, 0, 0, 1}));
        list.set_pipeline(draw);
        list.set_bind_group(0, rhi::BindGroup{}.texture(0, image, sampler));
        list.draw(3);
        list.end_render_pass();
    }));
    LOOM_ASSIGN_OR_FAIL(rhi::Image result, device().read_texture(target));
    EXPECT_EQ(rgba8_at(result, 0, 0), (std::array<int, 4>{0, 255, 0, 255}));
    EXPECT_EQ(rgba8_at(result, 7, 7), (std::array<int, 4>{0, 255, 0, 255}));
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(ComputeTest);

}  // namespace loom::test
