#include "loom/sample_common/output.hpp"

namespace loom::samples {

Status save_texture_png(rhi::Device& device, rhi::TextureHandle texture, const std::filesystem::path& path) {
    auto image = device.read_texture(texture);
    if (!image.ok()) return image.take_error();
    return rhi::write_png(*image, path);
}

}  // namespace loom::samples
