#pragma once
// Embedding the Vulkan backend in an application that owns the Vulkan objects (an engine with
// its own instance, device, queue, command buffers and images). docs/embedding.md is the guide.
//
//   auto device = loom::vulkan::create_vulkan_device_on({instance, physical, vk_device, queue, family});
//   auto target = loom::vulkan::import_vulkan_image(**device, {"engine color", image, VK_FORMAT_R8G8B8A8_UNORM,
//                                                             w, h, 1, 1, usage, VK_IMAGE_LAYOUT_UNDEFINED});
//   // every frame, with the application's command buffer `cmd` begun:
//   rhi::CommandList& commands = **loom::vulkan::begin_external_frame(**device, cmd);
//   executor.import_texture(fg::port("compose", "out"), *target, rhi::ResourceState::CopySrc);
//   executor.execute(graph, commands, options);       // recorded into cmd
//   device->end_frame();                              // neither ends nor submits cmd
//   auto signal = *loom::vulkan::external_frame_signal(**device);
//   // the application ends cmd and submits it, signalling signal.semaphore to signal.value
//
// Requirements on the application's device: Vulkan 1.3 with the dynamicRendering and
// synchronization2 features enabled, and timelineSemaphore (Vulkan 1.2) for frames recorded
// into its command buffers; a queue family with graphics and compute. loom uses the queue for
// its own uploads and readbacks (from the thread calling loom; the application must not use
// the queue from another thread at the same time) and submits the frames it records itself
// (Device::begin_frame) there too. It never destroys the application's objects.

#include <cstdint>
#include <memory>
#include <string>

#include <vulkan/vulkan.h>

#include "loom/rhi/descriptions.hpp"
#include "loom/rhi/device.hpp"
#include "loom/rhi/result.hpp"

namespace loom::vulkan {

/// The application's Vulkan objects a device runs on. loom never destroys them; they must
/// outlive the device.
struct ExternalDeviceDesc {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    /// A queue of `queue_family`, which must support graphics and compute.
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queue_family = 0;
    /// The core features the application enabled on `device`; loom uses fillModeNonSolid,
    /// depthClamp, samplerAnisotropy and independentBlend only where they are set here.
    VkPhysicalDeviceFeatures enabled_features{};
    /// The instance has VK_EXT_debug_utils enabled: loom names its objects and labels its
    /// passes for validation messages and debuggers. Validation itself (the layer and a
    /// messenger) is the application's.
    bool debug_utils = false;
    /// loom's checks of recorded commands (rhi::DeviceDesc::validation).
    bool validation = true;
};

/// Creates a device on the application's Vulkan objects. Unsupported when the physical device
/// is older than Vulkan 1.3 or the queue family lacks graphics or compute; InvalidArgument for
/// null handles. The message says which.
Result<std::unique_ptr<rhi::Device>> create_vulkan_device_on(const ExternalDeviceDesc& desc);

/// Begins a frame recorded into the application's command buffer `cmd` (in the recording
/// state, outside a render pass). Use the returned command list as the one of
/// Device::begin_frame(); Device::end_frame() then finishes loom's recording without ending or
/// submitting `cmd`, and submits the uploads made for the frame so that they run first. The
/// application ends and submits `cmd` on the device's queue, signalling
/// external_frame_signal(); it submits before the next call into loom that submits work (the
/// next end_frame, read_texture/read_buffer, wait_idle). Errors: InvalidArgument (not an
/// external Vulkan device, null command buffer), InvalidState (a frame is already being
/// recorded).
Result<rhi::CommandList*> begin_external_frame(rhi::Device& device, VkCommandBuffer cmd);

/// What the application's submission of a frame must signal: the timeline semaphore and the
/// value to signal it to (in VkSubmitInfo2::pSignalSemaphoreInfos, stage ALL_COMMANDS). loom
/// reuses the frame's resources (descriptors, uniform memory, timer queries) once the value is
/// reached.
struct FrameSignal {
    VkSemaphore semaphore = VK_NULL_HANDLE;
    uint64_t value = 0;
};

/// The signal of the latest frame ended with Device::end_frame after begin_external_frame.
/// InvalidState before the first such frame.
Result<FrameSignal> external_frame_signal(rhi::Device& device);

/// One of the application's images, to be used as a loom texture.
struct ExternalImage {
    std::string name;  ///< shown in errors, plans and debuggers
    VkImage image = VK_NULL_HANDLE;
    /// Must be the VkFormat of a loom format (e.g. R8G8B8A8_UNORM, B8G8R8A8_SRGB, D32_SFLOAT).
    VkFormat format = VK_FORMAT_UNDEFINED;
    uint32_t width = 0;
    uint32_t height = 0;
    uint32_t mip_levels = 1;
    uint32_t array_layers = 1;  ///< more than one: a Tex2DArray
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
    /// The usage the image was created with: loom's texture usage (and so what loom may do
    /// with it, e.g. read_texture needs TRANSFER_SRC) follows from it.
    VkImageUsageFlags usage = 0;
    /// The layout every subresource is in now (see state_for_layout for those loom knows).
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
};

/// Wraps the application's image as a loom texture, e.g. to bind it to a graph port with
/// fg::Executor::import_texture(port, texture, final_state): loom then transitions it from its
/// current layout and leaves it in layout_for_state(final_state) after its last use in the
/// frame. Destroying the handle (Device::destroy) forgets the wrapper (and loom's image views,
/// once the GPU is done with them); the image stays the application's. Imported images are
/// not counted in Device::resource_stats(). Errors: InvalidArgument (not a Vulkan device, a
/// null image, no loom format for `format`, a size of 0), Unsupported (a layout loom has no
/// state for, a format the device cannot use that way).
Result<rhi::TextureHandle> import_vulkan_image(rhi::Device& device, const ExternalImage& image);

/// Tells loom that the application moved every subresource of an imported image to `layout`
/// (with its own barrier), between frames: loom's next barrier starts from there. InvalidState
/// while a frame is being recorded; Unsupported for a layout loom has no state for.
Status set_image_layout(rhi::Device& device, rhi::TextureHandle texture, VkImageLayout layout);

/// The layout loom left every subresource of a texture in (after the frames recorded so far).
/// InvalidState when the subresources are in different layouts.
Result<VkImageLayout> image_layout(rhi::Device& device, rhi::TextureHandle texture);

/// The VkImage behind a loom texture of a Vulkan device (created by loom or imported), e.g. to
/// copy loom's result in the application's own commands.
Result<VkImage> vulkan_image(rhi::Device& device, rhi::TextureHandle texture);

/// The loom state whose layout is `layout`: UNDEFINED, SHADER_READ_ONLY_OPTIMAL,
/// COLOR_ATTACHMENT_OPTIMAL, DEPTH_STENCIL_ATTACHMENT_OPTIMAL, DEPTH_STENCIL_READ_ONLY_OPTIMAL,
/// GENERAL (Storage), TRANSFER_SRC/DST_OPTIMAL, PRESENT_SRC_KHR. Unsupported for other layouts.
Result<rhi::ResourceState> state_for_layout(VkImageLayout layout);

/// The layout a texture is in in `state` (depth/stencil formats use the depth layouts).
VkImageLayout layout_for_state(rhi::ResourceState state, bool depth_stencil);

}  // namespace loom::vulkan
