#pragma once
// Buffer specs: the constraints a buffer port puts on the buffer connected to it, the buffer
// counterpart of TextureSpec (texture_spec.hpp). A light list, indirect-draw arguments, a
// histogram or a particle buffer passes between passes like a texture does: its ports join, it
// lives from its producer to its last reader, and buffers whose lifetimes do not overlap share
// memory. docs/framegraph.md, "Buffers", shows them in use.
//
// Join (join_buffer_specs, join.hpp): the sizes must be equal once evaluated for the frame (like texture
// sizes), the alignment takes the largest, the usage the union.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "loom/framegraph/texture_spec.hpp"
#include "loom/rhi/descriptions.hpp"
#include "loom/rhi/result.hpp"

namespace loom::fg {

/// The largest buffer a plan may ask for: 1 TiB, far above any GPU's single allocation, and low
/// enough that sums of buffer sizes over a plan cannot overflow 64 bits.
inline constexpr uint64_t kMaxBufferBytes = uint64_t{1} << 40;
/// The largest alignment a buffer port may ask for (a power of two): 64 KiB, a memory page.
inline constexpr uint64_t kMaxBufferAlignment = 64 * 1024;

/// Size constraint of a buffer: bytes, or bytes per pixel or per tile of (a scale of) the frame.
struct BufferSize {
    /// How the size is given.
    enum class Kind : uint8_t {
        Absolute,  ///< `bytes` in total
        PerPixel,  ///< `bytes` per pixel of a frame scaled by `scale` (each side rounded, at least 1)
        PerTile,   ///< `bytes` per tile of `tile` pixels covering the frame (tiles rounded up)
    };

    Kind kind = Kind::Absolute;
    uint64_t bytes = 0;
    float scale = 1.0f;  ///< PerPixel only
    Extent2D tile{};     ///< PerTile only

    /// `bytes` bytes.
    static BufferSize absolute(uint64_t bytes);
    /// `bytes_per_pixel` for every pixel of the frame scaled by `scale` (e.g. a per-pixel
    /// linked-list head buffer, 4 bytes at 1x).
    static BufferSize per_pixel(uint64_t bytes_per_pixel, float scale = 1.0f);
    /// `bytes_per_tile` for every tile of `tile_width` x `tile_height` pixels covering the frame
    /// (e.g. a tiled light list: 16x16 tiles of 256 light indices, 1 KiB each).
    static BufferSize per_tile(uint32_t tile_width, uint32_t tile_height, uint64_t bytes_per_tile);

    /// The size in bytes for a frame of size `frame`; nullopt when it does not fit in 64 bits.
    [[nodiscard]] std::optional<uint64_t> evaluate(Extent2D frame) const;

    friend bool operator==(const BufferSize&, const BufferSize&) = default;
};

/// The constraints of one buffer port. Every member left empty is unconstrained; a buffer's size
/// must be given by at least one of its ports.
struct BufferSpec {
    std::optional<BufferSize> size;
    /// How this port uses the buffer (storage, uniform, vertex, index, indirect, copy). A port
    /// that reads names the one way it reads; none means storage (copy in a copy pass). Joined
    /// by union: the buffer is created with every port's usage.
    rhi::BufferUsage usage = rhi::BufferUsage::None;
    /// Least alignment of the buffer's offset in memory, a power of two (e.g. for a structure
    /// read with a dynamic offset). Joined by taking the largest.
    std::optional<uint64_t> alignment;

    /// A spec of `bytes` bytes.
    static BufferSpec of_size(uint64_t bytes);
    /// A spec of a size relative to the frame (BufferSize::per_pixel, per_tile).
    static BufferSpec sized(const BufferSize& size);
    /// The empty spec: no constraint at all.
    static BufferSpec any() { return {}; }

    /// This spec with `extra` usage.
    [[nodiscard]] BufferSpec with_usage(rhi::BufferUsage extra) const;
    /// This spec with an alignment (a power of two).
    [[nodiscard]] BufferSpec with_alignment(uint64_t alignment) const;

    /// True when no property is constrained.
    [[nodiscard]] bool unconstrained() const;

    friend bool operator==(const BufferSpec&, const BufferSpec&) = default;
};

/// The bytes of a buffer a port reads or writes: `size` bytes from `offset` (size 0: to the end).
/// Two ports of one pass may read and modify one buffer in place when their ranges do not overlap.
struct BufferRange {
    uint64_t offset = 0;
    uint64_t size = 0;

    /// True for the whole buffer.
    [[nodiscard]] bool whole() const { return offset == 0 && size == 0; }
    friend bool operator==(const BufferRange&, const BufferRange&) = default;
};

/// A joined buffer spec made concrete: what a physical buffer is created from.
struct ResolvedBufferSpec {
    uint64_t size = 0;
    rhi::BufferUsage usage = rhi::BufferUsage::None;
    uint64_t alignment = 1;

    friend bool operator==(const ResolvedBufferSpec&, const ResolvedBufferSpec&) = default;
};

/// Makes `spec` concrete for a frame of size `frame`. Errors (ErrorCode::Graph) name `what`: no
/// size, a size of 0 or above kMaxBufferBytes, an alignment that is not a power of two or is
/// above kMaxBufferAlignment. Usage is copied as is; the planner adds what the ports' roles need.
Result<ResolvedBufferSpec> resolve_buffer(const BufferSpec& spec, Extent2D frame, std::string_view what);

/// The rhi description of a buffer with this spec.
rhi::BufferDesc to_buffer_desc(const ResolvedBufferSpec& spec, std::string name);

/// "4096 bytes", "16 bytes per pixel", "16 bytes per pixel of 0.5 x frame", "1024 bytes per 16x16 tile".
std::string describe_buffer_size(const BufferSize& size);
/// "storage|indirect"; "none" for no flags.
std::string describe_buffer_usage(rhi::BufferUsage usage);
/// Short names of the buffer usage flags, as in graph files: "vertex", "index", "uniform",
/// "storage", "indirect", "copy_src", "copy_dst".
std::optional<rhi::BufferUsage> parse_buffer_usage_flag(std::string_view name);
/// e.g. "size=16 bytes per pixel usage=storage alignment=256".
std::string describe_buffer_spec(const BufferSpec& spec);
/// e.g. "buffer 8294400 bytes storage|vertex" (plus " aligned 256" when above 1).
std::string describe_resolved_buffer(const ResolvedBufferSpec& spec);

}  // namespace loom::fg
