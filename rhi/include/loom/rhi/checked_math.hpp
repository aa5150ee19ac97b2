#pragma once
// Checked arithmetic for sizes, offsets and counts. Every byte size, offset or element count
// that loom computes from numbers a user (or a file) gave goes through these, so that an
// overflow becomes an error naming the object at fault instead of a wrapped value (a texture
// "of 0 B", an offset at the end of a heap) or undefined behaviour (a double converted to an
// integer it does not fit).

#include <cmath>
#include <concepts>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <optional>
#include <utility>

namespace loom::checked {

/// a + b, or nullopt when it does not fit in T.
template <std::unsigned_integral T>
[[nodiscard]] constexpr std::optional<T> add(T a, T b) {
    T out{};
    if (__builtin_add_overflow(a, b, &out)) return std::nullopt;
    return out;
}

/// a × b, or nullopt when it does not fit in T.
template <std::unsigned_integral T>
[[nodiscard]] constexpr std::optional<T> mul(T a, T b) {
    T out{};
    if (__builtin_mul_overflow(a, b, &out)) return std::nullopt;
    return out;
}

/// The product of every factor in 64 bits, or nullopt when it overflows.
[[nodiscard]] constexpr std::optional<uint64_t> product(std::initializer_list<uint64_t> factors) {
    uint64_t out = 1;
    for (uint64_t factor : factors) {
        if (__builtin_mul_overflow(out, factor, &out)) return std::nullopt;
    }
    return out;
}

/// Whether the byte range [offset, offset + size) lies within [0, capacity), decided without
/// computing offset + size (which a hostile offset would wrap past 2^64 into range).
[[nodiscard]] constexpr bool range_fits(uint64_t offset, uint64_t size, uint64_t capacity) {
    return offset <= capacity && size <= capacity - offset;
}

/// value rounded up to a multiple of alignment (alignment > 0), or nullopt on overflow.
[[nodiscard]] constexpr std::optional<uint64_t> align_up(uint64_t value, uint64_t alignment) {
    if (alignment == 0) return std::nullopt;
    const uint64_t remainder = value % alignment;
    if (remainder == 0) return value;
    return add<uint64_t>(value, alignment - remainder);
}

/// value rounded up to a multiple of alignment (0 or 1: unchanged), unchecked: for values known
/// to be far from 2^64, such as offsets inside a buffer or heap loom made (it wraps otherwise).
/// Sizes and offsets from user input go through align_up.
[[nodiscard]] constexpr uint64_t align_up_in_range(uint64_t value, uint64_t alignment) {
    return alignment <= 1 ? value : (value + alignment - 1) / alignment * alignment;
}

/// `value` as an integer of type T when it is finite and in T's range (after the caller's
/// rounding), else nullopt. A plain static_cast of an out-of-range double is undefined.
template <std::integral T>
[[nodiscard]] std::optional<T> to_integer(double value) {
    if (!std::isfinite(value)) return std::nullopt;
    // Compare in double against bounds that are exactly representable: T's max + 1 is a
    // power of two; its min is 0 or minus a power of two.
    constexpr double upper = static_cast<double>(std::numeric_limits<T>::max() / 2 + 1) * 2.0;
    constexpr double lower = static_cast<double>(std::numeric_limits<T>::min());
    if (value < lower || value >= upper) return std::nullopt;
    return static_cast<T>(value);
}

/// `value` narrowed to T when it fits, else nullopt.
template <std::integral T, std::integral U>
[[nodiscard]] constexpr std::optional<T> narrow(U value) {
    if (!std::in_range<T>(value)) return std::nullopt;
    return static_cast<T>(value);
}

}  // namespace loom::checked
