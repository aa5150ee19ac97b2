// Heaps with textures placed at chosen offsets, including overlapping (aliased) ones used one
// after the other, under validation and synchronisation validation.
#include <gtest/gtest.h>

#include "loom/rhi/device.hpp"
#include "loom_test/test_support.hpp"
#include "vulkan_test_support.hpp"

namespace loom::test {
namespace {

std::array<int, 4> pixel(const rhi::Image& image, uint32_t x, uint32_t y) {
    auto t = image.texel(x, y);
    return {int(t[0]), int(t[1]), int(t[2]), int(t[3])};
}

rhi::TextureDesc placed(const std::string& name, rhi::HeapHandle heap, uint64_t offset) {
    rhi::TextureDesc d;
    d.name = name;
    d.format = rhi::Format::RGBA8Unorm;
    d.width = d.height = 64;
    d.usage = rhi::TextureUsage::ColorAttachment | rhi::TextureUsage::Sampled | rhi::TextureUsage::CopySrc;
    d.placement = rhi::TexturePlacement{heap, offset};
    return d;
}

class VulkanHeapTest : public ::testing::Test {
protected:
    void SetUp() override {
        device_ = make_vulkan_device();
        ASSERT_NE(device_, nullptr);
        ASSERT_TRUE(device_->capabilities().placed_resources);
    }
    void TearDown() override {
        if (device_) {
            EXPECT_TRUE(device_->wait_idle().ok());
        }
        device_.reset();
    }
    std::unique_ptr<rhi::Device> device_;
};

TEST_F(VulkanHeapTest, AliasedTexturesRenderOneAfterTheOther) {
    rhi::Device& device = *device_;
    rhi::TextureDesc probe = placed("probe", {}, 0);
    probe.placement.reset();
    LOOM_VK_ASSIGN(const rhi::MemoryRequirements req, device.texture_memory_requirements(probe));
    EXPECT_GE(req.size, 64u * 64u * 4u);
    EXPECT_EQ(req.alignment & (req.alignment - 1), 0u) << "alignment is a power of two";

    LOOM_VK_ASSIGN(auto heap, device.create_heap({"transients", 3 * req.size}));
    // a and b share the same bytes; c starts one alignment step in, overlapping both partly.
    LOOM_VK_ASSIGN(auto a, device.create_texture(placed("a", heap, 0)));
    LOOM_VK_ASSIGN(auto b, device.create_texture(placed("b", heap, 0)));
    LOOM_VK_ASSIGN(auto c, device.create_texture(placed("c", heap, req.alignment)));
    const rhi::ResourceStats stats = device.resource_stats();
    EXPECT_EQ(stats.heaps, 1u);
    EXPECT_EQ(stats.heap_bytes, 3 * req.size);
    EXPECT_EQ(stats.textures, 3u);
    EXPECT_EQ(stats.texture_bytes, 0u) << "placed textures' bytes are the heap's";

    LOOM_VK_ASSIGN(auto fill, make_fill_pipeline(device, rhi::Format::RGBA8Unorm));
    // Render into a: blue, with the left half red.
    LOOM_VK_OK(record_frame(device, [&](rhi::CommandList& list) {
        clear_and_fill(list, a, fill, {0, 0, 1, 1}, {1, 0, 0, 1}, {0, 0, 32, 64});
    }));
    LOOM_VK_ASSIGN(rhi::Image image_a, device.read_texture(a));
    EXPECT_EQ(pixel(image_a, 10, 10), (std::array<int, 4>{255, 0, 0, 255}));
    EXPECT_EQ(pixel(image_a, 50, 10), (std::array<int, 4>{0, 0, 255, 255}));

    // Render into b, which aliases a's bytes: green, with the top half white.
    LOOM_VK_OK(record_frame(device, [&](rhi::CommandList& list) {
        clear_and_fill(list, b, fill, {0, 1, 0, 1}, {1, 1, 1, 1}, {0, 0, 64, 32});
    }));
    LOOM_VK_ASSIGN(rhi::Image image_b, device.read_texture(b));
    EXPECT_EQ(pixel(image_b, 10, 10), (std::array<int, 4>{255, 255, 255, 255}));
    EXPECT_EQ(pixel(image_b, 10, 50), (std::array<int, 4>{0, 255, 0, 255}));
    EXPECT_EQ(pixel(image_b, 50, 50), (std::array<int, 4>{0, 255, 0, 255}));

    // All three in one frame, each handing the memory over to the next; then a again.
    LOOM_VK_OK(record_frame(device, [&](rhi::CommandList& list) {
        clear_and_fill(list, a, fill, {1, 0, 0, 1}, {1, 0, 0, 1}, {0, 0, 64, 64});
        clear_and_fill(list, b, fill, {0, 1, 0, 1}, {0, 1, 0, 1}, {0, 0, 64, 64});
        clear_and_fill(list, c, fill, {0, 0, 0, 1}, {1, 1, 0, 1}, {0, 0, 16, 16});
    }));
    LOOM_VK_ASSIGN(rhi::Image image_c, device.read_texture(c));
    EXPECT_EQ(pixel(image_c, 5, 5), (std::array<int, 4>{255, 255, 0, 255}));
    EXPECT_EQ(pixel(image_c, 40, 40), (std::array<int, 4>{0, 0, 0, 255}));
    LOOM_VK_OK(record_frame(device, [&](rhi::CommandList& list) {
        clear_and_fill(list, a, fill, {0, 0, 0, 1}, {0, 1, 1, 1}, {32, 32, 32, 32});
    }));
    LOOM_VK_ASSIGN(image_a, device.read_texture(a));
    EXPECT_EQ(pixel(image_a, 40, 40), (std::array<int, 4>{0, 255, 255, 255}));
    EXPECT_EQ(pixel(image_a, 10, 10), (std::array<int, 4>{0, 0, 0, 255}));

    // A heap with live placed textures cannot go.
    auto early = device.destroy(heap);
    ASSERT_FALSE(early.ok());
    EXPECT_EQ(early.error().code, ErrorCode::InvalidState);
    EXPECT_NE(early.error().message.find("transients"), std::string::npos) << early.error().message;

    LOOM_VK_OK(device.destroy(a));
    LOOM_VK_OK(device.destroy(b));
    LOOM_VK_OK(device.destroy(c));
    LOOM_VK_OK(device.destroy(fill));
    LOOM_VK_OK(device.destroy(heap));
    EXPECT_EQ(device.resource_stats().total_bytes(), 0u);
    EXPECT_EQ(device.resource_stats().textures, 0u);
    EXPECT_EQ(device.resource_stats().heaps, 0u);
}

TEST_F(VulkanHeapTest, SamplingAnAliasWhoseBytesWereTakenOverIsInvalidState) {
    rhi::Device& device = *device_;
    rhi::TextureDesc probe = placed("probe", {}, 0);
    probe.placement.reset();
    LOOM_VK_ASSIGN(const rhi::MemoryRequirements req, device.texture_memory_requirements(probe));
    LOOM_VK_ASSIGN(auto heap, device.create_heap({"shared", req.size}));
    LOOM_VK_ASSIGN(auto a, device.create_texture(placed("albedo", heap, 0)));
    LOOM_VK_ASSIGN(auto b, device.create_texture(placed("bloom", heap, 0)));
    rhi::TextureDesc target_desc = placed("target", {}, 0);
    target_desc.placement.reset();
    LOOM_VK_ASSIGN(auto target, device.create_texture(target_desc));
    LOOM_VK_ASSIGN(auto fill, make_fill_pipeline(device, rhi::Format::RGBA8Unorm));

    shader_compiler::ShaderCompiler compiler;
    LOOM_VK_ASSIGN(auto vs_module, compiler.compile({"fs.vert", rhi::ShaderStage::Vertex, R"(#version 450
void main() {
    vec2 p = vec2(gl_VertexIndex == 1 ? 3.0 : -1.0, gl_VertexIndex == 2 ? 3.0 : -1.0);
    gl_Position = vec4(p, 0.0, 1.0);
})", {}}));
    LOOM_VK_ASSIGN(auto fs_module, compiler.compile({"copy.frag", rhi::ShaderStage::Fragment, R"(#version 450
layout(set = 0, binding = 0) uniform sampler2D source;
layout(location = 0) out vec4 frag_color;
void main() { frag_color = texelFetch(source, ivec2(gl_FragCoord.xy), 0); })", {}}));
    LOOM_VK_ASSIGN(auto vs, device.create_shader(vs_module));
    LOOM_VK_ASSIGN(auto fs, device.create_shader(fs_module));
    rhi::GraphicsPipelineDesc pd;
    pd.name = "copy";
    pd.vertex = vs;
    pd.fragment = fs;
    pd.color_formats = {rhi::Format::RGBA8Unorm};
    LOOM_VK_ASSIGN(auto copy, device.create_graphics_pipeline(pd));
    LOOM_VK_ASSIGN(auto sampler, device.create_sampler({}));
    auto copy_into_target = [&](rhi::CommandList& list, rhi::TextureHandle source) {
        rhi::RenderPassDesc pass;
        pass.label = "copy";
        pass.colors.push_back({target});
        list.begin_render_pass(pass);
        list.set_pipeline(copy);
        list.set_bind_group(0, rhi::BindGroup{}.texture(0, source, sampler));
        list.draw(3);
        list.end_render_pass();
    };

    // albedo is written and made readable, then bloom takes the same bytes over.
    auto status = record_frame(device, [&](rhi::CommandList& list) {
        clear_and_fill(list, a, fill, {1, 0, 0, 1}, {1, 0, 0, 1}, {0, 0, 64, 64});
        list.transition(a, rhi::ResourceState::ShaderRead);
        clear_and_fill(list, b, fill, {0, 1, 0, 1}, {0, 1, 0, 1}, {0, 0, 64, 64});
        copy_into_target(list, a);
    });
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.error().code, ErrorCode::InvalidState);
    EXPECT_NE(status.error().message.find("'albedo'"), std::string::npos) << status.error().message;
    EXPECT_NE(status.error().message.find("'bloom'"), std::string::npos) << status.error().message;

    // Written again, albedo owns the bytes and samples fine (from an UNDEFINED hand-over).
    LOOM_VK_OK(record_frame(device, [&](rhi::CommandList& list) {
        list.transition(b, rhi::ResourceState::ShaderRead);
        clear_and_fill(list, a, fill, {0, 0, 1, 1}, {0, 0, 1, 1}, {0, 0, 64, 64});
        list.transition(a, rhi::ResourceState::ShaderRead);
        copy_into_target(list, a);
    }));
    LOOM_VK_ASSIGN(rhi::Image image, device.read_texture(target));
    EXPECT_EQ(pixel(image, 20, 20), (std::array<int, 4>{0, 0, 255, 255}));

    LOOM_VK_OK(device.destroy(a));
    LOOM_VK_OK(device.destroy(b));
    LOOM_VK_OK(device.destroy(heap));
}

TEST_F(VulkanHeapTest, BadPlacementsNameTextureAndHeap) {
    rhi::Device& device = *device_;
    rhi::TextureDesc probe = placed("probe", {}, 0);
    probe.placement.reset();
    LOOM_VK_ASSIGN(const rhi::MemoryRequirements req, device.texture_memory_requirements(probe));
    LOOM_VK_ASSIGN(auto heap, device.create_heap({"small heap", req.size + req.alignment}));

    if (req.alignment > 1) {
        auto misaligned = device.create_texture(placed("crooked", heap, req.alignment / 2));
        ASSERT_FALSE(misaligned.ok());
        EXPECT_EQ(misaligned.error().code, ErrorCode::InvalidArgument);
        EXPECT_NE(misaligned.error().message.find("crooked"), std::string::npos);
        EXPECT_NE(misaligned.error().message.find("small heap"), std::string::npos);
    }
    auto too_far = device.create_texture(placed("too far", heap, 2 * req.alignment));
    ASSERT_FALSE(too_far.ok());
    EXPECT_EQ(too_far.error().code, ErrorCode::InvalidArgument);
    EXPECT_NE(too_far.error().message.find("too far"), std::string::npos);
    EXPECT_NE(too_far.error().message.find("exceeds"), std::string::npos) << too_far.error().message;

    auto stale_heap = heap;
    LOOM_VK_OK(device.destroy(heap));
    auto orphan = device.create_texture(placed("orphan", stale_heap, 0));
    ASSERT_FALSE(orphan.ok());
    EXPECT_EQ(orphan.error().code, ErrorCode::InvalidArgument);
    EXPECT_NE(orphan.error().message.find("stale"), std::string::npos) << orphan.error().message;
    EXPECT_EQ(device.resource_stats().textures, 0u);

    auto empty = device.create_heap({"empty", 0});
    ASSERT_FALSE(empty.ok());
    EXPECT_EQ(empty.error().code, ErrorCode::InvalidArgument);
}

}  // namespace
}  // namespace loom::test
