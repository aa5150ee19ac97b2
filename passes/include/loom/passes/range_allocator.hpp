#pragma once
// First-fit allocation of ranges inside [0, capacity): vertices and indices in the shared
// geometry buffers, slots of uniform sets in their pools. A freed range merges with free
// neighbours and is handed out again, so buffers do not grow while objects come and go.

#include <cstdint>
#include <map>
#include <optional>

namespace loom::passes {

class RangeAllocator {
public:
    explicit RangeAllocator(uint64_t capacity = 0);

    /// The lowest free range of `size` units (first fit); nullopt when no free range is large
    /// enough (grow() and try again). A size of 0 is refused.
    std::optional<uint64_t> allocate(uint64_t size);
    /// Returns [offset, offset + size) (which must have been allocated) to the free ranges.
    void free(uint64_t offset, uint64_t size);
    /// Extends the capacity (never shrinks); the new space is free.
    void grow(uint64_t capacity);

    [[nodiscard]] uint64_t capacity() const { return capacity_; }
    /// Units allocated now.
    [[nodiscard]] uint64_t used() const { return used_; }
    /// One past the highest allocated unit (0 when nothing is allocated).
    [[nodiscard]] uint64_t high_water() const;
    /// Number of separate free ranges (1 for an empty allocator with capacity).
    [[nodiscard]] std::size_t free_ranges() const { return free_.size(); }

private:
    uint64_t capacity_ = 0;
    uint64_t used_ = 0;
    std::map<uint64_t, uint64_t> free_;  ///< offset -> size, no two adjacent
};

}  // namespace loom::passes
