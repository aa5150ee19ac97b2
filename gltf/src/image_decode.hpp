#pragma once
// Decoding of the images glTF materials use (PNG and JPEG: loom::image_io) into RGBA8
// rhi::Images, with the importer's size limit checked before any pixel memory is allocated.

#include <cstdint>
#include <span>

#include "loom/rhi/format.hpp"
#include "loom/rhi/image.hpp"
#include "loom/rhi/result.hpp"

namespace loom::gltf::detail {


/// Decodes `encoded` to an image of `format` (RGBA8Unorm or RGBA8Srgb: the bytes are the same,
/// the format says how to read them). Images wider or taller than `max_dimension` are
/// rejected. The error message says what is wrong, without naming the file.
[[nodiscard]] Result<rhi::Image> decode_image(std::span<const unsigned char> encoded, rhi::Format format,
                                              uint32_t max_dimension);

}  // namespace loom::gltf::detail
