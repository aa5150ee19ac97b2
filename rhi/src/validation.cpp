#include "loom/rhi/validation.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <optional>
#include <variant>
#include <vector>

#include "loom/rhi/binding_reuse.hpp"
#include "loom/rhi/checked_math.hpp"
#include "loom/rhi/format.hpp"
#include "loom/rhi/shader.hpp"
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
        return Error{ErrorCode::Unsupported, what + "size " + size_text(d.width, d.height, mip_extent(d, 0).depth) + " exceeds this device's limit of " +
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

// The sample counts loom knows: powers of two from 1 to 64 (whether a device has them is
// FormatCapabilities::sample_counts).
bool is_sample_count(uint32_t samples) { return samples >= 1 && samples <= 64 && std::has_single_bit(samples); }

// The subresource one side of a transfer or copy addresses exists, and z is used on 3D
// textures only. `side` starts the messages ("source ", or "" for a one-sided transfer);
// `extent_used` is false where the region's extent is ignored (a copy's destination).
Status region_subresource(const TextureDesc& t, const TextureRegion& r, const std::string& what, std::string_view side, bool extent_used) {
    const std::string in = what + std::string(side);
    if (r.mip >= t.mip_levels) {
        return Error{ErrorCode::InvalidArgument, in + "mip " + std::to_string(r.mip) + " does not exist (" + count_of(t.mip_levels, "level") + ")"};
    }
    if (t.dimension == TextureDimension::Tex3D) {
        if (r.layer != 0) {
            return Error{ErrorCode::InvalidArgument,
                         in + "layer " + std::to_string(r.layer) + ": a Tex3D texture has no layers (origin.z selects depth slices)"};
        }
        return {};
    }
    if (r.origin.z != 0 || (extent_used && r.extent.depth > 1)) {
        return Error{ErrorCode::InvalidArgument, in + "origin.z and extent.depth apply to Tex3D textures only"};
    }
    if (r.layer >= t.depth_or_layers) {
        return Error{ErrorCode::InvalidArgument,
                     in + "layer " + std::to_string(r.layer) + " does not exist (" + count_of(t.depth_or_layers, "layer") + ")"};
    }
    return {};
}

// The extent a region addresses in a mip level of size `mip`: its zeros are "the rest of the
// level from the origin".
Extent3D resolved_extent(const TextureRegion& r, const Extent3D& mip) {
    auto rest = [](uint32_t size, uint32_t origin) { return size > origin ? size - origin : 0u; };
    return {r.extent.width ? r.extent.width : rest(mip.width, r.origin.x), r.extent.height ? r.extent.height : rest(mip.height, r.origin.y),
            r.extent.depth ? r.extent.depth : rest(mip.depth, r.origin.z)};
}

// An `extent` at `origin` is not empty and lies inside mip `mip_index` (of size `mip`).
Status region_fits(const Origin3D& origin, const Extent3D& extent, uint32_t mip_index, const Extent3D& mip, const std::string& what,
                   std::string_view side) {
    const bool fits = extent.width > 0 && extent.height > 0 && extent.depth > 0 && checked::range_fits(origin.x, extent.width, mip.width) &&
                      checked::range_fits(origin.y, extent.height, mip.height) && checked::range_fits(origin.z, extent.depth, mip.depth);
    if (fits) return {};
    return Error{ErrorCode::InvalidArgument, what + "region " + size_text(extent.width, extent.height, extent.depth) + " at (" +
                                                 std::to_string(origin.x) + "," + std::to_string(origin.y) + "," + std::to_string(origin.z) +
                                                 ") does not fit " + std::string(side) + "mip " + std::to_string(mip_index) + " (" +
                                                 size_text(mip.width, mip.height, mip.depth) + ")"};
}

// "<what>: N bytes at [side ]offset O exceed its size S" when [offset, offset + size) leaves a
// buffer of `capacity` bytes (decided without overflow).
Status bytes_within(const std::string& what, std::string_view side, uint64_t offset, uint64_t size, uint64_t capacity) {
    if (checked::range_fits(offset, size, capacity)) return {};
    return Error{ErrorCode::InvalidArgument, what + ": " + std::to_string(size) + " bytes at " + std::string(side) + "offset " +
                                                 std::to_string(offset) + " exceed its size " + std::to_string(capacity)};
}

}  // namespace

std::string in_quotes(std::string_view name) {
    // Appended, not "'" + std::string(name): GCC 12 at -O3 warns falsely on that (-Wrestrict,
    // GCC bug 105651), and the project builds with warnings as errors.
    std::string out;
    out.reserve(name.size() + 2);
    out += '\'';
    out += name;
    out += '\'';
    return out;
}

std::string checks_in_log(std::string_view api_debug, bool debug, bool validation) {
    std::string text(api_debug);
    text += debug ? " on (DeviceDesc::debug, the default: it costs more per draw than loom; turn it off to ship or measure)"
                  : " off";
    text += ", loom's validation ";
    if (!kCompiled) {
        text += "compiled out (LOOM_RHI_VALIDATION=OFF)";
    } else {
        text += validation ? "on" : "off (DeviceDesc::validation: misuse is not checked)";
    }
    return text;
}

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
        return invalid("mip_levels " + std::to_string(d.mip_levels) + " is not in 1.." + std::to_string(max_mip_levels(d)) + " for a " +
                       size_text(d.width, d.height, mip_extent(d, 0).depth) + " texture");
    }
    if (!is_sample_count(d.samples)) {
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

Status buffer_desc(const BufferDesc& desc, const Capabilities& caps) {
    if (desc.placement && !caps.placed_resources) {
        return Error{ErrorCode::Unsupported, "buffer " + in_quotes(desc.name) + ": placement in a heap needs placed resources, which this device lacks"};
    }
    return buffer_memory_query(desc);
}

Status buffer_memory_query(const BufferDesc& desc) {
    if (desc.size == 0) return Error{ErrorCode::InvalidArgument, "buffer " + in_quotes(desc.name) + ": size is 0"};
    return {};
}

Status buffer_placement(const BufferDesc& desc, const HeapDesc& heap, const MemoryRequirements& requirements) {
    const std::string what = "buffer " + in_quotes(desc.name) + " placed in heap " + in_quotes(heap.name) + ": ";
    const uint64_t offset = desc.placement ? desc.placement->offset : 0;
    const uint64_t alignment = std::max<uint64_t>(1, requirements.alignment);
    if (offset % alignment != 0) {
        return Error{ErrorCode::InvalidArgument,
                     what + "offset " + std::to_string(offset) + " is not a multiple of the alignment " + std::to_string(alignment)};
    }
    if (!checked::range_fits(offset, requirements.size, heap.size)) {
        return Error{ErrorCode::InvalidArgument, what + "range " + std::to_string(offset) + "+" + std::to_string(requirements.size) +
                                                     " exceeds the heap size " + std::to_string(heap.size)};
    }
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
    return bytes_within("write_buffer to buffer " + in_quotes(buffer.name), "", offset, size, buffer.size);
}

Status buffer_read(const BufferDesc& buffer, uint64_t offset, uint64_t size) {
    return bytes_within("read_buffer of buffer " + in_quotes(buffer.name), "", offset, size, buffer.size);
}

Result<TextureWrite> texture_write(const TextureDesc& texture, const TextureRegion& region, uint64_t data_size) {
    const std::string what = "write_texture to texture " + in_quotes(texture.name) + ": ";
    auto invalid = [&](const std::string& message) { return Error{ErrorCode::InvalidArgument, what + message}; };
    if (texture.samples > 1) return Error{ErrorCode::Unsupported, what + "a multisampled texture cannot be uploaded to"};
    LOOM_TRY(region_subresource(texture, region, what, "", true));
    const bool is3d = texture.dimension == TextureDimension::Tex3D;
    const Extent3D full = mip_extent(texture, region.mip);
    TextureWrite out;
    out.mip = region.mip;
    out.layer = is3d ? 0 : region.layer;
    out.origin = region.origin;
    out.extent = resolved_extent(region, full);
    const Extent3D& e = out.extent;
    LOOM_TRY(region_fits(region.origin, e, region.mip, full, what, ""));
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

// ---- pipelines ---------------------------------------------------------------------------------

namespace {

std::string_view stage_article_name(ShaderStage stage) {
    switch (stage) {
        case ShaderStage::Vertex: return "a vertex";
        case ShaderStage::Fragment: return "a fragment";
        case ShaderStage::Compute: return "a compute";
    }
    return "an unknown";
}

// The shader at `handle`, of `stage`; `role` names it in messages ("vertex shader").
Result<ShaderFacts> shader_of_stage(const ShaderLookup& lookup, ShaderHandle handle, ShaderStage stage, const std::string& what,
                                    const std::string& role) {
    auto facts = lookup(handle);
    if (!facts.ok()) return Error{ErrorCode::InvalidHandle, what + role + ": " + facts.error().message};
    if (facts->stage != stage) {
        return Error{ErrorCode::InvalidArgument, what + role + " " + in_quotes(facts->name) + " is " +
                                                     std::string(stage_article_name(facts->stage)) + " shader"};
    }
    return facts;
}

}  // namespace

Status graphics_pipeline(const GraphicsPipelineDesc& d, const Capabilities& caps, const ShaderLookup& lookup) {
    const std::string what = "pipeline " + in_quotes(d.name) + ": ";
    auto invalid = [&](const std::string& message) { return Error{ErrorCode::InvalidArgument, what + message}; };
    auto unsupported = [&](const std::string& message) { return Error{ErrorCode::Unsupported, what + message}; };
    auto vs = shader_of_stage(lookup, d.vertex, ShaderStage::Vertex, what, "vertex shader");
    if (!vs.ok()) return vs.take_error();
    auto fs = shader_of_stage(lookup, d.fragment, ShaderStage::Fragment, what, "fragment shader");
    if (!fs.ok()) return fs.take_error();
    if (d.color_formats.empty() && d.depth_format == Format::Undefined) return invalid("no colour formats and no depth format");
    if (!is_sample_count(d.samples)) {
        return invalid("samples " + std::to_string(d.samples) + " is not a power of two from 1 to 64");
    }
    if (d.color_formats.size() > caps.max_color_attachments) {
        return unsupported(std::to_string(d.color_formats.size()) + " colour formats exceed this device's limit of " +
                           std::to_string(caps.max_color_attachments) + " colour attachments");
    }
    if (d.blend.size() > d.color_formats.size()) {
        return invalid(std::to_string(d.blend.size()) + " blend states for " + count_of(d.color_formats.size(), "colour format"));
    }
    auto samples_supported = [&](Format f, const std::string& field) -> Status {
        if (d.samples > 1 && (caps.format(f).sample_counts & d.samples) == 0) {
            return unsupported(field + " " + std::string(format_name(f)) + " cannot have " + std::to_string(d.samples) +
                               " samples on this device");
        }
        return {};
    };
    for (std::size_t i = 0; i < d.color_formats.size(); ++i) {
        const Format f = d.color_formats[i];
        const std::string field = "color_formats[" + std::to_string(i) + "]";
        if (f == Format::Undefined || !format_info(f).is_color()) {
            return invalid(field + " " + std::string(format_name(f)) + " is not a colour format");
        }
        if (!caps.format(f).color_attachment) {
            return unsupported(field + " " + std::string(format_name(f)) + " cannot be a colour attachment on this device");
        }
        if (i < d.blend.size() && d.blend[i].enabled && !caps.format(f).blendable) {
            return unsupported("blend[" + std::to_string(i) + "] is enabled but " + std::string(format_name(f)) +
                               " cannot be blended on this device");
        }
        LOOM_TRY(samples_supported(f, field));
    }
    if (d.depth_format != Format::Undefined) {
        const std::string format(format_name(d.depth_format));
        if (!format_info(d.depth_format).is_depth_stencil()) return invalid("depth_format " + format + " is not a depth/stencil format");
        if (!caps.format(d.depth_format).depth_stencil_attachment) {
            return unsupported("depth_format " + format + " cannot be a depth/stencil attachment on this device");
        }
        LOOM_TRY(samples_supported(d.depth_format, "depth_format"));
    } else if (d.depth.test || d.depth.write) {
        return invalid("depth test or write enabled without a depth_format");
    }
    if (d.raster.polygon == PolygonMode::Line && !caps.polygon_mode_line) {
        return unsupported("PolygonMode::Line needs polygon_mode_line, which this device lacks");
    }
    if (d.raster.depth_clamp && !caps.depth_clamp) return unsupported("depth_clamp needs depth clamping, which this device lacks");
    if (d.vertex_buffers.size() > kMaxVertexBuffers) {
        return invalid(std::to_string(d.vertex_buffers.size()) + " vertex buffers exceed the " + std::to_string(kMaxVertexBuffers) +
                       " slots loom supports");
    }
    std::vector<uint32_t> locations;
    for (std::size_t slot = 0; slot < d.vertex_buffers.size(); ++slot) {
        for (const VertexAttribute& a : d.vertex_buffers[slot].attributes) {
            if (std::find(locations.begin(), locations.end(), a.location) != locations.end()) {
                return invalid("vertex attribute location " + std::to_string(a.location) + " is given twice (again in slot " +
                               std::to_string(slot) + ")");
            }
            locations.push_back(a.location);
        }
    }
    for (const StageVariable& input : vs->reflection->inputs) {
        if (std::find(locations.begin(), locations.end(), input.location) == locations.end()) {
            return invalid("vertex shader " + in_quotes(vs->name) + " reads " + in_quotes(input.name) + " at location " +
                           std::to_string(input.location) + " but no vertex attribute provides it");
        }
    }
    return {};
}

Status compute_pipeline(const ComputePipelineDesc& desc, const ShaderLookup& lookup) {
    auto cs = shader_of_stage(lookup, desc.compute, ShaderStage::Compute, "pipeline " + in_quotes(desc.name) + ": ", "compute shader");
    return cs.ok() ? Status{} : Status(cs.take_error());
}

// ---- commands ----------------------------------------------------------------------------------

Result<RenderPassShape> render_pass(const RenderPassDesc& desc, const Capabilities& caps, const TextureLookup& lookup) {
    const std::string what = "begin_render_pass " + in_quotes(desc.label) + ": ";
    if (desc.colors.empty() && !desc.depth) return Error{ErrorCode::InvalidArgument, what + "no attachments"};
    if (desc.colors.size() > caps.max_color_attachments) {
        return Error{ErrorCode::Unsupported, what + std::to_string(desc.colors.size()) + " colour attachments exceed this device's limit of " +
                                                 std::to_string(caps.max_color_attachments)};
    }
    std::optional<RenderPassShape> shape;
    std::string first;  // the attachment that set the shape
    auto check = [&](TextureHandle handle, uint32_t mip, uint32_t layer, bool depth, const std::string& name) -> Status {
        auto found = lookup(handle);
        if (!found.ok()) return Error{ErrorCode::InvalidHandle, what + name + ": " + found.error().message};
        const TextureDesc& t = **found;
        const std::string tex = name + " (texture " + in_quotes(t.name) + ")";
        const FormatInfo& info = format_info(t.format);
        const std::string format(format_name(t.format));
        if (depth ? !info.is_depth_stencil() : !info.is_color()) {
            return Error{ErrorCode::InvalidArgument, what + tex + ": " + format + " is not a " + (depth ? "depth/stencil" : "colour") + " format"};
        }
        const TextureUsage usage = depth ? TextureUsage::DepthStencilAttachment : TextureUsage::ColorAttachment;
        if (!has_all(t.usage, usage)) {
            return Error{ErrorCode::InvalidArgument, what + tex + " lacks usage " + (depth ? "DepthStencilAttachment" : "ColorAttachment")};
        }
        if (t.dimension == TextureDimension::Tex3D) {
            return Error{ErrorCode::Unsupported, what + tex + ": rendering into a Tex3D texture is not supported"};
        }
        if (mip >= t.mip_levels || layer >= t.depth_or_layers) {
            return Error{ErrorCode::InvalidArgument, what + tex + ": mip " + std::to_string(mip) + " layer " + std::to_string(layer) +
                                                         " does not exist (" + count_of(t.mip_levels, "level") + ", " +
                                                         count_of(t.depth_or_layers, "layer") + ")"};
        }
        const Extent3D e = mip_extent(t, mip);
        if (!shape) {
            shape = RenderPassShape{e.width, e.height, t.samples, {}, Format::Undefined};
            first = name;
        } else if (e.width != shape->width || e.height != shape->height) {
            return Error{ErrorCode::InvalidArgument, what + tex + " is " + std::to_string(e.width) + "x" + std::to_string(e.height) + " but " +
                                                         first + " is " + std::to_string(shape->width) + "x" + std::to_string(shape->height)};
        } else if (t.samples != shape->samples) {
            return Error{ErrorCode::InvalidArgument, what + tex + " has " + count_of(t.samples, "sample") + " but " + first + " has " +
                                                         std::to_string(shape->samples)};
        }
        if (depth) {
            shape->depth_format = t.format;
        } else {
            shape->color_formats.push_back(t.format);
        }
        return {};
    };
    for (std::size_t i = 0; i < desc.colors.size(); ++i) {
        const ColorAttachment& c = desc.colors[i];
        LOOM_TRY(check(c.texture, c.mip, c.layer, false, "colors[" + std::to_string(i) + "]"));
    }
    if (desc.depth) LOOM_TRY(check(desc.depth->texture, desc.depth->mip, desc.depth->layer, true, "depth"));
    return *shape;
}

Result<TextureCopyRange> texture_copy(const TextureDesc& src, const TextureDesc& dst, bool same_texture, const TextureCopy& copy) {
    const std::string what = "copy_texture from " + in_quotes(src.name) + " to " + in_quotes(dst.name) + ": ";
    auto invalid = [&](const std::string& message) { return Error{ErrorCode::InvalidArgument, what + message}; };
    const FormatInfo& si = format_info(src.format);
    const FormatInfo& di = format_info(dst.format);
    const bool compatible = src.format == dst.format || (si.is_color() && di.is_color() && si.bytes_per_texel == di.bytes_per_texel);
    if (!compatible) {
        return invalid("formats " + std::string(format_name(src.format)) + " and " + std::string(format_name(dst.format)) +
                       " are not copy-compatible (equal, or colour formats of one texel size)");
    }
    if (src.samples != dst.samples) {
        return invalid("sample counts differ (" + std::to_string(src.samples) + " and " + std::to_string(dst.samples) + ")");
    }
    const bool src3d = src.dimension == TextureDimension::Tex3D;
    const bool dst3d = dst.dimension == TextureDimension::Tex3D;
    if (src3d != dst3d) {
        return Error{ErrorCode::Unsupported, what + "copies between a Tex3D texture and a " +
                                                 std::string(dimension_name(src3d ? dst.dimension : src.dimension)) + " texture are not supported"};
    }
    const TextureRegion& sr = copy.src_region;
    const TextureRegion& dr = copy.dst_region;
    LOOM_TRY(region_subresource(src, sr, what, "source ", true));
    LOOM_TRY(region_subresource(dst, dr, what, "destination ", false));
    const Extent3D se = mip_extent(src, sr.mip);
    const Extent3D de = mip_extent(dst, dr.mip);
    TextureCopyRange out;
    out.src_mip = sr.mip;
    out.src_layer = src3d ? 0 : sr.layer;
    out.src_origin = sr.origin;
    out.dst_mip = dr.mip;
    out.dst_layer = dst3d ? 0 : dr.layer;
    out.dst_origin = dr.origin;
    out.extent = resolved_extent(sr, se);
    LOOM_TRY(region_fits(sr.origin, out.extent, sr.mip, se, what, "source "));
    LOOM_TRY(region_fits(dr.origin, out.extent, dr.mip, de, what, "destination "));
    if (same_texture && out.src_mip == out.dst_mip && out.src_layer == out.dst_layer) {
        return invalid("source and destination are one subresource (mip " + std::to_string(out.src_mip) + ", layer " +
                       std::to_string(out.src_layer) + ")");
    }
    return out;
}

uint32_t range_layers(const TextureDesc& texture) {
    return texture.dimension == TextureDimension::Tex3D ? 1 : texture.depth_or_layers;
}

namespace {

// "mips 2..4", "mips 2.." (to the last), "0 mips from 2".
std::string span_text(std::string_view plural, uint32_t base, uint32_t count) {
    if (count == kRemainingSubresources) return std::string(plural) + " " + std::to_string(base) + "..";
    if (count == 0) return "0 " + std::string(plural) + " from " + std::to_string(base);
    return std::string(plural) + " " + std::to_string(base) + ".." + std::to_string(uint64_t{base} + count - 1);
}

// The count of `base`/`count` resolved against `total`, or nothing when the span is empty or
// leaves 0..total-1.
std::optional<uint32_t> resolved_count(uint32_t base, uint32_t count, uint32_t total) {
    if (base >= total || count == 0) return std::nullopt;
    if (count == kRemainingSubresources) return total - base;
    if (count > total - base) return std::nullopt;
    return count;
}

std::string_view texture_kind_name(TextureKind kind) {
    switch (kind) {
        case TextureKind::Tex2D: return "Tex2D";
        case TextureKind::Tex2DArray: return "Tex2DArray";
        case TextureKind::Tex3D: return "Tex3D";
        case TextureKind::Cube: return "Cube";
    }
    return "?";
}

bool same_shape(TextureKind kind, TextureDimension dimension) {
    switch (kind) {
        case TextureKind::Tex2D: return dimension == TextureDimension::Tex2D;
        case TextureKind::Tex2DArray: return dimension == TextureDimension::Tex2DArray;
        case TextureKind::Tex3D: return dimension == TextureDimension::Tex3D;
        case TextureKind::Cube: return dimension == TextureDimension::Cube;
    }
    return false;
}

// Whether `layers` layers of texture `t` can be seen as the shader's declaration `kind`: the
// views both APIs can make (a 2D one of one layer, an array one of 2D, array and cube layers, a
// cube one of six faces, a 3D one of a 3D texture).
// `site` makes the error's prefix, called only on a failure.
template <class Site>
Status kind_fits(const Site& site, TextureKind kind, const TextureDesc& t, uint32_t layers) {
    bool fits = false;
    std::string_view hint;
    switch (kind) {
        case TextureKind::Tex2D:
            fits = t.dimension != TextureDimension::Tex3D && layers == 1;
            hint = "a 2D declaration sees one layer: bind one (layer_count 1) or declare an array";
            break;
        case TextureKind::Tex2DArray:
            fits = t.dimension != TextureDimension::Tex3D;
            hint = "an array declaration sees layers of a Tex2D, Tex2DArray or Cube texture";
            break;
        case TextureKind::Cube:
            fits = t.dimension == TextureDimension::Cube && layers == 6;
            hint = "a cube declaration sees all 6 faces of a Cube texture";
            break;
        case TextureKind::Tex3D:
            fits = t.dimension == TextureDimension::Tex3D;
            hint = "a 3D declaration sees a Tex3D texture";
            break;
    }
    if (fits) return {};
    return Error{ErrorCode::InvalidArgument, site() + ": texture " + in_quotes(t.name) + " (" + std::string(dimension_name(t.dimension)) + ", " +
                                                 count_of(layers, "layer") + " bound) does not fit the shader's " +
                                                 std::string(texture_kind_name(kind)) + " declaration; " + std::string(hint)};
}

}  // namespace

Result<TextureRange> texture_range(std::string_view what, const TextureDesc& t, const TextureRange& range) {
    TextureRange out = range;
    const auto mips = resolved_count(range.base_mip, range.mip_count, t.mip_levels);
    if (!mips) {
        return Error{ErrorCode::InvalidArgument, std::string(what) + ": " + span_text("mips", range.base_mip, range.mip_count) +
                                                     " are not inside its " + count_of(t.mip_levels, "mip level")};
    }
    const uint32_t total_layers = range_layers(t);
    const auto layers = resolved_count(range.base_layer, range.layer_count, total_layers);
    if (!layers) {
        return Error{ErrorCode::InvalidArgument, std::string(what) + ": " + span_text("layers", range.base_layer, range.layer_count) +
                                                     " are not inside its " + count_of(total_layers, "layer") +
                                                     (t.dimension == TextureDimension::Tex3D ? " (the depth slices of a Tex3D texture are not layers)" : "")};
    }
    out.mip_count = *mips;
    out.layer_count = *layers;
    return out;
}

BoundRange bound_range(const PipelineSlot& slot, const TextureDesc& texture, const BindingEntry& entry) {
    BoundRange out;
    out.kind = slot.texture_kind;
    TextureRange wanted;
    bool all_mips = true;
    if (const auto* tb = std::get_if<TextureBinding>(&entry.resource)) {
        wanted = tb->range;
    } else if (const auto* sb = std::get_if<StorageTextureBinding>(&entry.resource)) {
        // A storage image is one level; "whole" is about its layers.
        wanted = TextureRange{sb->mip, 1, sb->base_layer, sb->layer_count};
        all_mips = false;
    }
    // Accepted by binding() before: the range resolves.
    auto resolved = texture_range("", texture, wanted);
    out.range = resolved.ok() ? *resolved : TextureRange{0, texture.mip_levels, 0, range_layers(texture)};
    const bool mips_whole = !all_mips || (out.range.base_mip == 0 && out.range.mip_count == texture.mip_levels);
    const bool layers_whole = out.range.base_layer == 0 && out.range.layer_count == range_layers(texture);
    out.whole = mips_whole && layers_whole && same_shape(out.kind, texture.dimension);
    return out;
}

Status buffer_copy(const BufferDesc& src, uint64_t src_offset, const BufferDesc& dst, uint64_t dst_offset, uint64_t size,
                   bool same_buffer) {
    const std::string command = "copy_buffer from " + in_quotes(src.name) + " to " + in_quotes(dst.name);
    const std::string what = command + ": ";
    LOOM_TRY(bytes_within(command, "source ", src_offset, size, src.size));
    LOOM_TRY(bytes_within(command, "destination ", dst_offset, size, dst.size));
    // Both ranges are inside one buffer here, so the sums cannot wrap.
    if (same_buffer && size > 0 && src_offset < dst_offset + size && dst_offset < src_offset + size) {
        return Error{ErrorCode::InvalidArgument, what + "the ranges at " + std::to_string(src_offset) + " and " + std::to_string(dst_offset) +
                                                     " overlap (" + std::to_string(size) + " bytes each)"};
    }
    return {};
}

namespace {

std::string_view binding_kind_name(BindingKind kind) {
    switch (kind) {
        case BindingKind::UniformBuffer: return "a uniform buffer";
        case BindingKind::StorageBuffer: return "a storage buffer";
        case BindingKind::SampledTexture: return "a sampled texture";
        case BindingKind::StorageImage: return "a storage image";
    }
    return "?";
}

std::string_view entry_kind_name(const BindingEntry& entry) {
    if (std::holds_alternative<BufferBinding>(entry.resource)) return "a buffer";
    if (std::holds_alternative<TextureBinding>(entry.resource)) return "a sampled texture";
    return "a storage image";
}

std::string slot_site(std::string_view command, std::string_view pipeline, const PipelineSlot& slot) {
    return std::string(command) + ": pipeline " + in_quotes(pipeline) + " set " + std::to_string(slot.set) + " binding " +
           std::to_string(slot.binding) + " (" + in_quotes(slot.name) + ")";
}

}  // namespace

Result<const BindingEntry*> binding(std::string_view command, std::string_view pipeline, const PipelineSlot& slot, const BindGroup* group,
                                    const Capabilities& caps, const ResourceLookup& lookup) {
    // Built only for an error: draws check every binding, and nearly all are fine.
    auto site = [&] { return slot_site(command, pipeline, slot); };
    const BindingEntry* entry = bound_entry(group, slot.binding);
    if (!entry) return Error{ErrorCode::InvalidState, site() + " is not bound"};
    auto wrong_kind = [&] {
        return Error{ErrorCode::InvalidArgument, site() + " is " + std::string(binding_kind_name(slot.kind)) + " but the bind group has " +
                                                     std::string(entry_kind_name(*entry)) + " there"};
    };
    auto handle_error = [&](Error e) {
        e.message = site() + ": " + e.message;
        return e;
    };
    // texture_range's message for `what` "" begins with ": ".
    auto in_texture = [&](Error e, const TextureDesc& t) {
        e.message = site() + ": texture " + in_quotes(t.name) + e.message;
        return e;
    };
    switch (slot.kind) {
        case BindingKind::UniformBuffer:
        case BindingKind::StorageBuffer: {
            const auto* range = std::get_if<BufferBinding>(&entry->resource);
            if (!range) return wrong_kind();
            auto found = lookup.buffer(range->buffer);
            if (!found.ok()) return handle_error(found.take_error());
            const BufferDesc& b = **found;
            const bool uniform = slot.kind == BindingKind::UniformBuffer;
            if (!has_all(b.usage, uniform ? BufferUsage::Uniform : BufferUsage::Storage)) {
                return Error{ErrorCode::InvalidArgument, site() + ": buffer " + in_quotes(b.name) + " lacks usage " + (uniform ? "Uniform" : "Storage")};
            }
            const uint64_t alignment = std::max<uint64_t>(1, uniform ? caps.uniform_buffer_offset_alignment : caps.storage_buffer_offset_alignment);
            const uint64_t size = range->size ? range->size : (b.size > range->offset ? b.size - range->offset : 0);
            if (range->offset % alignment != 0 || size == 0 || !checked::range_fits(range->offset, size, b.size)) {
                return Error{ErrorCode::InvalidArgument, site() + ": " + std::to_string(size) + " bytes at offset " + std::to_string(range->offset) +
                                                             " of buffer " + in_quotes(b.name) + " (" + std::to_string(b.size) +
                                                             " bytes) are empty, outside it or not aligned to " + std::to_string(alignment)};
            }
            return entry;
        }
        case BindingKind::SampledTexture: {
            const auto* tb = std::get_if<TextureBinding>(&entry->resource);
            if (!tb) return wrong_kind();
            auto texture = lookup.texture(tb->texture);
            if (!texture.ok()) return handle_error(texture.take_error());
            auto sampler = lookup.sampler(tb->sampler);
            if (!sampler.ok()) return handle_error(sampler.take_error());
            const TextureDesc& t = **texture;
            if (!has_all(t.usage, TextureUsage::Sampled)) {
                return Error{ErrorCode::InvalidArgument, site() + ": texture " + in_quotes(t.name) + " lacks usage Sampled"};
            }
            auto range = texture_range("", t, tb->range);
            if (!range.ok()) return in_texture(range.take_error(), t);
            LOOM_TRY(kind_fits(site, slot.texture_kind, t, range->layer_count));
            return entry;
        }
        case BindingKind::StorageImage: {
            const auto* sb = std::get_if<StorageTextureBinding>(&entry->resource);
            if (!sb) return wrong_kind();
            auto texture = lookup.texture(sb->texture);
            if (!texture.ok()) return handle_error(texture.take_error());
            const TextureDesc& t = **texture;
            if (!has_all(t.usage, TextureUsage::Storage)) {
                return Error{ErrorCode::InvalidArgument, site() + ": texture " + in_quotes(t.name) + " lacks usage Storage"};
            }
            if (sb->mip >= t.mip_levels) {
                return Error{ErrorCode::InvalidArgument, site() + ": mip " + std::to_string(sb->mip) + " of texture " + in_quotes(t.name) +
                                                             " does not exist (" + count_of(t.mip_levels, "level") + ")"};
            }
            auto range = texture_range("", t, TextureRange{sb->mip, 1, sb->base_layer, sb->layer_count});
            if (!range.ok()) return in_texture(range.take_error(), t);
            LOOM_TRY(kind_fits(site, slot.texture_kind, t, range->layer_count));
            return entry;
        }
    }
    return entry;
}

Error state_for_binding(std::string_view command, std::string_view pipeline, const PipelineSlot& slot, std::string_view texture,
                        ResourceState state, std::string_view needed) {
    return Error{ErrorCode::InvalidState, slot_site(command, pipeline, slot) + ": texture " + in_quotes(texture) + " is in state " +
                                              std::string(resource_state_name(state)) + "; transition it to " + std::string(needed) + " first"};
}

namespace {

// Whether a texture with (`depth_stencil`) or without a depth/stencil format can be in `state`.
bool texture_has_state(ResourceState state, bool depth_stencil) {
    switch (state) {
        case ResourceState::Undefined:
        case ResourceState::ShaderRead:
        case ResourceState::Storage:
        case ResourceState::CopySrc:
        case ResourceState::CopyDst: return true;
        case ResourceState::RenderTarget:
        case ResourceState::Present: return !depth_stencil;
        case ResourceState::DepthWrite:
        case ResourceState::DepthRead: return depth_stencil;
        case ResourceState::VertexBuffer:
        case ResourceState::IndexBuffer:
        case ResourceState::IndirectArgument: return false;
    }
    return false;
}

bool buffer_has_state(ResourceState state) {
    switch (state) {
        case ResourceState::RenderTarget:
        case ResourceState::DepthWrite:
        case ResourceState::DepthRead:
        case ResourceState::Present: return false;
        default: return true;
    }
}

}  // namespace

Status texture_transition(const TextureDesc& texture, ResourceState state, const Capabilities& caps) {
    const std::string what = "transition: texture " + in_quotes(texture.name);
    const std::string target(resource_state_name(state));
    const std::string format(format_name(texture.format));
    if (!texture_has_state(state, format_info(texture.format).is_depth_stencil())) {
        return Error{ErrorCode::InvalidArgument, what + " (" + format + ") cannot be in state " + target};
    }
    auto needs = [&](TextureUsage usage, const char* name) -> Status {
        if (has_all(texture.usage, usage)) return {};
        return Error{ErrorCode::InvalidArgument, what + " to " + target + " needs " + name + " usage"};
    };
    if (state == ResourceState::RenderTarget) return needs(TextureUsage::ColorAttachment, "ColorAttachment");
    if (state == ResourceState::DepthWrite) {
        return needs(TextureUsage::DepthStencilAttachment, "DepthStencilAttachment");
    }
    if (state == ResourceState::Storage) return needs(TextureUsage::Storage, "Storage");
    const bool sampled_state = state == ResourceState::ShaderRead || state == ResourceState::DepthRead;
    if (sampled_state && !caps.format(texture.format).sampled) {
        return Error{ErrorCode::Unsupported,
                     what + " to " + target + ": " + format + " cannot be sampled on this device"};
    }
    return {};
}

Result<TextureRange> texture_range_transition(const TextureDesc& texture, ResourceState state, const TextureRange& range,
                                              const Capabilities& caps) {
    LOOM_TRY(texture_transition(texture, state, caps));
    return texture_range("transition: texture " + in_quotes(texture.name), texture, range);
}

Status buffer_transition(const BufferDesc& buffer, ResourceState state) {
    if (buffer_has_state(state)) return {};
    return Error{ErrorCode::InvalidArgument, "transition: buffer " + in_quotes(buffer.name) + " cannot be in state " +
                                                 std::string(resource_state_name(state))};
}

Status viewport(const Viewport& v) {
    const bool ok = v.width > 0.0f && v.height > 0.0f && v.min_depth >= 0.0f && v.max_depth <= 1.0f && v.min_depth <= 1.0f &&
                    v.max_depth >= 0.0f && !std::isnan(v.x) && !std::isnan(v.y);
    if (!ok) {
        return Error{ErrorCode::InvalidArgument, "set_viewport: " + number(v.width) + "x" + number(v.height) + " at (" + number(v.x) + "," +
                                                     number(v.y) + ") with depths " + number(v.min_depth) + ".." + number(v.max_depth) +
                                                     ": the size must be positive and the depths within 0..1"};
    }
    return {};
}

Status push_constants(uint64_t offset, uint64_t size) {
    if (!checked::range_fits(offset, size, kMaxPushConstantBytes)) {
        return Error{ErrorCode::InvalidArgument, "push_constants: " + std::to_string(size) + " bytes at offset " + std::to_string(offset) +
                                                     " exceed the " + std::to_string(kMaxPushConstantBytes) + " bytes loom supports"};
    }
    return {};
}

Status bind_group(uint32_t set, const BindGroup& group) {
    if (set >= kMaxBindGroups) {
        return Error{ErrorCode::InvalidArgument, "set_bind_group: set " + std::to_string(set) + " is beyond the " +
                                                     std::to_string(kMaxBindGroups) + " sets loom supports"};
    }
    for (const BindingEntry& e : group.entries) {
        if (e.binding >= kMaxBindingsPerGroup) {
            return Error{ErrorCode::InvalidArgument, "set_bind_group: set " + std::to_string(set) + " binding " + std::to_string(e.binding) +
                                                         " is beyond the " + std::to_string(kMaxBindingsPerGroup) +
                                                         " bindings per set loom supports"};
        }
    }
    return {};
}

Status buffer_slot(uint32_t set, uint32_t binding) {
    if (set >= kMaxBindGroups || binding >= kMaxBindingsPerGroup) {
        return Error{ErrorCode::InvalidArgument, "set_buffer: set " + std::to_string(set) + " binding " + std::to_string(binding) +
                                                     " is beyond the " + std::to_string(kMaxBindGroups) + " sets of " +
                                                     std::to_string(kMaxBindingsPerGroup) + " bindings loom supports"};
    }
    return {};
}

Status vertex_buffer_slot_refused(uint32_t slot) {
    if (slot >= kMaxVertexBuffers) {
        return Error{ErrorCode::InvalidArgument, "set_vertex_buffer: slot " + std::to_string(slot) + " is beyond the " +
                                                     std::to_string(kMaxVertexBuffers) + " slots loom supports"};
    }
    return {};
}

Status vertex_buffer_refused(uint32_t slot, const BufferDesc& buffer, uint64_t offset) {
    const auto what = [&] { return std::string("set_vertex_buffer: slot " + std::to_string(slot) + ": buffer " + in_quotes(buffer.name)); };
    if (!has_all(buffer.usage, BufferUsage::Vertex)) return Error{ErrorCode::InvalidArgument, what() + " lacks usage Vertex"};
    if (offset >= buffer.size) {
        return Error{ErrorCode::InvalidArgument, what() + ": offset " + std::to_string(offset) + " is not inside its " +
                                                     std::to_string(buffer.size) + " bytes"};
    }
    return {};
}

Status index_buffer_refused(const BufferDesc& buffer, IndexType type, uint64_t offset) {
    const auto what = [&] { return std::string("set_index_buffer: buffer " + in_quotes(buffer.name)); };
    if (!has_all(buffer.usage, BufferUsage::Index)) return Error{ErrorCode::InvalidArgument, what() + " lacks usage Index"};
    if (offset >= buffer.size || offset % index_bytes(type) != 0) {
        return Error{ErrorCode::InvalidArgument, what() + ": offset " + std::to_string(offset) + " is not inside its " +
                                                     std::to_string(buffer.size) + " bytes or not a multiple of the index size " +
                                                     std::to_string(index_bytes(type))};
    }
    return {};
}

Status index_range(const BufferDesc& buffer, IndexType type, uint64_t offset, uint32_t first_index, uint32_t index_count) {
    if (!index_range_fits(buffer.size, type, offset, first_index, index_count)) {
        return Error{ErrorCode::InvalidArgument, "draw_indexed: " + std::to_string(index_count) + " indices from index " +
                                                     std::to_string(first_index) + " run past the end of index buffer " +
                                                     in_quotes(buffer.name) + " (" + std::to_string(buffer.size) + " bytes from offset " +
                                                     std::to_string(offset) + ")"};
    }
    return {};
}

Status indirect_draws(const BufferDesc& buffer, uint64_t offset, uint32_t draw_count, uint32_t stride) {
    // Built only on a failure (these run per bind or draw).
    const auto what = [&] { return std::string("draw_indexed_indirect: buffer " + in_quotes(buffer.name)); };
    constexpr uint64_t kCommandBytes = sizeof(DrawIndexedIndirectCommand);
    if (!has_all(buffer.usage, BufferUsage::Indirect)) return Error{ErrorCode::InvalidArgument, what() + " lacks usage Indirect"};
    if (offset % 4 != 0 || stride % 4 != 0 || stride < kCommandBytes) {
        return Error{ErrorCode::InvalidArgument, what() + ": offset " + std::to_string(offset) + " and stride " + std::to_string(stride) +
                                                     " must be multiples of 4, the stride at least " + std::to_string(kCommandBytes)};
    }
    // At most (2^32 - 1)^2 + kCommandBytes bytes: the span itself cannot overflow; offset + span can.
    if (draw_count > 0 && !checked::range_fits(offset, uint64_t{draw_count - 1} * stride + kCommandBytes, buffer.size)) {
        return Error{ErrorCode::InvalidArgument, what() + ": " + count_of(draw_count, "command") + " from offset " + std::to_string(offset) +
                                                     " run past its end (" + std::to_string(buffer.size) + " bytes)"};
    }
    return {};
}

}  // namespace loom::rhi::validation
