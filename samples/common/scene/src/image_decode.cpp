#include "image_decode.hpp"

#include <climits>
#include <cstring>
#include <memory>
#include <string>

#include <stb_image.h>

namespace loom::scene::detail {

Result<rhi::Image> decode_image(std::span<const unsigned char> encoded, rhi::Format format, uint32_t max_dimension) {
    if (encoded.empty()) return make_error(ErrorCode::Parse, "image data is empty");
    if (encoded.size() > static_cast<std::size_t>(INT_MAX)) {
        return make_error(ErrorCode::Parse, "image data of " + std::to_string(encoded.size()) + " bytes is too large");
    }
    const int size = static_cast<int>(encoded.size());
    int width = 0;
    int height = 0;
    int channels = 0;
    if (stbi_info_from_memory(encoded.data(), size, &width, &height, &channels) == 0) {
        return make_error(ErrorCode::Parse, std::string("cannot decode image: ") + stbi_failure_reason());
    }
    if (width <= 0 || height <= 0 || static_cast<uint32_t>(width) > max_dimension ||
        static_cast<uint32_t>(height) > max_dimension) {
        return make_error(ErrorCode::Parse, "image size " + std::to_string(width) + "x" + std::to_string(height) +
                                                " exceeds the importer's limit of " + std::to_string(max_dimension) +
                                                " (LoadOptions::max_image_dimension)");
    }
    const std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
        stbi_load_from_memory(encoded.data(), size, &width, &height, &channels, 4), stbi_image_free);
    if (!pixels) return make_error(ErrorCode::Parse, std::string("cannot decode image: ") + stbi_failure_reason());
    rhi::Image image(static_cast<uint32_t>(width), static_cast<uint32_t>(height), format);
    std::memcpy(image.pixels.data(), pixels.get(), image.pixels.size());
    return image;
}

}  // namespace loom::scene::detail
