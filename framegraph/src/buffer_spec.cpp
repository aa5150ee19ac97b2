#include "loom/framegraph/buffer_spec.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include "loom/rhi/checked_math.hpp"
#include "text.hpp"

namespace loom::fg {
namespace {

using rhi::BufferUsage;

constexpr std::array<std::pair<BufferUsage, std::string_view>, 7> kUsageNames{{
    {BufferUsage::Vertex, "vertex"},
    {BufferUsage::Index, "index"},
    {BufferUsage::Uniform, "uniform"},
    {BufferUsage::Storage, "storage"},
    {BufferUsage::Indirect, "indirect"},
    {BufferUsage::CopySrc, "copy_src"},
    {BufferUsage::CopyDst, "copy_dst"},
}};

std::string format_scale(float value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%g", static_cast<double>(value));
    return buffer;
}

// round(frame * scale), at least 1; nullopt past 32 bits (a scale no frame can have).
std::optional<uint64_t> scaled_side(uint32_t frame, float scale) {
    const double pixels = std::round(static_cast<double>(frame) * static_cast<double>(scale));
    if (!(pixels < 4294967296.0)) return std::nullopt;  // also refuses NaN
    return pixels < 1.0 ? uint64_t{1} : static_cast<uint64_t>(pixels);
}

bool power_of_two(uint64_t value) { return value != 0 && (value & (value - 1)) == 0; }

}  // namespace

BufferSize BufferSize::absolute(uint64_t bytes) {
    BufferSize size;
    size.kind = Kind::Absolute;
    size.bytes = bytes;
    return size;
}

BufferSize BufferSize::per_pixel(uint64_t bytes_per_pixel, float scale) {
    BufferSize size;
    size.kind = Kind::PerPixel;
    size.bytes = bytes_per_pixel;
    size.scale = scale;
    return size;
}

BufferSize BufferSize::per_tile(uint32_t tile_width, uint32_t tile_height, uint64_t bytes_per_tile) {
    BufferSize size;
    size.kind = Kind::PerTile;
    size.bytes = bytes_per_tile;
    size.tile = {tile_width, tile_height};
    return size;
}

std::optional<uint64_t> BufferSize::evaluate(Extent2D frame) const {
    switch (kind) {
        case Kind::Absolute: return bytes;
        case Kind::PerPixel: {
            auto w = scaled_side(frame.width, scale);
            auto h = scaled_side(frame.height, scale);
            if (!w || !h) return std::nullopt;
            auto pixels = checked::mul(*w, *h);
            if (!pixels) return std::nullopt;
            return checked::mul(*pixels, bytes);
        }
        case Kind::PerTile: {
            if (tile.width == 0 || tile.height == 0) return std::nullopt;
            const uint64_t across = (uint64_t{frame.width} + tile.width - 1) / tile.width;
            const uint64_t down = (uint64_t{frame.height} + tile.height - 1) / tile.height;
            auto tiles = checked::mul(across, down);
            if (!tiles) return std::nullopt;
            return checked::mul(*tiles, bytes);
        }
    }
    return std::nullopt;
}

BufferSpec BufferSpec::of_size(uint64_t bytes) { return sized(BufferSize::absolute(bytes)); }

BufferSpec BufferSpec::sized(const BufferSize& size) {
    BufferSpec spec;
    spec.size = size;
    return spec;
}

BufferSpec BufferSpec::with_usage(BufferUsage extra) const {
    BufferSpec out = *this;
    out.usage |= extra;
    return out;
}

BufferSpec BufferSpec::with_alignment(uint64_t value) const {
    BufferSpec out = *this;
    out.alignment = value;
    return out;
}

bool BufferSpec::unconstrained() const { return !size && usage == BufferUsage::None && !alignment; }

Result<ResolvedBufferSpec> resolve_buffer(const BufferSpec& spec, Extent2D frame, std::string_view what) {
    auto fail = [&](const std::string& message) {
        return make_error(ErrorCode::Graph, "buffer " + std::string(what) + ": " + message);
    };
    if (!spec.size) {
        return fail("no port gives its size (declare it on the producing port: BufferSpec::of_size, "
                    "BufferSize::per_pixel or BufferSize::per_tile)");
    }
    if (spec.size->kind == BufferSize::Kind::PerTile && (spec.size->tile.width == 0 || spec.size->tile.height == 0)) {
        return fail("size " + describe_buffer_size(*spec.size) + " has an empty tile");
    }
    const std::optional<uint64_t> bytes = spec.size->evaluate(frame);
    if (!bytes || *bytes > kMaxBufferBytes) {
        return fail("size " + describe_buffer_size(*spec.size) + " is more than loom's limit of " +
                    std::to_string(kMaxBufferBytes) + " bytes for a frame of " + std::to_string(frame.width) + "x" +
                    std::to_string(frame.height));
    }
    if (*bytes == 0) return fail("size " + describe_buffer_size(*spec.size) + " is 0 bytes");
    ResolvedBufferSpec out;
    out.size = *bytes;
    out.usage = spec.usage;
    if (spec.alignment) {
        if (!power_of_two(*spec.alignment) || *spec.alignment > kMaxBufferAlignment) {
            return fail("alignment " + std::to_string(*spec.alignment) + " is not a power of two up to " +
                        std::to_string(kMaxBufferAlignment));
        }
        out.alignment = *spec.alignment;
    }
    return out;
}

rhi::BufferDesc to_buffer_desc(const ResolvedBufferSpec& spec, std::string name) {
    rhi::BufferDesc desc;
    desc.name = std::move(name);
    desc.size = spec.size;
    desc.usage = spec.usage;
    return desc;
}

std::string describe_buffer_size(const BufferSize& size) {
    switch (size.kind) {
        case BufferSize::Kind::Absolute: return std::to_string(size.bytes) + " bytes";
        case BufferSize::Kind::PerPixel: {
            std::string text = std::to_string(size.bytes) + " bytes per pixel";
            if (size.scale != 1.0f) text += " of " + format_scale(size.scale) + " x frame";
            return text;
        }
        case BufferSize::Kind::PerTile:
            return std::to_string(size.bytes) + " bytes per " + std::to_string(size.tile.width) + "x" +
                   std::to_string(size.tile.height) + " tile";
    }
    return "?";
}

std::string describe_buffer_usage(BufferUsage usage) {
    std::string out;
    for (const auto& [flag, name] : kUsageNames) {
        if (rhi::has_all(usage, flag)) detail::append(out, out.empty() ? "" : "|", name);
    }
    return out.empty() ? "none" : out;
}

std::optional<BufferUsage> parse_buffer_usage_flag(std::string_view name) {
    for (const auto& [flag, flag_name] : kUsageNames) {
        if (flag_name == name) return flag;
    }
    return std::nullopt;
}

std::string describe_buffer_spec(const BufferSpec& spec) {
    std::string out;
    auto add = [&](const std::string& part) { out += (out.empty() ? "" : " ") + part; };
    if (spec.size) add("size=" + describe_buffer_size(*spec.size));
    if (spec.usage != BufferUsage::None) add("usage=" + describe_buffer_usage(spec.usage));
    if (spec.alignment) add("alignment=" + std::to_string(*spec.alignment));
    return out.empty() ? "any" : out;
}

std::string describe_resolved_buffer(const ResolvedBufferSpec& spec) {
    std::string out = "buffer " + std::to_string(spec.size) + " bytes " + describe_buffer_usage(spec.usage);
    if (spec.alignment > 1) out += " aligned " + std::to_string(spec.alignment);
    return out;
}

}  // namespace loom::fg
