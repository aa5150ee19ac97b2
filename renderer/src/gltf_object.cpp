#include "loom/renderer/gltf_object.hpp"

#include <array>
#include <string_view>

#include <glm/glm.hpp>

#include "loom/passes/parts.hpp"
#include "loom/passes/program.hpp"
#include "loom/passes/shader_pass.hpp"
#include "loom/scene/mesh.hpp"

namespace loom::renderer {
namespace {

/// Mirrors GltfObjectUniforms in shaders/include/loom/parts/gltf_object.glsl (std140).
struct GltfObjectUniforms {
    glm::mat4 model;
    glm::mat4 normal_matrix;
    glm::vec4 base_color_factor;
    glm::vec4 emissive_factor;
    glm::vec4 factors;    // metallic, roughness, normal scale, occlusion strength
    glm::vec4 alpha;      // mode, cutoff, mirror sign
    glm::ivec4 uv_sets;   // base colour, metallic-roughness, normal, occlusion
    glm::ivec4 textures;  // emissive UV set, texture bits
    std::array<glm::vec4, 10> uv_transform;  // two rows per texture, in the order of kSamplers
};
static_assert(sizeof(GltfObjectUniforms) == 384);

// Bits of GltfObjectUniforms::textures.y (kGltf* in gltf_object.glsl), in the order of kSamplers.
constexpr int kBaseColorBit = 1;
constexpr int kMetallicRoughnessBit = 2;
constexpr int kNormalBit = 4;
constexpr int kOcclusionBit = 8;
constexpr int kEmissiveBit = 16;

/// The material's sampler variables in "gltf-material", in the order of their bits.
constexpr std::array<std::string_view, 5> kSamplers = {"gltf_base_color", "gltf_metallic_roughness", "gltf_normal",
                                                       "gltf_occlusion", "gltf_emissive"};

float alpha_mode_value(scene::AlphaMode mode) {
    switch (mode) {
        case scene::AlphaMode::Mask: return 1.0f;
        case scene::AlphaMode::Blend: return 2.0f;
        case scene::AlphaMode::Opaque: break;
    }
    return 0.0f;
}

std::string object_name(const scene::Scene& scene, const scene::DrawItem& item) {
    const std::string& node = scene.nodes[item.node].name;
    const std::string& mesh = scene.meshes[item.mesh].name;
    return (node.empty() ? "node " + std::to_string(item.node) : node) + ": " +
           (mesh.empty() ? "mesh " + std::to_string(item.mesh) : mesh) + " #" + std::to_string(item.primitive);
}

}  // namespace

const std::shared_ptr<const passes::ObjectKind>& gltf_mesh_kind() {
    static const std::shared_ptr<const passes::ObjectKind> kind = std::make_shared<const passes::ObjectKind>(
        "gltf-mesh",
        std::vector<passes::ShaderPart>{
            passes::standard_part("gltf-geometry").shader,
            passes::standard_part("gltf-material").shader,  // one resource per sampler of kSamplers
        },
        std::vector<rhi::VertexBufferLayout>{scene::vertex_buffer_layout()});
    return kind;
}

GltfObject::GltfObject(std::shared_ptr<const GpuScene> gpu, uint32_t draw_item)
    : gpu_(std::move(gpu)), draw_item_(draw_item), name_(object_name(gpu_->scene(), item())) {}

const scene::DrawItem& GltfObject::item() const { return gpu_->scene().draw_items.at(draw_item_); }

const scene::Material& GltfObject::material() const { return gpu_->scene().materials.at(item().material); }

rhi::RasterState GltfObject::raster() const {
    rhi::RasterState state;
    state.cull = material().double_sided ? rhi::CullMode::None : rhi::CullMode::Back;
    state.front_face = item().flips_winding ? rhi::FrontFace::Clockwise : rhi::FrontFace::CounterClockwise;
    return state;
}

scene::Bounds GltfObject::world_bounds() const { return item().world_bounds; }

Status GltfObject::render(passes::DrawContext& context) const {
    const scene::DrawItem& draw = item();
    const scene::Material& m = material();
    const scene::PrimitiveRange& range = gpu_->prepared().geometry.range(draw);

    GltfObjectUniforms u;
    u.model = draw.world;
    u.normal_matrix = glm::mat4(draw.normal_matrix);
    u.base_color_factor = m.base_color_factor;
    u.emissive_factor = glm::vec4(m.emissive_factor, 0.0f);
    u.factors = glm::vec4(m.metallic_factor, m.roughness_factor, m.normal_scale, m.occlusion_strength);
    u.alpha = glm::vec4(alpha_mode_value(m.alpha_mode), m.alpha_cutoff, draw.flips_winding ? -1.0f : 1.0f, 0.0f);

    const std::array<const std::optional<scene::TextureRef>*, 5> refs = {
        &m.base_color_texture, &m.metallic_roughness_texture, &m.normal_texture, &m.occlusion_texture,
        &m.emissive_texture};
    constexpr std::array<int, 5> bits = {kBaseColorBit, kMetallicRoughnessBit, kNormalBit, kOcclusionBit, kEmissiveBit};
    std::array<int, 5> uv_sets{};
    int present = 0;
    for (std::size_t i = 0; i < refs.size(); ++i) {
        // The identity unless the texture has a KHR_texture_transform.
        std::array<glm::vec3, 2> rows = {glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f)};
        if (refs[i]->has_value() && (*refs[i])->transform) rows = (*refs[i])->transform->rows();
        u.uv_transform[2 * i] = glm::vec4(rows[0], 0.0f);
        u.uv_transform[2 * i + 1] = glm::vec4(rows[1], 0.0f);
        if (!refs[i]->has_value()) continue;
        present |= bits[i];
        uv_sets[i] = static_cast<int>((*refs[i])->uv_set);
    }
    u.uv_sets = glm::ivec4(uv_sets[0], uv_sets[1], uv_sets[2], uv_sets[3]);
    u.textures = glm::ivec4(uv_sets[4], present, 0, 0);

    passes::Bindings set(context.program, context.commands, passes::kObjectSet);
    set.uniforms("GltfObjectUniforms", u);
    for (std::size_t i = 0; i < refs.size(); ++i) {
        // Passes that leave the material out of their fragment stage have no samplers.
        if (!context.program.find(kSamplers[i])) continue;
        const rhi::TextureBinding binding = refs[i]->has_value() ? gpu_->texture((*refs[i])->texture) : gpu_->fallback();
        set.texture(kSamplers[i], binding.texture, binding.sampler);
    }
    LOOM_TRY(set.bind());

    if (range.index_count == 0) return {};
    context.commands.set_vertex_buffer(0, gpu_->vertex_buffer());
    context.commands.set_index_buffer(gpu_->index_buffer(), rhi::IndexType::Uint32);
    context.commands.draw_indexed(range.index_count, 1, range.first_index, range.base_vertex);
    return {};
}

}  // namespace loom::renderer
