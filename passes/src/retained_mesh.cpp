#include "loom/passes/retained_mesh.hpp"

#include <cstring>
#include <string_view>

#include "loom/passes/parts.hpp"
#include "loom/scene/scene.hpp"

namespace loom::passes {
namespace {

std::shared_ptr<const ObjectKind> retained_kind(std::string name, std::string_view material_part) {
    return std::make_shared<const ObjectKind>(
        std::move(name),
        std::vector<ShaderPart>{standard_part("retained-mesh").shader, standard_part(material_part).shader},
        std::vector<rhi::VertexBufferLayout>{mesh_vertex_layout(), object_index_layout()});
}

}  // namespace

ObjectRecord object_record(const glm::mat4& model) {
    // MeshObject::render and loom::renderer's GltfObject upload the same bits. The cofactor
    // matrix (scene::normal_matrix) rather than the inverse transpose: the same direction, and
    // defined for singular matrices too (a node scaled flat, or to 0 by an animation).
    bool flips_winding = false;
    return ObjectRecord{model, glm::mat4(scene::normal_matrix(model, flips_winding))};
}

rhi::VertexBufferLayout object_index_layout() {
    rhi::VertexBufferLayout layout;
    layout.stride = sizeof(uint32_t);
    layout.step = rhi::VertexStepMode::PerInstance;
    layout.attributes = {{kObjectIndexLocation, rhi::VertexFormat::Uint, 0}};
    return layout;
}

std::shared_ptr<const ObjectKind> retained_pbr_mesh_kind() {
    return retained_kind("retained-pbr-mesh", "pbr-material");
}

std::shared_ptr<const ObjectKind> retained_checker_mesh_kind() {
    return retained_kind("retained-checker-mesh", "checker-material");
}

std::shared_ptr<GpuMaterial> make_mesh_material(std::string name, std::shared_ptr<Param<MeshSurface>> params) {
    const rhi::CullMode cull = params->value().material.double_sided ? rhi::CullMode::None : rhi::CullMode::Back;
    auto uniforms = std::make_shared<UniformSet>(
        "MaterialUniforms", UpdateFrequency::PerMaterial, static_cast<uint32_t>(sizeof(MeshSurfaceUniforms)),
        [params](std::span<std::byte> block) {
            const MeshSurfaceUniforms u = mesh_surface_uniforms(params->value());
            std::memcpy(block.data(), &u, sizeof(u));
        },
        std::vector<std::shared_ptr<ParamNode>>{params});
    return std::make_shared<GpuMaterial>(std::move(name), std::move(uniforms), std::vector<MaterialTexture>{}, cull);
}

std::shared_ptr<GpuMaterial> make_mesh_material(std::string name, const MeshSurface& value) {
    return make_mesh_material(std::move(name), std::make_shared<InputParam<MeshSurface>>(value));
}

}  // namespace loom::passes
