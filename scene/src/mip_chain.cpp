#include "loom/scene/mip_chain.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstddef>

namespace loom::scene {
namespace {

/// sRGB-encoded byte to linear light (IEC 61966-2-1).
const std::array<float, 256>& srgb_to_linear_table() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (std::size_t i = 0; i < t.size(); ++i) {
            const double s = static_cast<double>(i) / 255.0;
            t[i] = static_cast<float>(s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4));
        }
        return t;
    }();
    return table;
}

std::byte linear_to_srgb_byte(float linear) {
    const double l = std::clamp(static_cast<double>(linear), 0.0, 1.0);
    const double s = l <= 0.0031308 ? l * 12.92 : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055;
    return static_cast<std::byte>(std::lround(s * 255.0));
}

/// The next level of `source`: each texel the mean of the (up to) 2x2 texels below it.
rhi::Image half_size(const rhi::Image& source, bool srgb) {
    const uint32_t width = std::max(source.width / 2, 1u);
    const uint32_t height = std::max(source.height / 2, 1u);
    rhi::Image out(width, height, source.format);
    const auto& to_linear = srgb_to_linear_table();
    for (uint32_t y = 0; y < height; ++y) {
        const uint32_t y0 = std::min(2 * y, source.height - 1);
        const uint32_t y1 = std::min(2 * y + 1, source.height - 1);
        for (uint32_t x = 0; x < width; ++x) {
            const uint32_t x0 = std::min(2 * x, source.width - 1);
            const uint32_t x1 = std::min(2 * x + 1, source.width - 1);
            const std::span<const std::byte> texels[4] = {source.texel(x0, y0), source.texel(x1, y0),
                                                          source.texel(x0, y1), source.texel(x1, y1)};
            std::span<std::byte> target = out.texel(x, y);
            for (std::size_t c = 0; c < 4; ++c) {
                // Alpha is linear in both formats.
                if (srgb && c < 3) {
                    float sum = 0.0f;
                    for (const auto& texel : texels) sum += to_linear[std::to_integer<std::size_t>(texel[c])];
                    target[c] = linear_to_srgb_byte(sum * 0.25f);
                } else {
                    uint32_t sum = 0;
                    for (const auto& texel : texels) sum += std::to_integer<uint32_t>(texel[c]);
                    target[c] = static_cast<std::byte>((sum + 2) / 4);
                }
            }
        }
    }
    return out;
}

}  // namespace

uint32_t mip_level_count(uint32_t width, uint32_t height) {
    uint32_t levels = 1;
    for (uint32_t size = std::max(width, height); size > 1; size /= 2) ++levels;
    return levels;
}

std::vector<rhi::Image> mip_chain(const rhi::Image& image) {
    assert(image.format == rhi::Format::RGBA8Unorm || image.format == rhi::Format::RGBA8Srgb);
    const bool srgb = image.format == rhi::Format::RGBA8Srgb;
    std::vector<rhi::Image> levels;
    const uint32_t count = mip_level_count(image.width, image.height);
    levels.reserve(count);
    levels.push_back(image);
    while (levels.size() < count) levels.push_back(half_size(levels.back(), srgb));
    return levels;
}

}  // namespace loom::scene
