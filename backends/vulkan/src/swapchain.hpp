#pragma once
// A GLFW window without a GL context and the Vulkan swapchain presenting to it. The
// swapchain is recreated when presentation reports OUT_OF_DATE or SUBOPTIMAL, or when the
// framebuffer size changes.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "loom/rhi/device.hpp"
#include "loom/rhi/result.hpp"

struct GLFWwindow;
namespace loom::backends {
class GlfwWindowInput;
}

namespace loom::vulkan {

class VulkanContext;

/// A GLFW window made for Vulkan (GLFW_NO_API).
class Window {
public:
    static loom::Result<std::unique_ptr<Window>> create(const rhi::WindowDesc& desc);
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    /// Instance extensions the window system needs.
    [[nodiscard]] static std::vector<std::string> required_instance_extensions();
    loom::Result<VkSurfaceKHR> create_surface(VkInstance instance) const;
    /// Processes events; false once the user asked to close the window.
    bool poll();
    /// Framebuffer size in pixels (0x0 while minimised).
    [[nodiscard]] rhi::Extent3D framebuffer_size() const;
    /// The input as of the latest poll().
    [[nodiscard]] const rhi::WindowInput& input() const;

private:
    Window() = default;
    GLFWwindow* window_ = nullptr;
    std::unique_ptr<backends::GlfwWindowInput> input_;
};

class Swapchain {
public:
    Swapchain(VulkanContext& context, bool vsync) : context_(context), vsync_(vsync) {}
    ~Swapchain();
    Swapchain(const Swapchain&) = delete;
    Swapchain& operator=(const Swapchain&) = delete;

    /// (Re)creates the swapchain for a framebuffer of `width` x `height`; the device must be
    /// idle with respect to the old images.
    loom::Status create(uint32_t width, uint32_t height);

    /// Index of the next image, signalling `signal` when it is ready; VK_ERROR_OUT_OF_DATE_KHR
    /// when the swapchain must be recreated first.
    VkResult acquire(VkSemaphore signal, uint32_t& index);
    /// Presents image `index` after `wait`; returns the presentation result.
    VkResult present(VkQueue queue, uint32_t index);

    [[nodiscard]] const std::vector<VkImage>& images() const { return images_; }
    [[nodiscard]] VkFormat format() const { return format_; }
    [[nodiscard]] rhi::Format loom_format() const { return loom_format_; }
    [[nodiscard]] VkExtent2D extent() const { return extent_; }
    /// Semaphore signalled by the frame that renders image `index`, waited on by present.
    [[nodiscard]] VkSemaphore render_finished(uint32_t index) const { return render_finished_[index]; }

private:
    void destroy_semaphores();

    VulkanContext& context_;
    bool vsync_;
    VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
    std::vector<VkImage> images_;
    std::vector<VkSemaphore> render_finished_;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    rhi::Format loom_format_ = rhi::Format::BGRA8Unorm;
    VkExtent2D extent_{};
};

}  // namespace loom::vulkan
