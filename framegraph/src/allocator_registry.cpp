#include <algorithm>
#include <array>
#include <functional>

#include "allocators.hpp"

namespace loom::fg {
namespace {

constexpr std::array<std::string_view, 3> kNames{"paper", "interval", "heap"};

}  // namespace

namespace detail {

uint32_t LowestFreeNumber::take() {
    // Every freed number is below next_, so the lowest free one is the heap's top if any.
    if (free_.empty()) return next_++;
    std::pop_heap(free_.begin(), free_.end(), std::greater<>{});
    const uint32_t number = free_.back();
    free_.pop_back();
    return number;
}

void LowestFreeNumber::release(uint32_t number) {
    free_.push_back(number);
    std::push_heap(free_.begin(), free_.end(), std::greater<>{});
}

}  // namespace detail

std::span<const std::string_view> allocator_names() { return kNames; }

Result<std::unique_ptr<Allocator>> make_allocator(std::string_view name) {
    if (name == "paper") return detail::make_paper_allocator();
    if (name == "interval") return detail::make_interval_allocator();
    if (name == "heap") return detail::make_heap_allocator();
    std::string known;
    for (std::string_view n : kNames) {
        if (!known.empty()) known += ", ";
        known += n;
    }
    return make_error(ErrorCode::InvalidArgument, "unknown allocator '" + std::string(name) + "' (known: " + known + ")");
}

}  // namespace loom::fg
