#pragma once
// A loaded glTF scene on a device: all geometry in one vertex and one index buffer, every
// texture uploaded once with its full mip chain (sRGB where the importer decoded sRGB), and one
// sampler per texture as the file describes it. GltfObjects draw from it; it lives as long as
// the last object that uses it.

#include <cstdint>
#include <memory>
#include <vector>

#include "loom/rhi/descriptions.hpp"
#include "loom/rhi/device.hpp"
#include "loom/rhi/image.hpp"
#include "loom/rhi/result.hpp"
#include "loom/scene/packed_geometry.hpp"
#include "loom/scene/scene.hpp"
#include "loom/renderer/skin_palette.hpp"

namespace loom::renderer {

/// A scene with what every upload needs computed once, so that it can go to several devices
/// (e.g. GL and Vulkan) without repeating the CPU work: the packed geometry and every image's
/// mip chain.
struct PreparedScene {
    scene::Scene scene;
    scene::PackedGeometry geometry;
    /// mips[i]: the mip chain of scene.images[i] (level 0 first).
    std::vector<std::vector<rhi::Image>> mips;
};

/// Packs the geometry and builds the mip chains of `scene`.
std::shared_ptr<const PreparedScene> prepare_scene(scene::Scene scene);

/// What GpuScene::create uploads.
enum class GpuSceneContent : uint8_t {
    All,           ///< geometry and textures
    TexturesOnly,  ///< no vertex or index buffer (another owner draws the geometry)
};

/// The GPU side of a PreparedScene on one device (see the top of this file). Destroying it
/// destroys its buffers, textures and samplers: the device must outlive it.
class GpuScene {
public:
    /// Uploads everything (`content`: or the textures only). Errors: the device's (naming the
    /// buffer or texture).
    static Result<std::shared_ptr<GpuScene>> create(rhi::Device& device, std::shared_ptr<const PreparedScene> prepared,
                                                    GpuSceneContent content = GpuSceneContent::All);
    ~GpuScene();
    GpuScene(const GpuScene&) = delete;
    GpuScene& operator=(const GpuScene&) = delete;

    [[nodiscard]] const PreparedScene& prepared() const { return *prepared_; }
    [[nodiscard]] const scene::Scene& scene() const { return prepared_->scene; }
    [[nodiscard]] rhi::Device& device() const { return *device_; }
    /// Null when the scene has no geometry or it was not uploaded (GpuSceneContent::TexturesOnly).
    [[nodiscard]] rhi::BufferHandle vertex_buffer() const { return vertices_; }
    [[nodiscard]] rhi::BufferHandle index_buffer() const { return indices_; }
    /// The packed geometry's skin influences (PackedGeometry::skin), parallel to the vertex
    /// buffer; null when no primitive is skinned or the geometry was not uploaded.
    [[nodiscard]] rhi::BufferHandle skin_buffer() const { return skin_; }
    /// The joint matrices of the scene's skins as it was prepared (its static pose: GltfObjects
    /// of the scene itself are deformed by them); null when it has no skins or the geometry was
    /// not uploaded.
    [[nodiscard]] const SkinPalette* skin_palette() const { return palette_.get(); }
    /// The texture and sampler of scene().textures[index] (index must be valid).
    [[nodiscard]] rhi::TextureBinding texture(uint32_t index) const { return textures_[index]; }
    /// A 1x1 opaque white texture with a default sampler, bound where a material has no texture.
    [[nodiscard]] rhi::TextureBinding fallback() const { return fallback_; }
    /// Bytes of every texture level uploaded (fallback included).
    [[nodiscard]] uint64_t texture_bytes() const { return texture_bytes_; }

private:
    GpuScene(rhi::Device& device, std::shared_ptr<const PreparedScene> prepared)
        : device_(&device), prepared_(std::move(prepared)) {}
    Status upload(GpuSceneContent content);
    Result<rhi::TextureHandle> upload_image(const std::vector<rhi::Image>& levels, const std::string& name);

    rhi::Device* device_;
    std::shared_ptr<const PreparedScene> prepared_;
    rhi::BufferHandle vertices_;
    rhi::BufferHandle indices_;
    rhi::BufferHandle skin_;
    std::unique_ptr<SkinPalette> palette_;
    std::vector<rhi::TextureHandle> images_;       ///< one per scene image
    std::vector<rhi::SamplerHandle> samplers_;     ///< one per scene texture
    std::vector<rhi::TextureBinding> textures_;    ///< one per scene texture
    rhi::TextureBinding fallback_;
    uint64_t texture_bytes_ = 0;
};

}  // namespace loom::renderer
