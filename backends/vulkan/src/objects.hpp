#pragma once
// The Vulkan objects behind loom's handles.

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include <vulkan/vulkan.h>

#include "descriptors.hpp"
#include "loom/rhi/descriptions.hpp"
#include "loom/rhi/shader.hpp"
#include "loom/vulkan/memory_allocator.hpp"

namespace loom::vulkan {

struct Texture {
    rhi::TextureDesc desc;
    VkImage image = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkImageAspectFlags aspect = 0;
    bool depth_stencil = false;
    uint32_t array_layers = 1;       ///< Vulkan array layers (1 for 3D textures)
    MemoryAllocation memory;         ///< empty for placed and swapchain textures
    uint64_t bytes = 0;              ///< counted in ResourceStats::texture_bytes
    bool swapchain = false;          ///< wraps a swapchain image (not counted, not destroyed)
    bool imported = false;           ///< wraps an application image (not counted, not destroyed)
    VkImageView sampled_view = VK_NULL_HANDLE;  ///< all mips and layers; depth aspect for depth/stencil
    std::unordered_map<uint64_t, VkImageView> views;  ///< attachment views by key
    /// Sampled and storage views of subresource ranges, made on first use (VulkanDevice::range_view):
    /// by {storage?, view type, base mip, mips, base layer, layers}.
    std::map<std::array<uint32_t, 6>, VkImageView> range_views;

    /// Tracked state of every subresource (index mip * array_layers + layer), as of the end
    /// of everything recorded so far.
    std::vector<rhi::ResourceState> states;
    /// States when the frame being recorded first touched the texture: uploads and readbacks
    /// recorded during a frame run before it, so they see (and update) these.
    std::vector<rhi::ResourceState> frame_start_states;
    uint64_t touched_epoch = 0;

    // Placed textures: where they live, and when they last took their bytes over (see
    // VulkanDevice::alias_owner; buffers placed in the same heap take part too).
    uint64_t heap_offset = 0;
    uint64_t heap_size = 0;
    uint64_t alias_stamp = 0;

    [[nodiscard]] uint32_t subresource(uint32_t mip, uint32_t layer) const { return mip * array_layers + layer; }
};

struct Buffer {
    rhi::BufferDesc desc;
    VkBuffer buffer = VK_NULL_HANDLE;
    MemoryAllocation memory;  ///< empty for placed buffers
    rhi::ResourceState state = rhi::ResourceState::Undefined;
    bool internal = false;  ///< backend-owned (transient uniform rings): not in ResourceStats

    // Placed buffers, as for textures: where they live and when they last took their bytes over.
    uint64_t heap_offset = 0;
    uint64_t heap_size = 0;
    uint64_t alias_stamp = 0;
};

struct Heap {
    rhi::HeapDesc desc;
    MemoryAllocation memory;
    uint32_t placed_textures = 0;
    std::vector<rhi::TextureHandle> placed;          ///< the textures placed in it
    std::vector<rhi::BufferHandle> placed_buffers;   ///< the buffers placed in it
    uint64_t stamp = 0;                              ///< counts hand-overs between aliases
};

struct Sampler {
    std::string name;
    VkSampler sampler = VK_NULL_HANDLE;
};

struct Shader {
    rhi::ShaderModule module;  ///< without the GL source; reflection for layouts
    VkShaderModule shader = VK_NULL_HANDLE;
};

struct Pipeline {
    std::string name;
    std::string key;  ///< the pipeline cache entry this uses
    VkPipeline pipeline = VK_NULL_HANDLE;
    const PipelineLayout* layout = nullptr;
    VkPipelineBindPoint bind_point = VK_PIPELINE_BIND_POINT_GRAPHICS;
    std::vector<rhi::Format> color_formats;
    rhi::Format depth_format = rhi::Format::Undefined;
    uint32_t samples = 1;
    uint32_t vertex_buffer_count = 0;
};

}  // namespace loom::vulkan
