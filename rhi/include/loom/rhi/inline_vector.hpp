#pragma once
// A vector that keeps up to N elements inside itself and moves to the heap only beyond that:
// descriptions built per frame (a render pass's colour attachments) then allocate nothing in
// the user's code, while a list longer than any device allows can still be built and is
// refused by validation with a message instead of failing where it is built.

#include <algorithm>
#include <array>
#include <cstddef>
#include <initializer_list>
#include <utility>
#include <vector>

namespace loom::rhi {

template <class T, std::size_t N>
class InlineVector {
public:
    using value_type = T;
    using iterator = T*;
    using const_iterator = const T*;

    InlineVector() = default;
    InlineVector(std::initializer_list<T> values) {
        for (const T& v : values) push_back(v);
    }

    [[nodiscard]] std::size_t size() const { return size_; }
    [[nodiscard]] bool empty() const { return size_ == 0; }
    /// Elements held without a heap allocation.
    static constexpr std::size_t inline_capacity() { return N; }

    T* data() { return spilled() ? heap_.data() : inline_.data(); }
    const T* data() const { return spilled() ? heap_.data() : inline_.data(); }
    T& operator[](std::size_t i) { return data()[i]; }
    const T& operator[](std::size_t i) const { return data()[i]; }
    T& front() { return data()[0]; }
    const T& front() const { return data()[0]; }
    T& back() { return data()[size_ - 1]; }
    const T& back() const { return data()[size_ - 1]; }
    iterator begin() { return data(); }
    iterator end() { return data() + size_; }
    const_iterator begin() const { return data(); }
    const_iterator end() const { return data() + size_; }

    void push_back(const T& value) { emplace_back(value); }
    void push_back(T&& value) { emplace_back(std::move(value)); }
    template <class... Args>
    T& emplace_back(Args&&... args) {
        if (size_ < N) {
            inline_[size_] = T(std::forward<Args>(args)...);
            return inline_[size_++];
        }
        if (size_ == N) heap_.assign(inline_.begin(), inline_.end());  // the first spill
        heap_.emplace_back(std::forward<Args>(args)...);
        ++size_;
        return heap_.back();
    }
    void pop_back() { resize(size_ - 1); }
    void clear() {
        heap_.clear();
        size_ = 0;
    }
    void resize(std::size_t n) { resize(n, T{}); }
    void resize(std::size_t n, const T& value) {
        if (n <= N) {
            if (spilled()) std::copy(heap_.begin(), heap_.begin() + static_cast<std::ptrdiff_t>(n), inline_.begin());
            for (std::size_t i = size_; i < n; ++i) inline_[i] = value;
            heap_.clear();
            size_ = n;
            return;
        }
        while (size_ < n) emplace_back(value);
        if (size_ > n) heap_.resize(n);
        size_ = n;
    }

    friend bool operator==(const InlineVector& a, const InlineVector& b) {
        return std::equal(a.begin(), a.end(), b.begin(), b.end());
    }

private:
    [[nodiscard]] bool spilled() const { return size_ > N; }

    std::array<T, N> inline_{};
    std::vector<T> heap_;  ///< every element, once there are more than N
    std::size_t size_ = 0;
};

}  // namespace loom::rhi
