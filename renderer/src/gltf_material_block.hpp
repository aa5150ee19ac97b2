#pragma once
// The C++ side of the "gltf-material" part, shared by GltfObject, which writes its block per
// draw, and RetainedGltfScene, which writes it once per material: the block (the members of
// GltfObjectUniforms after its two matrices, gltf_object.glsl, which are also the whole of the
// retained kinds' MaterialUniforms, retained_gltf_object.glsl), its sampler names, and the
// object kinds made of a glTF geometry part and this material part.

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "loom/passes/object.hpp"
#include "loom/rhi/descriptions.hpp"
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

/// The object kind `name`: the part `geometry_part` and "gltf-material", with `vertex_buffers`.
std::shared_ptr<const passes::ObjectKind> make_gltf_kind(std::string name, std::string_view geometry_part,
                                                         std::vector<rhi::VertexBufferLayout> vertex_buffers);

}  // namespace loom::renderer
