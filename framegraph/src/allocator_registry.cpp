#include <algorithm>
#include <array>

#include "allocators.hpp"

namespace loom::fg {
namespace {

// In the order of AllocatorKind's values, so that a kind indexes its name.
constexpr std::array<std::string_view, 3> kNames{"paper", "interval", "heap"};
constexpr std::array<AllocatorKind, 3> kKinds{AllocatorKind::Paper, AllocatorKind::Interval, AllocatorKind::Heap};

}  // namespace

std::span<const std::string_view> allocator_names() { return kNames; }

std::span<const AllocatorKind> allocator_kinds() { return kKinds; }

std::string_view allocator_name(AllocatorKind kind) { return kNames.at(static_cast<std::size_t>(kind)); }

Result<AllocatorKind> parse_allocator(std::string_view name) {
    for (std::size_t i = 0; i < kNames.size(); ++i) {
        if (kNames[i] == name) return kKinds[i];
    }
    std::string known;
    for (std::string_view n : kNames) {
        if (!known.empty()) known += ", ";
        known += n;
    }
    return make_error(ErrorCode::InvalidArgument, "unknown allocator '" + std::string(name) + "' (known: " + known + ")");
}

std::unique_ptr<Allocator> make_allocator(AllocatorKind kind) {
    switch (kind) {
        case AllocatorKind::Paper: return detail::make_paper_allocator();
        case AllocatorKind::Interval: return detail::make_interval_allocator();
        case AllocatorKind::Heap: return detail::make_heap_allocator();
    }
    return detail::make_interval_allocator();  // unreachable: every kind is handled above
}

Result<std::unique_ptr<Allocator>> make_allocator(std::string_view name) {
    auto kind = parse_allocator(name);
    if (!kind) return kind.take_error();
    return make_allocator(*kind);
}

}  // namespace loom::fg
