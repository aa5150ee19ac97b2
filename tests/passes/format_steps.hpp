#pragma once
// Comparing images in rounding steps of their storage format. A tolerance of "one step at the
// image's peak" allows what one rounding more or less does to the largest value present (one
// half-float step, one float step, one 8-bit level) and nothing that would show.

#include <cstdint>
#include <string>

#include "loom/rhi/format.hpp"
#include "loom/rhi/image.hpp"

namespace loom::test {

/// The distance between neighbouring values of `format`'s channels around `magnitude`: for
/// float channels 2^(floor(log2 magnitude) - mantissa bits), for 8-bit unorm 1/255.
double format_step(rhi::Format format, double magnitude);

struct StepComparison {
    uint64_t pixel_count = 0;
    uint64_t pixels_differing = 0;  ///< any channel differs at all
    double max_abs = 0.0;           ///< largest difference of a channel, in value units
    double peak = 0.0;              ///< largest magnitude of a channel in either image
    double step_at_peak = 0.0;      ///< format_step(format, peak)
    uint64_t pixels_beyond_one_step = 0;  ///< pixels with a channel differing by more than step_at_peak

    [[nodiscard]] double fraction_differing() const {
        return pixel_count == 0 ? 0.0 : static_cast<double>(pixels_differing) / static_cast<double>(pixel_count);
    }
    /// Largest difference of a channel in steps at that channel's own magnitude:
    /// |a - b| / format_step(format, max(|a|, |b|)). 1 means "neighbouring values".
    double max_local_steps = 0.0;

    /// True when no channel differs by more than one step at the peak.
    [[nodiscard]] bool within_one_step() const { return pixels_beyond_one_step == 0; }
    /// "12 of 57600 pixels differ (0.021%), by at most 0.000488 (one step at the peak 3.9: 0.00195;
    /// at most 1 step locally)"
    [[nodiscard]] std::string summary() const;
};

/// Compares two images of one size and format channel by channel (colour formats with 8-bit
/// unorm, 16- or 32-bit float channels, and Depth32F).
StepComparison compare_steps(const rhi::Image& a, const rhi::Image& b);

}  // namespace loom::test
