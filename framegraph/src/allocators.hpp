#pragma once
// Internal: the allocators behind make_allocator().

#include <algorithm>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "loom/framegraph/allocator.hpp"

namespace loom::fg::detail {

std::unique_ptr<Allocator> make_paper_allocator();
std::unique_ptr<Allocator> make_interval_allocator();
std::unique_ptr<Allocator> make_heap_allocator();

/// Hands out the lowest free number: what "the first available colour" of an array of
/// colours is, without scanning the array.
class LowestFreeNumber {
public:
    uint32_t take() {
        // Every freed number is below next_, so the lowest free one is the heap's top if any.
        if (free_.empty()) return next_++;
        std::pop_heap(free_.begin(), free_.end(), std::greater<>{});
        const uint32_t number = free_.back();
        free_.pop_back();
        return number;
    }
    void release(uint32_t number) {
        free_.push_back(number);
        std::push_heap(free_.begin(), free_.end(), std::greater<>{});
    }
    /// How many distinct numbers were ever handed out.
    [[nodiscard]] uint32_t used() const { return next_; }

private:
    std::vector<uint32_t> free_;  // a min-heap
    uint32_t next_ = 0;
};

}  // namespace loom::fg::detail
