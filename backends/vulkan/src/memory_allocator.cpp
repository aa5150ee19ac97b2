#include "loom/vulkan/memory_allocator.hpp"

#include <bit>
#include <cassert>
#include <string>

#include "loom/rhi/checked_math.hpp"
#include "loom/vulkan/context.hpp"

namespace loom::vulkan {

MemoryAllocator::MemoryAllocator(VkPhysicalDevice physical_device, VkDevice device, AllocatorOptions options)
    : device_(device), options_(options) {
    vkGetPhysicalDeviceMemoryProperties(physical_device, &memory_properties_);
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(physical_device, &props);
    granularity_ = props.limits.bufferImageGranularity;
}

MemoryAllocator::~MemoryAllocator() {
    for (auto& block : blocks_) {
        if (block) vkFreeMemory(device_, block->memory, nullptr);
    }
}

loom::Result<uint32_t> MemoryAllocator::find_memory_type(uint32_t type_bits, VkMemoryPropertyFlags required,
                                                         VkMemoryPropertyFlags preferred) const {
    int best = -1;
    int best_score = -1;
    for (uint32_t i = 0; i < memory_properties_.memoryTypeCount; ++i) {
        if (!(type_bits & (1u << i))) continue;
        const VkMemoryPropertyFlags flags = memory_properties_.memoryTypes[i].propertyFlags;
        if ((flags & required) != required) continue;
        const int score = std::popcount(flags & preferred);
        if (score > best_score) {
            best = static_cast<int>(i);
            best_score = score;
        }
    }
    if (best < 0) {
        return Error{ErrorCode::Unsupported, "no memory type among bits 0x" + std::to_string(type_bits) +
                                                 " has the required properties 0x" + std::to_string(required)};
    }
    return static_cast<uint32_t>(best);
}

loom::Result<VkDeviceMemory> MemoryAllocator::allocate_memory(VkDeviceSize size, uint32_t type,
                                                             const AllocationRequest* dedicated_for, void** mapped) {
    auto info = vk_init<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
    info.allocationSize = size;
    info.memoryTypeIndex = type;
    auto dedicated = vk_init<VkMemoryDedicatedAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_DEDICATED_ALLOCATE_INFO);
    if (dedicated_for && (dedicated_for->dedicated_image || dedicated_for->dedicated_buffer)) {
        dedicated.image = dedicated_for->dedicated_image;
        dedicated.buffer = dedicated_for->dedicated_buffer;
        info.pNext = &dedicated;
    }
    VkDeviceMemory memory = VK_NULL_HANDLE;
    if (VkResult r = vkAllocateMemory(device_, &info, nullptr, &memory); r != VK_SUCCESS) {
        return vk_error(r, "vkAllocateMemory of " + std::to_string(size) + " bytes");
    }
    *mapped = nullptr;
    if (memory_properties_.memoryTypes[type].propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) {
        if (VkResult r = vkMapMemory(device_, memory, 0, VK_WHOLE_SIZE, 0, mapped); r != VK_SUCCESS) {
            vkFreeMemory(device_, memory, nullptr);
            return vk_error(r, "vkMapMemory");
        }
    }
    return memory;
}

loom::Result<MemoryAllocation> MemoryAllocator::allocate_dedicated(const AllocationRequest& request, uint32_t type) {
    void* mapped = nullptr;
    auto memory = allocate_memory(request.requirements.size, type, &request, &mapped);
    if (!memory.ok()) return memory.take_error();
    ++dedicated_count_;
    dedicated_bytes_ += request.requirements.size;
    MemoryAllocation out;
    out.memory = *memory;
    out.offset = 0;
    out.size = request.requirements.size;
    out.memory_type = type;
    out.mapped = mapped;
    out.dedicated = true;
    return out;
}

bool MemoryAllocator::try_sub_allocate(Block& block, uint32_t block_id, const VkMemoryRequirements& req,
                                       MemoryAllocation& out) {
    for (auto it = block.free_ranges.begin(); it != block.free_ranges.end(); ++it) {
        const VkDeviceSize range_begin = it->first;
        const VkDeviceSize range_end = it->first + it->second;
        const VkDeviceSize offset = checked::align_up_in_range(range_begin, req.alignment);
        if (offset + req.size > range_end) continue;
        // Split the free range into what is left before and after the allocation.
        block.free_ranges.erase(it);
        if (offset > range_begin) block.free_ranges.emplace(range_begin, offset - range_begin);
        if (offset + req.size < range_end) block.free_ranges.emplace(offset + req.size, range_end - (offset + req.size));
        ++block.allocations;
        out.memory = block.memory;
        out.offset = offset;
        out.size = req.size;
        out.memory_type = block.memory_type;
        out.mapped = block.mapped ? static_cast<char*>(block.mapped) + offset : nullptr;
        out.dedicated = false;
        out.block = block_id;
        return true;
    }
    return false;
}

loom::Result<MemoryAllocation> MemoryAllocator::allocate(const AllocationRequest& request) {
    const VkMemoryRequirements& req = request.requirements;
    if (req.size == 0) return Error{ErrorCode::InvalidArgument, "memory allocation of 0 bytes"};
    auto type = find_memory_type(req.memoryTypeBits, request.required, request.preferred);
    if (!type.ok()) return type.take_error();

    if (request.dedicated || req.size >= options_.dedicated_threshold || req.size > options_.block_size) {
        return allocate_dedicated(request, *type);
    }
    for (uint32_t id = 0; id < blocks_.size(); ++id) {
        Block* block = blocks_[id].get();
        if (!block || block->memory_type != *type || block->kind != request.kind) continue;
        MemoryAllocation out;
        if (try_sub_allocate(*block, id, req, out)) return out;
    }
    // No room: a new block, in a free slot of blocks_ if there is one.
    void* mapped = nullptr;
    auto memory = allocate_memory(options_.block_size, *type, nullptr, &mapped);
    if (!memory.ok()) return memory.take_error();
    auto block = std::make_unique<Block>();
    block->memory = *memory;
    block->size = options_.block_size;
    block->memory_type = *type;
    block->kind = request.kind;
    block->mapped = mapped;
    block->free_ranges.emplace(0, options_.block_size);
    uint32_t id = 0;
    while (id < blocks_.size() && blocks_[id]) ++id;
    if (id == blocks_.size()) blocks_.emplace_back();
    blocks_[id] = std::move(block);
    MemoryAllocation out;
    const bool ok = try_sub_allocate(*blocks_[id], id, req, out);
    assert(ok && "a fresh block holds any request below the block size");
    (void)ok;
    return out;
}

void MemoryAllocator::free(const MemoryAllocation& allocation) {
    if (!allocation) return;
    if (allocation.dedicated) {
        vkFreeMemory(device_, allocation.memory, nullptr);
        --dedicated_count_;
        dedicated_bytes_ -= allocation.size;
        return;
    }
    assert(allocation.block < blocks_.size() && blocks_[allocation.block]);
    Block& block = *blocks_[allocation.block];
    VkDeviceSize begin = allocation.offset;
    VkDeviceSize size = allocation.size;
    // Merge with the free neighbours on both sides.
    auto next = block.free_ranges.lower_bound(begin);
    if (next != block.free_ranges.end() && next->first == begin + size) {
        size += next->second;
        next = block.free_ranges.erase(next);
    }
    if (next != block.free_ranges.begin()) {
        auto prev = std::prev(next);
        if (prev->first + prev->second == begin) {
            begin = prev->first;
            size += prev->second;
            block.free_ranges.erase(prev);
        }
    }
    block.free_ranges.emplace(begin, size);
    --block.allocations;
    if (block.allocations == 0) {
        // Keep one empty block per memory type and kind so that a create/destroy loop does
        // not allocate from the driver every time.
        bool another = false;
        for (uint32_t id = 0; id < blocks_.size(); ++id) {
            const Block* other = blocks_[id].get();
            if (other && id != allocation.block && other->memory_type == block.memory_type && other->kind == block.kind) {
                another = true;
            }
        }
        if (another) {
            vkFreeMemory(device_, block.memory, nullptr);
            blocks_[allocation.block].reset();
        }
    }
}

AllocatorStats MemoryAllocator::stats() const {
    AllocatorStats s;
    for (const auto& block : blocks_) {
        if (!block) continue;
        ++s.blocks;
        s.block_bytes += block->size;
        s.sub_allocations += block->allocations;
        VkDeviceSize free_bytes = 0;
        for (const auto& [offset, size] : block->free_ranges) free_bytes += size;
        s.sub_allocated_bytes += block->size - free_bytes;
    }
    s.dedicated_allocations = dedicated_count_;
    s.dedicated_bytes = dedicated_bytes_;
    return s;
}

}  // namespace loom::vulkan
