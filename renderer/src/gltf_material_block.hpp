#pragma once
// The glTF material as the "gltf-material" part reads it: the members of GltfObjectUniforms
// after its two matrices (gltf_object.glsl), which are also the whole of the retained kind's
// MaterialUniforms (retained_gltf_object.glsl). Shared by GltfObject, which writes the block per
// draw, and RetainedGltfScene, which writes it once per material.

#include <array>
#include <optional>
#include <string_view>

#include <glm/glm.hpp>

#include "loom/scene/material.hpp"

namespace loom::renderer {

/// std140, 256 bytes.
struct GltfMaterialBlock {
    glm::vec4 base_color_factor;
    glm::vec4 emissive_factor;
    glm::vec4 factors;    // metallic, roughness, normal scale, occlusion strength
    glm::vec4 alpha;      // mode, cutoff, (GltfObject: mirror sign; retained: unused)
    glm::ivec4 uv_sets;   // base colour, metallic-roughness, normal, occlusion
    glm::ivec4 textures;  // emissive UV set, texture bits
    std::array<glm::vec4, 10> uv_transform;  // two rows per texture, in the order of kGltfSamplers
};
static_assert(sizeof(GltfMaterialBlock) == 256);

/// The material's sampler variables in "gltf-material", in the order of its texture bits.
inline constexpr std::array<std::string_view, 5> kGltfSamplers = {
    "gltf_base_color", "gltf_metallic_roughness", "gltf_normal", "gltf_occlusion", "gltf_emissive"};

/// The material's textures in the order of kGltfSamplers (empty where it has none).
std::array<const std::optional<scene::TextureRef>*, 5> gltf_texture_refs(const scene::Material& material);

/// The block of `material` (alpha.z 0).
GltfMaterialBlock gltf_material_block(const scene::Material& material);

}  // namespace loom::renderer
