#pragma once
// Texture formats as one enum, each destructured into the features the frame graph's join works
// on (Hafner, ELS 2019, §6.1): per-channel bits and kind, depth bits, stencil bits, shared
// exponent bits, sRGB, compression. A set of features encodes back to its enum value.

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace loom::rhi {

/// Every texture format loom knows; format_info() destructures each into its features.
enum class Format : uint8_t {
    Undefined = 0,
    // 8 bits per channel
    R8Unorm, R8Snorm, R8Uint, R8Sint,
    RG8Unorm, RG8Snorm, RG8Uint, RG8Sint,
    RGBA8Unorm, RGBA8Snorm, RGBA8Uint, RGBA8Sint,
    RGBA8Srgb, BGRA8Unorm, BGRA8Srgb,
    // 16 bits per channel
    R16Unorm, RG16Unorm, RGBA16Unorm,
    R16Uint, R16Sint,
    R16Float, RG16Float, RGBA16Float,
    // 32 bits per channel
    R32Uint, R32Sint,
    R32Float, RG32Float, RGBA32Float,
    // packed
    R11G11B10Float, RGB10A2Unorm, RGB9E5Float,
    // depth / stencil
    Depth16, Depth24, Depth32F, Depth24Stencil8, Depth32FStencil8, Stencil8,
};

/// Number of enum values including Undefined; formats are 0..kFormatCount-1.
inline constexpr std::size_t kFormatCount = static_cast<std::size_t>(Format::Stencil8) + 1;

/// How the bits of one channel are interpreted (the paper's "format of the channel").
enum class ChannelKind : uint8_t { None, Unorm, Snorm, Float, Uint, Sint };

/// One channel: its bit count and kind. bits == 0 means the channel is absent.
struct Channel {
    uint8_t bits = 0;
    ChannelKind kind = ChannelKind::None;

    /// True when the channel exists.
    [[nodiscard]] bool present() const { return bits != 0; }
    friend bool operator==(const Channel&, const Channel&) = default;
};

/// The destructured features of a format: everything that distinguishes one enum value from
/// another, and nothing else (byte size and name are derived).
struct FormatFeatures {
    std::array<Channel, 4> color{};  ///< R, G, B, A in that order, whatever the memory order
    Channel depth{};                 ///< depth bits and kind (Unorm or Float)
    uint8_t stencil_bits = 0;        ///< stencil is always unsigned integer
    uint8_t shared_exponent_bits = 0;///< RGB9E5: 5; the colour channels then hold mantissas
    bool srgb = false;               ///< colour channels are sRGB-encoded
    bool compressed = false;         ///< block compressed (no such format in the enum yet)
    bool bgra = false;               ///< memory order is B, G, R, A (swapchain formats)

    friend bool operator==(const FormatFeatures&, const FormatFeatures&) = default;
};

/// Static description of a format.
struct FormatInfo {
    Format format = Format::Undefined;
    std::string_view name;          ///< e.g. "RGBA16Float"; parse_format accepts it back
    FormatFeatures features;
    uint32_t bytes_per_texel = 0;   ///< as stored for upload/readback

    /// True for formats with a depth channel.
    [[nodiscard]] bool has_depth() const { return features.depth.present(); }
    /// True for formats with stencil bits.
    [[nodiscard]] bool has_stencil() const { return features.stencil_bits != 0; }
    /// True for depth, stencil and depth/stencil formats.
    [[nodiscard]] bool is_depth_stencil() const { return has_depth() || has_stencil(); }
    /// True for colour formats.
    [[nodiscard]] bool is_color() const { return format != Format::Undefined && !is_depth_stencil(); }
    [[nodiscard]] uint32_t channel_count() const;  ///< colour channels present (0 for depth/stencil)
    /// Kind shared by all colour channels (None for depth/stencil or Undefined).
    [[nodiscard]] ChannelKind color_kind() const;
    /// True for Uint/Sint colour formats, which cannot be filtered or blended.
    [[nodiscard]] bool is_integer() const;
};

/// Description of `format`. Every enum value, including Undefined, has one.
const FormatInfo& format_info(Format format);

/// All formats except Undefined, in enum order.
std::span<const Format> all_formats();

/// The enum value with exactly these features, or nullopt if none exists.
std::optional<Format> format_from_features(const FormatFeatures& features);

/// Name of a format, as in the enum ("RGBA8Unorm").
std::string_view format_name(Format format);

/// Inverse of format_name; case-sensitive. nullopt for unknown names.
std::optional<Format> parse_format(std::string_view name);

/// "unorm", "float", ... for messages.
std::string_view channel_kind_name(ChannelKind kind);

}  // namespace loom::rhi
