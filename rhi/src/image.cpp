#include "loom/rhi/image.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

namespace loom::rhi {
namespace {

// ---- scalar conversions ----------------------------------------------------------------------

float half_to_float(uint16_t h) {
    const uint32_t sign = (h >> 15) & 1u;
    const uint32_t exponent = (h >> 10) & 0x1Fu;
    const uint32_t mantissa = h & 0x3FFu;
    float value;
    if (exponent == 0) {
        value = std::ldexp(static_cast<float>(mantissa), -24);
    } else if (exponent == 31) {
        value = mantissa == 0 ? std::numeric_limits<float>::infinity() : std::numeric_limits<float>::quiet_NaN();
    } else {
        value = std::ldexp(static_cast<float>(mantissa | 0x400u), static_cast<int>(exponent) - 25);
    }
    return sign ? -value : value;
}

// Round to nearest even, as GPUs do when writing half floats.
uint16_t float_to_half(float f) {
    const uint32_t bits = std::bit_cast<uint32_t>(f);
    const uint32_t sign = (bits >> 16) & 0x8000u;
    const uint32_t abs = bits & 0x7FFFFFFFu;
    if (abs >= 0x7F800000u) return static_cast<uint16_t>(sign | (abs > 0x7F800000u ? 0x7E00u : 0x7C00u));
    if (abs >= 0x477FF000u) return static_cast<uint16_t>(sign | 0x7C00u);  // overflow -> inf
    if (abs < 0x38800000u) {  // subnormal half (or zero)
        const float scaled = std::bit_cast<float>(abs) * 16777216.0f;  // * 2^24
        return static_cast<uint16_t>(sign | static_cast<uint32_t>(std::nearbyint(scaled)));
    }
    uint32_t half = ((abs - 0x38000000u) >> 13);
    const uint32_t rest = abs & 0x1FFFu;
    if (rest > 0x1000u || (rest == 0x1000u && (half & 1u))) ++half;
    return static_cast<uint16_t>(sign | half);
}

// Unsigned small floats of R11G11B10 (no sign bit, 5-bit exponent, bias 15).
double unsigned_small_float(uint32_t value, uint32_t mantissa_bits) {
    const uint32_t exponent = value >> mantissa_bits;
    const uint32_t mantissa = value & ((1u << mantissa_bits) - 1u);
    if (exponent == 0) return std::ldexp(static_cast<double>(mantissa), -14 - static_cast<int>(mantissa_bits));
    if (exponent == 31) return mantissa == 0 ? std::numeric_limits<double>::infinity() : std::numeric_limits<double>::quiet_NaN();
    return std::ldexp(static_cast<double>(mantissa | (1u << mantissa_bits)), static_cast<int>(exponent) - 15 - static_cast<int>(mantissa_bits));
}

uint32_t to_unsigned_small_float(double v, uint32_t mantissa_bits) {
    if (!(v > 0.0)) return 0;  // negatives and NaN clamp to 0
    const uint32_t max_exponent = 30;
    const double max_value = std::ldexp(2.0 - std::ldexp(1.0, -static_cast<int>(mantissa_bits)), 15);
    if (v >= max_value) return (max_exponent << mantissa_bits) | ((1u << mantissa_bits) - 1u);
    int e = 0;
    std::frexp(v, &e);  // v = m * 2^e, m in [0.5, 1)
    int exponent = e - 1 + 15;
    if (exponent <= 0) {  // denormal
        const double m = std::nearbyint(std::ldexp(v, 14 + static_cast<int>(mantissa_bits)));
        return static_cast<uint32_t>(m);
    }
    double m = std::nearbyint(std::ldexp(v, static_cast<int>(mantissa_bits) - (e - 1)));
    if (m >= std::ldexp(1.0, static_cast<int>(mantissa_bits) + 1)) {
        m /= 2;
        ++exponent;
    }
    return (static_cast<uint32_t>(exponent) << mantissa_bits) | (static_cast<uint32_t>(m) & ((1u << mantissa_bits) - 1u));
}

template <class T>
T read_as(const std::byte* p) {
    T v;
    std::memcpy(&v, p, sizeof(T));
    return v;
}
template <class T>
void write_as(std::byte* p, T v) {
    std::memcpy(p, &v, sizeof(T));
}

double max_level(uint8_t bits) { return std::ldexp(1.0, bits) - 1.0; }

// ---- texel codec -----------------------------------------------------------------------------
//
// A texel decodes to "levels": integer-valued numbers for normalised and integer channels
// (the stored integer), and values for float channels. Levels are the units of
// ImageCompareOptions::threshold; load() divides normalised levels by their maximum.

struct Levels {
    std::array<double, 4> v{0.0, 0.0, 0.0, 0.0};
};

Levels decode_levels(Format format, const std::byte* p) {
    Levels out;
    auto& v = out.v;
    switch (format) {
        case Format::R11G11B10Float: {
            const uint32_t w = read_as<uint32_t>(p);
            v = {unsigned_small_float(w & 0x7FFu, 6), unsigned_small_float((w >> 11) & 0x7FFu, 6),
                 unsigned_small_float((w >> 22) & 0x3FFu, 5), 0.0};
            return out;
        }
        case Format::RGB10A2Unorm: {
            const uint32_t w = read_as<uint32_t>(p);
            v = {double(w & 0x3FFu), double((w >> 10) & 0x3FFu), double((w >> 20) & 0x3FFu), double(w >> 30)};
            return out;
        }
        case Format::RGB9E5Float: {
            const uint32_t w = read_as<uint32_t>(p);
            const int exponent = static_cast<int>(w >> 27) - 15 - 9;
            v = {std::ldexp(double(w & 0x1FFu), exponent), std::ldexp(double((w >> 9) & 0x1FFu), exponent),
                 std::ldexp(double((w >> 18) & 0x1FFu), exponent), 0.0};
            return out;
        }
        case Format::Depth16: v[0] = read_as<uint16_t>(p); return out;
        case Format::Depth24: v[0] = read_as<uint32_t>(p) & 0xFFFFFFu; return out;
        case Format::Depth24Stencil8: {
            const uint32_t w = read_as<uint32_t>(p);
            v[0] = w & 0xFFFFFFu;
            v[1] = w >> 24;
            return out;
        }
        case Format::Depth32F: v[0] = read_as<float>(p); return out;
        case Format::Depth32FStencil8:
            v[0] = read_as<float>(p);
            v[1] = static_cast<uint8_t>(p[4]);
            return out;
        case Format::Stencil8: v[1] = static_cast<uint8_t>(p[0]); return out;
        default: break;
    }
    const FormatInfo& info = format_info(format);
    const auto& channels = info.features.color;
    const uint32_t count = info.channel_count();
    const uint32_t bytes = channels[0].bits / 8;
    for (uint32_t i = 0; i < count; ++i) {
        const std::byte* c = p + i * bytes;
        double value = 0.0;
        switch (channels[i].kind) {
            case ChannelKind::Unorm:
            case ChannelKind::Uint:
                value = bytes == 1 ? double(read_as<uint8_t>(c)) : bytes == 2 ? double(read_as<uint16_t>(c)) : double(read_as<uint32_t>(c));
                break;
            case ChannelKind::Snorm:
            case ChannelKind::Sint:
                value = bytes == 1 ? double(read_as<int8_t>(c)) : bytes == 2 ? double(read_as<int16_t>(c)) : double(read_as<int32_t>(c));
                break;
            case ChannelKind::Float:
                value = bytes == 2 ? double(half_to_float(read_as<uint16_t>(c))) : double(read_as<float>(c));
                break;
            case ChannelKind::None: break;
        }
        v[i] = value;
    }
    if (info.features.bgra) std::swap(v[0], v[2]);
    return out;
}

void encode_levels(Format format, std::byte* p, Levels in) {
    auto& v = in.v;
    auto clamp_round = [](double x, double lo, double hi) { return std::nearbyint(std::clamp(x, lo, hi)); };
    switch (format) {
        case Format::R11G11B10Float:
            write_as<uint32_t>(p, to_unsigned_small_float(v[0], 6) | (to_unsigned_small_float(v[1], 6) << 11) |
                                      (to_unsigned_small_float(v[2], 5) << 22));
            return;
        case Format::RGB10A2Unorm:
            write_as<uint32_t>(p, static_cast<uint32_t>(clamp_round(v[0], 0, 1023)) |
                                      (static_cast<uint32_t>(clamp_round(v[1], 0, 1023)) << 10) |
                                      (static_cast<uint32_t>(clamp_round(v[2], 0, 1023)) << 20) |
                                      (static_cast<uint32_t>(clamp_round(v[3], 0, 3)) << 30));
            return;
        case Format::RGB9E5Float: {
            // Shared exponent chosen from the largest channel (as in the GL spec, §8.5.2).
            const double max_v = std::max({v[0], v[1], v[2], 0.0});
            int exp_shared = 0;
            if (max_v > 0.0) {
                int e = 0;
                std::frexp(max_v, &e);
                exp_shared = std::max(-16, e - 1) + 1 + 15;
            }
            exp_shared = std::clamp(exp_shared, 0, 31);
            double scale = std::ldexp(1.0, 9 + 15 - exp_shared);
            if (std::nearbyint(max_v * scale) >= 512.0 && exp_shared < 31) {
                ++exp_shared;
                scale /= 2;
            }
            uint32_t word = static_cast<uint32_t>(exp_shared) << 27;
            for (int i = 0; i < 3; ++i) {
                word |= static_cast<uint32_t>(clamp_round(v[static_cast<std::size_t>(i)] * scale, 0, 511)) << (9 * i);
            }
            write_as<uint32_t>(p, word);
            return;
        }
        case Format::Depth16: write_as<uint16_t>(p, static_cast<uint16_t>(clamp_round(v[0], 0, 65535))); return;
        case Format::Depth24: write_as<uint32_t>(p, static_cast<uint32_t>(clamp_round(v[0], 0, 16777215))); return;
        case Format::Depth24Stencil8:
            write_as<uint32_t>(p, static_cast<uint32_t>(clamp_round(v[0], 0, 16777215)) |
                                      (static_cast<uint32_t>(clamp_round(v[1], 0, 255)) << 24));
            return;
        case Format::Depth32F: write_as<float>(p, static_cast<float>(v[0])); return;
        case Format::Depth32FStencil8:
            write_as<float>(p, static_cast<float>(v[0]));
            write_as<uint32_t>(p + 4, static_cast<uint32_t>(clamp_round(v[1], 0, 255)));
            return;
        case Format::Stencil8: p[0] = static_cast<std::byte>(clamp_round(v[1], 0, 255)); return;
        default: break;
    }
    const FormatInfo& info = format_info(format);
    if (info.features.bgra) std::swap(v[0], v[2]);
    const auto& channels = info.features.color;
    const uint32_t count = info.channel_count();
    const uint32_t bytes = channels[0].bits / 8;
    for (uint32_t i = 0; i < count; ++i) {
        std::byte* c = p + i * bytes;
        const double hi = std::ldexp(1.0, channels[i].bits) - 1.0;
        const double shi = std::ldexp(1.0, channels[i].bits - 1) - 1.0;
        switch (channels[i].kind) {
            case ChannelKind::Unorm:
            case ChannelKind::Uint: {
                const double x = clamp_round(v[i], 0.0, hi);
                if (bytes == 1) write_as<uint8_t>(c, static_cast<uint8_t>(x));
                else if (bytes == 2) write_as<uint16_t>(c, static_cast<uint16_t>(x));
                else write_as<uint32_t>(c, static_cast<uint32_t>(x));
                break;
            }
            case ChannelKind::Snorm:
            case ChannelKind::Sint: {
                const double x = clamp_round(v[i], -shi - 1.0, shi);
                if (bytes == 1) write_as<int8_t>(c, static_cast<int8_t>(x));
                else if (bytes == 2) write_as<int16_t>(c, static_cast<int16_t>(x));
                else write_as<int32_t>(c, static_cast<int32_t>(x));
                break;
            }
            case ChannelKind::Float:
                if (bytes == 2) write_as<uint16_t>(c, float_to_half(static_cast<float>(v[i])));
                else write_as<float>(c, static_cast<float>(v[i]));
                break;
            case ChannelKind::None: break;
        }
    }
}

/// Largest level of channel i for normalised channels, 0 for the others (no scaling).
std::array<double, 4> normalisation(Format format) {
    const FormatInfo& info = format_info(format);
    std::array<double, 4> n{0, 0, 0, 0};
    if (info.has_depth() && info.features.depth.kind == ChannelKind::Unorm) n[0] = max_level(info.features.depth.bits);
    if (info.is_depth_stencil()) return n;
    for (std::size_t i = 0; i < 4; ++i) {
        const Channel& c = info.features.color[i];
        if (c.kind == ChannelKind::Unorm) n[i] = max_level(c.bits);
        if (c.kind == ChannelKind::Snorm) n[i] = max_level(static_cast<uint8_t>(c.bits - 1));
    }
    return n;
}

/// Channels that carry data in a format (depth is channel 0, stencil channel 1).
std::array<bool, 4> present_channels(Format format) {
    const FormatInfo& info = format_info(format);
    if (info.is_depth_stencil()) return {info.has_depth(), info.has_stencil(), false, false};
    std::array<bool, 4> p{};
    for (std::size_t i = 0; i < 4; ++i) p[i] = info.features.color[i].present();
    return p;
}

}  // namespace

// ---- Image -----------------------------------------------------------------------------------

Image::Image(uint32_t w, uint32_t h, Format f)
    : width(w), height(h), format(f), pixels(std::size_t{w} * h * format_info(f).bytes_per_texel) {}

std::span<std::byte> Image::texel(uint32_t x, uint32_t y) {
    return {pixels.data() + std::size_t{y} * row_bytes() + std::size_t{x} * texel_bytes(), texel_bytes()};
}

std::span<const std::byte> Image::texel(uint32_t x, uint32_t y) const {
    return {pixels.data() + std::size_t{y} * row_bytes() + std::size_t{x} * texel_bytes(), texel_bytes()};
}

std::array<double, 4> Image::load(uint32_t x, uint32_t y) const {
    Levels l = decode_levels(format, texel(x, y).data());
    const auto n = normalisation(format);
    const auto present = present_channels(format);
    const bool color = format_info(format).is_color();
    for (std::size_t i = 0; i < 4; ++i) {
        if (n[i] != 0.0) l.v[i] = std::max(l.v[i] / n[i], -1.0);
        if (color && !present[i]) l.v[i] = (i == 3) ? 1.0 : 0.0;
    }
    return l.v;
}

void Image::store(uint32_t x, uint32_t y, const std::array<double, 4>& value) {
    Levels l{value};
    const auto n = normalisation(format);
    for (std::size_t i = 0; i < 4; ++i) {
        if (n[i] != 0.0) l.v[i] *= n[i];
    }
    encode_levels(format, texel(x, y).data(), l);
}

// ---- display and PNG -------------------------------------------------------------------------

Image to_rgba8(const Image& image, const DisplayOptions& options) {
    Image out(image.width, image.height, Format::RGBA8Unorm);
    const FormatInfo& info = format_info(image.format);
    if (image.format == Format::RGBA8Unorm || image.format == Format::RGBA8Srgb) {
        out.pixels = image.pixels;
        return out;
    }
    double lo = 0.0, hi = 1.0;
    if (info.is_depth_stencil() && info.has_depth() && options.normalize_depth) {
        lo = std::numeric_limits<double>::max();
        hi = std::numeric_limits<double>::lowest();
        for (uint32_t y = 0; y < image.height; ++y) {
            for (uint32_t x = 0; x < image.width; ++x) {
                const double d = image.load(x, y)[0];
                // The far plane (cleared depth) would flatten the range of what was drawn.
                if (d >= 1.0) continue;
                lo = std::min(lo, d);
                hi = std::max(hi, d);
            }
        }
        if (lo > hi) { lo = 0.0; hi = 1.0; }
        if (hi - lo < 1e-12) hi = lo + 1e-12;
    }
    const ChannelKind kind = info.color_kind();
    for (uint32_t y = 0; y < image.height; ++y) {
        for (uint32_t x = 0; x < image.width; ++x) {
            auto v = image.load(x, y);
            std::array<double, 4> rgba{};
            if (info.is_depth_stencil()) {
                const double g = info.has_depth() ? (v[0] >= 1.0 ? 1.0 : (v[0] - lo) / (hi - lo)) : v[1] / 255.0;
                rgba = {g, g, g, 1.0};
            } else {
                const uint32_t channels = info.channel_count();
                for (std::size_t i = 0; i < 4; ++i) {
                    double c = v[i];
                    if (kind == ChannelKind::Float) c /= options.float_white;
                    if (kind == ChannelKind::Uint || kind == ChannelKind::Sint) c = c / 255.0;
                    if (kind == ChannelKind::Snorm) c = c * 0.5 + 0.5;
                    rgba[i] = c;
                }
                if (channels == 1) rgba = {rgba[0], rgba[0], rgba[0], 1.0};
                if (channels < 4) rgba[3] = 1.0;
            }
            for (double& c : rgba) c = std::isnan(c) ? 0.0 : std::clamp(c, 0.0, 1.0);
            out.store(x, y, rgba);
        }
    }
    return out;
}

// ---- comparison ------------------------------------------------------------------------------

std::string ImageComparison::summary() const {
    char buf[160];
    std::snprintf(buf, sizeof buf, "max diff %g, %llu of %llu pixels above threshold, PSNR %s dB", max_channel_diff,
                  static_cast<unsigned long long>(pixels_above_threshold), static_cast<unsigned long long>(pixel_count),
                  std::isinf(psnr) ? "inf" : std::to_string(psnr).c_str());
    return buf;
}

Result<ImageComparison> compare_images(const Image& a, const Image& b, const ImageCompareOptions& options) {
    if (a.width != b.width || a.height != b.height) {
        return Error{ErrorCode::InvalidArgument, "images differ in size: " + std::to_string(a.width) + "x" +
                                                     std::to_string(a.height) + " vs " + std::to_string(b.width) +
                                                     "x" + std::to_string(b.height)};
    }
    if (a.format != b.format) {
        return Error{ErrorCode::InvalidArgument, "images differ in format: " + std::string(format_name(a.format)) +
                                                     " vs " + std::string(format_name(b.format))};
    }
    ImageComparison result;
    result.pixel_count = uint64_t{a.width} * a.height;
    const auto present = present_channels(a.format);
    const auto norm = normalisation(a.format);
    const FormatInfo& info = format_info(a.format);
    std::vector<double> pixel_diff(result.pixel_count, 0.0);
    // PSNR: normalised and integer channels compare against their largest level; float channels
    // against the largest magnitude present, known only at the end, so they sum separately.
    double squared_error = 0.0;
    double float_squared_error = 0.0;
    double float_peak = 1.0;
    uint64_t samples = 0;
    for (uint32_t y = 0; y < a.height; ++y) {
        for (uint32_t x = 0; x < a.width; ++x) {
            const auto la = decode_levels(a.format, a.texel(x, y).data()).v;
            const auto lb = decode_levels(b.format, b.texel(x, y).data()).v;
            double worst = 0.0;
            for (std::size_t i = 0; i < 4; ++i) {
                if (!present[i]) continue;
                double d;
                if (std::isnan(la[i]) || std::isnan(lb[i])) {
                    d = (std::isnan(la[i]) && std::isnan(lb[i])) ? 0.0 : std::numeric_limits<double>::infinity();
                } else if (la[i] == lb[i]) {
                    d = 0.0;  // also equal infinities
                } else {
                    d = std::abs(la[i] - lb[i]);
                }
                worst = std::max(worst, d);
                ++samples;
                const bool is_float = norm[i] == 0.0 && !info.is_integer() && !(info.has_stencil() && i == 1);
                if (is_float && std::isfinite(d)) {
                    if (std::isfinite(la[i])) float_peak = std::max(float_peak, std::abs(la[i]));
                    float_squared_error += d * d;
                    continue;
                }
                const double peak = norm[i] != 0.0 ? norm[i] : max_level(i == 1 && info.has_stencil() ? 8 : info.features.color[i].bits);
                const double e = std::isfinite(d) ? d / peak : 1.0;
                squared_error += e * e;
            }
            pixel_diff[std::size_t{y} * a.width + x] = worst;
            result.max_channel_diff = std::max(result.max_channel_diff, worst);
            if (worst > options.threshold) ++result.pixels_above_threshold;
        }
    }
    squared_error += float_squared_error / (float_peak * float_peak);
    const double mse = samples ? squared_error / static_cast<double>(samples) : 0.0;
    result.psnr = mse == 0.0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(1.0 / mse);
    if (options.heatmap) {
        Image heat(a.width, a.height, Format::RGBA8Unorm);
        const double scale = result.max_channel_diff > 0.0 && std::isfinite(result.max_channel_diff) ? result.max_channel_diff : 1.0;
        for (uint32_t y = 0; y < a.height; ++y) {
            for (uint32_t x = 0; x < a.width; ++x) {
                const double d = pixel_diff[std::size_t{y} * a.width + x];
                // Black where equal; red->yellow->white as the difference grows; any
                // difference above the threshold is at least clearly red.
                double t = std::isfinite(d) ? d / scale : 1.0;
                if (d > options.threshold) t = std::max(t, 0.35);
                heat.store(x, y, {std::min(1.0, t * 3.0), std::clamp(t * 3.0 - 1.0, 0.0, 1.0),
                                  std::clamp(t * 3.0 - 2.0, 0.0, 1.0), 1.0});
            }
        }
        result.heatmap = std::move(heat);
    }
    return result;
}

}  // namespace loom::rhi
