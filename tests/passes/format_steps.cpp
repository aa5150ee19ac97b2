#include "format_steps.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <vector>

namespace loom::test {

double format_step(rhi::Format format, double magnitude) {
    const rhi::FormatInfo& info = rhi::format_info(format);
    const rhi::Channel channel = info.has_depth() ? info.features.depth : info.features.color[0];
    if (channel.kind != rhi::ChannelKind::Float) return 1.0 / static_cast<double>((1u << channel.bits) - 1u);
    const int mantissa = channel.bits == 16 ? 10 : 23;
    const int smallest_exponent = channel.bits == 16 ? -14 : -126;
    const int exponent = magnitude > 0.0 ? std::max(static_cast<int>(std::floor(std::log2(magnitude))), smallest_exponent)
                                         : smallest_exponent;
    return std::ldexp(1.0, exponent - mantissa);
}

std::string StepComparison::summary() const {
    char text[320];
    std::snprintf(text, sizeof(text),
                  "%llu of %llu pixels differ (%.3f%%), %llu by more than one step at the peak %g (%g), by at "
                  "most %g (%g step(s) locally)",
                  static_cast<unsigned long long>(pixels_differing), static_cast<unsigned long long>(pixel_count),
                  100.0 * fraction_differing(), static_cast<unsigned long long>(pixels_beyond_one_step), peak,
                  step_at_peak, max_abs, max_local_steps);
    return text;
}

StepComparison compare_steps(const rhi::Image& a, const rhi::Image& b) {
    assert(a.width == b.width && a.height == b.height && a.format == b.format);
    const bool depth = rhi::format_info(a.format).has_depth();
    const int channels = depth ? 1 : 4;
    StepComparison out;
    out.pixel_count = uint64_t{a.width} * a.height;
    std::vector<double> worst;  // per differing pixel, its largest channel difference
    for (uint32_t y = 0; y < a.height; ++y) {
        for (uint32_t x = 0; x < a.width; ++x) {
            const auto la = a.load(x, y);
            const auto lb = b.load(x, y);
            double pixel_worst = 0.0;
            for (int c = 0; c < channels; ++c) {
                out.peak = std::max({out.peak, std::abs(la[c]), std::abs(lb[c])});
                const double diff = std::abs(la[c] - lb[c]);
                if (diff == 0.0) continue;
                pixel_worst = std::max(pixel_worst, diff);
                const double local = format_step(a.format, std::max(std::abs(la[c]), std::abs(lb[c])));
                out.max_local_steps = std::max(out.max_local_steps, diff / local);
            }
            if (pixel_worst == 0.0) continue;
            ++out.pixels_differing;
            out.max_abs = std::max(out.max_abs, pixel_worst);
            worst.push_back(pixel_worst);
        }
    }
    out.step_at_peak = format_step(a.format, out.peak);
    // A little slack for the decimal round trip of 8-bit levels (k/255 - (k-1)/255).
    for (double w : worst) out.pixels_beyond_one_step += w > out.step_at_peak * (1.0 + 1e-9) ? 1 : 0;
    return out;
}

}  // namespace loom::test
