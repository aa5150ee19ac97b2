#pragma once
// Storage for a backend's objects of one kind, addressed by typed handles. Shared by the
// backends so that null, stale and foreign handles are reported the same way everywhere.

#include <bit>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "loom/rhi/handles.hpp"
#include "loom/rhi/result.hpp"

namespace loom::rhi {

/// Returns a fresh id for a new Device (never 0), so that handles remember their device.
uint16_t next_device_id();

/// Objects of one kind stored by slot, addressed by typed handles (stale and foreign handles are detected).
template <class Tag, class T>
class HandlePool {
public:
    using HandleType = Handle<Tag>;

    /// An empty pool whose handles carry `device_id`.
    explicit HandlePool(uint16_t device_id) : device_id_(device_id) {}
    /// As above; every removal also counts into `shared_removals` (which outlives the pool), so
    /// that one comparison tells whether any of a device's pools lost an object.
    HandlePool(uint16_t device_id, uint64_t* shared_removals) : device_id_(device_id), shared_removals_(shared_removals) {}

    /// Stores `value` and returns its handle (reusing a free slot with a new generation).
    HandleType insert(T value) {
        uint32_t index;
        if (!free_.empty()) {
            index = free_.back();
            free_.pop_back();
        } else {
            index = static_cast<uint32_t>(slots_.size());
            slots_.push_back(Slot{std::nullopt, key(1, device_id_)});  // generation 0 is the null handle's
            slot_count_ = slots_.size();
        }
        Slot& slot = slots_[index];
        slot.value.emplace(std::move(value));
        ++live_;
        return HandleType{index, slot.generation(), device_id_};
    }

    /// The object behind `handle`, or an InvalidHandle error that says why there is none.
    Result<T*> get(HandleType handle) {
        if (T* found = find(handle)) return found;
        return std::move(*check(handle));
    }

    /// Like get(), but nullptr instead of an error (for hot paths that already validated).
    T* find(HandleType handle) {
        if (handle.index >= slot_count_) return nullptr;
        Slot& slot = slots_[handle.index];
        // The generation and the device in one comparison; a null handle's generation (0) is
        // no slot's.
        return slot.key == key(handle) && slot.value ? &*slot.value : nullptr;
    }
    /// Like find(), for const pools.
    const T* find(HandleType handle) const { return const_cast<HandlePool*>(this)->find(handle); }

    /// Removes and returns the object; the handle (and copies of it) become stale.
    Result<T> remove(HandleType handle) {
        if (auto error = check(handle)) return std::move(*error);
        Slot& slot = slots_[handle.index];
        T value = std::move(*slot.value);
        slot.value.reset();
        // Generation 0 is reserved for null handles.
        const uint16_t generation = slot.generation();
        slot.key = key(static_cast<uint16_t>(generation == 0xFFFF ? 1 : generation + 1), device_id_);
        free_.push_back(handle.index);
        --live_;
        ++removals_;
        if (shared_removals_) ++*shared_removals_;
        return value;
    }

    /// Objects removed so far: unchanged, every handle found alive before is still alive (a
    /// command list may then reuse what it checked for an earlier draw).
    [[nodiscard]] uint64_t removals() const { return removals_; }

    /// Objects alive in the pool.
    [[nodiscard]] std::size_t size() const { return live_; }

    /// Calls f(handle, value) for every object alive, in slot order.
    template <class F>
    void for_each(F&& f) {
        for (uint32_t i = 0; i < slots_.size(); ++i) {
            if (slots_[i].value) f(HandleType{i, slots_[i].generation(), device_id_}, *slots_[i].value);
        }
    }

    /// Removes every object (in slot order), calling f(handle, value) on each first.
    template <class F>
    void clear(F&& f) {
        for_each(f);
        for (uint32_t i = 0; i < slots_.size(); ++i) {
            if (slots_[i].value) (void)remove(HandleType{i, slots_[i].generation(), device_id_});
        }
    }

private:
    struct Slot {
        std::optional<T> value;
        uint32_t key = 0;  ///< key(generation, device_id_) of the handles that reach it now
        [[nodiscard]] uint16_t generation() const { return static_cast<uint16_t>(key); }
    };
    static uint32_t key(uint16_t generation, uint16_t device) { return uint32_t{generation} | uint32_t{device} << 16; }
    /// key(handle.generation, handle.device): on little-endian machines the handle's upper word,
    /// read whole (the handle arrives in one register).
    static uint32_t key(HandleType handle) {
        static_assert(sizeof(HandleType) == 8 && offsetof(HandleType, generation) == 4 && offsetof(HandleType, device) == 6);
        if constexpr (std::endian::native == std::endian::little) {
            return static_cast<uint32_t>(std::bit_cast<uint64_t>(handle) >> 32);
        } else {
            return key(handle.generation, handle.device);
        }
    }

    // The message is built only for a bad handle: lookups run on every draw.
    std::optional<Error> check(HandleType handle) const {
        if (find(handle) != nullptr) return std::nullopt;
        const std::string kind = Tag::kName;
        if (handle.is_null()) return Error{ErrorCode::InvalidHandle, kind + " handle is null"};
        if (handle.device != device_id_) {
            return Error{ErrorCode::InvalidHandle,
                         kind + " handle #" + std::to_string(handle.index) + " belongs to device " +
                             std::to_string(handle.device) + ", not to this device (" +
                             std::to_string(device_id_) + ")"};
        }
        return Error{ErrorCode::InvalidHandle,
                     kind + " handle #" + std::to_string(handle.index) + " is stale: the " + kind + " was destroyed"};
    }

    uint16_t device_id_;
    uint64_t* shared_removals_ = nullptr;
    std::vector<Slot> slots_;
    std::size_t slot_count_ = 0;  ///< slots_.size(), kept so that find() needs no division
    std::vector<uint32_t> free_;
    std::size_t live_ = 0;
    uint64_t removals_ = 0;
};

}  // namespace loom::rhi
