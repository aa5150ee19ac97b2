// Resource accounting on both backends: the same mix of resources gives the same counts; bytes
// are at least the texels and buffer sizes asked for (Vulkan reports what it allocated, with
// alignment and padding; GL what it asked the driver for), and everything returns to zero.
#include "cross_backend.hpp"
#include "render_helpers.hpp"

namespace loom::test {
namespace {

TEST_F(CrossBackendTest, ResourceAccountingMatchesAndReturnsToZero) {
    rhi::ResourceStats stats[2];
    int i = 0;
    for (rhi::Device* device : {&gl(), &vulkan()}) {
        SCOPED_TRACE(std::string(rhi::backend_name(device->backend())));
        std::vector<rhi::TextureHandle> textures;
        std::vector<rhi::BufferHandle> buffers;
        for (uint32_t size : {16u, 64u, 100u}) {
            auto t = make_target(*device, "colour " + std::to_string(size), rhi::Format::RGBA8Unorm, size, size);
            ASSERT_TRUE(t.ok()) << t.error().to_string();
            textures.push_back(*t);
        }
        auto depth = make_target(*device, "depth", rhi::Format::Depth32F, 32, 32);
        ASSERT_TRUE(depth.ok()) << depth.error().to_string();
        textures.push_back(*depth);
        for (uint64_t size : {64u, 1000u, 70000u}) {
            auto b = device->create_buffer({"buffer", size, rhi::BufferUsage::Vertex | rhi::BufferUsage::Uniform});
            ASSERT_TRUE(b.ok()) << b.error().to_string();
            buffers.push_back(*b);
        }
        auto sampler = device->create_sampler({});
        ASSERT_TRUE(sampler.ok());
        auto pipeline = make_solid_pipeline(*device, rhi::Format::RGBA8Unorm);
        ASSERT_TRUE(pipeline.ok()) << pipeline.error().to_string();

        stats[i] = device->resource_stats();
        EXPECT_EQ(stats[i].textures, 4u);
        EXPECT_EQ(stats[i].buffers, 3u);
        EXPECT_EQ(stats[i].samplers, 1u);
        EXPECT_EQ(stats[i].pipelines, 1u);
        EXPECT_GE(stats[i].texture_bytes, (16u * 16 + 64 * 64 + 100 * 100 + 32 * 32) * 4u);
        EXPECT_GE(stats[i].buffer_bytes, 64u + 1000u + 70000u);
        // Padding stays modest: within twice the payload.
        EXPECT_LE(stats[i].texture_bytes, 2 * (16u * 16 + 64 * 64 + 100 * 100 + 32 * 32) * 4u);

        for (auto t : textures) ASSERT_TRUE(device->destroy(t).ok());
        for (auto b : buffers) ASSERT_TRUE(device->destroy(b).ok());
        ASSERT_TRUE(device->destroy(*sampler).ok());
        ASSERT_TRUE(device->destroy(*pipeline).ok());
        const rhi::ResourceStats after = device->resource_stats();
        EXPECT_EQ(after.textures + after.buffers + after.samplers + after.pipelines + after.shaders + after.heaps, 0u);
        EXPECT_EQ(after.total_bytes(), 0u);
        ++i;
    }
    EXPECT_EQ(stats[0].textures, stats[1].textures);
    EXPECT_EQ(stats[0].buffers, stats[1].buffers);
}

}  // namespace
}  // namespace loom::test
