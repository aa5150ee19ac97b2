// loom on the application's Vulkan instance, device and queue: frames recorded into the
// application's command buffers and submitted by it, its images as graph resources handed back
// in the layout it asks for, loom's own frames and uploads on its queue, and the errors a user
// can make. The application's instance has validation and synchronisation validation on; any
// message fails the test.
#include <cstring>

#include <gtest/gtest.h>

#include "embed_test_support.hpp"
#include "loom/vulkan/vulkan_device.hpp"
#include "loom/vulkan/vulkan_embed.hpp"
#include "loom_test/test_support.hpp"
#include "vulkan_app_device.hpp"

namespace loom::test {
namespace {

constexpr uint32_t kWidth = 64;
constexpr uint32_t kHeight = 48;
constexpr VkImageUsageFlags kTargetUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                           VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
const std::array<float, 4> kClear{static_cast<float>(kEngineClear[0]), static_cast<float>(kEngineClear[1]),
                                  static_cast<float>(kEngineClear[2]), static_cast<float>(kEngineClear[3])};

class VulkanEmbed : public ::testing::Test {
protected:
    void SetUp() override {
        std::string error;
        app_ = AppVulkanDevice::create(error);
        ASSERT_TRUE(app_) << "the application's Vulkan device: " << error;
        auto device = vulkan::create_vulkan_device_on(app_->external_desc());
        ASSERT_TRUE(device.ok()) << device.error().to_string();
        device_ = std::move(*device);
    }
    void TearDown() override {
        if (device_) (void)device_->wait_idle();
        device_.reset();
        if (app_) {
            for (auto& image : images_) app_->destroy(image);
        }
        app_.reset();
    }

    AppVulkanDevice::Image& app_image(VkImageUsageFlags usage = kTargetUsage) {
        images_.push_back(app_->create_image(kWidth, kHeight, VK_FORMAT_R8G8B8A8_UNORM, usage));
        return images_.back();
    }

    /// One frame as an engine records it: its own clear of `image` (from the layout loom left
    /// it in), loom's overlay graph into the same command buffer, the image handed back in
    /// `final_state`, then the engine's own copy of it to its readback buffer. Returns the
    /// picture.
    rhi::Image engine_frame(fg::Executor& executor, OverlayGraph& overlay, const AppVulkanDevice::Image& image,
                            rhi::TextureHandle texture, rhi::ResourceState final_state) {
        auto layout = vulkan::image_layout(*device_, texture);
        EXPECT_TRUE(layout.ok()) << layout.error().to_string();
        VkCommandBuffer cmd = app_->begin_commands();
        AppVulkanDevice::barrier(cmd, image, *layout, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        AppVulkanDevice::clear(cmd, image, kClear);
        EXPECT_TRUE(vulkan::set_image_layout(*device_, texture, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL).ok());

        auto commands = vulkan::begin_external_frame(*device_, cmd);
        EXPECT_TRUE(commands.ok()) << commands.error().to_string();
        executor.import_texture(OverlayGraph::target_port(), texture, final_state);
        fg::PlanOptions options;
        options.frame = {kWidth, kHeight};
        const Status executed = executor.execute(overlay.graph(), **commands, options);
        EXPECT_TRUE(executed.ok()) << executed.error().to_string();
        const Status ended = device_->end_frame();
        EXPECT_TRUE(ended.ok()) << ended.error().to_string();

        // Handed back in the layout asked for: the engine's barrier starts from it (validation
        // reports a mismatch at submission).
        const VkImageLayout handed_back = vulkan::layout_for_state(final_state, false);
        auto reported = vulkan::image_layout(*device_, texture);
        EXPECT_TRUE(reported.ok() && *reported == handed_back);
        if (handed_back != VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL) {
            AppVulkanDevice::barrier(cmd, image, handed_back, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        }
        app_->copy_to_readback(cmd, image);
        if (handed_back != VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL) {
            AppVulkanDevice::barrier(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, handed_back);
        }
        auto signal = vulkan::external_frame_signal(*device_);
        EXPECT_TRUE(signal.ok()) << signal.error().to_string();
        app_->submit_and_wait(cmd, &*signal);
        return app_->readback(image);
    }

    std::unique_ptr<AppVulkanDevice> app_;
    std::unique_ptr<rhi::Device> device_;
    std::vector<AppVulkanDevice::Image> images_;
};

// Frames recorded into the application's command buffers, several in a row (so that loom
// reuses each frame's resources once the application's submission signalled them).
TEST_F(VulkanEmbed, FramesInApplicationCommandBuffers) {
    const auto& image = app_image();
    LOOM_EMBED_ASSIGN(const rhi::TextureHandle texture,
                      vulkan::import_vulkan_image(*device_, AppVulkanDevice::external(image, "engine target", VK_IMAGE_LAYOUT_UNDEFINED)));
    LOOM_EMBED_ASSIGN(auto overlay_graph, OverlayGraph::create(*device_, rhi::Format::RGBA8Unorm));
    OverlayGraph& overlay = *overlay_graph;
    fg::Executor executor(*device_);
    uint64_t last_signal = 0;
    for (int frame = 0; frame < 5; ++frame) {
        const rhi::Image picture = engine_frame(executor, overlay, image, texture, rhi::ResourceState::CopySrc);
        EXPECT_TRUE(matches_overlay(picture, "vulkan_external_frame_" + std::to_string(frame))) << "frame " << frame;
        LOOM_EMBED_ASSIGN(const vulkan::FrameSignal signal, vulkan::external_frame_signal(*device_));
        EXPECT_GT(signal.value, last_signal) << "every frame signals a new value";
        last_signal = signal.value;
    }
    // Only the pattern's texture is loom's.
    EXPECT_EQ(executor.stats().textures, 1u);
    EXPECT_EQ(device_->resource_stats().textures, 1u);
}

// The image is handed back in the layout of whatever final state the application asks for.
TEST_F(VulkanEmbed, ImagesAreHandedBackInTheLayoutAsked) {
    const auto& image = app_image(kTargetUsage | VK_IMAGE_USAGE_STORAGE_BIT);
    LOOM_EMBED_ASSIGN(const rhi::TextureHandle texture,
                      vulkan::import_vulkan_image(*device_, AppVulkanDevice::external(image, "engine target", VK_IMAGE_LAYOUT_UNDEFINED)));
    LOOM_EMBED_ASSIGN(auto overlay_graph, OverlayGraph::create(*device_, rhi::Format::RGBA8Unorm));
    OverlayGraph& overlay = *overlay_graph;
    fg::Executor executor(*device_);
    for (rhi::ResourceState state : {rhi::ResourceState::ShaderRead, rhi::ResourceState::RenderTarget,
                                     rhi::ResourceState::Storage, rhi::ResourceState::CopySrc, rhi::ResourceState::CopyDst}) {
        const rhi::Image picture = engine_frame(executor, overlay, image, texture, state);
        EXPECT_TRUE(matches_overlay(picture, "vulkan_layout_" + std::to_string(static_cast<int>(state))));
    }
    for (VkImageLayout layout : {VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                                 VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR}) {
        LOOM_EMBED_ASSIGN(const rhi::ResourceState state, vulkan::state_for_layout(layout));
        EXPECT_EQ(vulkan::layout_for_state(state, false), layout);
    }
}

// Uploads made while a frame is recorded into the application's command buffer run before it.
TEST_F(VulkanEmbed, UploadsRunBeforeTheApplicationsFrame) {
    const auto& image = app_image();
    LOOM_EMBED_ASSIGN(const rhi::TextureHandle target,
                      vulkan::import_vulkan_image(*device_, AppVulkanDevice::external(image, "engine target", VK_IMAGE_LAYOUT_UNDEFINED)));
    rhi::TextureDesc desc;
    desc.name = "uploaded";
    desc.width = kWidth;
    desc.height = kHeight;
    desc.usage = rhi::TextureUsage::Sampled | rhi::TextureUsage::CopySrc | rhi::TextureUsage::CopyDst;
    LOOM_EMBED_ASSIGN(const rhi::TextureHandle source, device_->create_texture(desc));
    for (uint8_t round = 1; round <= 3; ++round) {
        VkCommandBuffer cmd = app_->begin_commands();
        LOOM_EMBED_ASSIGN(rhi::CommandList * commands, vulkan::begin_external_frame(*device_, cmd));
        std::vector<std::byte> texels(std::size_t{kWidth} * kHeight * 4);
        for (std::size_t i = 0; i < texels.size(); ++i) texels[i] = static_cast<std::byte>((i * round + round) & 0xFF);
        LOOM_EMBED_OK(device_->write_texture(source, {}, texels));
        commands->copy_texture({source, {}, target, {}});
        commands->transition(target, rhi::ResourceState::CopySrc);
        LOOM_EMBED_OK(device_->end_frame());
        app_->copy_to_readback(cmd, image);
        LOOM_EMBED_ASSIGN(const vulkan::FrameSignal signal, vulkan::external_frame_signal(*device_));
        app_->submit_and_wait(cmd, &signal);
        const rhi::Image copied = app_->readback(image);
        EXPECT_EQ(0, std::memcmp(copied.pixels.data(), texels.data(), texels.size())) << "round " << int(round);
    }
}

// The same device also runs frames loom records and submits itself, on the application's
// queue, with readbacks.
TEST_F(VulkanEmbed, LoomsOwnFramesRunOnTheApplicationsQueue) {
    const auto& image = app_image();
    LOOM_EMBED_ASSIGN(const rhi::TextureHandle texture,
                      vulkan::import_vulkan_image(*device_, AppVulkanDevice::external(image, "engine target", VK_IMAGE_LAYOUT_UNDEFINED)));
    // The engine clears its image first, with its own commands.
    VkCommandBuffer cmd = app_->begin_commands();
    AppVulkanDevice::barrier(cmd, image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    AppVulkanDevice::clear(cmd, image, kClear);
    app_->submit_and_wait(cmd);
    LOOM_EMBED_OK(vulkan::set_image_layout(*device_, texture, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL));
    {
        LOOM_EMBED_ASSIGN(auto overlay_graph, OverlayGraph::create(*device_, rhi::Format::RGBA8Unorm));
        OverlayGraph& overlay = *overlay_graph;
        fg::Executor executor(*device_);
        executor.import_texture(OverlayGraph::target_port(), texture, rhi::ResourceState::ShaderRead);
        fg::PlanOptions options;
        options.frame = {kWidth, kHeight};
        LOOM_EMBED_OK(executor.run_frame(overlay.graph(), options));
        LOOM_EMBED_ASSIGN(const rhi::Image picture, device_->read_texture(texture));
        EXPECT_TRUE(matches_overlay(picture, "vulkan_own_frame"));
    }
    LOOM_EMBED_ASSIGN(const VkImageLayout layout, vulkan::image_layout(*device_, texture));
    EXPECT_EQ(layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    LOOM_EMBED_ASSIGN(const VkImage behind, vulkan::vulkan_image(*device_, texture));
    EXPECT_EQ(behind, image.image);
    // Forgetting the import leaves the image to the application (still valid: validation would
    // report a destroyed image used below).
    LOOM_EMBED_OK(device_->destroy(texture));
    LOOM_EMBED_OK(device_->wait_idle());
    cmd = app_->begin_commands();
    AppVulkanDevice::barrier(cmd, image, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    app_->copy_to_readback(cmd, image);
    app_->submit_and_wait(cmd);
    EXPECT_TRUE(matches_overlay(app_->readback(image), "vulkan_after_forget"));
}

TEST_F(VulkanEmbed, ErrorsSayWhatIsWrong) {
    auto expect_error = [](const auto& result, ErrorCode code, const std::string& needle) {
        ASSERT_FALSE(result.ok()) << "expected an error containing '" << needle << "'";
        EXPECT_EQ(result.error().code, code) << result.error().to_string();
        EXPECT_NE(result.error().message.find(needle), std::string::npos) << result.error().to_string();
    };
    const auto& image = app_image(VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT);
    expect_error(vulkan::external_frame_signal(*device_), ErrorCode::InvalidState, "no frame");
    vulkan::ExternalImage bad = AppVulkanDevice::external(image, "odd format", VK_IMAGE_LAYOUT_UNDEFINED);
    bad.format = VK_FORMAT_R8G8B8_UNORM;
    expect_error(vulkan::import_vulkan_image(*device_, bad), ErrorCode::InvalidArgument, "odd format");
    bad = AppVulkanDevice::external(image, "odd layout", VK_IMAGE_LAYOUT_PREINITIALIZED);
    expect_error(vulkan::import_vulkan_image(*device_, bad), ErrorCode::Unsupported, "odd layout");
    bad = AppVulkanDevice::external(image, "null", VK_IMAGE_LAYOUT_UNDEFINED);
    bad.image = VK_NULL_HANDLE;
    expect_error(vulkan::import_vulkan_image(*device_, bad), ErrorCode::InvalidArgument, "null");
    vulkan::ExternalDeviceDesc no_queue = app_->external_desc();
    no_queue.queue = VK_NULL_HANDLE;
    expect_error(vulkan::create_vulkan_device_on(no_queue), ErrorCode::InvalidArgument, "queue");

    LOOM_EMBED_ASSIGN(const rhi::TextureHandle texture,
                      vulkan::import_vulkan_image(*device_, AppVulkanDevice::external(image, "no transfer", VK_IMAGE_LAYOUT_UNDEFINED)));
    expect_error(device_->read_texture(texture), ErrorCode::InvalidArgument, "TRANSFER_SRC");
    expect_error(vulkan::begin_external_frame(*device_, VK_NULL_HANDLE), ErrorCode::InvalidArgument, "null");

    VkCommandBuffer cmd = app_->begin_commands();
    LOOM_EMBED_ASSIGN(rhi::CommandList * commands, vulkan::begin_external_frame(*device_, cmd));
    (void)commands;
    expect_error(vulkan::begin_external_frame(*device_, cmd), ErrorCode::InvalidState, "not ended");
    expect_error(vulkan::set_image_layout(*device_, texture, VK_IMAGE_LAYOUT_GENERAL), ErrorCode::InvalidState, "no transfer");
    rhi::TextureDesc desc;
    desc.name = "loom's";
    LOOM_EMBED_ASSIGN(const rhi::TextureHandle own, device_->create_texture(desc));
    expect_error(device_->read_texture(own), ErrorCode::InvalidState, "application's command buffer");
    LOOM_EMBED_OK(device_->end_frame());
    LOOM_EMBED_ASSIGN(const vulkan::FrameSignal signal, vulkan::external_frame_signal(*device_));
    app_->submit_and_wait(cmd, &signal);
    LOOM_EMBED_OK(device_->destroy(own));
    LOOM_EMBED_OK(device_->destroy(texture));

    // A device loom made itself records its own frames only.
    rhi::DeviceDesc own_desc;
    own_desc.backend = rhi::Backend::Vulkan;
    auto owned = vulkan::create_vulkan_device(own_desc);
    ASSERT_TRUE(owned.ok()) << owned.error().to_string();
    cmd = app_->begin_commands();
    expect_error(vulkan::begin_external_frame(**owned, cmd), ErrorCode::InvalidArgument, "create_vulkan_device_on");
    app_->submit_and_wait(cmd);
}

}  // namespace
}  // namespace loom::test
