#pragma once
// How many bytes a texture takes and how it must be aligned inside a heap. The planner asks a
// MemoryModel for every resource and texture; the executor plugs in the device's real
// rhi::Device::texture_memory_requirements, tests and tools use DefaultMemoryModel.

#include <cstdint>
#include <optional>

#include "loom/rhi/checked_math.hpp"
#include "loom/rhi/descriptions.hpp"
#include "loom/rhi/result.hpp"

namespace loom::fg {

/// Byte sizes and alignments of textures in heaps, for planning.
class MemoryModel {
public:
    /// Models are used through this interface.
    virtual ~MemoryModel() = default;
    /// Size and alignment of a texture described by `desc` inside a heap.
    virtual Result<rhi::MemoryRequirements> requirements(const rhi::TextureDesc& desc) = 0;

    /// The alignment buffer_requirements() gives by default: 256 bytes, the largest offset
    /// alignment Vulkan allows a device to ask of uniform and storage buffers.
    static constexpr uint64_t kDefaultBufferAlignment = 256;
    /// Size and alignment of a buffer described by `desc` inside a heap. By default its size
    /// rounded up to kDefaultBufferAlignment, aligned to that; a device's model asks the device.
    virtual Result<rhi::MemoryRequirements> buffer_requirements(const rhi::BufferDesc& desc);
};

/// bytes_per_texel × width × height × layers × samples, summed over the mip chain, rounded up
/// to the alignment (64 KiB by default, the usual granularity of GPU memory pages).
class DefaultMemoryModel final : public MemoryModel {
public:
    static constexpr uint64_t kDefaultAlignment = 64 * 1024;

    /// A model rounding every texture up to `alignment`.
    explicit DefaultMemoryModel(uint64_t alignment = kDefaultAlignment) : alignment_(alignment) {}

    /// Size (rounded up to the alignment) and alignment of `desc`.
    Result<rhi::MemoryRequirements> requirements(const rhi::TextureDesc& desc) override;

    /// The unaligned byte count of a texture, or nullopt when it does not fit in 64 bits.
    static std::optional<uint64_t> checked_texture_bytes(const rhi::TextureDesc& desc);
    /// The unaligned byte count of a texture, saturated at the largest uint64 (never wrapped).
    static uint64_t texture_bytes(const rhi::TextureDesc& desc);

private:
    uint64_t alignment_;
};

/// `value` rounded up to a multiple of `alignment` (alignment 0 or 1: unchanged). Wraps past
/// 2^64; sizes from user input go through checked::align_up instead.
constexpr uint64_t align_up(uint64_t value, uint64_t alignment) { return checked::align_up_in_range(value, alignment); }

}  // namespace loom::fg
