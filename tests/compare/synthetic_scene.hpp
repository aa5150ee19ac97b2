#pragma once
// Small loom::scene::Scenes built in code, for testing how glTF materials and geometry render
// without files: unit quads, materials, textures from pixel lists, a camera looking down -Z.

#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "loom/rhi/image.hpp"
#include "loom/scene/scene.hpp"

namespace loom::test {

/// Builds a Scene item by item (bounds, normal matrices and winding are derived as the importer
/// derives them).
class SceneBuilder {
public:
    SceneBuilder();

    /// Adds a material; returns its index.
    uint32_t material(const scene::Material& material);
    /// Adds an image (RGBA8Unorm or RGBA8Srgb) and a texture sampling it; returns the texture.
    uint32_t texture(const rhi::Image& image, const rhi::SamplerDesc& sampler);
    /// A 2 x 2 quad in the plane z = 0 facing +z, centred at the origin, placed by `world`: uv0
    /// (0,0) at the top-left corner (-1, 1), uv1 mirrored left to right, tangent +x, colour
    /// `color`. Returns the draw item's index.
    uint32_t quad(uint32_t material, const glm::mat4& world = glm::mat4(1.0f), const glm::vec4& color = glm::vec4(1.0f));
    /// The camera at (0, 0, distance) looking down -Z with a vertical field of view of 60°.
    void camera(float distance = 3.0f);

    [[nodiscard]] scene::Scene build() const { return scene_; }

private:
    scene::Scene scene_;
};

/// A nearest-filtering, edge-clamping sampler without mipmaps (texels land exactly).
rhi::SamplerDesc nearest_sampler();

/// An image of `width` x `height` from RGBA8 texels given row by row.
rhi::Image image_of(uint32_t width, uint32_t height, rhi::Format format, const std::vector<std::array<uint8_t, 4>>& texels);

/// sRGB-encoded byte to linear light.
double srgb_to_linear(uint8_t value);

}  // namespace loom::test
