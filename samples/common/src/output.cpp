#include "loom/sample_common/output.hpp"

#include "loom/image_io/image_io.hpp"

namespace loom::samples {

Status save_texture_png(rhi::Device& device, rhi::TextureHandle texture, const std::filesystem::path& path) {
    auto image = device.read_texture(texture);
    if (!image.ok()) return image.take_error();
    return image_io::write_png(*image, path);
}

}  // namespace loom::samples
