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
    [[nodiscard]] std::size_t size() const { return size_; }
    [[nodiscard]] bool empty() const { return size_ == 0; }
    void clear() { size_ = 0; }
    /// Shrinks to `n` records (n <= size()).
    void shrink_to(std::size_t n) { size_ = n; }

    T& operator[](std::size_t i) { return storage_[i]; }
    const T& operator[](std::size_t i) const { return storage_[i]; }
    T& back() { return storage_[size_ - 1]; }
    const T& back() const { return storage_[size_ - 1]; }

    /// Appends a copy of `value` (which may be a record of this array).
    void push_back(const T& value) {
        if (size_ == storage_.size()) [[unlikely]] {
            const T copy = value;  // growing moves the records
            grow();
            storage_[size_++] = copy;
            return;
        }
        storage_[size_++] = value;
    }
    /// Appends a default record and returns it.
    T& emplace_back() {
        if (size_ == storage_.size()) [[unlikely]] grow();
        storage_[size_] = T{};
        return storage_[size_++];
    }

private:
    [[gnu::noinline]] void grow() {
        // Here rather than at class scope: records nested in the class that holds the arrays
        // are complete only once it is.
        static_assert(std::is_trivially_copyable_v<T> && std::is_default_constructible_v<T>);
        storage_.resize(storage_.empty() ? 64 : storage_.size() * 2);
    }

    std::vector<T> storage_;  ///< all of it constructed; size_ of it used
    std::size_t size_ = 0;
};

}  // namespace loom::gl
