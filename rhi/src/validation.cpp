#include "loom/rhi/validation.hpp"

#include <algorithm>
#include <bit>
#include <cstdio>

#include "loom/rhi/checked_math.hpp"
#include "loom/rhi/format.hpp"
#include "loom/rhi/subresources.hpp"

namespace loom::rhi::validation {

namespace {

std::string_view dimension_name(TextureDimension dimension) {
    switch (dimension) {
        case TextureDimension::Tex2D: return "Tex2D";
        case TextureDimension::Tex2DArray: return "Tex2DArray";
        case TextureDimension::Tex3D: return "Tex3D";
        case TextureDimension::Cube: return "Cube";
    }
    return "?";
}

std::string number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

// "1 layer", "3 layers".
std::string count_of(uint64_t n, std::string_view noun) { return std::to_string(n) + " " + std::string(noun) + (n == 1 ? "" : "s"); }

std::string size_text(uint32_t width, uint32_t height, uint32_t depth) {
    return std::to_string(width) + "x" + std::to_string(height) + "x" + std::to_string(depth);
}

// The size-limit rule: 2D sizes against max_texture_size, cube faces against
// max_texture_size_cube, all three extents of a 3D texture against max_texture_size_3d.
Status size_within_limits(const TextureDesc& d, const Capabilities& caps, const std::string& what) {
    uint32_t limit = caps.max_texture_size;
    uint32_t largest = std::max(d.width, d.height);
    if (d.dimension == TextureDimension::Tex3D) {
        limit = caps.max_texture_size_3d;
        largest = std::max(largest, d.depth_or_layers);
    } else if (d.dimension == TextureDimension::Cube) {
        limit = caps.max_texture_size_cube;
    }
    if (largest > limit) {
        const uint32_t depth = d.dimension == TextureDimension::Tex3D ? d.depth_or_layers : 1;
        return Error{ErrorCode::Unsupported, what + "size " + size_text(d.width, d.height, depth) + " exceeds this device's limit of " +
                                                 std::to_string(limit) + " texels for a " + std::string(dimension_name(d.dimension)) +
                                                 " texture"};
    }
    if (d.dimension == TextureDimension::Tex2DArray && d.depth_or_layers > caps.max_texture_layers) {
        return Error{ErrorCode::Unsupported, what + std::to_string(d.depth_or_layers) + " layers exceed this device's limit of " +
                                                 std::to_string(caps.max_texture_layers)};
    }
    return {};
}

// Format features the usage needs, on this device.
Status usage_supported(const TextureDesc& d, const Capabilities& caps, const std::string& what) {
    const FormatCapabilities& fc = caps.format(d.format);
    const std::string format(format_name(d.format));
    auto unsupported = [&](const char* use) { return Error{ErrorCode::Unsupported, what + format + " cannot be " + use + " on this device"}; };
    if (!fc.sampled && !fc.color_attachment && !fc.depth_stencil_attachment && !fc.storage) return unsupported("used");
    if (has_any(d.usage, TextureUsage::Sampled) && !fc.sampled) return unsupported("sampled");
    if (has_any(d.usage, TextureUsage::ColorAttachment) && !fc.color_attachment) return unsupported("a colour attachment");
    if (has_any(d.usage, TextureUsage::DepthStencilAttachment) && !fc.depth_stencil_attachment) {
        return unsupported("a depth/stencil attachment");
    }
    if (has_any(d.usage, TextureUsage::Storage) && !fc.storage) return unsupported("a storage image");
    if (d.samples > 1 && (fc.sample_counts & d.samples) == 0) {
        return Error{ErrorCode::Unsupported, what + std::to_string(d.samples) + " samples of " + format + " are not supported on this device"};
    }
    return {};
}

}  // namespace

std::string in_quotes(std::string_view name) { return "'" + std::string(name) + "'"; }

Status texture_desc(const TextureDesc& d, const Capabilities& caps) {
    const std::string what = "texture " + in_quotes(d.name) + ": ";
    auto invalid = [&](const std::string& message) { return Error{ErrorCode::InvalidArgument, what + message}; };
    if (d.placement && !caps.placed_resources) {
        return Error{ErrorCode::Unsupported, what + "placement in a heap needs placed resources, which this device lacks"};
    }
    if (d.format == Format::Undefined) return invalid("format is Undefined");
    const FormatInfo& info = format_info(d.format);
    const std::string format(format_name(d.format));
    if (d.width == 0 || d.height == 0 || d.depth_or_layers == 0) {
        return invalid("size " + size_text(d.width, d.height, d.depth_or_layers) + " has a zero dimension");
    }
    switch (d.dimension) {
        case TextureDimension::Tex2D:
            if (d.depth_or_layers != 1) {
                return invalid("depth_or_layers is " + std::to_string(d.depth_or_layers) +
                               "; a Tex2D texture has 1 (Tex2DArray has layers)");
            }
            break;
        case TextureDimension::Tex2DArray: break;
        case TextureDimension::Tex3D:
            if (info.is_depth_stencil()) return invalid("a Tex3D texture cannot have the depth/stencil format " + format);
            break;
        case TextureDimension::Cube:
            if (d.depth_or_layers != 6) return invalid("depth_or_layers is " + std::to_string(d.depth_or_layers) + "; a Cube texture has 6");
            if (d.width != d.height) {
                return invalid("the faces of a Cube texture must be square, not " + std::to_string(d.width) + "x" + std::to_string(d.height));
            }
            break;
    }
    if (d.mip_levels == 0 || d.mip_levels > max_mip_levels(d)) {
        const uint32_t depth = d.dimension == TextureDimension::Tex3D ? d.depth_or_layers : 1;
        return invalid("mip_levels " + std::to_string(d.mip_levels) + " is not in 1.." + std::to_string(max_mip_levels(d)) + " for a " +
                       size_text(d.width, d.height, depth) + " texture");
    }
    if (d.samples == 0 || d.samples > 64 || !std::has_single_bit(d.samples)) {
        return invalid("samples " + std::to_string(d.samples) + " is not a power of two from 1 to 64");
    }
    if (d.samples > 1) {
        if (d.dimension != TextureDimension::Tex2D) {
            return invalid("a multisampled texture is Tex2D, not " + std::string(dimension_name(d.dimension)));
        }
        if (d.mip_levels != 1) return invalid("a multisampled texture has one mip level, not " + std::to_string(d.mip_levels));
        if (has_any(d.usage, TextureUsage::Storage)) return invalid("a multisampled texture cannot have Storage usage");
    }
    if (has_any(d.usage, TextureUsage::ColorAttachment) && !info.is_color()) {
        return invalid(format + " is not a colour format (usage ColorAttachment)");
    }
    if (has_any(d.usage, TextureUsage::DepthStencilAttachment) && !info.is_depth_stencil()) {
        return invalid(format + " is not a depth/stencil format (usage DepthStencilAttachment)");
    }
    LOOM_TRY(size_within_limits(d, caps, what));
    return usage_supported(d, caps, what);
}

Status texture_memory_query(const TextureDesc& desc, const Capabilities& caps) {
    if (!caps.placed_resources) {
        return Error{ErrorCode::Unsupported,
                     "texture " + in_quotes(desc.name) + ": memory requirements need placed resources, which this device lacks"};
    }
    return texture_desc(desc, caps);
}

Status buffer_desc(const BufferDesc& desc) {
    if (desc.size == 0) return Error{ErrorCode::InvalidArgument, "buffer " + in_quotes(desc.name) + ": size is 0"};
    return {};
}

Status sampler_desc(const SamplerDesc& desc) {
    const std::string what = "sampler " + in_quotes(desc.name) + ": ";
    // Written so that NaN fails too.
    if (!(desc.min_lod <= desc.max_lod)) {
        return Error{ErrorCode::InvalidArgument, what + "min_lod " + number(desc.min_lod) + " is above max_lod " + number(desc.max_lod)};
    }
    if (!(desc.max_anisotropy >= 1.0f)) {
        return Error{ErrorCode::InvalidArgument, what + "max_anisotropy " + number(desc.max_anisotropy) + " is below 1"};
    }
    return {};
}

Status heap_desc(const HeapDesc& desc, const Capabilities& caps) {
    const std::string what = "heap " + in_quotes(desc.name) + ": ";
    if (!caps.placed_resources) return Error{ErrorCode::Unsupported, what + "heaps need placed resources, which this device lacks"};
    if (desc.size == 0) return Error{ErrorCode::InvalidArgument, what + "size is 0"};
    return {};
}

Status buffer_write(const BufferDesc& buffer, uint64_t offset, uint64_t size) {
    if (!checked::range_fits(offset, size, buffer.size)) {
        return Error{ErrorCode::InvalidArgument, "write_buffer to buffer " + in_quotes(buffer.name) + ": " + std::to_string(size) +
                                                     " bytes at offset " + std::to_string(offset) + " exceed its size " +
                                                     std::to_string(buffer.size)};
    }
    return {};
}

Status buffer_read(const BufferDesc& buffer, uint64_t offset, uint64_t size) {
    if (!checked::range_fits(offset, size, buffer.size)) {
        return Error{ErrorCode::InvalidArgument, "read_buffer of buffer " + in_quotes(buffer.name) + ": " + std::to_string(size) +
                                                     " bytes at offset " + std::to_string(offset) + " exceed its size " +
                                                     std::to_string(buffer.size)};
    }
    return {};
}

Result<TextureWrite> texture_write(const TextureDesc& texture, const TextureRegion& region, uint64_t data_size) {
    const std::string what = "write_texture to texture " + in_quotes(texture.name) + ": ";
    auto invalid = [&](const std::string& message) { return Error{ErrorCode::InvalidArgument, what + message}; };
    if (texture.samples > 1) return Error{ErrorCode::Unsupported, what + "a multisampled texture cannot be uploaded to"};
    if (region.mip >= texture.mip_levels) {
        return invalid("mip " + std::to_string(region.mip) + " does not exist (" + count_of(texture.mip_levels, "level") + ")");
    }
    const bool is3d = texture.dimension == TextureDimension::Tex3D;
    if (is3d && region.layer != 0) {
        return invalid("layer " + std::to_string(region.layer) + ": a Tex3D texture has no layers (origin.z selects depth slices)");
    }
    if (!is3d && (region.origin.z != 0 || region.extent.depth > 1)) {
        return invalid("origin.z and extent.depth apply to Tex3D textures only");
    }
    if (!is3d && region.layer >= texture.depth_or_layers) {
        return invalid("layer " + std::to_string(region.layer) + " does not exist (" + count_of(texture.depth_or_layers, "layer") + ")");
    }
    const Extent3D full = mip_extent(texture, region.mip);
    auto rest = [](uint32_t size, uint32_t origin) { return size > origin ? size - origin : 0u; };
    TextureWrite out;
    out.mip = region.mip;
    out.layer = is3d ? 0 : region.layer;
    out.origin = region.origin;
    out.extent = {region.extent.width ? region.extent.width : rest(full.width, region.origin.x),
                  region.extent.height ? region.extent.height : rest(full.height, region.origin.y),
                  region.extent.depth ? region.extent.depth : rest(full.depth, region.origin.z)};
    const Extent3D& e = out.extent;
    if (e.width == 0 || e.height == 0 || e.depth == 0 || !checked::range_fits(region.origin.x, e.width, full.width) ||
        !checked::range_fits(region.origin.y, e.height, full.height) || !checked::range_fits(region.origin.z, e.depth, full.depth)) {
        return invalid("region " + size_text(e.width, e.height, e.depth) + " at (" + std::to_string(region.origin.x) + "," +
                       std::to_string(region.origin.y) + "," + std::to_string(region.origin.z) + ") does not fit mip " +
                       std::to_string(region.mip) + " (" + size_text(full.width, full.height, full.depth) + ")");
    }
    // Three extents near 2^32 would overflow 64 bits: checked.
    const auto bytes = checked::product({e.width, e.height, e.depth, format_info(texture.format).bytes_per_texel});
    if (!bytes || data_size != *bytes) {
        return invalid(std::to_string(data_size) + " bytes given, the region needs " + (bytes ? std::to_string(*bytes) : "more than 2^64"));
    }
    out.bytes = *bytes;
    return out;
}

Status texture_read(const TextureDesc& texture, uint32_t mip, uint32_t layer) {
    const std::string what = "read_texture of texture " + in_quotes(texture.name) + ": ";
    if (mip >= texture.mip_levels) {
        return Error{ErrorCode::InvalidArgument, what + "mip " + std::to_string(mip) + " does not exist (" +
                                                     count_of(texture.mip_levels, "level") + ")"};
    }
    const uint32_t layers = mip_layers(texture, mip);
    if (layer >= layers) {
        const bool is3d = texture.dimension == TextureDimension::Tex3D;
        const std::string where = is3d ? count_of(layers, "depth slice") + " in mip " + std::to_string(mip) : count_of(layers, "layer");
        return Error{ErrorCode::InvalidArgument,
                     what + (is3d ? "depth slice " : "layer ") + std::to_string(layer) + " does not exist (" + where + ")"};
    }
    if (texture.samples > 1 && !format_info(texture.format).is_color()) {
        return Error{ErrorCode::Unsupported, what + "a multisampled depth/stencil texture cannot be read back"};
    }
    return {};
}

}  // namespace loom::rhi::validation
