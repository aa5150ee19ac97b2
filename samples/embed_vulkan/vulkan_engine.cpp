#include "vulkan_engine.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

namespace loom::samples {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

template <class T>
T init(VkStructureType type) {
    T value{};
    value.sType = type;
    return value;
}

Error vk_failed(const char* what, VkResult result) {
    return Error{ErrorCode::Backend, std::string(what) + " failed (VkResult " + std::to_string(static_cast<int>(result)) + ")"};
}

VKAPI_ATTR VkBool32 VKAPI_CALL on_validation(VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                                             const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    std::fprintf(stderr, "validation: %s\n", data->pMessage ? data->pMessage : "(no message)");
    ++*static_cast<int*>(user);
    return VK_FALSE;
}

bool has_layer(const char* name) {
    uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    return std::any_of(layers.begin(), layers.end(), [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

void image_barrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to, VkPipelineStageFlags2 src_stage,
                   VkAccessFlags2 src_access, VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access) {
    auto b = init<VkImageMemoryBarrier2>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2);
    b.srcStageMask = src_stage;
    b.srcAccessMask = src_access;
    b.dstStageMask = dst_stage;
    b.dstAccessMask = dst_access;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    auto dep = init<VkDependencyInfo>(VK_STRUCTURE_TYPE_DEPENDENCY_INFO);
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &dep);
}

}  // namespace

Result<std::unique_ptr<VulkanEngine>> VulkanEngine::create(bool window, uint32_t width, uint32_t height) {
    std::unique_ptr<VulkanEngine> engine(new VulkanEngine());
    std::vector<const char*> extensions;
    if (window) {
        if (!glfwInit() || !glfwVulkanSupported()) return Error{ErrorCode::Unsupported, "no window system with Vulkan support"};
        glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
        engine->window_ = glfwCreateWindow(static_cast<int>(width), static_cast<int>(height), "loom embedded in a Vulkan engine",
                                           nullptr, nullptr);
        if (!engine->window_) return Error{ErrorCode::Unsupported, "cannot open a window (is there a display?)"};
        uint32_t count = 0;
        const char** names = glfwGetRequiredInstanceExtensions(&count);
        extensions.assign(names, names + count);
    }

    // The instance, with validation (and synchronisation validation) when the layer is there.
    const bool validation = has_layer(kValidationLayer);
    std::vector<const char*> layers;
    if (validation) {
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
        engine->debug_utils_ = true;
    }
    auto app = init<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
    app.pApplicationName = "loom-embed-vulkan";
    app.apiVersion = VK_API_VERSION_1_3;
    auto messenger = init<VkDebugUtilsMessengerCreateInfoEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT);
    messenger.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
    messenger.pfnUserCallback = on_validation;
    messenger.pUserData = &engine->validation_errors_;
    const VkValidationFeatureEnableEXT sync = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    auto features = init<VkValidationFeaturesEXT>(VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT);
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = &sync;
    auto info = init<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
    if (validation) {
        messenger.pNext = &features;
        info.pNext = &messenger;
    }
    info.pApplicationInfo = &app;
    info.enabledLayerCount = static_cast<uint32_t>(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    if (VkResult r = vkCreateInstance(&info, nullptr, &engine->instance_); r != VK_SUCCESS) return vk_failed("vkCreateInstance", r);
    if (validation) {
        messenger.pNext = nullptr;
        auto create_messenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(engine->instance_, "vkCreateDebugUtilsMessengerEXT"));
        if (create_messenger) create_messenger(engine->instance_, &messenger, nullptr, &engine->messenger_);
    }
    if (window) {
        if (VkResult r = glfwCreateWindowSurface(engine->instance_, engine->window_, nullptr, &engine->surface_); r != VK_SUCCESS) {
            return vk_failed("glfwCreateWindowSurface", r);
        }
    }
    LOOM_TRY(engine->create_device());
    if (window) {
        LOOM_TRY(engine->create_swapchain());
    } else {
        LOOM_TRY(engine->create_offscreen(width, height));
    }
    return engine;
}

Status VulkanEngine::create_device() {
    uint32_t count = 0;
    vkEnumeratePhysicalDevices(instance_, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    vkEnumeratePhysicalDevices(instance_, &count, devices.data());
    for (VkPhysicalDevice candidate : devices) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(candidate, &props);
        if (props.apiVersion < VK_API_VERSION_1_3) continue;
        uint32_t families = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(candidate, &families, nullptr);
        std::vector<VkQueueFamilyProperties> family_props(families);
        vkGetPhysicalDeviceQueueFamilyProperties(candidate, &families, family_props.data());
        for (uint32_t f = 0; f < families && !physical_; ++f) {
            const VkQueueFlags needed = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
            if ((family_props[f].queueFlags & needed) != needed) continue;
            VkBool32 present = VK_TRUE;
            if (surface_) vkGetPhysicalDeviceSurfaceSupportKHR(candidate, f, surface_, &present);
            if (!present) continue;
            physical_ = candidate;
            family_ = f;
        }
        if (physical_) break;
    }
    if (!physical_) return Error{ErrorCode::Unsupported, "no Vulkan 1.3 device with a graphics, compute (and present) queue"};

    // What loom needs (dynamic rendering, synchronization2, timeline semaphores), plus the
    // optional features it uses where the engine enabled them.
    VkPhysicalDeviceFeatures supported{};
    vkGetPhysicalDeviceFeatures(physical_, &supported);
    features_.fillModeNonSolid = supported.fillModeNonSolid;
    features_.samplerAnisotropy = supported.samplerAnisotropy;
    features_.independentBlend = supported.independentBlend;
    auto enable13 = init<VkPhysicalDeviceVulkan13Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES);
    enable13.dynamicRendering = VK_TRUE;
    enable13.synchronization2 = VK_TRUE;
    auto enable12 = init<VkPhysicalDeviceVulkan12Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES);
    enable12.timelineSemaphore = VK_TRUE;
    enable12.pNext = &enable13;
    auto enable = init<VkPhysicalDeviceFeatures2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2);
    enable.pNext = &enable12;
    enable.features = features_;
    const float priority = 1.0f;
    auto queue = init<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
    queue.queueFamilyIndex = family_;
    queue.queueCount = 1;
    queue.pQueuePriorities = &priority;
    const char* swapchain_extension = VK_KHR_SWAPCHAIN_EXTENSION_NAME;
    auto info = init<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
    info.pNext = &enable;
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queue;
    info.enabledExtensionCount = surface_ ? 1 : 0;
    info.ppEnabledExtensionNames = &swapchain_extension;
    if (VkResult r = vkCreateDevice(physical_, &info, nullptr, &device_); r != VK_SUCCESS) return vk_failed("vkCreateDevice", r);
    vkGetDeviceQueue(device_, family_, 0, &queue_);

    auto pool = init<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
    pool.queueFamilyIndex = family_;
    pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    if (VkResult r = vkCreateCommandPool(device_, &pool, nullptr, &pool_); r != VK_SUCCESS) return vk_failed("vkCreateCommandPool", r);
    for (Slot& slot : slots_) {
        auto alloc = init<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
        alloc.commandPool = pool_;
        alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        alloc.commandBufferCount = 1;
        vkAllocateCommandBuffers(device_, &alloc, &slot.cmd);
        auto fence = init<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
        fence.flags = VK_FENCE_CREATE_SIGNALED_BIT;
        vkCreateFence(device_, &fence, nullptr, &slot.fence);
        auto semaphore = init<VkSemaphoreCreateInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO);
        vkCreateSemaphore(device_, &semaphore, nullptr, &slot.acquired);
    }
    return {};
}

Result<uint32_t> VulkanEngine::memory_type(uint32_t bits, VkMemoryPropertyFlags wanted) const {
    VkPhysicalDeviceMemoryProperties props;
    vkGetPhysicalDeviceMemoryProperties(physical_, &props);
    for (uint32_t i = 0; i < props.memoryTypeCount; ++i) {
        if ((bits & (1u << i)) && (props.memoryTypes[i].propertyFlags & wanted) == wanted) return i;
    }
    return Error{ErrorCode::Unsupported, "no suitable memory type"};
}

Status VulkanEngine::create_offscreen(uint32_t width, uint32_t height) {
    format_ = VK_FORMAT_R8G8B8A8_UNORM;
    usage_ = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
             VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    extent_ = {width, height};
    auto info = init<VkImageCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO);
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format_;
    info.extent = {width, height, 1};
    info.mipLevels = 1;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = usage_;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    if (VkResult r = vkCreateImage(device_, &info, nullptr, &offscreen_); r != VK_SUCCESS) return vk_failed("vkCreateImage", r);
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device_, offscreen_, &req);
    auto type = memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (!type) return type.take_error();
    auto alloc = init<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = *type;
    if (VkResult r = vkAllocateMemory(device_, &alloc, nullptr, &offscreen_memory_); r != VK_SUCCESS) {
        return vk_failed("vkAllocateMemory", r);
    }
    vkBindImageMemory(device_, offscreen_, offscreen_memory_, 0);
    images_ = {offscreen_};
    ++generation_;
    return {};
}

Status VulkanEngine::create_swapchain() {
    VkSurfaceCapabilitiesKHR caps;
    vkGetPhysicalDeviceSurfaceCapabilitiesKHR(physical_, surface_, &caps);
    uint32_t count = 0;
    vkGetPhysicalDeviceSurfaceFormatsKHR(physical_, surface_, &count, nullptr);
    std::vector<VkSurfaceFormatKHR> formats(count);
    vkGetPhysicalDeviceSurfaceFormatsKHR(physical_, surface_, &count, formats.data());
    // A unorm format, so that the engine's picture holds the values written.
    auto chosen = std::find_if(formats.begin(), formats.end(), [](const VkSurfaceFormatKHR& f) {
        return f.format == VK_FORMAT_B8G8R8A8_UNORM || f.format == VK_FORMAT_R8G8B8A8_UNORM;
    });
    if (chosen == formats.end()) return Error{ErrorCode::Unsupported, "the window offers no 8-bit unorm swapchain format"};
    format_ = chosen->format;
    usage_ = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    if ((caps.supportedUsageFlags & usage_) != usage_) {
        return Error{ErrorCode::Unsupported, "swapchain images cannot be cleared and copied (transfer usage)"};
    }
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    extent_ = caps.currentExtent.width != UINT32_MAX
                  ? caps.currentExtent
                  : VkExtent2D{std::clamp(static_cast<uint32_t>(w), caps.minImageExtent.width, caps.maxImageExtent.width),
                               std::clamp(static_cast<uint32_t>(h), caps.minImageExtent.height, caps.maxImageExtent.height)};
    auto info = init<VkSwapchainCreateInfoKHR>(VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR);
    info.surface = surface_;
    info.minImageCount = std::max(caps.minImageCount, 2u);
    if (caps.maxImageCount != 0) info.minImageCount = std::min(info.minImageCount, caps.maxImageCount);
    info.imageFormat = format_;
    info.imageColorSpace = chosen->colorSpace;
    info.imageExtent = extent_;
    info.imageArrayLayers = 1;
    info.imageUsage = usage_;
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = caps.currentTransform;
    info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    info.presentMode = VK_PRESENT_MODE_FIFO_KHR;
    info.clipped = VK_TRUE;
    if (VkResult r = vkCreateSwapchainKHR(device_, &info, nullptr, &swapchain_); r != VK_SUCCESS) {
        return vk_failed("vkCreateSwapchainKHR", r);
    }
    vkGetSwapchainImagesKHR(device_, swapchain_, &count, nullptr);
    images_.resize(count);
    vkGetSwapchainImagesKHR(device_, swapchain_, &count, images_.data());
    rendered_.resize(count);
    for (VkSemaphore& s : rendered_) {
        auto semaphore = init<VkSemaphoreCreateInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO);
        vkCreateSemaphore(device_, &semaphore, nullptr, &s);
    }
    ++generation_;
    swapchain_stale_ = false;
    return {};
}

void VulkanEngine::destroy_swapchain() {
    for (VkSemaphore s : rendered_) vkDestroySemaphore(device_, s, nullptr);
    rendered_.clear();
    if (swapchain_) vkDestroySwapchainKHR(device_, swapchain_, nullptr);
    swapchain_ = VK_NULL_HANDLE;
    images_.clear();
}

VulkanEngine::~VulkanEngine() {
    if (device_) {
        vkDeviceWaitIdle(device_);
        destroy_swapchain();
        if (offscreen_) vkDestroyImage(device_, offscreen_, nullptr);
        if (offscreen_memory_) vkFreeMemory(device_, offscreen_memory_, nullptr);
        if (readback_) vkDestroyBuffer(device_, readback_, nullptr);
        if (readback_memory_) vkFreeMemory(device_, readback_memory_, nullptr);
        for (Slot& slot : slots_) {
            vkDestroyFence(device_, slot.fence, nullptr);
            vkDestroySemaphore(device_, slot.acquired, nullptr);
        }
        vkDestroyCommandPool(device_, pool_, nullptr);
        vkDestroyDevice(device_, nullptr);
    }
    if (surface_) vkDestroySurfaceKHR(instance_, surface_, nullptr);
    if (messenger_) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(instance_, messenger_, nullptr);
    }
    if (instance_) vkDestroyInstance(instance_, nullptr);
    if (window_) {
        glfwDestroyWindow(window_);
        glfwTerminate();
    }
}

vulkan::ExternalDeviceDesc VulkanEngine::loom_desc() const {
    vulkan::ExternalDeviceDesc desc;
    desc.instance = instance_;
    desc.physical_device = physical_;
    desc.device = device_;
    desc.queue = queue_;
    desc.queue_family = family_;
    desc.enabled_features = features_;
    desc.debug_utils = debug_utils_;
    return desc;
}

bool VulkanEngine::poll() {
    if (!window_) return true;
    glfwPollEvents();
    return !glfwWindowShouldClose(window_);
}

Status VulkanEngine::recreate_swapchain(const std::function<void()>& before_images_change) {
    vkDeviceWaitIdle(device_);
    before_images_change();
    destroy_swapchain();
    return create_swapchain();
}

Result<VulkanEngine::Frame> VulkanEngine::begin_frame(const std::function<void()>& before_images_change) {
    Slot& slot = slots_[frame_ % kFramesInFlight];
    vkWaitForFences(device_, 1, &slot.fence, VK_TRUE, UINT64_MAX);
    Frame frame;
    frame.cmd = slot.cmd;
    if (window_) {
        int w = 0, h = 0;
        glfwGetFramebufferSize(window_, &w, &h);
        if (swapchain_stale_ || static_cast<uint32_t>(w) != extent_.width || static_cast<uint32_t>(h) != extent_.height) {
            LOOM_TRY(recreate_swapchain(before_images_change));
        }
        VkResult r = vkAcquireNextImageKHR(device_, swapchain_, UINT64_MAX, slot.acquired, VK_NULL_HANDLE, &frame.image_index);
        if (r == VK_ERROR_OUT_OF_DATE_KHR) {
            LOOM_TRY(recreate_swapchain(before_images_change));
            r = vkAcquireNextImageKHR(device_, swapchain_, UINT64_MAX, slot.acquired, VK_NULL_HANDLE, &frame.image_index);
        }
        if (r == VK_SUBOPTIMAL_KHR) {
            swapchain_stale_ = true;
        } else if (r != VK_SUCCESS) {
            return vk_failed("vkAcquireNextImageKHR", r);
        }
    }
    vkResetFences(device_, 1, &slot.fence);
    vkResetCommandBuffer(frame.cmd, 0);
    auto begin = init<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkBeginCommandBuffer(frame.cmd, &begin);
    // The engine's own rendering: a clear of the whole image (its old contents are not needed).
    const VkImage image = images_[frame.image_index];
    image_barrier(frame.cmd, image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_CLEAR_BIT,
                  VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkClearColorValue clear{};
    std::copy(kClearColor.begin(), kClearColor.end(), clear.float32);
    const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(frame.cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &clear, 1, &range);
    return frame;
}

Status VulkanEngine::end_frame(const Frame& frame, const vulkan::FrameSignal& signal, VkImageLayout layout, bool screenshot) {
    Slot& slot = slots_[frame_ % kFramesInFlight];
    const VkImage image = images_[frame.image_index];
    if (screenshot) {
        const VkDeviceSize size = VkDeviceSize{extent_.width} * extent_.height * 4;
        if (size > readback_size_) {
            vkDeviceWaitIdle(device_);
            if (readback_) vkDestroyBuffer(device_, readback_, nullptr);
            if (readback_memory_) vkFreeMemory(device_, readback_memory_, nullptr);
            auto info = init<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
            info.size = size;
            info.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
            vkCreateBuffer(device_, &info, nullptr, &readback_);
            VkMemoryRequirements req;
            vkGetBufferMemoryRequirements(device_, readback_, &req);
            auto type = memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
            if (!type) return type.take_error();
            auto alloc = init<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
            alloc.allocationSize = req.size;
            alloc.memoryTypeIndex = *type;
            vkAllocateMemory(device_, &alloc, nullptr, &readback_memory_);
            vkBindBufferMemory(device_, readback_, readback_memory_, 0);
            readback_size_ = size;
        }
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {extent_.width, extent_.height, 1};
        vkCmdCopyImageToBuffer(frame.cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_, 1, &region);
        readback_extent_ = extent_;
    }
    if (window_ && layout != VK_IMAGE_LAYOUT_PRESENT_SRC_KHR) {
        image_barrier(frame.cmd, image, layout, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                      VK_ACCESS_2_MEMORY_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_NONE);
    }
    vkEndCommandBuffer(frame.cmd);

    auto buffer = init<VkCommandBufferSubmitInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO);
    buffer.commandBuffer = frame.cmd;
    auto wait = init<VkSemaphoreSubmitInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO);
    wait.semaphore = slot.acquired;
    wait.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    std::array<VkSemaphoreSubmitInfo, 2> signals{};
    uint32_t signal_count = 0;
    // loom reuses the frame's resources once its timeline reaches the value.
    signals[signal_count] = init<VkSemaphoreSubmitInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO);
    signals[signal_count].semaphore = signal.semaphore;
    signals[signal_count].value = signal.value;
    signals[signal_count++].stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    if (window_) {
        signals[signal_count] = init<VkSemaphoreSubmitInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO);
        signals[signal_count].semaphore = rendered_[frame.image_index];
        signals[signal_count++].stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    }
    auto submit = init<VkSubmitInfo2>(VK_STRUCTURE_TYPE_SUBMIT_INFO_2);
    submit.waitSemaphoreInfoCount = window_ ? 1 : 0;
    submit.pWaitSemaphoreInfos = &wait;
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &buffer;
    submit.signalSemaphoreInfoCount = signal_count;
    submit.pSignalSemaphoreInfos = signals.data();
    if (VkResult r = vkQueueSubmit2(queue_, 1, &submit, slot.fence); r != VK_SUCCESS) return vk_failed("vkQueueSubmit2", r);
    ++frame_;
    if (window_) {
        auto present = init<VkPresentInfoKHR>(VK_STRUCTURE_TYPE_PRESENT_INFO_KHR);
        present.waitSemaphoreCount = 1;
        present.pWaitSemaphores = &rendered_[frame.image_index];
        present.swapchainCount = 1;
        present.pSwapchains = &swapchain_;
        present.pImageIndices = &frame.image_index;
        const VkResult r = vkQueuePresentKHR(queue_, &present);
        if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR) {
            swapchain_stale_ = true;
        } else if (r != VK_SUCCESS) {
            return vk_failed("vkQueuePresentKHR", r);
        }
    }
    return {};
}

Result<rhi::Image> VulkanEngine::screenshot() {
    if (!readback_) return Error{ErrorCode::InvalidState, "no screenshot was taken"};
    vkDeviceWaitIdle(device_);
    rhi::Image image(readback_extent_.width, readback_extent_.height, rhi::Format::RGBA8Unorm);
    void* mapped = nullptr;
    vkMapMemory(device_, readback_memory_, 0, VK_WHOLE_SIZE, 0, &mapped);
    std::memcpy(image.pixels.data(), mapped, image.pixels.size());
    vkUnmapMemory(device_, readback_memory_);
    if (format_ == VK_FORMAT_B8G8R8A8_UNORM) {
        for (std::size_t i = 0; i < image.pixels.size(); i += 4) std::swap(image.pixels[i], image.pixels[i + 2]);
    }
    return image;
}

}  // namespace loom::samples
