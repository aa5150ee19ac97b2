#include "swapchain.hpp"

#include <algorithm>
#include <mutex>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "glfw_window_input.hpp"

#include "loom/rhi/log.hpp"
#include "loom/vulkan/context.hpp"

namespace loom::vulkan {
namespace {

// glfwInit/glfwTerminate are process-wide; count the windows that need GLFW.
std::mutex g_glfw_mutex;
int g_glfw_users = 0;

bool acquire_glfw(std::string& error) {
    std::lock_guard lock(g_glfw_mutex);
    if (g_glfw_users == 0) {
        glfwSetErrorCallback([](int code, const char* message) {
            loom::log_warning("vulkan", "GLFW error " + std::to_string(code) + ": " + (message ? message : ""));
        });
        if (!glfwInit()) {
            const char* description = nullptr;
            glfwGetError(&description);
            error = description ? description : "glfwInit failed";
            return false;
        }
    }
    ++g_glfw_users;
    return true;
}

void release_glfw() {
    std::lock_guard lock(g_glfw_mutex);
    if (--g_glfw_users == 0) glfwTerminate();
}

}  // namespace

loom::Result<std::unique_ptr<Window>> Window::create(const rhi::WindowDesc& desc) {
    std::string error;
    if (!acquire_glfw(error)) return Error{ErrorCode::Unsupported, "cannot open a window: " + error};
    if (!glfwVulkanSupported()) {
        release_glfw();
        return Error{ErrorCode::Unsupported, "cannot open a window: GLFW found no Vulkan loader with surface support"};
    }
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    glfwWindowHint(GLFW_RESIZABLE, desc.resizable ? GLFW_TRUE : GLFW_FALSE);
    GLFWwindow* window = glfwCreateWindow(static_cast<int>(desc.width), static_cast<int>(desc.height), desc.title.c_str(),
                                          nullptr, nullptr);
    if (!window) {
        release_glfw();
        return Error{ErrorCode::Unsupported, "cannot open a window '" + desc.title + "' (no display?)"};
    }
    std::unique_ptr<Window> out(new Window());
    out->window_ = window;
    out->input_ = std::make_unique<backends::GlfwWindowInput>();
    out->input_->attach(window);
    return out;
}

Window::~Window() {
    if (window_) {
        glfwDestroyWindow(window_);
        release_glfw();
    }
}

std::vector<std::string> Window::required_instance_extensions() {
    uint32_t count = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&count);
    std::vector<std::string> out;
    for (uint32_t i = 0; names && i < count; ++i) out.emplace_back(names[i]);
    return out;
}

loom::Result<VkSurfaceKHR> Window::create_surface(VkInstance instance) const {
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    if (VkResult r = glfwCreateWindowSurface(instance, window_, nullptr, &surface); r != VK_SUCCESS) {
        return vk_error(r, "glfwCreateWindowSurface");
    }
    return surface;
}

bool Window::poll() {
    glfwPollEvents();
    input_->publish();
    return !glfwWindowShouldClose(window_);
}

const rhi::WindowInput& Window::input() const { return input_->input(); }

rhi::Extent3D Window::framebuffer_size() const {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return {static_cast<uint32_t>(std::max(w, 0)), static_cast<uint32_t>(std::max(h, 0)), 1};
}

Swapchain::~Swapchain() {
    destroy_semaphores();
    if (swapchain_) vkDestroySwapchainKHR(context_.device(), swapchain_, nullptr);
}

void Swapchain::destroy_semaphores() {
    for (VkSemaphore s : render_finished_) vkDestroySemaphore(context_.device(), s, nullptr);
    render_finished_.clear();
}

loom::Status Swapchain::create(uint32_t width, uint32_t height) {
    VkPhysicalDevice gpu = context_.physical_device();
    VkSurfaceKHR surface = context_.surface();
    VkSurfaceCapabilitiesKHR caps{};
    if (VkResult r = vkGetPhysicalDeviceSurfaceCapabilitiesKHR(gpu, surface, &caps); r != VK_SUCCESS) {
        return vk_error(r, "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
    }
    uint32_t count = 0;
    vkGetPhysicalDeviceSurfaceFormatsKHR(gpu, surface, &count, nullptr);
    std::vector<VkSurfaceFormatKHR> formats(count);
    vkGetPhysicalDeviceSurfaceFormatsKHR(gpu, surface, &count, formats.data());
    if (formats.empty()) return Error{ErrorCode::Unsupported, "the window surface reports no formats"};
    // BGRA8 (linear) is what every desktop offers and what loom's samples write as PNG.
    VkSurfaceFormatKHR chosen = formats.front();
    for (const VkSurfaceFormatKHR& f : formats) {
        if (f.format == VK_FORMAT_B8G8R8A8_UNORM && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) chosen = f;
    }
    if (chosen.format == VK_FORMAT_B8G8R8A8_UNORM) {
        loom_format_ = rhi::Format::BGRA8Unorm;
    } else if (chosen.format == VK_FORMAT_R8G8B8A8_UNORM) {
        loom_format_ = rhi::Format::RGBA8Unorm;
    } else if (chosen.format == VK_FORMAT_B8G8R8A8_SRGB) {
        loom_format_ = rhi::Format::BGRA8Srgb;
    } else if (chosen.format == VK_FORMAT_R8G8B8A8_SRGB) {
        loom_format_ = rhi::Format::RGBA8Srgb;
    } else {
        return Error{ErrorCode::Unsupported, "the window surface offers no 8-bit RGBA/BGRA format"};
    }

    uint32_t mode_count = 0;
    vkGetPhysicalDeviceSurfacePresentModesKHR(gpu, surface, &mode_count, nullptr);
    std::vector<VkPresentModeKHR> modes(mode_count);
    vkGetPhysicalDeviceSurfacePresentModesKHR(gpu, surface, &mode_count, modes.data());
    VkPresentModeKHR mode = VK_PRESENT_MODE_FIFO_KHR;  // always supported
    if (!vsync_) {
        for (VkPresentModeKHR m : modes) {
            if (m == VK_PRESENT_MODE_MAILBOX_KHR || (m == VK_PRESENT_MODE_IMMEDIATE_KHR && mode != VK_PRESENT_MODE_MAILBOX_KHR)) mode = m;
        }
    }

    VkExtent2D extent = caps.currentExtent;
    if (extent.width == UINT32_MAX) {
        extent.width = std::clamp(width, caps.minImageExtent.width, caps.maxImageExtent.width);
        extent.height = std::clamp(height, caps.minImageExtent.height, caps.maxImageExtent.height);
    }
    uint32_t image_count = std::max(caps.minImageCount + 1, 2u);
    if (caps.maxImageCount > 0) image_count = std::min(image_count, caps.maxImageCount);

    auto info = vk_init<VkSwapchainCreateInfoKHR>(VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR);
    info.surface = surface;
    info.minImageCount = image_count;
    info.imageFormat = chosen.format;
    info.imageColorSpace = chosen.colorSpace;
    info.imageExtent = extent;
    info.imageArrayLayers = 1;
    info.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | (caps.supportedUsageFlags & (VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                                                                         VK_IMAGE_USAGE_TRANSFER_DST_BIT));
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = caps.currentTransform;
    info.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                              ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                              : static_cast<VkCompositeAlphaFlagBitsKHR>(caps.supportedCompositeAlpha & -caps.supportedCompositeAlpha);
    info.presentMode = mode;
    info.clipped = VK_TRUE;
    info.oldSwapchain = swapchain_;
    VkSwapchainKHR created = VK_NULL_HANDLE;
    if (VkResult r = vkCreateSwapchainKHR(context_.device(), &info, nullptr, &created); r != VK_SUCCESS) {
        return vk_error(r, "vkCreateSwapchainKHR");
    }
    if (swapchain_) vkDestroySwapchainKHR(context_.device(), swapchain_, nullptr);
    swapchain_ = created;
    format_ = chosen.format;
    extent_ = extent;

    vkGetSwapchainImagesKHR(context_.device(), swapchain_, &count, nullptr);
    images_.resize(count);
    vkGetSwapchainImagesKHR(context_.device(), swapchain_, &count, images_.data());
    destroy_semaphores();
    for (uint32_t i = 0; i < count; ++i) {
        auto si = vk_init<VkSemaphoreCreateInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO);
        VkSemaphore s = VK_NULL_HANDLE;
        if (VkResult r = vkCreateSemaphore(context_.device(), &si, nullptr, &s); r != VK_SUCCESS) return vk_error(r, "vkCreateSemaphore");
        render_finished_.push_back(s);
    }
    return {};
}

VkResult Swapchain::acquire(VkSemaphore signal, uint32_t& index) {
    return vkAcquireNextImageKHR(context_.device(), swapchain_, UINT64_MAX, signal, VK_NULL_HANDLE, &index);
}

VkResult Swapchain::present(VkQueue queue, uint32_t index) {
    auto info = vk_init<VkPresentInfoKHR>(VK_STRUCTURE_TYPE_PRESENT_INFO_KHR);
    info.waitSemaphoreCount = 1;
    info.pWaitSemaphores = &render_finished_[index];
    info.swapchainCount = 1;
    info.pSwapchains = &swapchain_;
    info.pImageIndices = &index;
    return vkQueuePresentKHR(queue, &info);
}

}  // namespace loom::vulkan
