#pragma once
// A growable array of plain records for the command list's per-frame storage (draws and the
// states they share). std::vector would do, but its push_back is not inlined into the per-draw
// paths, which are large once their checks are inlined: here appending is a comparison and a
// store, and the rare growth is a call of its own. Storage is kept from frame to frame (clear
// keeps it), so that steady-state recording allocates nothing.

#include <cstdint>
#include <type_traits>
#include <vector>

namespace loom::gl {

template <class T>
class FrameArray {
public:
    FrameArray() = default;
    FrameArray(const FrameArray&) = delete;  // data_ points into storage_
    FrameArray& operator=(const FrameArray&) = delete;

    [[nodiscard]] std::size_t size() const { return size_; }
    [[nodiscard]] bool empty() const { return size_ == 0; }
    void clear() { size_ = 0; }
    /// Shrinks to `n` records (n <= size()).
    void shrink_to(std::size_t n) { size_ = n; }

    T& operator[](std::size_t i) { return data_[i]; }
    const T& operator[](std::size_t i) const { return data_[i]; }
    T& back() { return data_[size_ - 1]; }
    const T& back() const { return data_[size_ - 1]; }

    /// Appends a copy of `value` (which may be a record of this array).
    void push_back(const T& value) {
        if (!has_room()) [[unlikely]] {
            const T copy = value;  // growing moves the records
            grow();
            data_[size_++] = copy;
            return;
        }
        data_[size_++] = value;
    }
    /// Whether one more record fits without growing: a caller that checks it first appends
    /// with push_back_in_room, which makes no call (a path without calls needs no stack frame).
    [[nodiscard]] bool has_room() const { return size_ != capacity_; }
    void push_back_in_room(const T& value) { data_[size_++] = value; }
    /// Grows when full, so that push_back_in_room may follow.
    void make_room() {
        if (!has_room()) grow();
    }
    /// Appends a default record and returns it.
    T& emplace_back() {
        if (!has_room()) [[unlikely]] grow();
        data_[size_] = T{};
        return data_[size_++];
    }

private:
    [[gnu::noinline]] void grow() {
        // Here rather than at class scope: records nested in the class that holds the arrays
        // are complete only once it is.
        static_assert(std::is_trivially_copyable_v<T> && std::is_default_constructible_v<T>);
        storage_.resize(storage_.empty() ? 64 : storage_.size() * 2);
        data_ = storage_.data();
        capacity_ = storage_.size();
    }

    std::vector<T> storage_;  ///< all of it constructed; size_ of it used
    T* data_ = nullptr;       ///< storage_.data() and .size(), kept apart from the vector so that
    std::size_t capacity_ = 0;  ///< the per-draw paths read them without a division
    std::size_t size_ = 0;
};

}  // namespace loom::gl
