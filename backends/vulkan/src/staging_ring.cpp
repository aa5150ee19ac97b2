#include "staging_ring.hpp"

#include "loom/rhi/checked_math.hpp"
#include "loom/vulkan/context.hpp"

namespace loom::vulkan {

StagingRing::StagingRing(VkDevice device, MemoryAllocator& allocator, VkDeviceSize capacity)
    : device_(device), allocator_(allocator), capacity_(capacity) {}

StagingRing::~StagingRing() {
    if (buffer_) vkDestroyBuffer(device_, buffer_, nullptr);
    allocator_.free(memory_);
}

loom::Status StagingRing::init() {
    auto info = vk_init<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
    info.size = capacity_;
    info.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    if (VkResult r = vkCreateBuffer(device_, &info, nullptr, &buffer_); r != VK_SUCCESS) return vk_error(r, "vkCreateBuffer (staging ring)");
    AllocationRequest request;
    vkGetBufferMemoryRequirements(device_, buffer_, &request.requirements);
    request.required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    request.preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
    request.kind = ResourceKind::Buffer;
    request.dedicated = true;
    auto memory = allocator_.allocate(request);
    if (!memory.ok()) return memory.take_error();
    memory_ = *memory;
    if (VkResult r = vkBindBufferMemory(device_, buffer_, memory_.memory, memory_.offset); r != VK_SUCCESS) {
        return vk_error(r, "vkBindBufferMemory (staging ring)");
    }
    return {};
}

std::optional<StagingRing::Span> StagingRing::allocate(VkDeviceSize size, VkDeviceSize alignment, uint64_t serial) {
    if (size > capacity_ || size == 0) return std::nullopt;
    if (regions_.empty()) {
        head_ = 0;
        tail_ = 0;
        full_ = false;
    }
    VkDeviceSize offset = 0;
    if (full_) return std::nullopt;
    if (regions_.empty() || head_ > tail_) {
        // Free space is [head, capacity) and [0, tail): try the end first, then wrap.
        const VkDeviceSize at = checked::align_up_in_range(head_, alignment);
        if (at + size <= capacity_) {
            offset = at;
        } else if (size <= tail_) {
            offset = 0;
        } else {
            return std::nullopt;
        }
    } else {
        // Free space is [head, tail).
        const VkDeviceSize at = checked::align_up_in_range(head_, alignment);
        if (at + size > tail_) return std::nullopt;
        offset = at;
    }
    head_ = offset + size;
    if (head_ == capacity_) head_ = 0;
    full_ = head_ == tail_;
    if (!regions_.empty() && regions_.back().serial == serial) {
        regions_.back().end = head_;
    } else {
        regions_.push_back({serial, head_});
    }
    return Span{buffer_, offset, static_cast<std::byte*>(memory_.mapped) + offset, nullptr};
}

void StagingRing::release(uint64_t completed_serial) {
    while (!regions_.empty() && regions_.front().serial <= completed_serial) {
        tail_ = regions_.front().end;
        regions_.pop_front();
        full_ = false;
    }
    if (regions_.empty()) {
        head_ = 0;
        tail_ = 0;
    }
}

}  // namespace loom::vulkan
