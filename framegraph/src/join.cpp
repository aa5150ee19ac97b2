#include "loom/framegraph/join.hpp"

#include <algorithm>
#include <optional>

namespace loom::fg {
namespace {

using rhi::Channel;
using rhi::FormatFeatures;

Error conflict(const JoinContext& context, std::string_view property, const std::string& a_value,
               const std::string& b_value, std::string_view detail = {}) {
    std::string message = "cannot join " + std::string(context.a_name) + " and " + std::string(context.b_name) + ": " + std::string(property) +
                          " " + a_value + " vs " + b_value;
    if (!detail.empty()) message += " (" + std::string(detail) + ")";
    return make_error(ErrorCode::Join, std::move(message));
}

bool has_color(const FormatFeatures& f) {
    return std::any_of(f.color.begin(), f.color.end(), [](const Channel& c) { return c.present(); });
}
bool has_depth_stencil(const FormatFeatures& f) { return f.depth.present() || f.stencil_bits != 0; }

// The join of two channels (§6.1): same kind when both are present, bits take the maximum; a
// channel present on one side only is kept; absent on both stays absent.
std::optional<Channel> join_channel(const Channel& a, const Channel& b) {
    if (a.present() && b.present()) {
        if (a.kind != b.kind) return std::nullopt;
        return Channel{std::max(a.bits, b.bits), a.kind};
    }
    return a.present() ? a : b;
}

std::string describe_channel(const Channel& c) {
    if (!c.present()) return "absent";
    return std::to_string(c.bits) + " " + std::string(rhi::channel_kind_name(c.kind));
}

std::string yes_no(bool value, std::string_view yes, std::string_view no) {
    return std::string(value ? yes : no);
}

std::string describe_count(const std::optional<uint32_t>& count) {
    return count ? std::to_string(*count) : "unconstrained";
}

}  // namespace

Result<FormatFeatures> join_features(const FormatFeatures& a, const FormatFeatures& b, const JoinContext& context) {
    // Descriptions are built only for error messages; the happy path stays cheap.
    auto both = [&] { return describe_features(a) + " vs " + describe_features(b); };

    // Step 1: the feature flags and the sharing must be the same.
    if (a.srgb != b.srgb) return conflict(context, "format sRGB", yes_no(a.srgb, "srgb", "linear"), yes_no(b.srgb, "srgb", "linear"), both());
    if (a.compressed != b.compressed) {
        return conflict(context, "format compression", yes_no(a.compressed, "compressed", "uncompressed"),
                        yes_no(b.compressed, "compressed", "uncompressed"), both());
    }
    if (a.bgra != b.bgra) {
        return conflict(context, "format memory order", yes_no(a.bgra, "bgra", "rgba"), yes_no(b.bgra, "bgra", "rgba"), both());
    }
    if (a.shared_exponent_bits != b.shared_exponent_bits) {
        return conflict(context, "format shared exponent", std::to_string(a.shared_exponent_bits) + " bits",
                        std::to_string(b.shared_exponent_bits) + " bits", both());
    }

    const bool a_ds = has_depth_stencil(a);
    const bool b_ds = has_depth_stencil(b);
    if (a_ds != b_ds || (a_ds && (has_color(a) || has_color(b)))) {
        return conflict(context, "format", describe_features(a), describe_features(b),
                        "depth/stencil and colour formats do not join");
    }

    // Step 2: the flags are the same on both sides; start from either.
    FormatFeatures out = a;
    if (a_ds) {
        // Steps 3 and 4: depth and stencil are joined separately.
        auto depth = join_channel(a.depth, b.depth);
        if (!depth) {
            return conflict(context, "format depth kind", std::string(rhi::channel_kind_name(a.depth.kind)),
                            std::string(rhi::channel_kind_name(b.depth.kind)), both());
        }
        out.depth = *depth;
        out.stencil_bits = std::max(a.stencil_bits, b.stencil_bits);
        return out;
    }
    // Step 5: colour channels one by one.
    static constexpr std::string_view kChannelNames = "RGBA";
    for (std::size_t i = 0; i < 4; ++i) {
        auto channel = join_channel(a.color[i], b.color[i]);
        if (!channel) {
            return conflict(context, "format channel " + std::string(1, kChannelNames[i]) + " kind",
                            describe_channel(a.color[i]), describe_channel(b.color[i]), both());
        }
        out.color[i] = *channel;
    }
    return out;
}

Result<TextureSpec> join(const TextureSpec& a, const TextureSpec& b, const JoinContext& context) {
    TextureSpec out;

    if (a.format && b.format) {
        auto features = join_features(*a.format, *b.format, context);
        if (!features) return features.take_error();
        out.format = *features;
    } else {
        out.format = a.format ? a.format : b.format;
    }

    if (a.size && b.size) {
        const SizeSpec& sa = *a.size;
        const SizeSpec& sb = *b.size;
        if (sa == sb) {
            out.size = sa;
        } else if (context.frame) {
            const Extent2D ea = sa.evaluate(*context.frame);
            const Extent2D eb = sb.evaluate(*context.frame);
            if (ea != eb) {
                auto show = [](const SizeSpec& s, Extent2D e) {
                    std::string text = std::to_string(e.width) + "x" + std::to_string(e.height);
                    if (s.kind == SizeSpec::Kind::Relative) text += " (" + describe_size(s) + ")";
                    return text;
                };
                return conflict(context, "size", show(sa, ea), show(sb, eb),
                                "frame " + std::to_string(context.frame->width) + "x" +
                                    std::to_string(context.frame->height));
            }
            // Equal once evaluated: keep the absolute one, which says the same for this frame.
            out.size = sa.kind == SizeSpec::Kind::Absolute ? sa : sb;
        } else {
            return conflict(context, "size", describe_size(sa), describe_size(sb),
                            "differently declared sizes can only be compared against a frame size");
        }
    } else {
        out.size = a.size ? a.size : b.size;
    }

    auto join_count = [&](std::string_view property, const std::optional<uint32_t>& x,
                          const std::optional<uint32_t>& y, std::optional<uint32_t>& result) -> Status {
        if (x && y && *x != *y) return conflict(context, property, describe_count(x), describe_count(y));
        result = x ? x : y;
        return {};
    };
    LOOM_TRY(join_count("samples", a.samples, b.samples, out.samples));
    LOOM_TRY(join_count("mips", a.mips, b.mips, out.mips));
    LOOM_TRY(join_count("layers", a.layers, b.layers, out.layers));

    out.usage = a.usage | b.usage;
    out.cube = a.cube || b.cube;
    return out;
}

Result<BufferSpec> join_buffer_specs(const BufferSpec& a, const BufferSpec& b, const JoinContext& context) {
    BufferSpec out;
    if (a.size && b.size && *a.size != *b.size) {
        const BufferSize& sa = *a.size;
        const BufferSize& sb = *b.size;
        if (!context.frame) {
            return conflict(context, "buffer size", describe_buffer_size(sa), describe_buffer_size(sb),
                            "differently declared sizes can only be compared against a frame size");
        }
        const std::optional<uint64_t> ea = sa.evaluate(*context.frame);
        const std::optional<uint64_t> eb = sb.evaluate(*context.frame);
        if (!ea || !eb || *ea != *eb) {
            auto show = [](const BufferSize& s, const std::optional<uint64_t>& bytes) {
                const std::string total = bytes ? std::to_string(*bytes) + " bytes" : "more than 2^64 bytes";
                return s.kind == BufferSize::Kind::Absolute ? total : total + " (" + describe_buffer_size(s) + ")";
            };
            return conflict(context, "buffer size", show(sa, ea), show(sb, eb),
                            "frame " + std::to_string(context.frame->width) + "x" +
                                std::to_string(context.frame->height));
        }
        // Equal for this frame: keep the absolute one, which says the same.
        out.size = sa.kind == BufferSize::Kind::Absolute ? sa : sb;
    } else {
        out.size = a.size ? a.size : b.size;
    }
    if (a.alignment && b.alignment) {
        out.alignment = std::max(*a.alignment, *b.alignment);
    } else {
        out.alignment = a.alignment ? a.alignment : b.alignment;
    }
    out.usage = a.usage | b.usage;
    return out;
}

bool joinable(const TextureSpec& a, const TextureSpec& b, std::optional<Extent2D> frame) {
    JoinContext context;
    context.frame = frame;
    return join(a, b, context).ok();
}

}  // namespace loom::fg
