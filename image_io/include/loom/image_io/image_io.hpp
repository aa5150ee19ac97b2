#pragma once
// Encoded images in and out of loom's CPU images (rhi::Image): PNG files written and read by
// the samples, tools and tests, and PNG or JPEG bytes decoded for the glTF importer. The one
// place loom uses an image codec (stb_image), kept out of loom::rhi so that the interface
// every backend and user includes links none.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

#include "loom/rhi/image.hpp"
#include "loom/rhi/result.hpp"

namespace loom::image_io {

/// Writes `image` as PNG (converted with rhi::to_rgba8 unless it is RGBA8/RGBA8Srgb already),
/// creating the folder it goes into. Errors: InvalidArgument for an empty image, Io naming the
/// path when the file cannot be written.
Status write_png(const rhi::Image& image, const std::filesystem::path& path, const rhi::DisplayOptions& options = {});

/// Reads a PNG into an RGBA8Unorm image. Errors: Io naming the path and the decoder's reason.
Result<rhi::Image> read_png(const std::filesystem::path& path);

/// Compares (rhi::compare_images) and, when the images differ, writes `<stem>.a.png`,
/// `<stem>.b.png` and `<stem>.diff.png` (the heat map) next to each other under `dir`.
Result<rhi::ImageComparison> compare_and_report(const rhi::Image& a, const rhi::Image& b,
                                                const std::filesystem::path& dir, const std::string& stem,
                                                const rhi::ImageCompareOptions& options = {});

/// Width and height of an encoded image (any format stb_image reads: PNG, JPEG, ...).
struct EncodedImageSize {
    uint32_t width = 0;
    uint32_t height = 0;
};

/// The size of `encoded`, read from its header without decoding pixels, so that a caller can
/// refuse huge images before any pixel memory is allocated. Errors are Parse; the message says
/// what is wrong (the decoder's reason, made printable) without naming a file.
Result<EncodedImageSize> encoded_image_size(std::span<const unsigned char> encoded);

/// Decodes `encoded` to an image of `format` (RGBA8Unorm or RGBA8Srgb: the bytes are the same,
/// the format says how to read them). Errors as encoded_image_size(); InvalidArgument for any
/// other format.
Result<rhi::Image> decode_image(std::span<const unsigned char> encoded, rhi::Format format);

}  // namespace loom::image_io
