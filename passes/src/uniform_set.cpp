#include "loom/passes/uniform_set.hpp"

#include <algorithm>
#include <cstring>
#include <functional>

namespace loom::passes {
namespace {

/// The largest minUniformBufferOffsetAlignment Vulkan allows (and more than GL drivers ask).
constexpr uint32_t kMaxUniformOffsetAlignment = 256;

uint32_t align_up(uint32_t value, uint32_t alignment) { return (value + alignment - 1) / alignment * alignment; }

}  // namespace

std::string_view update_frequency_name(UpdateFrequency frequency) {
    switch (frequency) {
        case UpdateFrequency::PerFrame: return "per-frame";
        case UpdateFrequency::PerPass: return "per-pass";
        case UpdateFrequency::PerMaterial: return "per-material";
        case UpdateFrequency::PerObject: return "per-object";
    }
    return "unknown";
}

// ---- UniformSet ------------------------------------------------------------------------------

UniformSet::UniformSet(std::string block, UpdateFrequency frequency, uint32_t size, Writer write,
                       std::vector<std::shared_ptr<ParamNode>> inputs)
    : block_(std::move(block)), frequency_(frequency), write_(std::move(write)), inputs_(std::move(inputs)),
      bytes_(size), scratch_(size) {
    for (const auto& input : inputs_) depend_on(*input);
}

bool UniformSet::refresh() {
    if (!stale()) return false;
    std::fill(scratch_.begin(), scratch_.end(), std::byte{0});
    write_(scratch_);
    ++recomputations_;
    mark_valid();
    const bool changed = !refreshed_ || scratch_ != bytes_;
    refreshed_ = true;
    if (changed) bytes_.swap(scratch_);
    return changed;
}

void UniformSet::on_invalidated() {
    if (on_stale_) on_stale_(*this);
}

UploadStats& UploadStats::operator+=(const UploadStats& other) {
    sets += other.sets;
    bytes += other.bytes;
    writes += other.writes;
    growths += other.growths;
    growth_bytes += other.growth_bytes;
    return *this;
}

// ---- UniformSetPool --------------------------------------------------------------------------

UniformSetPool::UniformSetPool(std::string name, rhi::BufferUsage usage, uint32_t set_size, Layout layout,
                               uint32_t initial_slots)
    : name_(std::move(name)), usage_(usage), set_size_(set_size),
      stride_(layout == Layout::Array ? set_size : align_up(set_size, kMaxUniformOffsetAlignment)), layout_(layout) {
    const uint32_t slots = std::max(initial_slots, 1u);
    mirror_.resize(std::size_t{slots} * stride_);
    live_flags_.resize(slots);
    pending_flags_.resize(slots);
}

UniformSetPool::~UniformSetPool() { release_gpu(); }

uint32_t UniformSetPool::allocate() {
    uint32_t slot;
    if (!free_slots_.empty()) {
        std::pop_heap(free_slots_.begin(), free_slots_.end(), std::greater<>());
        slot = free_slots_.back();
        free_slots_.pop_back();
    } else {
        slot = next_slot_++;
        if (slot >= live_flags_.size()) {
            const std::size_t slots = live_flags_.size() * 2;
            mirror_.resize(slots * stride_);
            live_flags_.resize(slots);
            pending_flags_.resize(slots);
        }
    }
    live_flags_[slot] = 1;
    std::memset(mirror_.data() + offset(slot), 0, stride_);
    ++live_;
    return slot;
}

void UniformSetPool::release(uint32_t slot) {
    if (slot >= next_slot_ || !live_flags_[slot]) return;
    live_flags_[slot] = 0;
    if (pending_flags_[slot]) {
        pending_flags_[slot] = 0;
        std::erase(pending_, slot);
    }
    free_slots_.push_back(slot);
    std::push_heap(free_slots_.begin(), free_slots_.end(), std::greater<>());
    --live_;
}

bool UniformSetPool::write(uint32_t slot, std::span<const std::byte> bytes, bool force) {
    if (slot >= next_slot_ || !live_flags_[slot]) return false;
    const std::size_t size = std::min<std::size_t>(bytes.size(), set_size_);
    std::byte* target = mirror_.data() + offset(slot);
    if (!force && std::memcmp(target, bytes.data(), size) == 0) return false;
    std::memcpy(target, bytes.data(), size);
    if (!pending_flags_[slot]) {
        pending_flags_[slot] = 1;
        pending_.push_back(slot);
    }
    return true;
}

Status UniformSetPool::upload(rhi::Device& device, UploadStats& stats) {
    if (device_ && device_ != &device) {
        return make_error(ErrorCode::InvalidState,
                          "uniform set pool '" + name_ + "' holds a buffer of another device (release_gpu() first)");
    }
    device_ = &device;
    if (next_slot_ > buffer_slots_) {
        // Outgrown (or never made): a buffer for every slot the mirror has room for, filled from
        // the mirror, since the slots keep their offsets.
        const auto slots = static_cast<uint32_t>(live_flags_.size());
        rhi::BufferDesc desc;
        desc.name = name_;
        desc.size = uint64_t{slots} * stride_;
        desc.usage = usage_;
        auto buffer = device.create_buffer(desc);
        if (!buffer) return buffer.take_error();
        if (buffer_) (void)device.destroy(buffer_);
        buffer_ = *buffer;
        buffer_slots_ = slots;
        const uint64_t used = uint64_t{next_slot_} * stride_;
        LOOM_TRY(device.write_buffer(buffer_, 0, std::span<const std::byte>(mirror_.data(), used)));
        ++stats.growths;
        ++stats.writes;
        stats.growth_bytes += used;
        stats.bytes += used;
        stats.sets += live_;
        for (uint32_t slot : pending_) pending_flags_[slot] = 0;
        pending_.clear();
        return {};
    }
    if (pending_.empty()) return {};
    std::sort(pending_.begin(), pending_.end());
    for (std::size_t i = 0; i < pending_.size();) {
        std::size_t end = i + 1;
        // Array slots have no padding between them: adjacent ones go in one write.
        if (layout_ == Layout::Array) {
            while (end < pending_.size() && pending_[end] == pending_[end - 1] + 1) ++end;
        }
        const uint64_t first = offset(pending_[i]);
        const uint64_t size = uint64_t{stride_} * (end - i - 1) + set_size_;
        LOOM_TRY(device.write_buffer(buffer_, first, std::span<const std::byte>(mirror_.data() + first, size)));
        ++stats.writes;
        stats.bytes += size;
        stats.sets += end - i;
        i = end;
    }
    for (uint32_t slot : pending_) pending_flags_[slot] = 0;
    pending_.clear();
    return {};
}

void UniformSetPool::release_gpu() {
    if (device_ && buffer_) (void)device_->destroy(buffer_);
    buffer_ = {};
    buffer_slots_ = 0;
    device_ = nullptr;
    // Everything must be written again into the next buffer.
}

}  // namespace loom::passes
