#include "loom/vulkan/resource_states.hpp"

#include "loom/vulkan/context.hpp"

namespace loom::vulkan {

using rhi::ResourceState;

namespace {

constexpr VkPipelineStageFlags2 kShaderStages = VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
                                                VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
                                                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
constexpr VkPipelineStageFlags2 kDepthStages = VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT |
                                               VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
constexpr VkAccessFlags2 kAllReads = VK_ACCESS_2_MEMORY_READ_BIT;

}  // namespace

StateAccess texture_state_access(ResourceState state, bool depth_stencil) {
    switch (state) {
        case ResourceState::Undefined:
            return {VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT, false, true};
        case ResourceState::ShaderRead:
            return {VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, kShaderStages, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, false, true};
        case ResourceState::RenderTarget:
            return {VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, true, !depth_stencil};
        case ResourceState::DepthWrite:
            return {VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL, kDepthStages,
                    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, true,
                    depth_stencil};
        case ResourceState::DepthRead:
            return {VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, kDepthStages | kShaderStages,
                    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, false,
                    depth_stencil};
        case ResourceState::Storage:
            return {VK_IMAGE_LAYOUT_GENERAL, kShaderStages,
                    VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, true, true};
        case ResourceState::CopySrc:
            return {VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                    VK_ACCESS_2_TRANSFER_READ_BIT, false, true};
        case ResourceState::CopyDst:
            return {VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                    VK_ACCESS_2_TRANSFER_WRITE_BIT, true, true};
        case ResourceState::Present:
            // Presentation is ordered by semaphores; the acquire semaphore is waited on at the
            // colour-output stage, so that is where a barrier out of Present starts.
            return {VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_NONE,
                    false, !depth_stencil};
        case ResourceState::VertexBuffer:
        case ResourceState::IndexBuffer:
        case ResourceState::IndirectArgument:
            return {VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, false, false};
    }
    return {VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, false, false};
}

StateAccess buffer_state_access(ResourceState state) {
    const VkImageLayout none = VK_IMAGE_LAYOUT_UNDEFINED;
    switch (state) {
        case ResourceState::Undefined:
            return {none, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, kAllReads, false, true};
        case ResourceState::ShaderRead:
            return {none, kShaderStages, VK_ACCESS_2_UNIFORM_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT, false, true};
        case ResourceState::Storage:
            return {none, kShaderStages, VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, true,
                    true};
        case ResourceState::CopySrc:
            return {none, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT, false, true};
        case ResourceState::CopyDst:
            return {none, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, true, true};
        case ResourceState::VertexBuffer:
            return {none, VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT, VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT, false, true};
        case ResourceState::IndexBuffer:
            return {none, VK_PIPELINE_STAGE_2_INDEX_INPUT_BIT, VK_ACCESS_2_INDEX_READ_BIT, false, true};
        case ResourceState::IndirectArgument:
            return {none, VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT, false, true};
        case ResourceState::RenderTarget:
        case ResourceState::DepthWrite:
        case ResourceState::DepthRead:
        case ResourceState::Present:
            return {none, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, false, false};
    }
    return {none, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, false, false};
}

VkImageAspectFlags aspect_mask(VkFormat format) {
    switch (format) {
        case VK_FORMAT_D16_UNORM:
        case VK_FORMAT_X8_D24_UNORM_PACK32:
        case VK_FORMAT_D32_SFLOAT:
            return VK_IMAGE_ASPECT_DEPTH_BIT;
        case VK_FORMAT_S8_UINT:
            return VK_IMAGE_ASPECT_STENCIL_BIT;
        case VK_FORMAT_D16_UNORM_S8_UINT:
        case VK_FORMAT_D24_UNORM_S8_UINT:
        case VK_FORMAT_D32_SFLOAT_S8_UINT:
            return VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT;
        default:
            return VK_IMAGE_ASPECT_COLOR_BIT;
    }
}

void BarrierBatch::image(VkImage image, const VkImageSubresourceRange& range, ResourceState from, ResourceState to,
                         bool depth_stencil, bool discard) {
    const StateAccess src = texture_state_access(discard ? ResourceState::Undefined : from, depth_stencil);
    const StateAccess dst = texture_state_access(to, depth_stencil);
    if (!discard && from == to && !dst.writes) return;
    auto b = vk_init<VkImageMemoryBarrier2>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2);
    b.srcStageMask = src.stages;
    b.srcAccessMask = src.access;
    b.dstStageMask = dst.stages;
    b.dstAccessMask = dst.access;
    b.oldLayout = src.layout;
    b.newLayout = dst.layout;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = range;
    images_.push_back(b);
}

void BarrierBatch::buffer(VkBuffer buffer, ResourceState from, ResourceState to) {
    const StateAccess src = buffer_state_access(from);
    const StateAccess dst = buffer_state_access(to);
    if (from == to && !dst.writes) return;
    auto b = vk_init<VkBufferMemoryBarrier2>(VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2);
    // A read-only source state needs only an execution dependency (write-after-read). Undefined
    // is "whatever happened to these bytes before", as for images: writes of an alias that used
    // them (placed buffers) included, so it makes every earlier write available.
    b.srcStageMask = src.stages;
    b.srcAccessMask = from == ResourceState::Undefined ? VK_ACCESS_2_MEMORY_WRITE_BIT : src.writes ? src.access : VK_ACCESS_2_NONE;
    b.dstStageMask = dst.stages;
    b.dstAccessMask = dst.access;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.buffer = buffer;
    b.offset = 0;
    b.size = VK_WHOLE_SIZE;
    buffers_.push_back(b);
}

void BarrierBatch::memory(VkPipelineStageFlags2 src_stages, VkAccessFlags2 src_access, VkPipelineStageFlags2 dst_stages,
                          VkAccessFlags2 dst_access) {
    auto b = vk_init<VkMemoryBarrier2>(VK_STRUCTURE_TYPE_MEMORY_BARRIER_2);
    b.srcStageMask = src_stages;
    b.srcAccessMask = src_access;
    b.dstStageMask = dst_stages;
    b.dstAccessMask = dst_access;
    memory_.push_back(b);
}

void BarrierBatch::before_transfer() {
    memory(VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
           VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT);
}

void BarrierBatch::after_transfer() {
    memory(VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
           VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
}

void BarrierBatch::transfer_to_host() {
    memory(VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
           VK_ACCESS_2_HOST_READ_BIT);
}

uint32_t BarrierBatch::flush(VkCommandBuffer cmd) {
    if (empty()) return 0;
    auto info = vk_init<VkDependencyInfo>(VK_STRUCTURE_TYPE_DEPENDENCY_INFO);
    info.memoryBarrierCount = static_cast<uint32_t>(memory_.size());
    info.pMemoryBarriers = memory_.data();
    info.bufferMemoryBarrierCount = static_cast<uint32_t>(buffers_.size());
    info.pBufferMemoryBarriers = buffers_.data();
    info.imageMemoryBarrierCount = static_cast<uint32_t>(images_.size());
    info.pImageMemoryBarriers = images_.data();
    vkCmdPipelineBarrier2(cmd, &info);
    images_.clear();
    buffers_.clear();
    memory_.clear();
    return 1;
}

}  // namespace loom::vulkan
