#pragma once
// CPU-side images: what a texture readback returns (rows top-first, tightly packed, in the
// texture's own format), their conversion for viewing, and the comparison that tests and tools
// share to prove two renderings equal. Encoded files (PNG, JPEG) are loom::image_io's.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "loom/rhi/format.hpp"
#include "loom/rhi/result.hpp"

namespace loom::rhi {

/// A 2D image in a loom format. Row 0 is the top row; rows are tightly packed
/// (row_bytes() == width * bytes_per_texel).
struct Image {
    uint32_t width = 0;
    uint32_t height = 0;
    Format format = Format::RGBA8Unorm;
    std::vector<std::byte> pixels;

    Image() = default;
    Image(uint32_t w, uint32_t h, Format f);  ///< zero-filled

    /// True when the image has no texels.
    [[nodiscard]] bool empty() const { return width == 0 || height == 0; }
    /// Bytes of one texel.
    [[nodiscard]] std::size_t texel_bytes() const { return format_info(format).bytes_per_texel; }
    /// Bytes of one row (rows are tightly packed).
    [[nodiscard]] std::size_t row_bytes() const { return std::size_t{width} * texel_bytes(); }
    /// The bytes of texel (x, y), row 0 on top.
    [[nodiscard]] std::span<std::byte> texel(uint32_t x, uint32_t y);
    /// The bytes of texel (x, y), row 0 on top.
    [[nodiscard]] std::span<const std::byte> texel(uint32_t x, uint32_t y) const;

    /// The texel decoded to four doubles in its natural units: normalised formats in [0,1]
    /// ([-1,1] for snorm, sRGB values as stored, not linearised), float formats as floats,
    /// integer formats as integers, depth as depth ([0,1]) in [0] and stencil in [1].
    /// Missing colour channels read as 0, missing alpha as 1.
    [[nodiscard]] std::array<double, 4> load(uint32_t x, uint32_t y) const;

    /// Stores four values, converted and rounded to the format (inverse of load()).
    void store(uint32_t x, uint32_t y, const std::array<double, 4>& value);
};

/// How to turn a non-RGBA8 image into something viewable.
struct DisplayOptions {
    /// For depth images: map [min, max] of the values present (not [0,1]) to black..white,
    /// so that shadow maps and depth buffers are visible.
    bool normalize_depth = true;
    /// For float images: the value mapped to white (values are clamped to [0, 1] after scaling).
    double float_white = 1.0;
};

/// An RGBA8Unorm copy of `image` suitable for viewing (see DisplayOptions).
Image to_rgba8(const Image& image, const DisplayOptions& options = {});

/// How compare_images compares.
struct ImageCompareOptions {
    /// A pixel counts as different when any channel differs by more than this, in the
    /// channel's natural units (levels 0..255 for 8-bit unorm, values for float formats).
    /// Exact by default; any looser tolerance is set per test with a comment saying why.
    double threshold = 0.0;
    /// Build a heat map of the differences (black = equal, bright = largest difference).
    bool heatmap = true;
};

/// What compare_images found.
struct ImageComparison {
    /// Largest per-channel difference over all pixels, in natural units (see threshold).
    double max_channel_diff = 0.0;
    /// Pixels whose largest channel difference exceeds the threshold.
    uint64_t pixels_above_threshold = 0;
    uint64_t pixel_count = 0;
    /// Peak signal-to-noise ratio in dB over all channels; +infinity for identical images.
    double psnr = 0.0;
    /// RGBA8 heat map of per-pixel differences (when requested).
    std::optional<Image> heatmap;

    /// True when no pixel is above the threshold.
    [[nodiscard]] bool equal() const { return pixels_above_threshold == 0; }
    /// "max diff 3, 12 of 65536 pixels above 0, PSNR 51.2 dB"
    [[nodiscard]] std::string summary() const;
};

/// Compares two images of the same size and format; an InvalidArgument error says which of
/// size or format differs.
Result<ImageComparison> compare_images(const Image& a, const Image& b, const ImageCompareOptions& options = {});

}  // namespace loom::rhi
