#include "loom/vulkan/context.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <string>

#include "loom/rhi/log.hpp"
#include "loom/vulkan/vulkan_embed.hpp"

namespace loom::vulkan {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

// Validation warnings and errors fail tests, so both are logged as errors; the rest is noise
// kept at Debug.
VKAPI_ATTR VkBool32 VKAPI_CALL debug_callback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data, void* /*user*/) {
    std::string message;
    if (data->pMessageIdName) {
        message += data->pMessageIdName;
        message += ": ";
    }
    message += data->pMessage ? data->pMessage : "(no message)";
    const bool severe = (severity & (VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                     VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT)) != 0;
    loom::log(severe ? LogLevel::Error : LogLevel::Debug, "vulkan", message);
    return VK_FALSE;
}

VkDebugUtilsMessengerCreateInfoEXT messenger_info() {
    auto info = vk_init<VkDebugUtilsMessengerCreateInfoEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT);
    info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_VERBOSE_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_INFO_BIT_EXT |
                           VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    info.pfnUserCallback = debug_callback;
    return info;
}

bool has_layer(const char* name) {
    uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    return std::any_of(layers.begin(), layers.end(), [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

bool has_instance_extension(const char* layer, const char* name) {
    uint32_t count = 0;
    vkEnumerateInstanceExtensionProperties(layer, &count, nullptr);
    std::vector<VkExtensionProperties> exts(count);
    vkEnumerateInstanceExtensionProperties(layer, &count, exts.data());
    return std::any_of(exts.begin(), exts.end(), [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

bool env_is(const char* name, std::string_view value) {
    const char* v = std::getenv(name);
    return v != nullptr && std::string_view(v) == value;
}

// Discrete GPUs first, then integrated, virtual, CPU (lavapipe), other.
int device_type_rank(VkPhysicalDeviceType type) {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
        default: return 4;
    }
}

// A physical device loom can use and the queue family it would take.
struct Candidate {
    VkPhysicalDevice device;
    uint32_t index;
    uint32_t queue_family;
    VkPhysicalDeviceProperties properties;
};

}  // namespace

std::string_view vk_result_name(VkResult result) {
    switch (result) {
#define LOOM_VK_RESULT(name) case name: return #name;
        LOOM_VK_RESULT(VK_SUCCESS)
        LOOM_VK_RESULT(VK_NOT_READY)
        LOOM_VK_RESULT(VK_TIMEOUT)
        LOOM_VK_RESULT(VK_INCOMPLETE)
        LOOM_VK_RESULT(VK_SUBOPTIMAL_KHR)
        LOOM_VK_RESULT(VK_ERROR_OUT_OF_HOST_MEMORY)
        LOOM_VK_RESULT(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        LOOM_VK_RESULT(VK_ERROR_INITIALIZATION_FAILED)
        LOOM_VK_RESULT(VK_ERROR_DEVICE_LOST)
        LOOM_VK_RESULT(VK_ERROR_MEMORY_MAP_FAILED)
        LOOM_VK_RESULT(VK_ERROR_LAYER_NOT_PRESENT)
        LOOM_VK_RESULT(VK_ERROR_EXTENSION_NOT_PRESENT)
        LOOM_VK_RESULT(VK_ERROR_FEATURE_NOT_PRESENT)
        LOOM_VK_RESULT(VK_ERROR_INCOMPATIBLE_DRIVER)
        LOOM_VK_RESULT(VK_ERROR_TOO_MANY_OBJECTS)
        LOOM_VK_RESULT(VK_ERROR_FORMAT_NOT_SUPPORTED)
        LOOM_VK_RESULT(VK_ERROR_FRAGMENTED_POOL)
        LOOM_VK_RESULT(VK_ERROR_OUT_OF_POOL_MEMORY)
        LOOM_VK_RESULT(VK_ERROR_SURFACE_LOST_KHR)
        LOOM_VK_RESULT(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR)
        LOOM_VK_RESULT(VK_ERROR_OUT_OF_DATE_KHR)
#undef LOOM_VK_RESULT
        default: return "VkResult(unknown)";
    }
}

loom::Error vk_error(VkResult result, std::string_view what) {
    ErrorCode code = ErrorCode::Backend;
    if (result == VK_ERROR_DEVICE_LOST) code = ErrorCode::DeviceLost;
    if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY) code = ErrorCode::OutOfMemory;
    return Error{code, std::string(what) + " failed: " + std::string(vk_result_name(result))};
}

loom::Result<std::unique_ptr<VulkanContext>> VulkanContext::create(const ContextOptions& options) {
    std::unique_ptr<VulkanContext> context(new VulkanContext());
    LOOM_TRY(context->init(options));
    return context;
}

loom::Status VulkanContext::init(const ContextOptions& options) {
    LOOM_TRY(create_instance(options));
    if (options.create_surface) {
        auto surface = options.create_surface(instance_);
        if (!surface.ok()) return surface.take_error();
        surface_ = *surface;
    }
    LOOM_TRY(choose_physical_device());
    return create_logical_device();
}

// The instance with the validation layer, debug utils and synchronisation validation when
// asked for and installed.
loom::Status VulkanContext::create_instance(const ContextOptions& options) {
    uint32_t loader_version = 0;
    vkEnumerateInstanceVersion(&loader_version);
    if (loader_version < VK_API_VERSION_1_3) {
        return Error{ErrorCode::Unsupported, "the Vulkan loader supports only " +
                                                 std::to_string(VK_API_VERSION_MAJOR(loader_version)) + "." +
                                                 std::to_string(VK_API_VERSION_MINOR(loader_version)) + ", loom needs 1.3"};
    }

    std::vector<const char*> layers;
    std::vector<const char*> extensions;
    for (const std::string& e : options.instance_extensions) extensions.push_back(e.c_str());
    bool debug_utils = false;
    if (options.validation) {
        if (has_layer(kValidationLayer)) {
            layers.push_back(kValidationLayer);
            validation_enabled_ = true;
        } else {
            loom::log_warning("vulkan", "VK_LAYER_KHRONOS_validation is not installed; running without validation");
        }
    }
    if (options.validation && (has_instance_extension(nullptr, VK_EXT_DEBUG_UTILS_EXTENSION_NAME) ||
                               (validation_enabled_ && has_instance_extension(kValidationLayer, VK_EXT_DEBUG_UTILS_EXTENSION_NAME)))) {
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        debug_utils = true;
    }
    const bool want_sync = validation_enabled_ && options.synchronization_validation &&
                           !env_is("LOOM_VK_SYNC_VALIDATION", "0") &&
                           has_instance_extension(kValidationLayer, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
    if (want_sync) extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);

    auto app = vk_init<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
    app.pApplicationName = "loom";
    app.pEngineName = "loom";
    app.apiVersion = VK_API_VERSION_1_3;

    auto info = vk_init<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
    info.pApplicationInfo = &app;
    info.enabledLayerCount = static_cast<uint32_t>(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();

    // The messenger in the chain also reports problems of vkCreateInstance itself.
    VkDebugUtilsMessengerCreateInfoEXT messenger = messenger_info();
    const VkValidationFeatureEnableEXT sync_feature = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    auto features = vk_init<VkValidationFeaturesEXT>(VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT);
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = &sync_feature;
    if (debug_utils) {
        messenger.pNext = want_sync ? &features : nullptr;
        info.pNext = &messenger;
    } else if (want_sync) {
        info.pNext = &features;
    }
    sync_validation_enabled_ = want_sync;

    if (VkResult r = vkCreateInstance(&info, nullptr, &instance_); r != VK_SUCCESS) {
        if (r == VK_ERROR_INCOMPATIBLE_DRIVER) return Error{ErrorCode::Unsupported, "no Vulkan 1.3 driver found (vkCreateInstance: VK_ERROR_INCOMPATIBLE_DRIVER)"};
        return vk_error(r, "vkCreateInstance");
    }
    if (debug_utils) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
        VkDebugUtilsMessengerCreateInfoEXT m = messenger_info();
        if (create) create(instance_, &m, nullptr, &messenger_);
        load_debug_utils();
    }
    return {};
}

// The first Vulkan 1.3 device with a graphics+compute queue (that can present, with a surface),
// discrete GPUs first, or the one LOOM_VK_DEVICE names (index or part of the name).
loom::Status VulkanContext::choose_physical_device() {
    uint32_t count = 0;
    vkEnumeratePhysicalDevices(instance_, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    vkEnumeratePhysicalDevices(instance_, &count, devices.data());

    std::vector<Candidate> candidates;
    std::string rejected;
    for (uint32_t i = 0; i < count; ++i) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(devices[i], &props);
        if (props.apiVersion < VK_API_VERSION_1_3) {
            rejected += std::string(" ") + props.deviceName + " (Vulkan " + std::to_string(VK_API_VERSION_MAJOR(props.apiVersion)) +
                        "." + std::to_string(VK_API_VERSION_MINOR(props.apiVersion)) + ")";
            continue;
        }
        uint32_t qcount = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(devices[i], &qcount, nullptr);
        std::vector<VkQueueFamilyProperties> families(qcount);
        vkGetPhysicalDeviceQueueFamilyProperties(devices[i], &qcount, families.data());
        const VkQueueFlags needed = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
        for (uint32_t q = 0; q < qcount; ++q) {
            if ((families[q].queueFlags & needed) != needed) continue;
            if (surface_) {
                VkBool32 present = VK_FALSE;
                vkGetPhysicalDeviceSurfaceSupportKHR(devices[i], q, surface_, &present);
                if (!present) continue;
            }
            candidates.push_back({devices[i], i, q, props});
            break;
        }
    }
    if (candidates.empty()) {
        return Error{ErrorCode::Unsupported, "no Vulkan 1.3 device with a graphics+compute queue" +
                                                 std::string(surface_ ? " able to present to the window" : "") +
                                                 (rejected.empty() ? std::string() : "; rejected:" + rejected)};
    }
    std::stable_sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
        return device_type_rank(a.properties.deviceType) < device_type_rank(b.properties.deviceType);
    });
    const Candidate* chosen = &candidates.front();
    if (const char* wanted = std::getenv("LOOM_VK_DEVICE"); wanted && *wanted) {
        const std::string w = wanted;
        const Candidate* match = nullptr;
        for (const Candidate& c : candidates) {
            const bool by_index = std::all_of(w.begin(), w.end(), [](char ch) { return ch >= '0' && ch <= '9'; }) &&
                                  std::to_string(c.index) == w;
            if (by_index || std::string(c.properties.deviceName).find(w) != std::string::npos) {
                match = &c;
                break;
            }
        }
        if (!match) return Error{ErrorCode::Unsupported, "LOOM_VK_DEVICE=" + w + " matches no Vulkan 1.3 device"};
        chosen = match;
    }
    physical_device_ = chosen->device;
    queue_family_ = chosen->queue_family;
    query_device_properties();
    return {};
}

// The device with the features loom uses (those the physical device has) and its one queue.
loom::Status VulkanContext::create_logical_device() {
    VkPhysicalDeviceFeatures supported{};
    vkGetPhysicalDeviceFeatures(physical_device_, &supported);
    auto supported13 = vk_init<VkPhysicalDeviceVulkan13Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES);
    auto supported2 = vk_init<VkPhysicalDeviceFeatures2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2);
    supported2.pNext = &supported13;
    vkGetPhysicalDeviceFeatures2(physical_device_, &supported2);
    if (!supported13.dynamicRendering || !supported13.synchronization2) {
        return Error{ErrorCode::Unsupported, std::string(properties_.deviceName) + " lacks dynamicRendering or synchronization2"};
    }

    auto enable13 = vk_init<VkPhysicalDeviceVulkan13Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES);
    enable13.dynamicRendering = VK_TRUE;
    enable13.synchronization2 = VK_TRUE;
    auto enable = vk_init<VkPhysicalDeviceFeatures2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2);
    enable.pNext = &enable13;
    fill_mode_non_solid_ = supported.fillModeNonSolid;
    depth_clamp_ = supported.depthClamp;
    sampler_anisotropy_ = supported.samplerAnisotropy;
    independent_blend_ = supported.independentBlend;
    multi_draw_indirect_ = supported.multiDrawIndirect;
    draw_indirect_first_instance_ = supported.drawIndirectFirstInstance;
    enable.features.fillModeNonSolid = supported.fillModeNonSolid;
    enable.features.depthClamp = supported.depthClamp;
    enable.features.samplerAnisotropy = supported.samplerAnisotropy;
    enable.features.independentBlend = supported.independentBlend;
    enable.features.depthBiasClamp = supported.depthBiasClamp;
    enable.features.shaderStorageImageWriteWithoutFormat = supported.shaderStorageImageWriteWithoutFormat;
    enable.features.shaderStorageImageReadWithoutFormat = supported.shaderStorageImageReadWithoutFormat;
    // Storage images of formats beyond Vulkan's base set (r8, rg32f, r16f, ...), as GL 4.5 allows.
    enable.features.shaderStorageImageExtendedFormats = supported.shaderStorageImageExtendedFormats;
    enable.features.fragmentStoresAndAtomics = supported.fragmentStoresAndAtomics;
    enable.features.vertexPipelineStoresAndAtomics = supported.vertexPipelineStoresAndAtomics;
    enable.features.imageCubeArray = supported.imageCubeArray;
    enable.features.multiDrawIndirect = supported.multiDrawIndirect;
    enable.features.drawIndirectFirstInstance = supported.drawIndirectFirstInstance;

    // A second queue of the same family runs async compute beside the graphics queue: no
    // queue-ownership transfers are needed between queues of one family.
    uint32_t family_count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &family_count, nullptr);
    std::vector<VkQueueFamilyProperties> families(family_count);
    vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &family_count, families.data());
    const bool second_queue = families[queue_family_].queueCount >= 2 && !env_is("LOOM_VK_ASYNC_COMPUTE", "off");
    const std::array<float, 2> priorities{1.0f, 1.0f};
    auto queue_info = vk_init<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
    queue_info.queueFamilyIndex = queue_family_;
    queue_info.queueCount = second_queue ? 2 : 1;
    queue_info.pQueuePriorities = priorities.data();

    std::vector<const char*> device_extensions;
    if (surface_) device_extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);

    auto device_info = vk_init<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
    device_info.pNext = &enable;
    device_info.queueCreateInfoCount = 1;
    device_info.pQueueCreateInfos = &queue_info;
    device_info.enabledExtensionCount = static_cast<uint32_t>(device_extensions.size());
    device_info.ppEnabledExtensionNames = device_extensions.data();
    if (VkResult r = vkCreateDevice(physical_device_, &device_info, nullptr, &device_); r != VK_SUCCESS) {
        return vk_error(r, std::string("vkCreateDevice on ") + properties_.deviceName);
    }
    vkGetDeviceQueue(device_, queue_family_, 0, &queue_);
    compute_queue_ = queue_;
    if (second_queue) vkGetDeviceQueue(device_, queue_family_, 1, &compute_queue_);
    return {};
}

loom::Result<std::unique_ptr<VulkanContext>> VulkanContext::adopt(const ExternalDeviceDesc& desc) {
    if (!desc.instance || !desc.physical_device || !desc.device || !desc.queue) {
        return Error{ErrorCode::InvalidArgument,
                     "create_vulkan_device_on: instance, physical_device, device and queue must all be set"};
    }
    std::unique_ptr<VulkanContext> context(new VulkanContext());
    context->adopted_ = true;
    context->instance_ = desc.instance;
    context->physical_device_ = desc.physical_device;
    context->device_ = desc.device;
    context->queue_ = desc.queue;
    context->compute_queue_ = desc.queue;  // the application's one queue runs everything in order
    context->queue_family_ = desc.queue_family;
    context->query_device_properties();
    const VkPhysicalDeviceProperties& props = context->properties_;
    if (props.apiVersion < VK_API_VERSION_1_3) {
        return Error{ErrorCode::Unsupported, std::string(props.deviceName) + " supports Vulkan " +
                                                 std::to_string(VK_API_VERSION_MAJOR(props.apiVersion)) + "." +
                                                 std::to_string(VK_API_VERSION_MINOR(props.apiVersion)) + ", loom needs 1.3"};
    }
    uint32_t qcount = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(desc.physical_device, &qcount, nullptr);
    std::vector<VkQueueFamilyProperties> families(qcount);
    vkGetPhysicalDeviceQueueFamilyProperties(desc.physical_device, &qcount, families.data());
    const VkQueueFlags needed = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    if (desc.queue_family >= qcount || (families[desc.queue_family].queueFlags & needed) != needed) {
        return Error{ErrorCode::Unsupported, "queue family " + std::to_string(desc.queue_family) + " of " + props.deviceName +
                                                 " does not exist or lacks graphics and compute"};
    }
    context->fill_mode_non_solid_ = desc.enabled_features.fillModeNonSolid;
    context->depth_clamp_ = desc.enabled_features.depthClamp;
    context->sampler_anisotropy_ = desc.enabled_features.samplerAnisotropy;
    context->independent_blend_ = desc.enabled_features.independentBlend;
    context->multi_draw_indirect_ = desc.enabled_features.multiDrawIndirect;
    context->draw_indirect_first_instance_ = desc.enabled_features.drawIndirectFirstInstance;
    if (desc.debug_utils) context->load_debug_utils();
    return context;
}

void VulkanContext::query_device_properties() {
    vkGetPhysicalDeviceProperties(physical_device_, &properties_);
    vkGetPhysicalDeviceMemoryProperties(physical_device_, &memory_properties_);
    uint32_t qcount = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &qcount, nullptr);
    std::vector<VkQueueFamilyProperties> families(qcount);
    vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &qcount, families.data());
    timestamp_valid_bits_ = queue_family_ < qcount ? families[queue_family_].timestampValidBits : 0;
}

void VulkanContext::load_debug_utils() {
    set_object_name_ = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
        vkGetInstanceProcAddr(instance_, "vkSetDebugUtilsObjectNameEXT"));
    cmd_begin_label_ = reinterpret_cast<PFN_vkCmdBeginDebugUtilsLabelEXT>(
        vkGetInstanceProcAddr(instance_, "vkCmdBeginDebugUtilsLabelEXT"));
    cmd_end_label_ = reinterpret_cast<PFN_vkCmdEndDebugUtilsLabelEXT>(
        vkGetInstanceProcAddr(instance_, "vkCmdEndDebugUtilsLabelEXT"));
}

VulkanContext::~VulkanContext() {
    if (adopted_) return;  // the application's objects
    if (device_) vkDestroyDevice(device_, nullptr);
    if (surface_) vkDestroySurfaceKHR(instance_, surface_, nullptr);
    if (messenger_) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(instance_, messenger_, nullptr);
    }
    if (instance_) vkDestroyInstance(instance_, nullptr);
}

void VulkanContext::set_name(VkObjectType type, uint64_t handle, std::string_view name) const {
    if (!set_object_name_ || name.empty() || handle == 0) return;
    const std::string copy(name);
    auto info = vk_init<VkDebugUtilsObjectNameInfoEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT);
    info.objectType = type;
    info.objectHandle = handle;
    info.pObjectName = copy.c_str();
    set_object_name_(device_, &info);
}

void VulkanContext::begin_label(VkCommandBuffer cmd, std::string_view label) const {
    if (!cmd_begin_label_) return;
    const std::string copy(label);
    auto info = vk_init<VkDebugUtilsLabelEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT);
    info.pLabelName = copy.c_str();
    cmd_begin_label_(cmd, &info);
}

void VulkanContext::end_label(VkCommandBuffer cmd) const {
    if (cmd_end_label_) cmd_end_label_(cmd);
}

}  // namespace loom::vulkan
