#include "loom/framegraph/resolved_spec.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>

#include "text.hpp"

namespace loom::fg {
namespace {

using rhi::Channel;
using rhi::FormatFeatures;

bool channel_covers(const Channel& candidate, const Channel& wanted) {
    if (!wanted.present()) return !candidate.present();
    return candidate.present() && candidate.kind == wanted.kind && candidate.bits >= wanted.bits;
}

uint32_t max_mip_levels(Extent2D extent) {
    const uint32_t largest = std::max(extent.width, extent.height);
    return static_cast<uint32_t>(std::bit_width(largest));
}

}  // namespace

std::string_view format_match_name(FormatMatch match) {
    switch (match) {
        case FormatMatch::Default: return "default";
        case FormatMatch::Exact: return "exact";
        case FormatMatch::Covering: return "covering";
    }
    return "unknown";
}

bool covers(const FormatFeatures& candidate, const FormatFeatures& wanted) {
    if (candidate.srgb != wanted.srgb || candidate.compressed != wanted.compressed || candidate.bgra != wanted.bgra ||
        candidate.shared_exponent_bits != wanted.shared_exponent_bits) {
        return false;
    }
    for (std::size_t i = 0; i < 3; ++i) {
        if (!channel_covers(candidate.color[i], wanted.color[i])) return false;
    }
    // Alpha may be added (RGB16 float → RGBA16Float), with the kind of the other channels.
    const Channel& alpha = candidate.color[3];
    if (wanted.color[3].present()) {
        if (!channel_covers(alpha, wanted.color[3])) return false;
    } else if (alpha.present()) {
        const Channel& red = wanted.color[0];
        if (!red.present() || alpha.kind != red.kind) return false;
    }
    if (!channel_covers(candidate.depth, wanted.depth)) return false;
    if (wanted.stencil_bits == 0) return candidate.stencil_bits == 0;
    return candidate.stencil_bits >= wanted.stencil_bits;
}

Result<FormatResolution> resolve_format(const std::optional<FormatFeatures>& features, std::string_view what) {
    if (!features) return FormatResolution{kDefaultFormat, FormatMatch::Default};
    if (auto exact = rhi::format_from_features(*features)) return FormatResolution{*exact, FormatMatch::Exact};

    std::optional<rhi::Format> best;
    for (rhi::Format candidate : rhi::all_formats()) {
        const rhi::FormatInfo& info = rhi::format_info(candidate);
        if (!covers(info.features, *features)) continue;
        if (!best || info.bytes_per_texel < rhi::format_info(*best).bytes_per_texel) best = candidate;
    }
    if (!best) {
        return make_error(ErrorCode::Join, std::string(what) + ": no format has or covers the joined features " +
                                               describe_features(*features));
    }
    return FormatResolution{*best, FormatMatch::Covering};
}

Result<ResolvedSpec> resolve(const TextureSpec& spec, Extent2D frame, std::string_view what) {
    auto format = resolve_format(spec.format, what);
    if (!format) return format.take_error();

    ResolvedSpec out;
    out.format = format->format;
    out.format_match = format->match;
    out.samples = spec.samples.value_or(1);
    out.mips = spec.mips.value_or(1);
    out.layers = spec.layers.value_or(spec.cube ? 6 : 1);
    out.usage = spec.usage;
    out.cube = spec.cube;
    return resolve_for_frame(out, spec.size, frame, what);
}

// Every check of resolve() is here, after the extent: a count that is wrong at any size (3
// samples) is reported by resolve as it always was, and re-resolving for another frame runs the
// checks that a smaller or larger extent may now fail (mips, a cube's square faces, the limit).
Result<ResolvedSpec> resolve_for_frame(ResolvedSpec out, const std::optional<SizeSpec>& size, Extent2D frame,
                                       std::string_view what) {
    out.extent = size ? size->evaluate(frame) : frame;

    auto fail = [&](const std::string& problem) {
        return make_error(ErrorCode::Graph, std::string(what) + ": " + problem);
    };
    // The size as asked (a scale times the frame, exactly), so that a size past the limit is
    // reported as written, not as a value that overflowed on its way.
    const auto asked = [&](uint32_t frame_side, float scale, uint32_t evaluated) -> double {
        if (!size || size->kind == SizeSpec::Kind::Absolute) return evaluated;
        return std::round(static_cast<double>(frame_side) * static_cast<double>(scale));
    };
    const double asked_width = asked(frame.width, size ? size->scale_x : 1.0f, out.extent.width);
    const double asked_height = asked(frame.height, size ? size->scale_y : 1.0f, out.extent.height);
    if (asked_width > kMaxTextureExtent || asked_height > kMaxTextureExtent) {
        char asked_size[64];
        std::snprintf(asked_size, sizeof asked_size, "%.0fx%.0f", asked_width, asked_height);
        std::string problem = std::string("size ") + asked_size;
        if (size && size->kind == SizeSpec::Kind::Relative) {
            problem += " (" + describe_size(*size) + " of " + std::to_string(frame.width) + "x" +
                       std::to_string(frame.height) + ")";
        }
        return fail(problem + " is beyond the limit of " + std::to_string(kMaxTextureExtent) + " texels per side");
    }
    if (out.extent.width == 0 || out.extent.height == 0) {
        return fail("size " + std::to_string(out.extent.width) + "x" + std::to_string(out.extent.height) +
                    " is empty");
    }
    if (out.samples == 0 || out.samples > kMaxTextureSamples || !std::has_single_bit(out.samples)) {
        return fail("samples " + std::to_string(out.samples) + " is not one of 1, 2, 4, 8, 16, 32, 64");
    }
    if (out.layers == 0) return fail("layers must be at least 1");
    if (out.layers > kMaxTextureLayers) {
        return fail("layers " + std::to_string(out.layers) + " is beyond the limit of " +
                    std::to_string(kMaxTextureLayers));
    }
    if (out.mips == 0 || out.mips > max_mip_levels(out.extent)) {
        return fail("mips " + std::to_string(out.mips) + " not in 1.." + std::to_string(max_mip_levels(out.extent)) +
                    " for size " + std::to_string(out.extent.width) + "x" + std::to_string(out.extent.height));
    }
    if (out.cube && (out.layers != 6 || out.extent.width != out.extent.height || out.samples != 1)) {
        return fail("a cube map has 6 square single-sampled faces, not " + std::to_string(out.layers) + " layers of " +
                    std::to_string(out.extent.width) + "x" + std::to_string(out.extent.height) + " with " +
                    std::to_string(out.samples) + " samples");
    }
    if (out.samples > 1 && out.mips > 1) {
        return fail("a multisampled texture (" + std::to_string(out.samples) + " samples) cannot have " +
                    std::to_string(out.mips) + " mips");
    }
    return out;
}

bool same_texture_shape(const ResolvedSpec& a, const ResolvedSpec& b) {
    return a.format == b.format && a.extent == b.extent && a.samples == b.samples && a.mips == b.mips &&
           a.layers == b.layers && a.cube == b.cube;
}

rhi::TextureDesc to_texture_desc(const ResolvedSpec& spec, std::string name) {
    rhi::TextureDesc desc;
    desc.name = std::move(name);
    desc.dimension = spec.cube ? rhi::TextureDimension::Cube
                               : (spec.layers > 1 ? rhi::TextureDimension::Tex2DArray : rhi::TextureDimension::Tex2D);
    desc.format = spec.format;
    desc.width = spec.extent.width;
    desc.height = spec.extent.height;
    desc.depth_or_layers = spec.layers;
    desc.mip_levels = spec.mips;
    desc.samples = spec.samples;
    desc.usage = spec.usage;
    return desc;
}

std::string describe_resolved(const ResolvedSpec& spec) {
    std::string out = detail::concat(rhi::format_name(spec.format), " ", spec.extent.width, "x", spec.extent.height);
    if (spec.samples != 1) detail::append(out, " x", spec.samples, " samples");
    if (spec.mips != 1) detail::append(out, " ", spec.mips, " mips");
    if (spec.cube) {
        detail::append(out, " cube");
    } else if (spec.layers != 1) {
        detail::append(out, " ", spec.layers, " layers");
    }
    return out;
}

}  // namespace loom::fg
