#pragma once
// The Vulkan instance, validation messenger, physical device choice and logical device: what
// every other part of the backend is built on. Public so that Vulkan-only tests can build an
// allocator or provoke a validation message on a real device.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <vulkan/vulkan.h>

#include "loom/rhi/result.hpp"

namespace loom::vulkan {

struct ExternalDeviceDesc;

/// How VulkanContext::create makes the instance and device.
struct ContextOptions {
    /// Enable VK_LAYER_KHRONOS_validation and route its messages to loom::log.
    bool validation = true;
    /// Enable synchronisation validation too (VK_EXT_validation_features), unless the
    /// LOOM_VK_SYNC_VALIDATION environment variable is "0".
    bool synchronization_validation = true;
    /// Instance extensions a window system needs (from glfwGetRequiredInstanceExtensions).
    std::vector<std::string> instance_extensions;
    /// Called once the instance exists, to create the window surface; the chosen queue
    /// family must be able to present to it, and VK_KHR_swapchain is enabled.
    std::function<loom::Result<VkSurfaceKHR>(VkInstance)> create_surface;
};

/// Owns VkInstance, the debug messenger, the surface (if any) and VkDevice with a queue that
/// does graphics, compute and transfer (and presentation when there is a surface), and a second
/// queue of its family for async compute where the family has two.
class VulkanContext {
public:
    /// Creates instance and device. Fails with Unsupported when no Vulkan 1.3 device exists.
    static loom::Result<std::unique_ptr<VulkanContext>> create(const ContextOptions& options);
    /// Wraps the application's instance, device and queue (loom/vulkan/vulkan_embed.hpp); the
    /// context then destroys nothing. Unsupported for a device older than 1.3 or a queue family
    /// without graphics and compute.
    static loom::Result<std::unique_ptr<VulkanContext>> adopt(const ExternalDeviceDesc& desc);
    ~VulkanContext();
    VulkanContext(const VulkanContext&) = delete;
    VulkanContext& operator=(const VulkanContext&) = delete;

    /// The instance.
    [[nodiscard]] VkInstance instance() const { return instance_; }
    /// The physical device chosen (or given).
    [[nodiscard]] VkPhysicalDevice physical_device() const { return physical_device_; }
    /// The logical device.
    [[nodiscard]] VkDevice device() const { return device_; }
    /// The queue loom submits to.
    [[nodiscard]] VkQueue queue() const { return queue_; }
    /// The family of queue().
    [[nodiscard]] uint32_t queue_family() const { return queue_family_; }
    /// The queue of CommandList::set_queue(QueueType::Compute): a second queue of queue()'s
    /// family when the family has one (and LOOM_VK_ASYNC_COMPUTE is not "off"), else queue()
    /// itself (lavapipe, adopted devices).
    [[nodiscard]] VkQueue compute_queue() const { return compute_queue_; }
    /// The window surface (null headless).
    [[nodiscard]] VkSurfaceKHR surface() const { return surface_; }
    /// Properties and limits of the physical device.
    [[nodiscard]] const VkPhysicalDeviceProperties& properties() const { return properties_; }
    /// Memory types and heaps of the physical device.
    [[nodiscard]] const VkPhysicalDeviceMemoryProperties& memory_properties() const { return memory_properties_; }
    /// Valid bits of timestamps on queue() (0: no timestamps).
    [[nodiscard]] uint32_t timestamp_valid_bits() const { return timestamp_valid_bits_; }
    /// True when loom enabled the validation layer.
    [[nodiscard]] bool validation_enabled() const { return validation_enabled_; }
    /// True when loom enabled synchronisation validation.
    [[nodiscard]] bool synchronization_validation_enabled() const { return sync_validation_enabled_; }
    /// True when VK_EXT_debug_utils is available for names and labels.
    [[nodiscard]] bool debug_utils() const { return set_object_name_ != nullptr; }
    /// True for the application's objects (adopt): validation and debug output are the
    /// application's, and nothing is destroyed with the context.
    [[nodiscard]] bool adopted() const { return adopted_; }
    /// Optional device features that were available and enabled.
    [[nodiscard]] bool fill_mode_non_solid() const { return fill_mode_non_solid_; }
    /// The depthClamp feature is enabled.
    [[nodiscard]] bool depth_clamp() const { return depth_clamp_; }
    /// The samplerAnisotropy feature is enabled.
    [[nodiscard]] bool sampler_anisotropy() const { return sampler_anisotropy_; }
    /// The independentBlend feature is enabled.
    [[nodiscard]] bool independent_blend() const { return independent_blend_; }
    /// Indirect draws of more than one command in one call (draw_indexed_indirect).
    [[nodiscard]] bool multi_draw_indirect() const { return multi_draw_indirect_; }
    /// Indirect draws may start at a first instance other than 0 (drawIndirectFirstInstance).
    [[nodiscard]] bool draw_indirect_first_instance() const { return draw_indirect_first_instance_; }

    /// Names an object for validation messages and debuggers (no-op without debug utils).
    void set_name(VkObjectType type, uint64_t handle, std::string_view name) const;
    /// Debug labels in a command buffer (no-op without debug utils).
    void begin_label(VkCommandBuffer cmd, std::string_view label) const;
    /// Ends the label begun last in `cmd`.
    void end_label(VkCommandBuffer cmd) const;

private:
    VulkanContext() = default;
    /// create_instance, the surface (if asked for), choose_physical_device, create_logical_device.
    loom::Status init(const ContextOptions& options);
    loom::Status create_instance(const ContextOptions& options);
    loom::Status choose_physical_device();
    loom::Status create_logical_device();
    /// Properties, memory properties and timestamp bits of the chosen device and queue family.
    void query_device_properties();
    /// The debug-utils entry points, once the instance has the extension.
    void load_debug_utils();

    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkSurfaceKHR surface_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    VkQueue compute_queue_ = VK_NULL_HANDLE;
    uint32_t queue_family_ = 0;
    uint32_t timestamp_valid_bits_ = 0;
    VkPhysicalDeviceProperties properties_{};
    VkPhysicalDeviceMemoryProperties memory_properties_{};
    bool validation_enabled_ = false;
    bool sync_validation_enabled_ = false;
    bool fill_mode_non_solid_ = false;
    bool depth_clamp_ = false;
    bool sampler_anisotropy_ = false;
    bool independent_blend_ = false;
    bool multi_draw_indirect_ = false;
    bool draw_indirect_first_instance_ = false;
    bool adopted_ = false;
    PFN_vkSetDebugUtilsObjectNameEXT set_object_name_ = nullptr;
    PFN_vkCmdBeginDebugUtilsLabelEXT cmd_begin_label_ = nullptr;
    PFN_vkCmdEndDebugUtilsLabelEXT cmd_end_label_ = nullptr;
};

/// A zeroed Vulkan structure with its sType set (`T x{sType}` would trip
/// -Wmissing-field-initializers).
template <class T>
constexpr T vk_init(VkStructureType type) {
    T value{};
    value.sType = type;
    return value;
}

/// "VK_ERROR_OUT_OF_DEVICE_MEMORY" etc.
std::string_view vk_result_name(VkResult result);

/// A Backend error (DeviceLost / OutOfMemory where they apply) for a failed Vulkan call.
loom::Error vk_error(VkResult result, std::string_view what);

}  // namespace loom::vulkan
