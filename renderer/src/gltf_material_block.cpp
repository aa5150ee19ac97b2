#include "gltf_material_block.hpp"

#include "loom/passes/parts.hpp"

namespace loom::renderer {
namespace {

float alpha_mode_value(scene::AlphaMode mode) {
    switch (mode) {
        case scene::AlphaMode::Mask: return 1.0f;
        case scene::AlphaMode::Blend: return 2.0f;
        case scene::AlphaMode::Opaque: break;
    }
    return 0.0f;
}

}  // namespace

std::array<const std::optional<scene::TextureRef>*, 5> gltf_texture_refs(const scene::Material& m) {
    return {&m.base_color_texture, &m.metallic_roughness_texture, &m.normal_texture, &m.occlusion_texture,
            &m.emissive_texture};
}

std::shared_ptr<const passes::ObjectKind> make_gltf_kind(std::string name, std::string_view geometry_part,
                                                         std::vector<rhi::VertexBufferLayout> vertex_buffers) {
    return std::make_shared<const passes::ObjectKind>(
        std::move(name),
        // "gltf-material" has one resource per sampler of kGltfSamplers.
        std::vector<passes::ShaderPart>{passes::standard_part(geometry_part).shader,
                                        passes::standard_part("gltf-material").shader},
        std::move(vertex_buffers));
}

GltfMaterialBlock gltf_material_block(const scene::Material& m) {
    // Bits of GltfMaterialBlock::textures.y (kGltf* in gltf_material_constants.glsl), in the
    // order of kGltfSamplers.
    constexpr std::array<int, 5> bits = {1, 2, 4, 8, 16};
    GltfMaterialBlock block;
    block.base_color_factor = m.base_color_factor;
    block.emissive_factor = glm::vec4(m.emissive_factor, 0.0f);
    block.factors = glm::vec4(m.metallic_factor, m.roughness_factor, m.normal_scale, m.occlusion_strength);
    block.alpha = glm::vec4(alpha_mode_value(m.alpha_mode), m.alpha_cutoff, 0.0f, 0.0f);
    const auto refs = gltf_texture_refs(m);
    std::array<int, 5> uv_sets{};
    int present = 0;
    for (std::size_t i = 0; i < refs.size(); ++i) {
        // The identity unless the texture has a KHR_texture_transform.
        std::array<glm::vec3, 2> rows = {glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f)};
        if (refs[i]->has_value() && (*refs[i])->transform) rows = (*refs[i])->transform->rows();
        block.uv_transform[2 * i] = glm::vec4(rows[0], 0.0f);
        block.uv_transform[2 * i + 1] = glm::vec4(rows[1], 0.0f);
        if (!refs[i]->has_value()) continue;
        present |= bits[i];
        uv_sets[i] = static_cast<int>((*refs[i])->uv_set);
    }
    block.uv_sets = glm::ivec4(uv_sets[0], uv_sets[1], uv_sets[2], uv_sets[3]);
    block.textures = glm::ivec4(uv_sets[4], present, 0, 0);
    return block;
}

}  // namespace loom::renderer
