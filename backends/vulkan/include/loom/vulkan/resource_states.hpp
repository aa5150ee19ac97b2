#pragma once
// The one place where loom's explicit resource states become Vulkan synchronisation: the
// mapping ResourceState -> (image layout, pipeline stages, access) and the emission of
// barriers between two states. Every layout transition and memory dependency of the backend
// goes through BarrierBatch.

#include <vector>

#include <vulkan/vulkan.h>

#include "loom/rhi/descriptions.hpp"

namespace loom::vulkan {

/// How a resource in one state is accessed: the layout an image must be in, and the
/// pipeline stages and memory accesses that touch it.
struct StateAccess {
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_NONE;
    VkAccessFlags2 access = VK_ACCESS_2_NONE;
    /// True when the state includes writes (a barrier is needed even between equal states).
    bool writes = false;
    /// False for states that make no sense for this kind of resource (e.g. a texture as
    /// VertexBuffer).
    bool valid = true;
};

/// The access of a texture in `state`. `depth_stencil` selects the depth variants (e.g.
/// DepthRead is valid only for depth/stencil formats, RenderTarget only for colour ones).
///
/// As the source of a barrier, Undefined means "whatever happened before to this memory":
/// all commands and all writes. That orders the first use of an image after the last use of
/// another image aliasing its memory (placed textures), after a swapchain acquire, and after
/// anything else, at no cost that matters.
StateAccess texture_state_access(rhi::ResourceState state, bool depth_stencil);

/// The access of a buffer in `state`. Undefined is a buffer's resting state: all commands as
/// the source of a barrier, any read as the destination (what write_buffer and copies leave
/// behind when the user never transitioned the buffer).
StateAccess buffer_state_access(rhi::ResourceState state);

/// Image aspects of a VkFormat (colour, depth, stencil).
VkImageAspectFlags aspect_mask(VkFormat format);

/// Collects barriers and records them with one vkCmdPipelineBarrier2.
class BarrierBatch {
public:
    /// Transition of a subresource range of `image` from `from` to `to`. When `discard` is
    /// true the old contents are not needed and the old layout is UNDEFINED. Nothing is
    /// recorded when the states are equal and read-only.
    void image(VkImage image, const VkImageSubresourceRange& range, rhi::ResourceState from, rhi::ResourceState to,
               bool depth_stencil, bool discard = false);
    /// Dependency for a whole buffer between two states.
    void buffer(VkBuffer buffer, rhi::ResourceState from, rhi::ResourceState to);
    /// A global memory dependency.
    void memory(VkPipelineStageFlags2 src_stages, VkAccessFlags2 src_access, VkPipelineStageFlags2 dst_stages,
                VkAccessFlags2 dst_access);

    // Global dependencies around copies that do not track a buffer's state (uploads through
    // staging, readbacks, a copy within one buffer).
    /// Everything before (reads and writes) happens before transfers that read and write.
    void before_transfer();
    /// Transfer writes are visible to everything after.
    void after_transfer();
    /// Transfer writes are visible to the host (readbacks, before the fence wait).
    void transfer_to_host();

    /// True when nothing was collected.
    [[nodiscard]] bool empty() const { return images_.empty() && buffers_.empty() && memory_.empty(); }
    /// Barriers collected.
    [[nodiscard]] std::size_t size() const { return images_.size() + buffers_.size() + memory_.size(); }
    /// The image barriers collected (for tests).
    [[nodiscard]] const std::vector<VkImageMemoryBarrier2>& image_barriers() const { return images_; }
    /// The buffer barriers collected (for tests).
    [[nodiscard]] const std::vector<VkBufferMemoryBarrier2>& buffer_barriers() const { return buffers_; }

    /// Records everything collected (if anything) and empties the batch. Returns the number
    /// of vkCmd* calls made (0 or 1).
    uint32_t flush(VkCommandBuffer cmd);

private:
    std::vector<VkImageMemoryBarrier2> images_;
    std::vector<VkBufferMemoryBarrier2> buffers_;
    std::vector<VkMemoryBarrier2> memory_;
};

}  // namespace loom::vulkan
