#pragma once
// What an application brings to loom on Vulkan: its own instance (with the Khronos validation
// layer, synchronisation validation and a messenger that logs to loom::log, so that any
// validation message fails the test), device, queue, command buffers, images and buffers.

#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include <vulkan/vulkan.h>

#include "loom/rhi/image.hpp"
#include "loom/vulkan/vulkan_embed.hpp"

namespace loom::test {

/// The application's Vulkan objects (see the top of this file).
class AppVulkanDevice {
public:
    /// Null (with `error` set) when the machine has no Vulkan 1.3 device.
    static std::unique_ptr<AppVulkanDevice> create(std::string& error);
    ~AppVulkanDevice();
    AppVulkanDevice(const AppVulkanDevice&) = delete;
    AppVulkanDevice& operator=(const AppVulkanDevice&) = delete;

    /// What loom::vulkan::create_vulkan_device_on needs.
    [[nodiscard]] vulkan::ExternalDeviceDesc external_desc() const;
    [[nodiscard]] VkDevice device() const { return device_; }

    /// An image with its own memory, in layout UNDEFINED.
    struct Image {
        VkImage image = VK_NULL_HANDLE;
        VkDeviceMemory memory = VK_NULL_HANDLE;
        uint32_t width = 0, height = 0;
        VkFormat format = VK_FORMAT_UNDEFINED;
        VkImageUsageFlags usage = 0;
    };
    Image create_image(uint32_t width, uint32_t height, VkFormat format, VkImageUsageFlags usage);
    void destroy(Image& image);
    /// The description loom::vulkan::import_vulkan_image takes for `image` in `layout`.
    static vulkan::ExternalImage external(const Image& image, const std::string& name, VkImageLayout layout);

    /// A command buffer in the recording state.
    VkCommandBuffer begin_commands();
    /// Ends `cmd`, submits it (signalling `signal` when given) and waits for it.
    void submit_and_wait(VkCommandBuffer cmd, const vulkan::FrameSignal* signal = nullptr);

    /// Records a layout transition of the whole colour image (all earlier work before it).
    static void barrier(VkCommandBuffer cmd, const Image& image, VkImageLayout from, VkImageLayout to);
    /// Records a clear of the whole colour image (it must be in TRANSFER_DST_OPTIMAL).
    static void clear(VkCommandBuffer cmd, const Image& image, const std::array<float, 4>& color);
    /// Records a copy of the image (in TRANSFER_SRC_OPTIMAL) into the readback buffer.
    void copy_to_readback(VkCommandBuffer cmd, const Image& image);
    /// The readback buffer's contents after the copy's submission finished, as an RGBA8 image.
    [[nodiscard]] rhi::Image readback(const Image& image) const;

private:
    AppVulkanDevice() = default;
    uint32_t memory_type(uint32_t bits, VkMemoryPropertyFlags wanted) const;

    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t family_ = 0;
    VkPhysicalDeviceFeatures features_{};
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    VkBuffer readback_ = VK_NULL_HANDLE;
    VkDeviceMemory readback_memory_ = VK_NULL_HANDLE;
    void* readback_mapped_ = nullptr;
    static constexpr VkDeviceSize kReadbackBytes = 4u << 20;
};

}  // namespace loom::test
