#pragma once
// Uniform sets ("usets" in the LPSG manual): a shader's parameters grouped by how often they
// change — per frame, per pass, per material, per object — each group one uniform block. A set
// keeps its block's bytes on the CPU, computes them from lazy parameters (param.hpp) and goes
// stale when one of them changes; refreshing it recomputes the bytes, and only a set whose bytes
// really changed is uploaded.
//
// Sets of one kind live together in a UniformSetPool, one slot each in one GPU buffer: every
// object's set in one storage buffer indexed by the object's slot (the shader reads
// records[slot]), every material's set in one uniform buffer bound at the material's offset.
// A pool uploads only the slots written since its last upload, adjacent slots in one write.

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "loom/passes/param.hpp"
#include "loom/rhi/descriptions.hpp"
#include "loom/rhi/device.hpp"
#include "loom/rhi/result.hpp"

namespace loom::passes {

/// How often the values of a uniform set change, which decides where it lives and how it is
/// bound: per frame and per pass (a pass's own block, bound with the pass's resources), per
/// material (one slot per material, bound once per material), per object (one record per
/// object in one buffer, read by the object's index).
enum class UpdateFrequency : uint8_t { PerFrame, PerPass, PerMaterial, PerObject };

/// "per-frame", "per-pass", "per-material", "per-object".
std::string_view update_frequency_name(UpdateFrequency frequency);

/// The bytes of one uniform block, computed from parameter nodes and cached until one changes.
class UniformSet final : public ParamNode {
public:
    /// Fills the block (std140/std430 bytes, `size` of them, zeroed before the call) from the
    /// set's inputs; reading them recomputes what changed.
    using Writer = std::function<void(std::span<std::byte> block)>;

    /// A set for the block `block` of `size` bytes, written by `write` from `inputs` (the nodes
    /// it reads; a change of any of them makes the set stale). A new set is stale.
    UniformSet(std::string block, UpdateFrequency frequency, uint32_t size, Writer write,
               std::vector<std::shared_ptr<ParamNode>> inputs);

    [[nodiscard]] const std::string& block() const { return block_; }
    [[nodiscard]] UpdateFrequency frequency() const { return frequency_; }
    [[nodiscard]] uint32_t size() const { return static_cast<uint32_t>(bytes_.size()); }

    /// True when an input changed since the last refresh() (and before the first).
    [[nodiscard]] bool stale() const { return !valid(); }
    /// Recomputes the bytes if the set is stale. True when they differ from the previous bytes
    /// (always after the first refresh): only then does the set need uploading.
    bool refresh();
    /// The bytes of the latest refresh() (zeros before the first).
    [[nodiscard]] std::span<const std::byte> bytes() const { return bytes_; }
    /// How many times refresh() recomputed the bytes.
    [[nodiscard]] uint64_t recomputations() const { return recomputations_; }

    /// Called every time the set goes stale: how a scene puts it on its upload queue.
    void on_stale(std::function<void(UniformSet&)> callback) { on_stale_ = std::move(callback); }

protected:
    void on_invalidated() override;

private:
    std::string block_;
    UpdateFrequency frequency_;
    Writer write_;
    std::vector<std::shared_ptr<ParamNode>> inputs_;
    std::vector<std::byte> bytes_;
    std::vector<std::byte> scratch_;
    std::function<void(UniformSet&)> on_stale_;
    uint64_t recomputations_ = 0;
    bool refreshed_ = false;
};

/// What uploads wrote.
struct UploadStats {
    uint64_t sets = 0;          ///< uniform sets (or other items) uploaded
    uint64_t bytes = 0;         ///< bytes written with Device::write_buffer
    uint64_t writes = 0;        ///< write_buffer calls
    uint64_t growths = 0;       ///< buffers replaced by larger ones
    uint64_t growth_bytes = 0;  ///< bytes re-uploaded into grown buffers (included in `bytes`)

    UploadStats& operator+=(const UploadStats& other);
};

/// Uniform sets of one size in one GPU buffer, a slot each, with a CPU copy of the buffer that
/// uploads read from.
class UniformSetPool {
public:
    /// How slots are laid out.
    enum class Layout : uint8_t {
        /// Slot i at i * set_size: an array the shader indexes (a storage buffer of records).
        Array,
        /// Slot i at i * 256 (the largest uniform-buffer offset alignment any device may ask
        /// for): each slot can be bound on its own at its offset.
        Bindable,
    };

    /// A pool named `name` (the buffer's name) of sets of `set_size` bytes; the buffer gets
    /// `usage` (Uniform or Storage). It grows as slots are allocated.
    UniformSetPool(std::string name, rhi::BufferUsage usage, uint32_t set_size, Layout layout,
                   uint32_t initial_slots = 64);
    /// Destroys the buffer: the device it was made on must still be alive (or release_gpu()).
    ~UniformSetPool();
    UniformSetPool(const UniformSetPool&) = delete;
    UniformSetPool& operator=(const UniformSetPool&) = delete;

    [[nodiscard]] const std::string& name() const { return name_; }
    [[nodiscard]] uint32_t set_size() const { return set_size_; }
    /// Bytes from one slot to the next.
    [[nodiscard]] uint32_t stride() const { return stride_; }
    /// Slots in use.
    [[nodiscard]] uint32_t live() const { return live_; }

    /// A free slot (the lowest; freed slots are reused). Its bytes are zero until written.
    uint32_t allocate();
    /// Frees `slot`; a pending upload of it is dropped.
    void release(uint32_t slot);
    /// Copies `bytes` (at most set_size) into the slot and marks it for upload when they
    /// differ from what it holds, or always with `force` (a slot new to its set, whose buffer
    /// bytes may be an earlier set's). Returns whether it was marked.
    bool write(uint32_t slot, std::span<const std::byte> bytes, bool force = false);
    /// Slots written since the last upload.
    [[nodiscard]] std::size_t pending() const { return pending_.size(); }

    /// Makes the GPU buffer match: creates it (or a larger one, copying every live slot into
    /// it) when the slots outgrew it, then writes the pending slots, runs of adjacent slots in
    /// one write_buffer when the layout is Array. The first call binds the pool to `device`;
    /// another device is an InvalidState error.
    Status upload(rhi::Device& device, UploadStats& stats);

    /// The buffer (null before the first upload).
    [[nodiscard]] rhi::BufferHandle buffer() const { return buffer_; }
    /// Byte offset of `slot` in the buffer.
    [[nodiscard]] uint64_t offset(uint32_t slot) const { return uint64_t{slot} * stride_; }
    /// The range of one slot, for binding it as a uniform block.
    [[nodiscard]] rhi::BufferBinding binding(uint32_t slot) const { return {buffer_, offset(slot), set_size_}; }
    /// The whole buffer, for binding the array of every slot.
    [[nodiscard]] rhi::BufferBinding whole() const { return {buffer_, 0, 0}; }

    /// Destroys the buffer; the next upload() creates it again (on any device).
    void release_gpu();

private:
    std::string name_;
    rhi::BufferUsage usage_;
    uint32_t set_size_;
    uint32_t stride_;
    Layout layout_;
    std::vector<std::byte> mirror_;       ///< capacity() * stride_ bytes
    std::vector<uint8_t> live_flags_;     ///< per slot
    std::vector<uint8_t> pending_flags_;  ///< per slot
    std::vector<uint32_t> pending_;
    std::vector<uint32_t> free_slots_;    ///< freed slots, reused lowest first
    uint32_t next_slot_ = 0;              ///< slots below it were handed out at least once
    uint32_t live_ = 0;
    rhi::Device* device_ = nullptr;
    rhi::BufferHandle buffer_;
    uint32_t buffer_slots_ = 0;
};

}  // namespace loom::passes
