#pragma once
// Overflow-safe arithmetic for offsets, strides and counts that come from files: every result
// is either exact or reported as an overflow, never wrapped.

#include <cstdint>
#include <optional>

namespace loom::gltf::detail {


/// a + b, or nullopt when the sum does not fit in 64 bits.
[[nodiscard]] inline std::optional<uint64_t> checked_add(uint64_t a, uint64_t b) {
    uint64_t result = 0;
    if (__builtin_add_overflow(a, b, &result)) return std::nullopt;
    return result;
}

/// a * b, or nullopt when the product does not fit in 64 bits.
[[nodiscard]] inline std::optional<uint64_t> checked_mul(uint64_t a, uint64_t b) {
    uint64_t result = 0;
    if (__builtin_mul_overflow(a, b, &result)) return std::nullopt;
    return result;
}

/// True when the byte range [offset, offset + size) lies within [0, limit), without overflow.
[[nodiscard]] inline bool range_fits(uint64_t offset, uint64_t size, uint64_t limit) {
    const std::optional<uint64_t> end = checked_add(offset, size);
    return end.has_value() && *end <= limit;
}

/// The byte span of `count` elements of `element_size` bytes placed `stride` bytes apart:
/// stride * (count - 1) + element_size (0 for count 0), or nullopt on overflow.
[[nodiscard]] inline std::optional<uint64_t> strided_span(uint64_t count, uint64_t stride, uint64_t element_size) {
    if (count == 0) return uint64_t{0};
    const std::optional<uint64_t> body = checked_mul(count - 1, stride);
    if (!body) return std::nullopt;
    return checked_add(*body, element_size);
}

}  // namespace loom::gltf::detail
