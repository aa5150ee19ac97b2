// Embedding: a device on the application's Vulkan objects, frames recorded into the
// application's command buffers, and the application's images as loom textures
// (loom/vulkan/vulkan_embed.hpp).
#include "formats.hpp"
#include "vulkan_device.hpp"
#include "loom/rhi/validation.hpp"

namespace loom::vulkan {

using rhi::ResourceState;

namespace {

using rhi::validation::in_quotes;

loom::Result<VulkanDevice*> as_vulkan_device(rhi::Device& device, std::string_view what) {
    auto* vk = dynamic_cast<VulkanDevice*>(&device);
    if (!vk) {
        return Error{ErrorCode::InvalidArgument, std::string(what) + ": the device is a " +
                                                     std::string(rhi::backend_name(device.backend())) +
                                                     " device, not a Vulkan one"};
    }
    return vk;
}

std::string layout_name(VkImageLayout layout) {
    switch (layout) {
        case VK_IMAGE_LAYOUT_UNDEFINED: return "UNDEFINED";
        case VK_IMAGE_LAYOUT_GENERAL: return "GENERAL";
        case VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL: return "COLOR_ATTACHMENT_OPTIMAL";
        case VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL: return "DEPTH_STENCIL_ATTACHMENT_OPTIMAL";
        case VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL: return "DEPTH_STENCIL_READ_ONLY_OPTIMAL";
        case VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL: return "SHADER_READ_ONLY_OPTIMAL";
        case VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL: return "TRANSFER_SRC_OPTIMAL";
        case VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL: return "TRANSFER_DST_OPTIMAL";
        case VK_IMAGE_LAYOUT_PRESENT_SRC_KHR: return "PRESENT_SRC_KHR";
        default: return "VkImageLayout " + std::to_string(static_cast<int>(layout));
    }
}

/// The loom format whose VkFormat is `format`.
std::optional<rhi::Format> from_vk_format(VkFormat format) {
    for (rhi::Format f : rhi::all_formats()) {
        if (to_vk_format(f) == format) return f;
    }
    return std::nullopt;
}

rhi::TextureUsage usage_from_vk(VkImageUsageFlags usage) {
    rhi::TextureUsage out = rhi::TextureUsage::None;
    if (usage & VK_IMAGE_USAGE_SAMPLED_BIT) out |= rhi::TextureUsage::Sampled;
    if (usage & VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT) out |= rhi::TextureUsage::ColorAttachment;
    if (usage & VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT) out |= rhi::TextureUsage::DepthStencilAttachment;
    if (usage & VK_IMAGE_USAGE_STORAGE_BIT) out |= rhi::TextureUsage::Storage;
    if (usage & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) out |= rhi::TextureUsage::CopySrc;
    if (usage & VK_IMAGE_USAGE_TRANSFER_DST_BIT) out |= rhi::TextureUsage::CopyDst;
    return out;
}

}  // namespace

// ---- free functions ----------------------------------------------------------------------------

loom::Result<std::unique_ptr<rhi::Device>> create_vulkan_device_on(const ExternalDeviceDesc& desc) {
    return VulkanDevice::create_external(desc);
}

loom::Result<rhi::CommandList*> begin_external_frame(rhi::Device& device, VkCommandBuffer cmd) {
    auto vk = as_vulkan_device(device, "begin_external_frame");
    if (!vk.ok()) return vk.take_error();
    return (*vk)->begin_external_frame(cmd);
}

loom::Result<FrameSignal> external_frame_signal(rhi::Device& device) {
    auto vk = as_vulkan_device(device, "external_frame_signal");
    if (!vk.ok()) return vk.take_error();
    return (*vk)->external_frame_signal();
}

loom::Result<rhi::TextureHandle> import_vulkan_image(rhi::Device& device, const ExternalImage& image) {
    auto vk = as_vulkan_device(device, "import_vulkan_image of " + in_quotes(image.name));
    if (!vk.ok()) return vk.take_error();
    return (*vk)->import_image(image);
}

loom::Status set_image_layout(rhi::Device& device, rhi::TextureHandle texture, VkImageLayout layout) {
    auto vk = as_vulkan_device(device, "set_image_layout");
    if (!vk.ok()) return vk.take_error();
    return (*vk)->set_image_layout(texture, layout);
}

loom::Result<VkImageLayout> image_layout(rhi::Device& device, rhi::TextureHandle texture) {
    auto vk = as_vulkan_device(device, "image_layout");
    if (!vk.ok()) return vk.take_error();
    return (*vk)->image_layout(texture);
}

loom::Result<VkImage> vulkan_image(rhi::Device& device, rhi::TextureHandle texture) {
    auto vk = as_vulkan_device(device, "vulkan_image");
    if (!vk.ok()) return vk.take_error();
    return (*vk)->image(texture);
}

loom::Result<ResourceState> state_for_layout(VkImageLayout layout) {
    switch (layout) {
        case VK_IMAGE_LAYOUT_UNDEFINED: return ResourceState::Undefined;
        case VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL: return ResourceState::ShaderRead;
        case VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL: return ResourceState::RenderTarget;
        case VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL: return ResourceState::DepthWrite;
        case VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL: return ResourceState::DepthRead;
        case VK_IMAGE_LAYOUT_GENERAL: return ResourceState::Storage;
        case VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL: return ResourceState::CopySrc;
        case VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL: return ResourceState::CopyDst;
        case VK_IMAGE_LAYOUT_PRESENT_SRC_KHR: return ResourceState::Present;
        default:
            return Error{ErrorCode::Unsupported, "image layout " + layout_name(layout) +
                                                     " is none of the layouts loom's resource states use"};
    }
}

VkImageLayout layout_for_state(ResourceState state, bool depth_stencil) {
    return texture_state_access(state, depth_stencil).layout;
}

// ---- frames in application command buffers -----------------------------------------------------

loom::Result<rhi::CommandList*> VulkanDevice::begin_external_frame(VkCommandBuffer cmd) {
    if (!context_->adopted()) {
        return Error{ErrorCode::InvalidArgument,
                     "begin_external_frame: the device was not made with create_vulkan_device_on (it owns its frames)"};
    }
    if (cmd == VK_NULL_HANDLE) return Error{ErrorCode::InvalidArgument, "begin_external_frame: the command buffer is null"};
    LOOM_TRY(command_list_->state().check_begin_frame("begin_external_frame"));
    if (!frame_timeline_) {
        auto type = vk_init<VkSemaphoreTypeCreateInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO);
        type.semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE;
        type.initialValue = 0;
        auto info = vk_init<VkSemaphoreCreateInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO);
        info.pNext = &type;
        if (VkResult r = vkCreateSemaphore(context_->device(), &info, nullptr, &frame_timeline_); r != VK_SUCCESS) {
            return vk_error(r, "vkCreateSemaphore (timeline of the application's frames; needs the timelineSemaphore feature)");
        }
        context_->set_name(VK_OBJECT_TYPE_SEMAPHORE, reinterpret_cast<uint64_t>(frame_timeline_), "loom frames");
    }
    // A frame two frames ago that the application never submitted is an error, not a hang.
    LOOM_TRY(recycle_current_slot());
    external_frame_ = true;
    command_list_->state().begin_frame();
    FrameSlot& slot = current_frame();
    if (slot.timestamps) vkCmdResetQueryPool(cmd, slot.timestamps, 0, 2 * kMaxTimersPerFrame);
    command_list_->begin(cmd, true);
    if (slot.timestamps) command_list_->count_api_calls(1);
    return static_cast<rhi::CommandList*>(command_list_.get());
}

loom::Status VulkanDevice::end_external_frame() {
    command_list_->finish();
    FrameSlot& slot = current_frame();
    // Uploads made for this frame run before it: submitted now, ahead of the application's
    // submission of the frame.
    Status result = flush_setup();
    slot.serial = submissions_->add_external(frame_timeline_, ++frame_timeline_value_);
    ++epoch_;
    slot.timers_pending = true;
    command_list_->state().end_frame();
    external_frame_ = false;
    last_frame_stats_ = command_list_->stats();
    last_frame_stats_.bytes_uploaded += bytes_uploaded_;
    bytes_uploaded_ = 0;
    ++frame_index_;
    if (auto error = command_list_->take_error()) return *error;
    return result;
}

loom::Result<FrameSignal> VulkanDevice::external_frame_signal() const {
    if (frame_timeline_value_ == 0) {
        return Error{ErrorCode::InvalidState, "external_frame_signal: no frame recorded into an application command buffer "
                                              "has been ended yet"};
    }
    return FrameSignal{frame_timeline_, frame_timeline_value_};
}

// ---- application images --------------------------------------------------------------------------

loom::Result<rhi::TextureHandle> VulkanDevice::import_image(const ExternalImage& image) {
    const std::string what = "import_vulkan_image of " + in_quotes(image.name) + ": ";
    if (image.image == VK_NULL_HANDLE) return Error{ErrorCode::InvalidArgument, what + "the image is null"};
    const std::optional<rhi::Format> format = from_vk_format(image.format);
    if (!format) {
        return Error{ErrorCode::InvalidArgument, what + "VkFormat " + std::to_string(static_cast<int>(image.format)) +
                                                     " is the format of no loom texture format"};
    }
    auto state = state_for_layout(image.layout);
    if (!state.ok()) return Error{ErrorCode::Unsupported, what + state.error().message};

    Texture t;
    t.desc.name = image.name;
    t.desc.dimension = image.array_layers > 1 ? rhi::TextureDimension::Tex2DArray : rhi::TextureDimension::Tex2D;
    t.desc.format = *format;
    t.desc.width = image.width;
    t.desc.height = image.height;
    t.desc.depth_or_layers = image.array_layers;
    t.desc.mip_levels = image.mip_levels;
    t.desc.samples = static_cast<uint32_t>(image.samples);
    t.desc.usage = usage_from_vk(image.usage);
    LOOM_TRY(rhi::validation::texture_desc(t.desc, caps_));
    t.image = image.image;
    t.format = image.format;
    t.aspect = aspect_mask(image.format);
    t.depth_stencil = rhi::format_info(*format).is_depth_stencil();
    t.array_layers = image.array_layers;
    t.imported = true;
    if (image.usage & VK_IMAGE_USAGE_SAMPLED_BIT) {
        auto vi = vk_init<VkImageViewCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO);
        vi.image = t.image;
        vi.viewType = image.array_layers > 1 ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
        vi.format = t.format;
        // A sampler reads one aspect: depth for depth(/stencil) formats.
        VkImageAspectFlags aspect = t.aspect;
        if (aspect & VK_IMAGE_ASPECT_DEPTH_BIT) aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
        vi.subresourceRange = {aspect, 0, image.mip_levels, 0, image.array_layers};
        if (VkResult r = vkCreateImageView(context_->device(), &vi, nullptr, &t.sampled_view); r != VK_SUCCESS) {
            return vk_error(r, "vkCreateImageView for " + in_quotes(image.name));
        }
    }
    t.states.assign(std::size_t{image.mip_levels} * image.array_layers, *state);
    t.frame_start_states = t.states;
    return textures_.insert(std::move(t));
}

loom::Status VulkanDevice::set_image_layout(rhi::TextureHandle texture, VkImageLayout layout) {
    auto found = textures_.get(texture);
    if (!found.ok()) return found.take_error();
    Texture& t = **found;
    if (frame_recording()) {
        return Error{ErrorCode::InvalidState, "set_image_layout of " + in_quotes(t.desc.name) +
                                                  " while a frame is being recorded: call it before begin_external_frame"};
    }
    auto state = state_for_layout(layout);
    if (!state.ok()) return Error{ErrorCode::Unsupported, "set_image_layout of " + in_quotes(t.desc.name) + ": " + state.error().message};
    std::fill(t.states.begin(), t.states.end(), *state);
    t.frame_start_states = t.states;
    return {};
}

loom::Result<VkImageLayout> VulkanDevice::image_layout(rhi::TextureHandle texture) {
    auto found = textures_.get(texture);
    if (!found.ok()) return found.take_error();
    const Texture& t = **found;
    if (!texture_all_in(t, t.states.front())) {
        return Error{ErrorCode::InvalidState, "image_layout of " + in_quotes(t.desc.name) +
                                                  ": its mip levels or layers are in different layouts"};
    }
    return layout_for_state(t.states.front(), t.depth_stencil);
}

loom::Result<VkImage> VulkanDevice::image(rhi::TextureHandle texture) {
    auto found = textures_.get(texture);
    if (!found.ok()) return found.take_error();
    return (*found)->image;
}

}  // namespace loom::vulkan
