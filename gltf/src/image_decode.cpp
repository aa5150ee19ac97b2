#include "image_decode.hpp"

#include <string>

#include "loom/image_io/image_io.hpp"

namespace loom::gltf::detail {


Result<rhi::Image> decode_image(std::span<const unsigned char> encoded, rhi::Format format, uint32_t max_dimension) {
    auto size = image_io::encoded_image_size(encoded);
    if (!size) return size.take_error();
    if (size->width > max_dimension || size->height > max_dimension) {
        return make_error(ErrorCode::Parse, "image size " + std::to_string(size->width) + "x" +
                                                std::to_string(size->height) + " exceeds the importer's limit of " +
                                                std::to_string(max_dimension) + " (LoadOptions::max_image_dimension)");
    }
    return image_io::decode_image(encoded, format);
}

}  // namespace loom::gltf::detail
