#pragma once
// loom's own Vulkan memory allocator (no VMA): a few large VkDeviceMemory blocks per memory
// type, sub-allocated first-fit with alignment, freed ranges merged and reused; dedicated
// allocations for big resources and for heaps. Buffers and images never share a block, so
// bufferImageGranularity can never put a linear and an optimal resource on the same page.

#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include <vulkan/vulkan.h>

#include "loom/rhi/result.hpp"

namespace loom::vulkan {

/// Linear (buffers) and optimal-tiling (images) resources go to different blocks.
enum class ResourceKind : uint8_t { Buffer, Image };

/// Where a resource lives: a memory object and a byte range in it.
struct MemoryAllocation {
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize offset = 0;
    VkDeviceSize size = 0;         ///< bytes reserved (the requested size)
    uint32_t memory_type = 0;
    void* mapped = nullptr;        ///< host address of `offset` for host-visible memory
    bool dedicated = false;        ///< owns `memory` alone
    uint32_t block = UINT32_MAX;   ///< allocator-internal block id (UINT32_MAX if dedicated)

    /// True for a real allocation.
    explicit operator bool() const { return memory != VK_NULL_HANDLE; }
};

/// What to allocate: requirements, memory properties, kind and whether dedicated.
struct AllocationRequest {
    VkMemoryRequirements requirements{};
    VkMemoryPropertyFlags required = 0;    ///< properties the memory type must have
    VkMemoryPropertyFlags preferred = 0;   ///< properties chosen when possible
    ResourceKind kind = ResourceKind::Buffer;
    /// Allocate a VkDeviceMemory of its own (also chosen for sizes >= dedicated_threshold).
    bool dedicated = false;
    /// For VkMemoryDedicatedAllocateInfo when the driver asks for a dedicated allocation.
    VkImage dedicated_image = VK_NULL_HANDLE;
    VkBuffer dedicated_buffer = VK_NULL_HANDLE;
};

/// Block size and the size from which allocations are dedicated.
struct AllocatorOptions {
    VkDeviceSize block_size = VkDeviceSize{32} << 20;
    /// Requests at least this big get a dedicated allocation.
    VkDeviceSize dedicated_threshold = VkDeviceSize{16} << 20;
};

/// Counts of what the allocator holds from the driver and hands out.
struct AllocatorStats {
    uint64_t blocks = 0;
    uint64_t block_bytes = 0;
    uint64_t dedicated_allocations = 0;
    uint64_t dedicated_bytes = 0;
    uint64_t sub_allocations = 0;
    uint64_t sub_allocated_bytes = 0;
};

/// Sub-allocates VkDeviceMemory blocks per memory type (see the top of this file).
class MemoryAllocator {
public:
    MemoryAllocator(VkPhysicalDevice physical_device, VkDevice device, AllocatorOptions options = {});
    ~MemoryAllocator();
    MemoryAllocator(const MemoryAllocator&) = delete;
    MemoryAllocator& operator=(const MemoryAllocator&) = delete;

    /// Reserves memory for `request`; OutOfMemory when the driver refuses, Unsupported when
    /// no memory type fits.
    loom::Result<MemoryAllocation> allocate(const AllocationRequest& request);
    /// Returns the range (and the block, once it is empty and not the last of its kind).
    void free(const MemoryAllocation& allocation);

    /// The best memory type among `type_bits` with all `required` flags, preferring `preferred`.
    [[nodiscard]] loom::Result<uint32_t> find_memory_type(uint32_t type_bits, VkMemoryPropertyFlags required,
                                                          VkMemoryPropertyFlags preferred) const;
    /// What the allocator holds and hands out now.
    [[nodiscard]] AllocatorStats stats() const;
    /// The options it was made with.
    [[nodiscard]] const AllocatorOptions& options() const { return options_; }
    /// The device's bufferImageGranularity.
    [[nodiscard]] VkDeviceSize buffer_image_granularity() const { return granularity_; }
    /// The memory types and heaps allocated from.
    [[nodiscard]] const VkPhysicalDeviceMemoryProperties& memory_properties() const { return memory_properties_; }

private:
    struct Block {
        VkDeviceMemory memory = VK_NULL_HANDLE;
        VkDeviceSize size = 0;
        uint32_t memory_type = 0;
        ResourceKind kind = ResourceKind::Buffer;
        void* mapped = nullptr;
        std::map<VkDeviceSize, VkDeviceSize> free_ranges;  ///< offset -> size, never adjacent
        uint64_t allocations = 0;
    };

    loom::Result<MemoryAllocation> allocate_dedicated(const AllocationRequest& request, uint32_t type);
    bool try_sub_allocate(Block& block, uint32_t block_id, const VkMemoryRequirements& req, MemoryAllocation& out);
    loom::Result<VkDeviceMemory> allocate_memory(VkDeviceSize size, uint32_t type, const AllocationRequest* dedicated_for,
                                                 void** mapped);

    VkDevice device_;
    AllocatorOptions options_;
    VkPhysicalDeviceMemoryProperties memory_properties_{};
    VkDeviceSize granularity_ = 1;
    std::vector<std::unique_ptr<Block>> blocks_;  ///< index = block id; null when freed
    uint64_t dedicated_count_ = 0;
    uint64_t dedicated_bytes_ = 0;
};

}  // namespace loom::vulkan
