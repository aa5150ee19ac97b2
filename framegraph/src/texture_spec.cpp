#include "loom/framegraph/texture_spec.hpp"

#include <limits>

#include "loom/rhi/checked_math.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <utility>

namespace loom::fg {
namespace {

using rhi::ChannelKind;
using rhi::TextureUsage;

constexpr std::array<std::pair<TextureUsage, std::string_view>, 6> kUsageNames{{
    {TextureUsage::Sampled, "sampled"},
    {TextureUsage::ColorAttachment, "color_attachment"},
    {TextureUsage::DepthStencilAttachment, "depth_stencil_attachment"},
    {TextureUsage::Storage, "storage"},
    {TextureUsage::CopySrc, "copy_src"},
    {TextureUsage::CopyDst, "copy_dst"},
}};

// Shortest text that reads back as the same float ("0.5", "1", "0.333333").
std::string format_scale(float value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%g", static_cast<double>(value));
    return buffer;
}

// Saturates at the largest uint32 instead of converting an out-of-range double (undefined
// behaviour); resolve() refuses such sizes with the real value.
uint32_t scaled(uint32_t frame, float scale) {
    const double texels = std::round(static_cast<double>(frame) * static_cast<double>(scale));
    if (texels < 1.0) return 1u;
    return checked::to_integer<uint32_t>(texels).value_or(std::numeric_limits<uint32_t>::max());
}

}  // namespace

SizeSpec SizeSpec::absolute(uint32_t width, uint32_t height) {
    SizeSpec size;
    size.kind = Kind::Absolute;
    size.extent = {width, height};
    return size;
}

SizeSpec SizeSpec::relative(float scale_x_, float scale_y_) {
    SizeSpec size;
    size.kind = Kind::Relative;
    size.scale_x = scale_x_;
    size.scale_y = scale_y_;
    return size;
}

Extent2D SizeSpec::evaluate(Extent2D frame) const {
    if (kind == Kind::Absolute) return extent;
    return {scaled(frame.width, scale_x), scaled(frame.height, scale_y)};
}

TextureSpec TextureSpec::of(rhi::Format format) { return TextureSpec{}.with_format(format); }

TextureSpec TextureSpec::color(uint32_t channels, uint32_t bits, ChannelKind kind) {
    return TextureSpec{}.with_features(color_features(channels, bits, kind));
}

TextureSpec TextureSpec::depth_stencil(uint32_t depth_bits, ChannelKind depth_kind, uint32_t stencil_bits) {
    rhi::FormatFeatures features{};
    if (depth_bits != 0) features.depth = rhi::Channel{static_cast<uint8_t>(depth_bits), depth_kind};
    features.stencil_bits = static_cast<uint8_t>(stencil_bits);
    return TextureSpec{}.with_features(features);
}

TextureSpec TextureSpec::with_format(rhi::Format f) const { return with_features(rhi::format_info(f).features); }

TextureSpec TextureSpec::with_features(const rhi::FormatFeatures& features) const {
    TextureSpec copy = *this;
    copy.format = features;
    return copy;
}

TextureSpec TextureSpec::with_size(uint32_t width, uint32_t height) const {
    TextureSpec copy = *this;
    copy.size = SizeSpec::absolute(width, height);
    return copy;
}

TextureSpec TextureSpec::with_scale(float scale_x, float scale_y) const {
    TextureSpec copy = *this;
    copy.size = SizeSpec::relative(scale_x, scale_y);
    return copy;
}

TextureSpec TextureSpec::with_samples(uint32_t count) const {
    TextureSpec copy = *this;
    copy.samples = count;
    return copy;
}

TextureSpec TextureSpec::with_mips(uint32_t count) const {
    TextureSpec copy = *this;
    copy.mips = count;
    return copy;
}

TextureSpec TextureSpec::with_layers(uint32_t count) const {
    TextureSpec copy = *this;
    copy.layers = count;
    return copy;
}

TextureSpec TextureSpec::with_usage(TextureUsage extra) const {
    TextureSpec copy = *this;
    copy.usage |= extra;
    return copy;
}

TextureSpec TextureSpec::with_cube() const {
    TextureSpec copy = *this;
    copy.cube = true;
    copy.layers = 6;
    return copy;
}

namespace {
// Compared whole, so that a field added to TextureSpec counts too; built once rather than per call
// (unconstrained() runs for every declared port).
const TextureSpec kUnconstrainedSpec{};
}  // namespace

bool TextureSpec::unconstrained() const { return *this == kUnconstrainedSpec; }

rhi::FormatFeatures color_features(uint32_t channels, uint32_t bits, ChannelKind kind) {
    rhi::FormatFeatures features{};
    const uint32_t count = std::min<uint32_t>(channels, 4);
    for (uint32_t i = 0; i < count; ++i) features.color[i] = rhi::Channel{static_cast<uint8_t>(bits), kind};
    return features;
}

std::string describe_features(const rhi::FormatFeatures& features) {
    if (auto exact = rhi::format_from_features(features)) return std::string(rhi::format_name(*exact));

    std::string out;
    const auto& c = features.color;
    const bool uniform = std::all_of(c.begin(), c.end(), [&](const rhi::Channel& ch) {
        return !ch.present() || (ch.bits == c[0].bits && ch.kind == c[0].kind);
    });
    // Uniform channels that are a prefix of R, G, B, A read as "RGB16 float".
    std::size_t prefix = 0;
    while (prefix < 4 && c[prefix].present()) ++prefix;
    const bool is_prefix = std::none_of(c.begin() + static_cast<std::ptrdiff_t>(prefix), c.end(),
                                        [](const rhi::Channel& ch) { return ch.present(); });
    static constexpr std::string_view kNames = "RGBA";
    if (prefix > 0 && uniform && is_prefix) {
        out += kNames.substr(0, prefix);
        out += std::to_string(c[0].bits) + " " + std::string(rhi::channel_kind_name(c[0].kind));
    } else {
        for (std::size_t i = 0; i < 4; ++i) {
            if (!c[i].present()) continue;
            if (!out.empty()) out += ' ';
            out += kNames[i];
            out += std::to_string(c[i].bits) + " " + std::string(rhi::channel_kind_name(c[i].kind));
        }
    }
    if (features.depth.present()) {
        if (!out.empty()) out += ' ';
        out += "depth" + std::to_string(features.depth.bits) + " " +
               std::string(rhi::channel_kind_name(features.depth.kind));
    }
    if (features.stencil_bits != 0) {
        if (!out.empty()) out += " + ";
        out += "stencil" + std::to_string(features.stencil_bits);
    }
    if (out.empty()) out = "no channels";
    if (features.srgb) out += " srgb";
    if (features.bgra) out += " bgra";
    if (features.compressed) out += " compressed";
    if (features.shared_exponent_bits != 0) out += " shared-exponent" + std::to_string(features.shared_exponent_bits);
    return out;
}

std::string describe_size(const SizeSpec& size) {
    if (size.kind == SizeSpec::Kind::Absolute) {
        return std::to_string(size.extent.width) + "x" + std::to_string(size.extent.height);
    }
    if (size.scale_x == size.scale_y) return format_scale(size.scale_x) + " x frame";
    return format_scale(size.scale_x) + "x" + format_scale(size.scale_y) + " x frame";
}

std::string describe_usage(TextureUsage usage) {
    std::string out;
    for (const auto& [flag, name] : kUsageNames) {
        if (!rhi::has_all(usage, flag)) continue;
        if (!out.empty()) out += '|';
        out += name;
    }
    return out.empty() ? "none" : out;
}

std::optional<TextureUsage> parse_usage_flag(std::string_view name) {
    for (const auto& [flag, flag_name] : kUsageNames) {
        if (flag_name == name) return flag;
    }
    return std::nullopt;
}

std::string describe_spec(const TextureSpec& spec) {
    std::string out;
    auto add = [&](std::string part) {
        if (!out.empty()) out += ' ';
        out += std::move(part);
    };
    if (spec.format) add("format=" + describe_features(*spec.format));
    if (spec.size) add("size=" + describe_size(*spec.size));
    if (spec.samples) add("samples=" + std::to_string(*spec.samples));
    if (spec.mips) add("mips=" + std::to_string(*spec.mips));
    if (spec.layers) add("layers=" + std::to_string(*spec.layers));
    if (spec.usage != TextureUsage::None) add("usage=" + describe_usage(spec.usage));
    if (spec.cube) add("cube");
    return out.empty() ? "unconstrained" : out;
}

}  // namespace loom::fg
