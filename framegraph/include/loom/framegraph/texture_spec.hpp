#pragma once
// Texture specs: the constraints a port puts on the texture connected to it. Each property is
// optional; an unconstrained property takes whatever the connected ports ask for, or a default
// (see resolve()) when nobody asks. Specs of connected ports are reduced by join() (join.hpp).

#include <cstdint>
#include <optional>
#include <string>

#include "loom/rhi/descriptions.hpp"
#include "loom/rhi/format.hpp"

namespace loom::fg {

/// Limits on what a port, a frame or a plan may ask for: one set, enforced by resolve() for the
/// C++ API and by the graph-file loader and loom-plan before that. They are at or above what
/// GPUs offer today (2D textures of 16384 or 32768 texels per side, 2048 array layers, 64 as
/// Vulkan's largest sample-count flag), so no plan a device could realise is refused here, and
/// low enough that no byte size overflows 64 bits: 65536² texels × 16 bytes × 2048 layers × 64
/// samples is 2^53 bytes. A device's own, lower texture size is checked when a plan is realised
/// (Executor).
inline constexpr uint32_t kMaxTextureExtent = 65536;  ///< texels per side, frames included
inline constexpr uint32_t kMaxTextureLayers = 2048;   ///< array layers
inline constexpr uint32_t kMaxTextureSamples = 64;    ///< samples per texel (a power of two)

/// A width × height in texels.
struct Extent2D {
    uint32_t width = 0;
    uint32_t height = 0;

    friend bool operator==(const Extent2D&, const Extent2D&) = default;
};

/// Size constraint: an absolute extent, or a scale of the frame size.
struct SizeSpec {
    /// Texels, or a scale of the frame size.
    enum class Kind : uint8_t { Absolute, Relative };

    Kind kind = Kind::Relative;
    Extent2D extent{};    ///< Absolute: the size in texels
    float scale_x = 1.0f; ///< Relative: width = round(frame.width × scale_x), at least 1
    float scale_y = 1.0f; ///< Relative: height = round(frame.height × scale_y), at least 1

    /// A size in texels.
    static SizeSpec absolute(uint32_t width, uint32_t height);
    /// A size of `scale` times the frame size.
    static SizeSpec relative(float scale) { return relative(scale, scale); }
    /// A size of (scale_x, scale_y) times the frame size.
    static SizeSpec relative(float scale_x, float scale_y);

    /// The size in texels for a frame of size `frame`.
    [[nodiscard]] Extent2D evaluate(Extent2D frame) const;

    friend bool operator==(const SizeSpec&, const SizeSpec&) = default;
};

/// The constraints of one port. Every member left empty is unconstrained.
struct TextureSpec {
    /// Internal format as destructured features (rhi::FormatInfo::features). A full format sets
    /// every feature; a partial constraint ("3 channels, 16 bits, float") sets only those
    /// channels, and the join (bits take the maximum) lets a richer format satisfy it.
    std::optional<rhi::FormatFeatures> format;
    std::optional<SizeSpec> size;
    std::optional<uint32_t> samples;
    std::optional<uint32_t> mips;
    std::optional<uint32_t> layers;
    /// Usage this port needs beyond what its role implies (see derive_port_usage); e.g.
    /// Storage for a port written or read as a storage image. Joined by union.
    rhi::TextureUsage usage = rhi::TextureUsage::None;
    /// A cube map: six square layers (faces +X, -X, +Y, -Y, +Z, -Z) sampled as a samplerCube and
    /// written face by face through layer ranges. Joined by "or": one port asking is enough.
    bool cube = false;

    /// A spec that asks for exactly `format` and nothing else.
    static TextureSpec of(rhi::Format format);
    /// A partial colour constraint: the first `channels` of R, G, B, A with `bits` bits of `kind`.
    static TextureSpec color(uint32_t channels, uint32_t bits, rhi::ChannelKind kind);
    /// A partial depth/stencil constraint (depth_bits or stencil_bits may be 0).
    static TextureSpec depth_stencil(uint32_t depth_bits, rhi::ChannelKind depth_kind, uint32_t stencil_bits = 0);
    /// The empty spec: no constraint at all.
    static TextureSpec any() { return {}; }

    // Copies of this spec with one more constraint, for chaining:
    // TextureSpec::of(Format::RGBA16Float).with_scale(0.5f).with_samples(4).
    [[nodiscard]] TextureSpec with_format(rhi::Format f) const;
    /// This spec with the format constrained to `features` (possibly partial).
    [[nodiscard]] TextureSpec with_features(const rhi::FormatFeatures& features) const;
    /// This spec with an absolute size.
    [[nodiscard]] TextureSpec with_size(uint32_t width, uint32_t height) const;
    /// This spec with a size relative to the frame.
    [[nodiscard]] TextureSpec with_scale(float scale) const { return with_scale(scale, scale); }
    /// This spec with a size relative to the frame, per axis.
    [[nodiscard]] TextureSpec with_scale(float scale_x, float scale_y) const;
    /// This spec with a sample count.
    [[nodiscard]] TextureSpec with_samples(uint32_t count) const;
    /// This spec with a mip level count.
    [[nodiscard]] TextureSpec with_mips(uint32_t count) const;
    /// This spec with an array layer count.
    [[nodiscard]] TextureSpec with_layers(uint32_t count) const;
    /// This spec asking for extra usage (e.g. Storage).
    [[nodiscard]] TextureSpec with_usage(rhi::TextureUsage extra) const;
    /// This spec as a cube map (and 6 layers).
    [[nodiscard]] TextureSpec with_cube() const;

    /// True when no property is constrained.
    [[nodiscard]] bool unconstrained() const;

    friend bool operator==(const TextureSpec&, const TextureSpec&) = default;
};

/// Features of a partial colour constraint (see TextureSpec::color).
rhi::FormatFeatures color_features(uint32_t channels, uint32_t bits, rhi::ChannelKind kind);

/// Readable form of a feature set: the format name when one matches exactly ("RGBA16Float"),
/// else the channels ("RGB16 float", "R16 float G8 unorm", "depth24 unorm + stencil8", with
/// " srgb", " bgra", " shared-exponent5" appended as they apply).
std::string describe_features(const rhi::FormatFeatures& features);

/// "1920x1080" or "0.5 x frame" / "0.5x0.25 x frame".
std::string describe_size(const SizeSpec& size);

/// "sampled|color_attachment"; "none" for no flags.
std::string describe_usage(rhi::TextureUsage usage);

/// Short names of the usage flags, as in graph files: "sampled", "color_attachment",
/// "depth_stencil_attachment", "storage", "copy_src", "copy_dst".
std::optional<rhi::TextureUsage> parse_usage_flag(std::string_view name);

/// Readable form of a whole spec, e.g. "format=RGBA16Float size=1 x frame samples=4".
std::string describe_spec(const TextureSpec& spec);

}  // namespace loom::fg
