#include "loom/passes/range_allocator.hpp"

#include <cassert>
#include <iterator>

namespace loom::passes {

RangeAllocator::RangeAllocator(uint64_t capacity) { grow(capacity); }

std::optional<uint64_t> RangeAllocator::allocate(uint64_t size) {
    if (size == 0) return std::nullopt;
    for (auto it = free_.begin(); it != free_.end(); ++it) {
        if (it->second < size) continue;
        const uint64_t offset = it->first;
        const uint64_t rest = it->second - size;
        free_.erase(it);
        if (rest > 0) free_.emplace(offset + size, rest);
        used_ += size;
        return offset;
    }
    return std::nullopt;
}

void RangeAllocator::free(uint64_t offset, uint64_t size) {
    if (size == 0) return;
    assert(offset + size <= capacity_ && size <= used_);
    used_ -= size;
    auto next = free_.lower_bound(offset);
    assert(next == free_.end() || next->first >= offset + size);
    // Merge with the free range that ends where this one starts, and the one that starts where
    // it ends.
    if (next != free_.begin()) {
        auto previous = std::prev(next);
        assert(previous->first + previous->second <= offset);
        if (previous->first + previous->second == offset) {
            offset = previous->first;
            size += previous->second;
            free_.erase(previous);
        }
    }
    if (next != free_.end() && next->first == offset + size) {
        size += next->second;
        free_.erase(next);
    }
    free_.emplace(offset, size);
}

void RangeAllocator::grow(uint64_t capacity) {
    if (capacity <= capacity_) return;
    const uint64_t added = capacity - capacity_;
    const uint64_t start = capacity_;
    capacity_ = capacity;
    used_ += added;  // free() subtracts it again
    free(start, added);
}

uint64_t RangeAllocator::high_water() const {
    if (used_ == 0) return 0;
    // Everything past the last free range's start is free when that range reaches the end.
    if (!free_.empty()) {
        auto last = std::prev(free_.end());
        if (last->first + last->second == capacity_) return last->first;
    }
    return capacity_;
}

}  // namespace loom::passes
