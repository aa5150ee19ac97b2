#include "loom/renderer/gltf_object.hpp"

#include <array>

#include <glm/glm.hpp>

#include "loom/passes/program.hpp"
#include "loom/passes/shader_pass.hpp"
#include "loom/scene/mesh.hpp"

#include "gltf_material_block.hpp"

namespace loom::renderer {
namespace {

/// Mirrors GltfObjectUniforms in shaders/include/loom/parts/gltf_object.glsl (std140).
struct GltfObjectUniforms {
    glm::mat4 model;
    glm::mat4 normal_matrix;
    GltfMaterialBlock material;  // alpha.z: the mirror sign
};
static_assert(sizeof(GltfObjectUniforms) == 384);

}  // namespace

std::string gltf_item_name(const scene::Scene& scene, uint32_t index) {
    const scene::DrawItem& item = scene.draw_items.at(index);
    const std::string& node = scene.nodes[item.node].name;
    const std::string& mesh = scene.meshes[item.mesh].name;
    return (node.empty() ? "node " + std::to_string(item.node) : node) + ": " +
           (mesh.empty() ? "mesh " + std::to_string(item.mesh) : mesh) + " #" + std::to_string(item.primitive);
}

const std::shared_ptr<const passes::ObjectKind>& gltf_skinned_mesh_kind() {
    static const std::shared_ptr<const passes::ObjectKind> kind = make_gltf_kind(
        "gltf-skinned-mesh", "gltf-skinned-geometry", {scene::vertex_buffer_layout(), scene::skin_buffer_layout()});
    return kind;
}

const std::shared_ptr<const passes::ObjectKind>& gltf_mesh_kind() {
    static const std::shared_ptr<const passes::ObjectKind> kind =
        make_gltf_kind("gltf-mesh", "gltf-geometry", {scene::vertex_buffer_layout()});
    return kind;
}

GltfObject::GltfObject(std::shared_ptr<const GpuScene> gpu, uint32_t draw_item)
    : GltfObject(gpu, std::shared_ptr<const scene::Scene>(gpu, &gpu->scene()),
                 gpu->skin_palette() ? std::shared_ptr<const SkinPalette>(gpu, gpu->skin_palette()) : nullptr, draw_item) {}

GltfObject::GltfObject(std::shared_ptr<const GpuScene> gpu, std::shared_ptr<const scene::Scene> placements,
                       uint32_t draw_item)
    : GltfObject(std::move(gpu), std::move(placements), nullptr, draw_item) {}

GltfObject::GltfObject(std::shared_ptr<const GpuScene> gpu, std::shared_ptr<const scene::Scene> placements,
                       std::shared_ptr<const SkinPalette> palette, uint32_t draw_item)
    : gpu_(std::move(gpu)),
      placements_(std::move(placements)),
      palette_(std::move(palette)),
      draw_item_(draw_item),
      skinned_(palette_ && item().skin && gpu_->skin_buffer()),
      name_(gltf_item_name(gpu_->scene(), draw_item)) {}

const scene::DrawItem& GltfObject::item() const { return placements_->draw_items.at(draw_item_); }

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
    // The matrices of passes::object_record(draw.world), which a RetainedScene uploads for the
    // item (retained_gltf_scene.hpp): both ways of drawing it give the same bits.
    u.model = draw.world;
    u.normal_matrix = glm::mat4(draw.normal_matrix);
    u.material = gltf_material_block(m);
    u.material.alpha.z = draw.flips_winding ? -1.0f : 1.0f;
    const auto refs = gltf_texture_refs(m);

    passes::Bindings set(context.program, context.commands, passes::kObjectSet);
    set.uniforms("GltfObjectUniforms", u);
    if (skinned_) set.buffer("JointMatrices", palette_->range(*draw.skin));
    for (std::size_t i = 0; i < refs.size(); ++i) {
        // Passes that leave the material out of their fragment stage have no samplers.
        if (!context.program.find(kGltfSamplers[i])) continue;
        const rhi::TextureBinding binding = refs[i]->has_value() ? gpu_->texture((*refs[i])->texture) : gpu_->fallback();
        set.texture(kGltfSamplers[i], binding.texture, binding.sampler);
    }
    LOOM_TRY(set.bind());

    if (range.index_count == 0) return {};
    if (!gpu_->vertex_buffer()) {
        return make_error(ErrorCode::InvalidState,
                          "object '" + name_ + "': its GpuScene has no geometry (created with the textures only)");
    }
    context.commands.set_vertex_buffer(0, gpu_->vertex_buffer());
    if (skinned_) context.commands.set_vertex_buffer(1, gpu_->skin_buffer());
    context.commands.set_index_buffer(gpu_->index_buffer(), rhi::IndexType::Uint32);
    context.commands.draw_indexed(range.index_count, 1, range.first_index, range.base_vertex);
    return {};
}

}  // namespace loom::renderer
