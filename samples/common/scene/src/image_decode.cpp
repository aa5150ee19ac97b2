#include "image_decode.hpp"

#include <climits>
#include <cstring>
#include <memory>
#include <string>

#include <stb_image.h>

namespace loom::scene::detail {
namespace {

// stb_image's failure reason, printable. For an unknown critical PNG chunk stb_image puts the
// chunk's four type bytes, taken from the file, into the reason ("XXXX PNG chunk not known"),
// so a file could put a newline (or any byte) into the importer's one-line error.
std::string failure_reason() {
    static constexpr char kHex[] = "0123456789abcdef";
    std::string out = "cannot decode image: ";
    const char* reason = stbi_failure_reason();
    for (const char* c = reason != nullptr ? reason : "unknown reason"; *c != '\0'; ++c) {
        const auto byte = static_cast<unsigned char>(*c);
        if (byte < 0x20 || byte >= 0x7f) {
            out += "\\x";
            out += kHex[byte >> 4];
            out += kHex[byte & 15];
        } else {
            out += *c;
        }
    }
    return out;
}

}  // namespace

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
        return make_error(ErrorCode::Parse, failure_reason());
    }
    if (width <= 0 || height <= 0 || static_cast<uint32_t>(width) > max_dimension ||
        static_cast<uint32_t>(height) > max_dimension) {
        return make_error(ErrorCode::Parse, "image size " + std::to_string(width) + "x" + std::to_string(height) +
                                                " exceeds the importer's limit of " + std::to_string(max_dimension) +
                                                " (LoadOptions::max_image_dimension)");
    }
    const std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
        stbi_load_from_memory(encoded.data(), size, &width, &height, &channels, 4), stbi_image_free);
    if (!pixels) return make_error(ErrorCode::Parse, failure_reason());
    rhi::Image image(static_cast<uint32_t>(width), static_cast<uint32_t>(height), format);
    std::memcpy(image.pixels.data(), pixels.get(), image.pixels.size());
    return image;
}

}  // namespace loom::scene::detail
