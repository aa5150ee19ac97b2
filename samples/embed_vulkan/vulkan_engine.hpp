#pragma once
// The "engine" of loom-embed-vulkan: it owns the Vulkan instance (with the validation layer
// when installed), the device and queue, its command buffers, frames in flight and either a
// window with a swapchain (GLFW) or an offscreen render target. Each frame it clears the target
// with its own commands, lets loom record into the same command buffer, takes a screenshot when
// asked, and submits and presents itself (samples/embed_vulkan/main.cpp).

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <vulkan/vulkan.h>

#include "loom/rhi/image.hpp"
#include "loom/rhi/result.hpp"
#include "loom/vulkan/vulkan_embed.hpp"

struct GLFWwindow;

namespace loom::samples {

class VulkanEngine {
public:
    /// The engine's clear colour, exact in 8-bit unorm: (51, 102, 153, 255).
    static constexpr std::array<float, 4> kClearColor{0.2f, 0.4f, 0.6f, 1.0f};

    /// Instance, device and queue, and a window of width x height with its swapchain (`window`)
    /// or an offscreen RGBA8 target of that size. Unsupported when no Vulkan 1.3 device (or no
    /// window system) is there.
    static Result<std::unique_ptr<VulkanEngine>> create(bool window, uint32_t width, uint32_t height);
    ~VulkanEngine();
    VulkanEngine(const VulkanEngine&) = delete;
    VulkanEngine& operator=(const VulkanEngine&) = delete;

    /// What loom::vulkan::create_vulkan_device_on needs.
    [[nodiscard]] vulkan::ExternalDeviceDesc loom_desc() const;
    /// The application images loom may draw into (the swapchain images, or the one offscreen
    /// target); they change when the swapchain is recreated (generation() then changes).
    [[nodiscard]] const std::vector<VkImage>& images() const { return images_; }
    [[nodiscard]] uint64_t generation() const { return generation_; }
    [[nodiscard]] VkFormat format() const { return format_; }
    [[nodiscard]] VkImageUsageFlags image_usage() const { return usage_; }
    [[nodiscard]] VkExtent2D extent() const { return extent_; }
    [[nodiscard]] bool windowed() const { return window_ != nullptr; }
    /// Validation messages at warning or error severity so far.
    [[nodiscard]] int validation_errors() const { return validation_errors_; }

    /// Processes window events; false once the window was closed (always true headless).
    bool poll();

    /// One frame of the engine: the command buffer (recording) and the image it renders to.
    struct Frame {
        VkCommandBuffer cmd = VK_NULL_HANDLE;
        uint32_t image_index = 0;
    };
    /// Waits for the frame slot, acquires the next image (recreating the swapchain when it is
    /// out of date or the window was resized: `before_images_change` runs first, for whoever
    /// holds the old images), begins the command buffer and records the engine's clear of the
    /// image, which is then in TRANSFER_DST_OPTIMAL.
    Result<Frame> begin_frame(const std::function<void()>& before_images_change);
    /// With `screenshot`, copies the image (which loom left in TRANSFER_SRC_OPTIMAL) to the
    /// readback buffer; then moves a swapchain image from `layout` to PRESENT_SRC_KHR, ends the
    /// command buffer and submits it, signalling loom's `signal`, and presents.
    Status end_frame(const Frame& frame, const vulkan::FrameSignal& signal, VkImageLayout layout, bool screenshot);
    /// Waits for the GPU and returns the last screenshot as RGBA8 (rows top-first).
    Result<rhi::Image> screenshot();

private:
    VulkanEngine() = default;
    Status create_device();
    Status create_swapchain();
    /// Waits for the GPU and replaces the swapchain (after `before_images_change`).
    Status recreate_swapchain(const std::function<void()>& before_images_change);
    void destroy_swapchain();
    Status create_offscreen(uint32_t width, uint32_t height);
    Result<uint32_t> memory_type(uint32_t bits, VkMemoryPropertyFlags wanted) const;

    static constexpr uint32_t kFramesInFlight = 2;

    GLFWwindow* window_ = nullptr;
    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    bool debug_utils_ = false;
    VkSurfaceKHR surface_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t family_ = 0;
    VkPhysicalDeviceFeatures features_{};
    VkCommandPool pool_ = VK_NULL_HANDLE;
    struct Slot {
        VkCommandBuffer cmd = VK_NULL_HANDLE;
        VkFence fence = VK_NULL_HANDLE;
        VkSemaphore acquired = VK_NULL_HANDLE;
    };
    std::array<Slot, kFramesInFlight> slots_{};
    uint64_t frame_ = 0;

    VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
    std::vector<VkSemaphore> rendered_;  ///< per swapchain image, waited on by present
    bool swapchain_stale_ = false;
    VkImage offscreen_ = VK_NULL_HANDLE;
    VkDeviceMemory offscreen_memory_ = VK_NULL_HANDLE;
    std::vector<VkImage> images_;
    uint64_t generation_ = 0;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    VkImageUsageFlags usage_ = 0;
    VkExtent2D extent_{};

    VkBuffer readback_ = VK_NULL_HANDLE;
    VkDeviceMemory readback_memory_ = VK_NULL_HANDLE;
    VkDeviceSize readback_size_ = 0;
    VkExtent2D readback_extent_{};

    int validation_errors_ = 0;
};

}  // namespace loom::samples
