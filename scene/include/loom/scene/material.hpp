#pragma once
// PBR metallic-roughness materials (the glTF 2.0 core model) and the textures they sample.

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>

#include "loom/rhi/descriptions.hpp"
#include "loom/rhi/image.hpp"
#include "loom/scene/glm.hpp"

namespace loom::scene {

/// How a material's alpha is used (glTF alphaMode).
enum class AlphaMode : uint8_t {
    Opaque,  ///< alpha is ignored; the surface is fully opaque
    Mask,    ///< alpha below Material::alpha_cutoff is discarded, the rest is opaque
    Blend,   ///< alpha blends the surface over what lies behind it
};

/// How a texture's coordinates are moved before sampling (glTF KHR_texture_transform):
/// uv' = translation(offset) * rotation(rotation) * scale(scale) * uv.
struct TextureTransform {
    glm::vec2 offset{0.0f};
    float rotation = 0.0f;  ///< radians, counter-clockwise in UV space
    glm::vec2 scale{1.0f};

    /// The two rows of the 2x3 matrix that applies the transform: uv' = (dot(row0, (u, v, 1)),
    /// dot(row1, (u, v, 1))).
    [[nodiscard]] std::array<glm::vec3, 2> rows() const {
        const float c = std::cos(rotation), s = std::sin(rotation);
        return {glm::vec3(c * scale.x, s * scale.y, offset.x), glm::vec3(-s * scale.x, c * scale.y, offset.y)};
    }

    friend bool operator==(const TextureTransform&, const TextureTransform&) = default;
};

/// A material's use of a texture: which texture and which UV set (0 = Vertex::uv0, 1 = uv1).
struct TextureRef {
    uint32_t texture = 0;  ///< index into Scene::textures
    uint32_t uv_set = 0;
    /// Absent: the coordinates as they are.
    std::optional<TextureTransform> transform = std::nullopt;

    friend bool operator==(const TextureRef&, const TextureRef&) = default;
};

/// A glTF metallic-roughness material with its factors (glTF defaults) and optional textures.
/// The final value of each property is factor × texture (when there is a texture).
struct Material {
    std::string name;
    glm::vec4 base_color_factor{1.0f};  ///< linear RGBA
    float metallic_factor = 1.0f;
    float roughness_factor = 1.0f;
    glm::vec3 emissive_factor{0.0f};     ///< linear RGB
    float normal_scale = 1.0f;           ///< scales the normal map's X and Y
    float occlusion_strength = 1.0f;     ///< 0 = no occlusion, 1 = full occlusion
    AlphaMode alpha_mode = AlphaMode::Opaque;
    float alpha_cutoff = 0.5f;           ///< used by AlphaMode::Mask only
    bool double_sided = false;           ///< back faces are drawn (and lit with a flipped normal)

    std::optional<TextureRef> base_color_texture;          ///< sRGB; RGBA
    std::optional<TextureRef> metallic_roughness_texture;  ///< linear; roughness in G, metallic in B
    std::optional<TextureRef> normal_texture;              ///< linear; tangent-space normal
    std::optional<TextureRef> occlusion_texture;           ///< linear; occlusion in R
    std::optional<TextureRef> emissive_texture;            ///< sRGB; RGB

    friend bool operator==(const Material&, const Material&) = default;
};

/// A decoded image as the GPU will get it: RGBA8Srgb for colour (base colour, emissive),
/// RGBA8Unorm for data (metallic-roughness, normal, occlusion). Row 0 is the image's top row,
/// which is where glTF's texture coordinate v = 0 lies.
struct TextureImage {
    std::string name;     ///< the glTF image's name, or its URI, or "image <index>"
    uint32_t source = 0;  ///< index of the image in the glTF file
    rhi::Image image;
};

/// A texture: an image and how to sample it (glTF sampler → rhi::SamplerDesc).
struct Texture {
    std::string name;
    uint32_t image = 0;  ///< index into Scene::images
    rhi::SamplerDesc sampler;
};

}  // namespace loom::scene
