// Vulkan device behaviour the RHI render tests do not reach: depth/stencil readback layouts,
// uploads larger than the staging ring, ring wrap-around, frames in flight with deferred
// destruction, readback in the middle of a frame, growth of the transient uniform ring.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <gtest/gtest.h>

#include "loom/rhi/device.hpp"
#include "loom_test/test_support.hpp"
#include "vulkan_test_support.hpp"

namespace loom::test {
namespace {

class VulkanDeviceTest : public ::testing::Test {
protected:
    void SetUp() override {
        device_ = make_vulkan_device();
        ASSERT_NE(device_, nullptr);
    }
    void TearDown() override {
        if (device_) {
            EXPECT_TRUE(device_->wait_idle().ok());
        }
        device_.reset();
    }
    rhi::TextureHandle make_texture(const std::string& name, rhi::Format format, uint32_t w, uint32_t h,
                                    rhi::TextureUsage usage) {
        rhi::TextureDesc d;
        d.name = name;
        d.format = format;
        d.width = w;
        d.height = h;
        d.usage = usage;
        auto t = device_->create_texture(d);
        EXPECT_TRUE(t.ok()) << t.error().to_string();
        return t.ok() ? *t : rhi::TextureHandle{};
    }
    std::unique_ptr<rhi::Device> device_;
};

TEST_F(VulkanDeviceTest, DepthStencilClearsReadBackInLoomLayout) {
    for (rhi::Format format : {rhi::Format::Depth24Stencil8, rhi::Format::Depth32FStencil8}) {
        SCOPED_TRACE(std::string(rhi::format_name(format)));
        if (!device_->capabilities().format(format).depth_stencil_attachment) continue;
        auto depth = make_texture("ds", format, 8, 8, rhi::TextureUsage::DepthStencilAttachment);
        LOOM_VK_OK(record_frame(*device_, [&](rhi::CommandList& list) {
            rhi::RenderPassDesc pass;
            pass.label = "clear depth and stencil";
            rhi::DepthAttachment d;
            d.texture = depth;
            d.clear_depth = 0.25f;
            d.stencil_load = rhi::LoadOp::Clear;
            d.stencil_store = rhi::StoreOp::Store;
            d.clear_stencil = 0x5A;
            pass.depth = d;
            list.begin_render_pass(pass);
            list.end_render_pass();
        }));
        LOOM_VK_ASSIGN(rhi::Image image, device_->read_texture(depth));
        ASSERT_EQ(image.format, format);
        const auto value = image.load(3, 5);
        EXPECT_NEAR(value[0], 0.25, 1e-6);
        EXPECT_EQ(value[1], 0x5A);
        if (format == rhi::Format::Depth24Stencil8) {
            uint32_t word;
            std::memcpy(&word, image.texel(0, 0).data(), 4);
            EXPECT_EQ(word >> 24, 0x5Au) << "stencil in the high byte";
            EXPECT_EQ(word & 0xFFFFFFu, static_cast<uint32_t>(std::lround(0.25 * 0xFFFFFF))) << "depth in the low 24 bits";
        } else {
            float d;
            std::memcpy(&d, image.texel(0, 0).data(), 4);
            EXPECT_EQ(d, 0.25f);
            EXPECT_EQ(static_cast<int>(image.texel(0, 0)[4]), 0x5A) << "stencil byte at offset 4";
        }
        // Upload in loom's layout, read back the same bytes.
        rhi::Image upload(8, 8, format);
        for (uint32_t y = 0; y < 8; ++y) {
            for (uint32_t x = 0; x < 8; ++x) upload.store(x, y, {(x + 8.0 * y) / 64.0, double(x * 16 + y), 0, 0});
        }
        LOOM_VK_OK(device_->write_texture(depth, {}, upload.pixels));
        LOOM_VK_ASSIGN(rhi::Image back, device_->read_texture(depth));
        EXPECT_EQ(back.pixels, upload.pixels);
        LOOM_VK_OK(device_->destroy(depth));
    }
}

TEST_F(VulkanDeviceTest, UploadLargerThanTheStagingRingRoundTrips) {
    // 2400 x 2000 RGBA8 is 18.3 MiB, more than the 16 MiB ring.
    const uint32_t w = 2400, h = 2000;
    auto texture = make_texture("big", rhi::Format::RGBA8Unorm, w, h, rhi::TextureUsage::Sampled);
    std::vector<std::byte> data(std::size_t{w} * h * 4);
    for (std::size_t i = 0; i < data.size(); ++i) data[i] = static_cast<std::byte>((i * 7 + i / 4093) & 0xFF);
    LOOM_VK_OK(device_->write_texture(texture, {}, data));
    LOOM_VK_ASSIGN(rhi::Image image, device_->read_texture(texture));
    EXPECT_TRUE(image.pixels == data) << "large upload and readback differ";
}

TEST_F(VulkanDeviceTest, ManyUploadsWrapTheStagingRing) {
    // 40 MiB of uploads through a 16 MiB ring, with frames in between.
    LOOM_VK_ASSIGN(auto buffer, device_->create_buffer({"target", 1 << 20, rhi::BufferUsage::Storage}));
    std::vector<std::byte> chunk(1 << 20);
    for (int i = 0; i < 40; ++i) {
        std::memset(chunk.data(), i, chunk.size());
        LOOM_VK_OK(device_->write_buffer(buffer, 0, chunk));
        if (i % 7 == 0) LOOM_VK_OK(record_frame(*device_, [](rhi::CommandList&) {}));
    }
    LOOM_VK_ASSIGN(auto back, device_->read_buffer(buffer, 1000, 16));
    for (std::byte b : back) EXPECT_EQ(static_cast<int>(b), 39);
}

TEST_F(VulkanDeviceTest, FramesInFlightWithDeferredDestruction) {
    LOOM_VK_ASSIGN(auto fill, make_fill_pipeline(*device_, rhi::Format::RGBA8Unorm));
    auto keep = make_texture("kept", rhi::Format::RGBA8Unorm, 16, 16, rhi::TextureUsage::ColorAttachment);
    for (int frame = 0; frame < 8; ++frame) {
        // A texture used by this frame and destroyed right after end_frame, while the GPU may
        // still be working on it: destruction waits for the frame's fence.
        auto scratch = make_texture("scratch " + std::to_string(frame), rhi::Format::RGBA8Unorm, 16, 16,
                                    rhi::TextureUsage::ColorAttachment);
        const float shade = static_cast<float>(frame) / 8.0f;
        LOOM_VK_OK(record_frame(*device_, [&](rhi::CommandList& list) {
            clear_and_fill(list, scratch, fill, {0, 0, 0, 1}, {shade, 0, 0, 1}, {0, 0, 16, 16});
            clear_and_fill(list, keep, fill, {0, 0, 0, 1}, {0, shade, 0, 1}, {0, 0, 16, 16});
        }));
        LOOM_VK_OK(device_->destroy(scratch));
        EXPECT_EQ(device_->resource_stats().textures, 1u);
    }
    LOOM_VK_ASSIGN(rhi::Image image, device_->read_texture(keep));
    EXPECT_EQ(static_cast<int>(image.texel(8, 8)[1]), static_cast<int>(std::lround(7.0 / 8.0 * 255.0)));
}

TEST_F(VulkanDeviceTest, ReadbackInTheMiddleOfAFrameSeesEarlierCommands) {
    LOOM_VK_ASSIGN(auto fill, make_fill_pipeline(*device_, rhi::Format::RGBA8Unorm));
    auto target = make_texture("mid-frame", rhi::Format::RGBA8Unorm, 8, 8, rhi::TextureUsage::ColorAttachment);
    rhi::CommandList& list = device_->begin_frame();
    clear_and_fill(list, target, fill, {1, 0, 0, 1}, {1, 0, 0, 1}, {0, 0, 8, 8});
    LOOM_VK_ASSIGN(rhi::Image first, device_->read_texture(target));
    EXPECT_EQ(static_cast<int>(first.texel(4, 4)[0]), 255);
    EXPECT_EQ(static_cast<int>(first.texel(4, 4)[1]), 0);
    // The frame goes on, with its pipeline still bound.
    clear_and_fill(list, target, fill, {0, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 8, 8});
    LOOM_VK_OK(device_->end_frame());
    LOOM_VK_ASSIGN(rhi::Image second, device_->read_texture(target));
    EXPECT_EQ(static_cast<int>(second.texel(4, 4)[0]), 0);
    EXPECT_EQ(static_cast<int>(second.texel(4, 4)[1]), 255);
}

TEST_F(VulkanDeviceTest, TransientUniformRingGrowsWithinAFrame) {
    shader_compiler::ShaderCompiler compiler;
    LOOM_VK_ASSIGN(auto vs_module, compiler.compile({"fill.vert", rhi::ShaderStage::Vertex, R"(#version 450
void main() {
    vec2 p = vec2(gl_VertexIndex == 1 ? 3.0 : -1.0, gl_VertexIndex == 2 ? 3.0 : -1.0);
    gl_Position = vec4(p, 0.0, 1.0);
})", {}}));
    LOOM_VK_ASSIGN(auto fs_module, compiler.compile({"ubo.frag", rhi::ShaderStage::Fragment, R"(#version 450
layout(set = 0, binding = 0) uniform Params { vec4 color; } params;
layout(location = 0) out vec4 frag_color;
void main() { frag_color = params.color; })", {}}));
    LOOM_VK_ASSIGN(auto vs, device_->create_shader(vs_module));
    LOOM_VK_ASSIGN(auto fs, device_->create_shader(fs_module));
    rhi::GraphicsPipelineDesc pd;
    pd.name = "ubo fill";
    pd.vertex = vs;
    pd.fragment = fs;
    pd.color_formats = {rhi::Format::RGBA8Unorm};
    LOOM_VK_ASSIGN(auto pipeline, device_->create_graphics_pipeline(pd));
    auto target = make_texture("ubo target", rhi::Format::RGBA8Unorm, 4, 4, rhi::TextureUsage::ColorAttachment);
    LOOM_VK_OK(record_frame(*device_, [&](rhi::CommandList& list) {
        rhi::RenderPassDesc pass;
        pass.label = "many uniforms";
        pass.colors.push_back({target});
        list.begin_render_pass(pass);
        list.set_pipeline(pipeline);
        // 3000 x 256 bytes: far more than the initial 256 KiB ring of the frame.
        for (int i = 0; i < 3000; ++i) {
            std::array<float, 64> block{};
            block[0] = 0.0f;
            block[1] = static_cast<float>(i % 256) / 255.0f;
            block[2] = 1.0f;
            block[3] = 1.0f;
            list.set_bind_group(0, rhi::BindGroup{}.buffer(0, list.transient_uniforms_of(block)));
            list.draw(3);
        }
        list.end_render_pass();
    }));
    LOOM_VK_ASSIGN(rhi::Image image, device_->read_texture(target));
    EXPECT_EQ(static_cast<int>(image.texel(1, 1)[1]), 2999 % 256) << "the last draw's uniforms won";
    EXPECT_EQ(static_cast<int>(image.texel(1, 1)[2]), 255);
    EXPECT_EQ(device_->resource_stats().buffers, 0u) << "uniform rings are the backend's own";
}

TEST_F(VulkanDeviceTest, CapabilitiesComeFromTheDevice) {
    const rhi::Capabilities& caps = device_->capabilities();
    EXPECT_EQ(caps.backend, rhi::Backend::Vulkan);
    EXPECT_TRUE(caps.placed_resources);
    EXPECT_FALSE(caps.device_name.empty());
    // The device's own version: 1.3 on lavapipe 22.3, 1.4 on current NVIDIA drivers; loom needs 1.3.
    unsigned major = 0, minor = 0;
    ASSERT_EQ(std::sscanf(caps.api_version.c_str(), "Vulkan %u.%u", &major, &minor), 2) << caps.api_version;
    EXPECT_TRUE(major > 1 || (major == 1 && minor >= 3)) << caps.api_version;
    EXPECT_TRUE(caps.format(rhi::Format::RGBA8Unorm).color_attachment);
    EXPECT_TRUE(caps.format(rhi::Format::RGBA8Unorm).blendable);
    EXPECT_TRUE(caps.format(rhi::Format::Depth32F).depth_stencil_attachment);
    EXPECT_FALSE(caps.format(rhi::Format::Depth32F).color_attachment);
    EXPECT_FALSE(caps.format(rhi::Format::RGBA8Uint).blendable) << "integer formats never blend";
    EXPECT_FALSE(caps.format(rhi::Format::RGB9E5Float).color_attachment) << "shared-exponent formats are sample-only";
    EXPECT_GE(caps.max_color_attachments, 4u);
}

TEST(VulkanDeviceChoice, EnvironmentOverridePicksOrRejectsADevice) {
    const char* previous = std::getenv("LOOM_VK_DEVICE");
    const std::string saved = previous ? previous : "";
    rhi::DeviceDesc desc;
    desc.backend = rhi::Backend::Vulkan;
    std::string name;
    {
        auto device = rhi::create_device(desc);
        ASSERT_TRUE(device.ok()) << device.error().to_string();
        name = (*device)->capabilities().device_name;
    }
    // By a substring of its name, and by index 0 (there is at least one device).
    ::setenv("LOOM_VK_DEVICE", name.substr(0, 4).c_str(), 1);
    auto by_name = rhi::create_device(desc);
    ::setenv("LOOM_VK_DEVICE", "0", 1);
    auto by_index = rhi::create_device(desc);
    ::setenv("LOOM_VK_DEVICE", "no such gpu", 1);
    auto missing = rhi::create_device(desc);
    if (previous) {
        ::setenv("LOOM_VK_DEVICE", saved.c_str(), 1);
    } else {
        ::unsetenv("LOOM_VK_DEVICE");
    }
    ASSERT_TRUE(by_name.ok()) << by_name.error().to_string();
    EXPECT_EQ((*by_name)->capabilities().device_name, name);
    EXPECT_TRUE(by_index.ok()) << by_index.error().to_string();
    ASSERT_FALSE(missing.ok());
    EXPECT_EQ(missing.error().code, ErrorCode::Unsupported);
    EXPECT_NE(missing.error().message.find("no such gpu"), std::string::npos) << missing.error().message;
}

TEST_F(VulkanDeviceTest, WindowedDeviceWithoutDisplayFailsCleanly) {
    if (std::getenv("DISPLAY") || std::getenv("WAYLAND_DISPLAY")) GTEST_SKIP() << "a display is available";
    rhi::DeviceDesc desc;
    desc.backend = rhi::Backend::Vulkan;
    desc.headless = false;
    ScopedLogCapture capture;  // GLFW reports the missing display as a warning
    auto device = rhi::create_device(desc);
    ASSERT_FALSE(device.ok());
    EXPECT_EQ(device.error().code, ErrorCode::Unsupported) << device.error().to_string();
}

}  // namespace
}  // namespace loom::test
