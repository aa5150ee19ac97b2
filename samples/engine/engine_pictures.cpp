#include "engine_pictures.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace loom::engine {
namespace {

bool has_prefix(const std::string& name, const char* prefix) { return name.rfind(prefix, 0) == 0; }

/// Grey from the nearest to the farthest value below 1 (the cleared depth, white), channel `c`.
rhi::Image depth_grey(const rhi::Image& image, int c) {
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    for (uint32_t y = 0; y < image.height; ++y) {
        for (uint32_t x = 0; x < image.width; ++x) {
            const double v = image.load(x, y)[c];
            if (v >= 1.0) continue;
            lo = std::min(lo, v);
            hi = std::max(hi, v);
        }
    }
    rhi::Image out(image.width, image.height, rhi::Format::RGBA8Unorm);
    for (uint32_t y = 0; y < image.height; ++y) {
        for (uint32_t x = 0; x < image.width; ++x) {
            const double v = image.load(x, y)[c];
            const double g = v >= 1.0 ? 1.0 : (hi > lo ? 0.85 * (v - lo) / (hi - lo) : 0.0);
            out.store(x, y, {g, g, g, 1.0});
        }
    }
    return out;
}

/// HDR colour scaled by `gain`, mapped by x / (1 + x) and encoded with gamma 1/2.2.
rhi::Image tone_mapped(const rhi::Image& image, double gain) {
    rhi::Image out(image.width, image.height, rhi::Format::RGBA8Unorm);
    for (uint32_t y = 0; y < image.height; ++y) {
        for (uint32_t x = 0; x < image.width; ++x) {
            const auto v = image.load(x, y);
            std::array<double, 4> c{0, 0, 0, 1};
            for (int i = 0; i < 3; ++i) {
                const double s = std::max(0.0, v[i] * gain);
                c[i] = std::pow(s / (1.0 + s), 1.0 / 2.2);
            }
            out.store(x, y, c);
        }
    }
    return out;
}

/// Black (no light) through blue, green and yellow to red (32 lights or more).
std::array<double, 3> heat(double count) {
    const double t = std::clamp(count / 32.0, 0.0, 1.0) * 4.0;
    static const std::array<std::array<double, 3>, 5> ramp = {{{0, 0, 0}, {0, 0.2, 1}, {0, 0.9, 0.3}, {1, 0.9, 0}, {1, 0.1, 0}}};
    const int i = std::min(static_cast<int>(t), 3);
    const double f = t - i;
    return {ramp[i][0] + (ramp[i + 1][0] - ramp[i][0]) * f, ramp[i][1] + (ramp[i + 1][1] - ramp[i][1]) * f,
            ramp[i][2] + (ramp[i + 1][2] - ramp[i][2]) * f};
}

}  // namespace

Result<std::map<std::string, rhi::Image>> read_intermediates(rhi::Device& device, EngineFrame& frame) {
    std::map<std::string, rhi::Image> out;
    for (const Intermediate& captured : frame.intermediates()) {
        for (uint32_t mip = 0; mip < captured.mips; ++mip) {
            for (uint32_t layer = 0; layer < captured.layers; ++layer) {
                std::string name = captured.name;
                if (captured.mips > 1) name += ".mip" + std::to_string(mip);
                if (captured.layers > 1) name += ".layer" + std::to_string(layer);
                // bloom_up writes levels 0..3 only; its level 4 is bloom_down's.
                if (captured.name == "bloom_up" && mip + 1 == captured.mips) continue;
                auto image = device.read_texture(captured.texture, mip, layer);
                if (!image) return image.take_error();
                out.emplace(std::move(name), std::move(*image));
            }
        }
    }
    if (frame.captured_light_list()) {
        auto bytes = device.read_buffer(frame.captured_light_list(), 0, frame.captured_light_list_bytes());
        if (!bytes) return bytes.take_error();
        const auto final_image = out.find("final");
        if (final_image != out.end()) {
            const fg::Extent2D tiles = EngineFrame::tile_count({final_image->second.width, final_image->second.height});
            rhi::Image counts(tiles.width, tiles.height, rhi::Format::R32Uint);
            for (uint32_t y = 0; y < tiles.height; ++y) {
                for (uint32_t x = 0; x < tiles.width; ++x) {
                    const std::size_t offset = (std::size_t{y} * tiles.width + x) * kTileStride * sizeof(uint32_t);
                    uint32_t count = 0;
                    if (offset + sizeof(count) <= bytes->size()) std::memcpy(&count, bytes->data() + offset, sizeof(count));
                    counts.store(x, y, {static_cast<double>(count), 0, 0, 0});
                }
            }
            out.emplace("light_list", std::move(counts));
        }
    }
    return out;
}

rhi::Image viewable(const std::string& name, const rhi::Image& image, const rhi::Image& final) {
    if (name == "light_list") {
        rhi::Image out(final.width, final.height, rhi::Format::RGBA8Unorm);
        for (uint32_t y = 0; y < final.height; ++y) {
            for (uint32_t x = 0; x < final.width; ++x) {
                const auto under = final.load(x, y);
                const double grey = 0.3 * (0.2126 * under[0] + 0.7152 * under[1] + 0.0722 * under[2]);
                const auto h = heat(image.load(std::min(x / kTileSize, image.width - 1), std::min(y / kTileSize, image.height - 1))[0]);
                const bool edge = x % kTileSize == 0 || y % kTileSize == 0;
                const double keep = edge ? 0.5 : 0.75;
                out.store(x, y, {grey + keep * h[0], grey + keep * h[1], grey + keep * h[2], 1.0});
            }
        }
        return out;
    }
    if (name == "depth" || has_prefix(name, "shadow_cascades")) return depth_grey(image, 0);
    if (has_prefix(name, "hzb")) return depth_grey(image, 1);
    if (name == "hdr") return tone_mapped(image, 1.0);
    if (has_prefix(name, "bloom")) return tone_mapped(image, 4.0);
    return rhi::to_rgba8(image);
}

rhi::Image contact_sheet(const std::map<std::string, rhi::Image>& pictures, const std::vector<std::string>& names,
                         uint32_t columns, fg::Extent2D cell) {
    const auto count = static_cast<uint32_t>(names.size());
    const uint32_t rows = (count + columns - 1) / columns;
    rhi::Image sheet(cell.width * columns, cell.height * rows, rhi::Format::RGBA8Unorm);
    for (uint32_t i = 0; i < count; ++i) {
        const auto found = pictures.find(names[i]);
        if (found == pictures.end()) continue;
        const rhi::Image& picture = found->second;
        const double scale = std::min(static_cast<double>(cell.width) / picture.width, static_cast<double>(cell.height) / picture.height);
        const auto w = static_cast<uint32_t>(picture.width * scale), h = static_cast<uint32_t>(picture.height * scale);
        const uint32_t x0 = (i % columns) * cell.width + (cell.width - w) / 2;
        const uint32_t y0 = (i / columns) * cell.height + (cell.height - h) / 2;
        for (uint32_t y = 0; y < h; ++y) {
            for (uint32_t x = 0; x < w; ++x) {
                const auto sx = std::min(static_cast<uint32_t>((x + 0.5) / scale), picture.width - 1);
                const auto sy = std::min(static_cast<uint32_t>((y + 0.5) / scale), picture.height - 1);
                sheet.store(x0 + x, y0 + y, picture.load(sx, sy));
            }
        }
    }
    return sheet;
}

}  // namespace loom::engine
