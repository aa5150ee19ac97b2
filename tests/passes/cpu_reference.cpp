#include "cpu_reference.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace loom::test {
namespace {

using Vec4 = std::array<float, 4>;

Vec4 load(const rhi::Image& image, int x, int y) {
    const auto v = image.load(static_cast<uint32_t>(x), static_cast<uint32_t>(y));
    return {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]), static_cast<float>(v[3])};
}

/// float to half float rounding toward zero, as llvmpipe and lavapipe write RGBA16F attachments
/// (measured: every GPU result that differed from round-to-nearest lay below it).
uint16_t half_toward_zero(float value) {
    uint32_t bits = 0;
    std::memcpy(&bits, &value, sizeof(bits));
    const auto sign = static_cast<uint16_t>((bits >> 16) & 0x8000u);
    const uint32_t magnitude = bits & 0x7fffffffu;
    if (magnitude >= 0x7f800000u) return static_cast<uint16_t>(sign | (magnitude > 0x7f800000u ? 0x7e00u : 0x7c00u));
    const int exponent = static_cast<int>(magnitude >> 23) - 127;
    if (exponent > 15) return static_cast<uint16_t>(sign | 0x7bffu);  // the largest finite half
    if (exponent >= -14) {
        return static_cast<uint16_t>(sign | (static_cast<uint32_t>(exponent + 15) << 10) | ((magnitude >> 13) & 0x3ffu));
    }
    if (exponent < -25) return sign;
    const uint32_t mantissa = (magnitude & 0x7fffffu) | 0x800000u;  // subnormal half: mantissa * 2^-24
    return static_cast<uint16_t>(sign | (mantissa >> (-exponent - 1)));
}

void store(rhi::Image& image, int x, int y, const Vec4& v) {
    const auto ux = static_cast<uint32_t>(x), uy = static_cast<uint32_t>(y);
    if (image.format == rhi::Format::RGBA16Float) {
        uint16_t halves[4];
        for (int c = 0; c < 4; ++c) halves[c] = half_toward_zero(v[c]);
        std::memcpy(image.texel(ux, uy).data(), halves, sizeof(halves));
        return;
    }
    image.store(ux, uy, {v[0], v[1], v[2], v[3]});
}

float luminance(float r, float g, float b) { return r * 0.2126f + g * 0.7152f + b * 0.0722f; }

float aces(float x) {
    return std::clamp((x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
}

float linear_to_srgb(float c) {
    return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

}  // namespace

rhi::Image reference_blur(const rhi::Image& source, passes::BlurAxis axis, const std::vector<float>& weights) {
    rhi::Image out(source.width, source.height, source.format);
    const int w = static_cast<int>(source.width), h = static_cast<int>(source.height);
    const int dx = axis == passes::BlurAxis::Horizontal ? 1 : 0;
    const int dy = 1 - dx;
    const int radius = static_cast<int>(weights.size()) - 1;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            Vec4 sum = load(source, x, y);
            for (float& c : sum) c *= weights[0];
            for (int i = 1; i <= radius; ++i) {
                const Vec4 ahead = load(source, std::clamp(x + dx * i, 0, w - 1), std::clamp(y + dy * i, 0, h - 1));
                const Vec4 behind = load(source, std::clamp(x - dx * i, 0, w - 1), std::clamp(y - dy * i, 0, h - 1));
                for (int c = 0; c < 4; ++c) sum[c] += (ahead[c] + behind[c]) * weights[static_cast<std::size_t>(i)];
            }
            store(out, x, y, sum);
        }
    }
    return out;
}

rhi::Image reference_high_pass(const rhi::Image& source, float threshold) {
    rhi::Image out(source.width, source.height, source.format);
    for (uint32_t y = 0; y < source.height; ++y) {
        for (uint32_t x = 0; x < source.width; ++x) {
            const Vec4 c = load(source, static_cast<int>(x), static_cast<int>(y));
            const float l = luminance(c[0], c[1], c[2]);
            const float keep = std::max(l - threshold, 0.0f) / std::max(l, 1e-4f);
            store(out, static_cast<int>(x), static_cast<int>(y), {c[0] * keep, c[1] * keep, c[2] * keep, 1.0f});
        }
    }
    return out;
}

rhi::Image reference_composite(const rhi::Image& color, const rhi::Image& bloom, float exposure, float strength,
                               bool srgb) {
    rhi::Image out(color.width, color.height, color.format);
    for (uint32_t y = 0; y < color.height; ++y) {
        for (uint32_t x = 0; x < color.width; ++x) {
            const Vec4 c = load(color, static_cast<int>(x), static_cast<int>(y));
            const Vec4 b = load(bloom, static_cast<int>(x), static_cast<int>(y));
            Vec4 result{0.0f, 0.0f, 0.0f, 1.0f};
            for (int i = 0; i < 3; ++i) {
                const float mapped = aces((c[i] + b[i] * strength) * exposure);
                result[i] = srgb ? linear_to_srgb(mapped) : mapped;
            }
            store(out, static_cast<int>(x), static_cast<int>(y), result);
        }
    }
    return out;
}

rhi::Image reference_blit(const rhi::Image& source, rhi::Format format) {
    rhi::Image out(source.width, source.height, format);
    for (uint32_t y = 0; y < source.height; ++y) {
        for (uint32_t x = 0; x < source.width; ++x) out.store(x, y, source.load(x, y));
    }
    return out;
}

}  // namespace loom::test
