#pragma once
// The joint matrices of a scene's skins on a device: one storage buffer ("JointMatrices" in the
// skinned glTF parts) holding every skin's scene::joint_matrices(), each skin's range starting at
// the device's storage-buffer offset alignment, so that a draw can bind its skin's range alone
// (GltfObject) or the whole palette with joint indices offset by base() (RetainedGltfScene).
// Written per skin: posing writes only the skins whose joints moved.

#include <cstdint>
#include <memory>
#include <vector>

#include "loom/rhi/descriptions.hpp"
#include "loom/rhi/device.hpp"
#include "loom/rhi/result.hpp"
#include "loom/scene/scene.hpp"

namespace loom::renderer {

class SkinPalette {
public:
    /// A palette for `scene`'s skins, written with their current joint matrices. Errors: the
    /// device's (naming the buffer); a scene without skins gets a palette of one matrix.
    static Result<std::unique_ptr<SkinPalette>> create(rhi::Device& device, const scene::Scene& scene);
    ~SkinPalette();
    SkinPalette(const SkinPalette&) = delete;
    SkinPalette& operator=(const SkinPalette&) = delete;

    /// The first matrix of skin `skin` in the buffer.
    [[nodiscard]] uint32_t base(uint32_t skin) const { return bases_.at(skin); }
    /// The range of skin `skin`'s matrices.
    [[nodiscard]] rhi::BufferBinding range(uint32_t skin) const;
    /// The whole buffer.
    [[nodiscard]] rhi::BufferBinding whole() const { return rhi::BufferBinding{buffer_, 0, size_}; }

    /// Writes skin `skin`'s joint matrices as `scene` (the scene the palette was made for, posed)
    /// places its joints now.
    Status write(const scene::Scene& scene, uint32_t skin);
    /// Writes every skin's.
    Status write_all(const scene::Scene& scene);
    /// Bytes written since creation (the first write included).
    [[nodiscard]] uint64_t bytes_written() const { return bytes_written_; }

private:
    SkinPalette(rhi::Device& device) : device_(&device) {}

    rhi::Device* device_;
    rhi::BufferHandle buffer_;
    uint64_t size_ = 0;
    std::vector<uint32_t> bases_;   ///< per skin, in matrices
    std::vector<uint32_t> counts_;  ///< per skin, its joints
    uint64_t bytes_written_ = 0;
};

}  // namespace loom::renderer
