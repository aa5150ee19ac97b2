#include "vulkan_app_device.hpp"

#include <cstring>
#include <vector>

#include "loom/rhi/log.hpp"

namespace loom::test {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

template <class T>
T init(VkStructureType type) {
    T value{};
    value.sType = type;
    return value;
}

VKAPI_ATTR VkBool32 VKAPI_CALL on_validation(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                             VkDebugUtilsMessageTypeFlagsEXT, const VkDebugUtilsMessengerCallbackDataEXT* data,
                                             void*) {
    // The test main fails the running test on any error logged.
    const bool severe =
        (severity & (VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT)) != 0;
    loom::log(severe ? LogLevel::Error : LogLevel::Debug, "vulkan (application's messenger)",
              data->pMessage ? data->pMessage : "(no message)");
    return VK_FALSE;
}

bool has_layer(const char* name) {
    uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    for (const auto& l : layers) {
        if (std::strcmp(l.layerName, name) == 0) return true;
    }
    return false;
}

}  // namespace

std::unique_ptr<AppVulkanDevice> AppVulkanDevice::create(std::string& error) {
    std::unique_ptr<AppVulkanDevice> app(new AppVulkanDevice());
    const bool validation = has_layer(kValidationLayer);
    std::vector<const char*> layers;
    std::vector<const char*> extensions{VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
    if (validation) {
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
    }
    auto app_info = init<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
    app_info.pApplicationName = "embedding test";
    app_info.apiVersion = VK_API_VERSION_1_3;
    auto messenger = init<VkDebugUtilsMessengerCreateInfoEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT);
    messenger.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                            VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messenger.pfnUserCallback = on_validation;
    const VkValidationFeatureEnableEXT sync = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    auto features = init<VkValidationFeaturesEXT>(VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT);
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = &sync;
    if (validation) messenger.pNext = &features;
    auto info = init<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
    info.pNext = &messenger;
    info.pApplicationInfo = &app_info;
    info.enabledLayerCount = static_cast<uint32_t>(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    if (vkCreateInstance(&info, nullptr, &app->instance_) != VK_SUCCESS) {
        error = "vkCreateInstance failed";
        return nullptr;
    }
    auto create_messenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(app->instance_, "vkCreateDebugUtilsMessengerEXT"));
    messenger.pNext = nullptr;  // the validation features belong to vkCreateInstance only
    create_messenger(app->instance_, &messenger, nullptr, &app->messenger_);

    uint32_t count = 0;
    vkEnumeratePhysicalDevices(app->instance_, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    vkEnumeratePhysicalDevices(app->instance_, &count, devices.data());
    for (VkPhysicalDevice candidate : devices) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(candidate, &props);
        if (props.apiVersion < VK_API_VERSION_1_3) continue;
        uint32_t families = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(candidate, &families, nullptr);
        std::vector<VkQueueFamilyProperties> family_props(families);
        vkGetPhysicalDeviceQueueFamilyProperties(candidate, &families, family_props.data());
        for (uint32_t f = 0; f < families; ++f) {
            if ((family_props[f].queueFlags & (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) ==
                (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) {
                app->physical_ = candidate;
                app->family_ = f;
                break;
            }
        }
        if (app->physical_) break;
    }
    if (!app->physical_) {
        error = "no Vulkan 1.3 device with a graphics and compute queue";
        return nullptr;
    }

    // The features loom needs, and the optional ones it uses where enabled.
    VkPhysicalDeviceFeatures supported{};
    vkGetPhysicalDeviceFeatures(app->physical_, &supported);
    app->features_.fillModeNonSolid = supported.fillModeNonSolid;
    app->features_.depthClamp = supported.depthClamp;
    app->features_.samplerAnisotropy = supported.samplerAnisotropy;
    app->features_.independentBlend = supported.independentBlend;
    auto enable13 = init<VkPhysicalDeviceVulkan13Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES);
    enable13.dynamicRendering = VK_TRUE;
    enable13.synchronization2 = VK_TRUE;
    auto enable12 = init<VkPhysicalDeviceVulkan12Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES);
    enable12.timelineSemaphore = VK_TRUE;
    enable12.pNext = &enable13;
    auto enable = init<VkPhysicalDeviceFeatures2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2);
    enable.pNext = &enable12;
    enable.features = app->features_;
    const float priority = 1.0f;
    auto queue = init<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
    queue.queueFamilyIndex = app->family_;
    queue.queueCount = 1;
    queue.pQueuePriorities = &priority;
    auto device_info = init<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
    device_info.pNext = &enable;
    device_info.queueCreateInfoCount = 1;
    device_info.pQueueCreateInfos = &queue;
    if (vkCreateDevice(app->physical_, &device_info, nullptr, &app->device_) != VK_SUCCESS) {
        error = "vkCreateDevice failed";
        return nullptr;
    }
    vkGetDeviceQueue(app->device_, app->family_, 0, &app->queue_);
    auto pool = init<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
    pool.queueFamilyIndex = app->family_;
    pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    vkCreateCommandPool(app->device_, &pool, nullptr, &app->pool_);
    auto fence = init<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
    vkCreateFence(app->device_, &fence, nullptr, &app->fence_);

    auto buffer = init<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
    buffer.size = kReadbackBytes;
    buffer.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    vkCreateBuffer(app->device_, &buffer, nullptr, &app->readback_);
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(app->device_, app->readback_, &req);
    auto alloc = init<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex =
        app->memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    vkAllocateMemory(app->device_, &alloc, nullptr, &app->readback_memory_);
    vkBindBufferMemory(app->device_, app->readback_, app->readback_memory_, 0);
    vkMapMemory(app->device_, app->readback_memory_, 0, VK_WHOLE_SIZE, 0, &app->readback_mapped_);
    return app;
}

AppVulkanDevice::~AppVulkanDevice() {
    if (device_) {
        vkDeviceWaitIdle(device_);
        vkDestroyBuffer(device_, readback_, nullptr);
        vkFreeMemory(device_, readback_memory_, nullptr);
        vkDestroyFence(device_, fence_, nullptr);
        vkDestroyCommandPool(device_, pool_, nullptr);
        vkDestroyDevice(device_, nullptr);
    }
    if (messenger_) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        destroy(instance_, messenger_, nullptr);
    }
    if (instance_) vkDestroyInstance(instance_, nullptr);
}

vulkan::ExternalDeviceDesc AppVulkanDevice::external_desc() const {
    vulkan::ExternalDeviceDesc desc;
    desc.instance = instance_;
    desc.physical_device = physical_;
    desc.device = device_;
    desc.queue = queue_;
    desc.queue_family = family_;
    desc.enabled_features = features_;
    desc.debug_utils = true;
    return desc;
}

uint32_t AppVulkanDevice::memory_type(uint32_t bits, VkMemoryPropertyFlags wanted) const {
    VkPhysicalDeviceMemoryProperties props;
    vkGetPhysicalDeviceMemoryProperties(physical_, &props);
    for (uint32_t i = 0; i < props.memoryTypeCount; ++i) {
        if ((bits & (1u << i)) && (props.memoryTypes[i].propertyFlags & wanted) == wanted) return i;
    }
    return 0;
}

AppVulkanDevice::Image AppVulkanDevice::create_image(uint32_t width, uint32_t height, VkFormat format, VkImageUsageFlags usage) {
    Image image;
    image.width = width;
    image.height = height;
    image.format = format;
    image.usage = usage;
    auto info = init<VkImageCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO);
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {width, height, 1};
    info.mipLevels = 1;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = usage;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    vkCreateImage(device_, &info, nullptr, &image.image);
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device_, image.image, &req);
    auto alloc = init<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    vkAllocateMemory(device_, &alloc, nullptr, &image.memory);
    vkBindImageMemory(device_, image.image, image.memory, 0);
    return image;
}

void AppVulkanDevice::destroy(Image& image) {
    vkDestroyImage(device_, image.image, nullptr);
    vkFreeMemory(device_, image.memory, nullptr);
    image = {};
}

vulkan::ExternalImage AppVulkanDevice::external(const Image& image, const std::string& name, VkImageLayout layout) {
    vulkan::ExternalImage out;
    out.name = name;
    out.image = image.image;
    out.format = image.format;
    out.width = image.width;
    out.height = image.height;
    out.usage = image.usage;
    out.layout = layout;
    return out;
}

VkCommandBuffer AppVulkanDevice::begin_commands() {
    auto info = init<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
    info.commandPool = pool_;
    info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    info.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    vkAllocateCommandBuffers(device_, &info, &cmd);
    auto begin = init<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkBeginCommandBuffer(cmd, &begin);
    return cmd;
}

void AppVulkanDevice::submit_and_wait(VkCommandBuffer cmd, const vulkan::FrameSignal* signal) {
    vkEndCommandBuffer(cmd);
    auto buffer = init<VkCommandBufferSubmitInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO);
    buffer.commandBuffer = cmd;
    auto signal_info = init<VkSemaphoreSubmitInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO);
    auto submit = init<VkSubmitInfo2>(VK_STRUCTURE_TYPE_SUBMIT_INFO_2);
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &buffer;
    if (signal) {
        signal_info.semaphore = signal->semaphore;
        signal_info.value = signal->value;
        signal_info.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        submit.signalSemaphoreInfoCount = 1;
        submit.pSignalSemaphoreInfos = &signal_info;
    }
    vkQueueSubmit2(queue_, 1, &submit, fence_);
    vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX);
    vkResetFences(device_, 1, &fence_);
    vkFreeCommandBuffers(device_, pool_, 1, &cmd);
}

void AppVulkanDevice::barrier(VkCommandBuffer cmd, const Image& image, VkImageLayout from, VkImageLayout to) {
    auto b = init<VkImageMemoryBarrier2>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2);
    b.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    b.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT | VK_ACCESS_2_MEMORY_READ_BIT;
    b.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    b.dstAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT | VK_ACCESS_2_MEMORY_READ_BIT;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image.image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    auto dep = init<VkDependencyInfo>(VK_STRUCTURE_TYPE_DEPENDENCY_INFO);
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &dep);
}

void AppVulkanDevice::clear(VkCommandBuffer cmd, const Image& image, const std::array<float, 4>& color) {
    VkClearColorValue value{};
    for (std::size_t i = 0; i < 4; ++i) value.float32[i] = color[i];
    const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &value, 1, &range);
}

void AppVulkanDevice::copy_to_readback(VkCommandBuffer cmd, const Image& image) {
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {image.width, image.height, 1};
    vkCmdCopyImageToBuffer(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_, 1, &region);
    auto b = init<VkMemoryBarrier2>(VK_STRUCTURE_TYPE_MEMORY_BARRIER_2);
    b.srcStageMask = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
    b.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    b.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
    b.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
    auto dep = init<VkDependencyInfo>(VK_STRUCTURE_TYPE_DEPENDENCY_INFO);
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &dep);
}

rhi::Image AppVulkanDevice::readback(const Image& image) const {
    rhi::Image out(image.width, image.height, rhi::Format::RGBA8Unorm);
    std::memcpy(out.pixels.data(), readback_mapped_, out.pixels.size());
    return out;
}

}  // namespace loom::test
