#include <climits>
#include <cstring>
#include <memory>

#include <stb_image.h>

#include "decoder_reason.hpp"
#include "loom/image_io/image_io.hpp"

namespace loom::image_io {
namespace {

Error cannot_decode() { return make_error(ErrorCode::Parse, "cannot decode image: " + detail::decoder_reason()); }

// stb_image takes the length as an int.
Result<int> encoded_length(std::span<const unsigned char> encoded) {
    if (encoded.empty()) return make_error(ErrorCode::Parse, "image data is empty");
    if (encoded.size() > static_cast<std::size_t>(INT_MAX)) {
        return make_error(ErrorCode::Parse, "image data of " + std::to_string(encoded.size()) + " bytes is too large");
    }
    return static_cast<int>(encoded.size());
}

}  // namespace

Result<EncodedImageSize> encoded_image_size(std::span<const unsigned char> encoded) {
    auto length = encoded_length(encoded);
    if (!length) return length.take_error();
    int width = 0;
    int height = 0;
    int channels = 0;
    if (stbi_info_from_memory(encoded.data(), *length, &width, &height, &channels) == 0) return cannot_decode();
    if (width <= 0 || height <= 0) {
        return make_error(ErrorCode::Parse,
                          "image size " + std::to_string(width) + "x" + std::to_string(height) + " is empty");
    }
    return EncodedImageSize{static_cast<uint32_t>(width), static_cast<uint32_t>(height)};
}

Result<rhi::Image> decode_image(std::span<const unsigned char> encoded, rhi::Format format) {
    if (format != rhi::Format::RGBA8Unorm && format != rhi::Format::RGBA8Srgb) {
        return make_error(ErrorCode::InvalidArgument, "decode_image: format " + std::string(rhi::format_name(format)) +
                                                          " is not RGBA8Unorm or RGBA8Srgb");
    }
    auto length = encoded_length(encoded);
    if (!length) return length.take_error();
    int width = 0;
    int height = 0;
    int channels = 0;
    const std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
        stbi_load_from_memory(encoded.data(), *length, &width, &height, &channels, 4), stbi_image_free);
    if (!pixels) return cannot_decode();
    rhi::Image image(static_cast<uint32_t>(width), static_cast<uint32_t>(height), format);
    std::memcpy(image.pixels.data(), pixels.get(), image.pixels.size());
    return image;
}

}  // namespace loom::image_io
