#include "visualize.hpp"

#include <algorithm>
#include <cmath>

namespace loom::deferred {
namespace {

double srgb_encode(double linear) {
    linear = std::clamp(linear, 0.0, 1.0);
    return linear <= 0.0031308 ? linear * 12.92 : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

/// Rec. 709 relative luminance of a linear colour.
double luminance(const std::array<double, 4>& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

double aces(double x) {
    return std::clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

template <class F>
rhi::Image map_pixels(const rhi::Image& image, F f) {
    rhi::Image out(image.width, image.height, rhi::Format::RGBA8Unorm);
    for (uint32_t y = 0; y < image.height; ++y) {
        for (uint32_t x = 0; x < image.width; ++x) {
            std::array<double, 4> c = f(x, y, image.load(x, y));
            for (double& v : c) v = std::clamp(v, 0.0, 1.0);
            out.store(x, y, c);
        }
    }
    return out;
}

bool is_background(const std::map<std::string, rhi::Image>& all, uint32_t x, uint32_t y) {
    auto normal = all.find("geometry.normal");
    if (normal == all.end()) return false;
    const auto n = normal->second.load(x, y);
    return n[0] * n[0] + n[1] * n[1] + n[2] * n[2] < 0.25;
}

bool ends_with(const std::string& text, const std::string& suffix) {
    return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

rhi::Image visualize(const std::string& name, const rhi::Image& image, const std::map<std::string, rhi::Image>& all,
                     const DisplaySettings& settings) {
    const rhi::FormatInfo& info = rhi::format_info(image.format);
    if (info.has_depth()) return rhi::to_rgba8(image);  // normalised to the depths present
    if (image.format == rhi::Format::RGBA8Unorm || image.format == rhi::Format::RGBA8Srgb) return image;

    if (name == "geometry.position") {
        const glm::vec3 lo = settings.scene_bounds.min;
        const glm::vec3 size = glm::max(settings.scene_bounds.max - lo, glm::vec3(1e-6f));
        return map_pixels(image, [&](uint32_t x, uint32_t y, std::array<double, 4> c) -> std::array<double, 4> {
            if (is_background(all, x, y)) return {0, 0, 0, 1};
            return {(c[0] - lo.x) / size.x, (c[1] - lo.y) / size.y, (c[2] - lo.z) / size.z, 1.0};
        });
    }
    if (name == "geometry.normal") {
        return map_pixels(image, [&](uint32_t x, uint32_t y, std::array<double, 4> c) -> std::array<double, 4> {
            if (is_background(all, x, y)) return {0, 0, 0, 1};
            return {c[0] * 0.5 + 0.5, c[1] * 0.5 + 0.5, c[2] * 0.5 + 0.5, 1.0};
        });
    }
    if (name == "geometry.albedo") {
        return map_pixels(image, [&](uint32_t, uint32_t, std::array<double, 4> c) -> std::array<double, 4> {
            return {srgb_encode(c[0]), srgb_encode(c[1]), srgb_encode(c[2]), 1.0};
        });
    }
    if (ends_with(name, ".final")) {
        // Already tone-mapped and sRGB-encoded by the composite pass.
        return map_pixels(image, [](uint32_t, uint32_t, std::array<double, 4> c) -> std::array<double, 4> {
            return {c[0], c[1], c[2], 1.0};
        });
    }
    // HDR colour (lit colour, high pass, bloom): the composite's exposure and curve.
    const double exposure = settings.exposure;
    return map_pixels(image, [&](uint32_t, uint32_t, std::array<double, 4> c) -> std::array<double, 4> {
        return {srgb_encode(aces(c[0] * exposure)), srgb_encode(aces(c[1] * exposure)),
                srgb_encode(aces(c[2] * exposure)), 1.0};
    });
}

rhi::Image material_map(const rhi::Image& position, const rhi::Image& normal, const rhi::Image& emission) {
    rhi::Image out(position.width, position.height, rhi::Format::RGBA8Unorm);
    for (uint32_t y = 0; y < out.height; ++y) {
        for (uint32_t x = 0; x < out.width; ++x) {
            const auto n = normal.load(x, y);
            if (n[0] * n[0] + n[1] * n[1] + n[2] * n[2] < 0.25) {
                out.store(x, y, {0, 0, 0, 1});
                continue;
            }
            out.store(x, y, {std::clamp(position.load(x, y)[3], 0.0, 1.0), std::clamp(n[3], 0.0, 1.0),
                             std::clamp(luminance(emission.load(x, y)) / 16.0, 0.0, 1.0), 1.0});
        }
    }
    return out;
}

rhi::Image mosaic(const rhi::Image& top_left, const rhi::Image& top_right, const rhi::Image& bottom_left,
                  const rhi::Image& bottom_right) {
    const uint32_t w = top_left.width / 2, h = top_left.height / 2;
    rhi::Image out(w * 2, h * 2, rhi::Format::RGBA8Unorm);
    const rhi::Image* tiles[4] = {&top_left, &top_right, &bottom_left, &bottom_right};
    for (int t = 0; t < 4; ++t) {
        const uint32_t ox = (t % 2) * w, oy = (t / 2) * h;
        for (uint32_t y = 0; y < h; ++y) {
            for (uint32_t x = 0; x < w; ++x) {
                // Average of the 2x2 texels each output texel covers.
                std::array<double, 4> sum{};
                for (uint32_t dy = 0; dy < 2; ++dy) {
                    for (uint32_t dx = 0; dx < 2; ++dx) {
                        const auto c = tiles[t]->load(x * 2 + dx, y * 2 + dy);
                        for (int i = 0; i < 4; ++i) sum[i] += c[i] * 0.25;
                    }
                }
                out.store(ox + x, oy + y, sum);
            }
        }
    }
    return out;
}

}  // namespace loom::deferred
