#include "loom/rhi/format.hpp"

#include <algorithm>

namespace loom::rhi {
namespace {

using K = ChannelKind;

constexpr Channel ch(uint8_t bits, ChannelKind kind) { return Channel{bits, kind}; }
constexpr Channel none{};

constexpr FormatFeatures color(Channel r, Channel g, Channel b, Channel a) {
    FormatFeatures f{};
    f.color = {r, g, b, a};
    return f;
}
constexpr FormatFeatures with_srgb(FormatFeatures f) { f.srgb = true; return f; }
constexpr FormatFeatures with_bgra(FormatFeatures f) { f.bgra = true; return f; }
constexpr FormatFeatures with_shared_exponent(FormatFeatures f, uint8_t bits) {
    f.shared_exponent_bits = bits;
    return f;
}
constexpr FormatFeatures depth_stencil(Channel depth, uint8_t stencil) {
    FormatFeatures f{};
    f.depth = depth;
    f.stencil_bits = stencil;
    return f;
}

constexpr FormatFeatures r(uint8_t b, K k) { return color(ch(b, k), none, none, none); }
constexpr FormatFeatures rg(uint8_t b, K k) { return color(ch(b, k), ch(b, k), none, none); }
constexpr FormatFeatures rgba(uint8_t b, K k) { return color(ch(b, k), ch(b, k), ch(b, k), ch(b, k)); }

// Indexed by the enum value; the static_assert below keeps it in step with the enum.
constexpr std::array<FormatInfo, kFormatCount> kFormats{{
    {Format::Undefined, "Undefined", {}, 0},
    {Format::R8Unorm, "R8Unorm", r(8, K::Unorm), 1},
    {Format::R8Snorm, "R8Snorm", r(8, K::Snorm), 1},
    {Format::R8Uint, "R8Uint", r(8, K::Uint), 1},
    {Format::R8Sint, "R8Sint", r(8, K::Sint), 1},
    {Format::RG8Unorm, "RG8Unorm", rg(8, K::Unorm), 2},
    {Format::RG8Snorm, "RG8Snorm", rg(8, K::Snorm), 2},
    {Format::RG8Uint, "RG8Uint", rg(8, K::Uint), 2},
    {Format::RG8Sint, "RG8Sint", rg(8, K::Sint), 2},
    {Format::RGBA8Unorm, "RGBA8Unorm", rgba(8, K::Unorm), 4},
    {Format::RGBA8Snorm, "RGBA8Snorm", rgba(8, K::Snorm), 4},
    {Format::RGBA8Uint, "RGBA8Uint", rgba(8, K::Uint), 4},
    {Format::RGBA8Sint, "RGBA8Sint", rgba(8, K::Sint), 4},
    {Format::RGBA8Srgb, "RGBA8Srgb", with_srgb(rgba(8, K::Unorm)), 4},
    {Format::BGRA8Unorm, "BGRA8Unorm", with_bgra(rgba(8, K::Unorm)), 4},
    {Format::BGRA8Srgb, "BGRA8Srgb", with_bgra(with_srgb(rgba(8, K::Unorm))), 4},
    {Format::R16Unorm, "R16Unorm", r(16, K::Unorm), 2},
    {Format::RG16Unorm, "RG16Unorm", rg(16, K::Unorm), 4},
    {Format::RGBA16Unorm, "RGBA16Unorm", rgba(16, K::Unorm), 8},
    {Format::R16Uint, "R16Uint", r(16, K::Uint), 2},
    {Format::R16Sint, "R16Sint", r(16, K::Sint), 2},
    {Format::R16Float, "R16Float", r(16, K::Float), 2},
    {Format::RG16Float, "RG16Float", rg(16, K::Float), 4},
    {Format::RGBA16Float, "RGBA16Float", rgba(16, K::Float), 8},
    {Format::R32Uint, "R32Uint", r(32, K::Uint), 4},
    {Format::R32Sint, "R32Sint", r(32, K::Sint), 4},
    {Format::R32Float, "R32Float", r(32, K::Float), 4},
    {Format::RG32Float, "RG32Float", rg(32, K::Float), 8},
    {Format::RGBA32Float, "RGBA32Float", rgba(32, K::Float), 16},
    {Format::R11G11B10Float, "R11G11B10Float",
     color(ch(11, K::Float), ch(11, K::Float), ch(10, K::Float), none), 4},
    {Format::RGB10A2Unorm, "RGB10A2Unorm",
     color(ch(10, K::Unorm), ch(10, K::Unorm), ch(10, K::Unorm), ch(2, K::Unorm)), 4},
    // Three 9-bit mantissas sharing one 5-bit exponent.
    {Format::RGB9E5Float, "RGB9E5Float",
     with_shared_exponent(color(ch(9, K::Float), ch(9, K::Float), ch(9, K::Float), none), 5), 4},
    {Format::Depth16, "Depth16", depth_stencil(ch(16, K::Unorm), 0), 2},
    // 24-bit depth is stored in 32 bits (X8_D24 in Vulkan) for upload and readback.
    {Format::Depth24, "Depth24", depth_stencil(ch(24, K::Unorm), 0), 4},
    {Format::Depth32F, "Depth32F", depth_stencil(ch(32, K::Float), 0), 4},
    {Format::Depth24Stencil8, "Depth24Stencil8", depth_stencil(ch(24, K::Unorm), 8), 4},
    // Stored as 32-bit float depth plus 8-bit stencil padded to 64 bits, as GL does.
    {Format::Depth32FStencil8, "Depth32FStencil8", depth_stencil(ch(32, K::Float), 8), 8},
    {Format::Stencil8, "Stencil8", depth_stencil(none, 8), 1},
}};

constexpr bool formats_indexed_by_enum() {
    for (std::size_t i = 0; i < kFormats.size(); ++i) {
        if (static_cast<std::size_t>(kFormats[i].format) != i) return false;
    }
    return true;
}
static_assert(formats_indexed_by_enum(), "kFormats must list every Format in enum order");

constexpr std::array<Format, kFormatCount - 1> make_all_formats() {
    std::array<Format, kFormatCount - 1> out{};
    for (std::size_t i = 1; i < kFormatCount; ++i) out[i - 1] = static_cast<Format>(i);
    return out;
}
constexpr auto kAllFormats = make_all_formats();

}  // namespace

uint32_t FormatInfo::channel_count() const {
    return static_cast<uint32_t>(std::count_if(features.color.begin(), features.color.end(),
                                               [](const Channel& c) { return c.present(); }));
}

ChannelKind FormatInfo::color_kind() const {
    return features.color[0].present() ? features.color[0].kind : ChannelKind::None;
}

bool FormatInfo::is_integer() const {
    const ChannelKind k = color_kind();
    return k == ChannelKind::Uint || k == ChannelKind::Sint;
}

const FormatInfo& format_info(Format format) {
    const auto index = static_cast<std::size_t>(format);
    return index < kFormats.size() ? kFormats[index] : kFormats[0];
}

std::span<const Format> all_formats() { return kAllFormats; }

std::optional<Format> format_from_features(const FormatFeatures& features) {
    for (const FormatInfo& info : kFormats) {
        if (info.format != Format::Undefined && info.features == features) return info.format;
    }
    return std::nullopt;
}

std::string_view format_name(Format format) { return format_info(format).name; }

std::optional<Format> parse_format(std::string_view name) {
    for (const FormatInfo& info : kFormats) {
        if (info.name == name) return info.format;
    }
    return std::nullopt;
}

std::string_view channel_kind_name(ChannelKind kind) {
    switch (kind) {
        case ChannelKind::None: return "none";
        case ChannelKind::Unorm: return "unorm";
        case ChannelKind::Snorm: return "snorm";
        case ChannelKind::Float: return "float";
        case ChannelKind::Uint: return "uint";
        case ChannelKind::Sint: return "sint";
    }
    return "unknown";
}

}  // namespace loom::rhi
