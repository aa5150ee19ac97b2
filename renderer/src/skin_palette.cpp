#include "loom/renderer/skin_palette.hpp"

#include <algorithm>
#include <span>
#include <string>

namespace loom::renderer {

Result<std::unique_ptr<SkinPalette>> SkinPalette::create(rhi::Device& device, const scene::Scene& scene) {
    std::unique_ptr<SkinPalette> palette(new SkinPalette(device));
    // Each skin's range starts at a multiple of the alignment (a whole number of matrices: the
    // alignments are powers of two, and a matrix is 64 bytes).
    const uint64_t alignment = std::max<uint64_t>(device.capabilities().storage_buffer_offset_alignment, sizeof(glm::mat4));
    const uint64_t step = alignment / sizeof(glm::mat4);
    uint64_t next = 0;
    for (const scene::Skin& skin : scene.skins) {
        palette->bases_.push_back(static_cast<uint32_t>(next));
        palette->counts_.push_back(static_cast<uint32_t>(skin.joints.size()));
        next += (std::max<uint64_t>(skin.joints.size(), 1) + step - 1) / step * step;
    }
    palette->size_ = std::max<uint64_t>(next, 1) * sizeof(glm::mat4);
    auto buffer = device.create_buffer(rhi::BufferDesc{scene.source + " joint matrices", palette->size_, rhi::BufferUsage::Storage});
    if (!buffer) return buffer.take_error();
    palette->buffer_ = *buffer;
    LOOM_TRY(palette->write_all(scene));
    return palette;
}

SkinPalette::~SkinPalette() {
    if (buffer_) (void)device_->destroy(buffer_);
}

rhi::BufferBinding SkinPalette::range(uint32_t skin) const {
    return rhi::BufferBinding{buffer_, uint64_t{bases_.at(skin)} * sizeof(glm::mat4),
                              std::max<uint64_t>(counts_.at(skin), 1) * sizeof(glm::mat4)};
}

Status SkinPalette::write(const scene::Scene& scene, uint32_t skin) {
    const std::vector<glm::mat4> matrices = scene::joint_matrices(scene, skin);
    if (matrices.empty()) return {};
    const std::span<const std::byte> bytes = std::as_bytes(std::span(matrices));
    LOOM_TRY(device_->write_buffer(buffer_, uint64_t{bases_.at(skin)} * sizeof(glm::mat4), bytes));
    bytes_written_ += bytes.size();
    return {};
}

Status SkinPalette::write_all(const scene::Scene& scene) {
    for (uint32_t s = 0; s < scene.skins.size(); ++s) LOOM_TRY(write(scene, s));
    return {};
}

}  // namespace loom::renderer
