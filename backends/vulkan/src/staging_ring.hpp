#pragma once
// A host-visible, coherent ring buffer for uploads and readbacks. Space is handed out in
// submission order and given back when the submission that used it completes.

#include <cstdint>
#include <deque>
#include <memory>
#include <optional>

#include <vulkan/vulkan.h>

#include "loom/vulkan/memory_allocator.hpp"

namespace loom::vulkan {

class StagingRing {
public:
    struct Span {
        VkBuffer buffer = VK_NULL_HANDLE;
        VkDeviceSize offset = 0;
        std::byte* data = nullptr;
        /// For temporary buffers (requests larger than the ring): the buffer is released once
        /// the last copy of the span is gone, so a readback can read it after waiting.
        std::shared_ptr<void> keep_alive;
    };

    StagingRing(VkDevice device, MemoryAllocator& allocator, VkDeviceSize capacity);
    ~StagingRing();
    StagingRing(const StagingRing&) = delete;
    StagingRing& operator=(const StagingRing&) = delete;

    [[nodiscard]] loom::Status init();
    [[nodiscard]] VkDeviceSize capacity() const { return capacity_; }

    /// `size` bytes aligned to `alignment`, used by submission `serial`; nullopt when the ring
    /// has no contiguous room now (wait for older submissions and retry).
    std::optional<Span> allocate(VkDeviceSize size, VkDeviceSize alignment, uint64_t serial);
    /// Gives back the space of every submission up to `completed_serial`.
    void release(uint64_t completed_serial);
    /// The oldest serial still holding space (0 if none).
    [[nodiscard]] uint64_t oldest_serial() const { return regions_.empty() ? 0 : regions_.front().serial; }

private:
    struct Region {
        uint64_t serial;
        VkDeviceSize end;  ///< the ring's head after this serial's last allocation
    };

    VkDevice device_;
    MemoryAllocator& allocator_;
    VkDeviceSize capacity_;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    MemoryAllocation memory_;
    VkDeviceSize head_ = 0;  ///< next free byte
    VkDeviceSize tail_ = 0;  ///< first byte still in use
    bool full_ = false;      ///< head_ == tail_ with everything in use
    std::deque<Region> regions_;
};

}  // namespace loom::vulkan
