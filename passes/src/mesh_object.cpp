#include "loom/passes/mesh_object.hpp"

#include <cstddef>
#include <limits>

#include "loom/passes/parts.hpp"
#include "loom/passes/program.hpp"
#include "loom/passes/retained_mesh.hpp"
#include "loom/passes/shader_pass.hpp"

namespace loom::passes {
namespace {

/// Mirrors ObjectUniforms in shaders/include/loom/passes/mesh_object.glsl (std140).
struct ObjectUniforms {
    glm::mat4 model;
    glm::mat4 normal_matrix;
    MeshSurfaceUniforms surface;  // base_color, secondary_color, emissive, material
};
static_assert(sizeof(ObjectUniforms) == 192);

}  // namespace

MeshSurfaceUniforms mesh_surface_uniforms(const MeshSurface& surface) {
    const scene::Material& material = surface.material;
    return MeshSurfaceUniforms{material.base_color_factor, surface.checker.secondary_color,
                               glm::vec4(material.emissive_factor, 0.0f),
                               glm::vec4(material.metallic_factor, material.roughness_factor,
                                         surface.checker.cells_per_unit, 0.0f)};
}

rhi::VertexBufferLayout mesh_vertex_layout() {
    rhi::VertexBufferLayout layout;
    layout.stride = sizeof(MeshVertex);
    layout.attributes = {
        {0, rhi::VertexFormat::Float3, static_cast<uint32_t>(offsetof(MeshVertex, position))},
        {1, rhi::VertexFormat::Float3, static_cast<uint32_t>(offsetof(MeshVertex, normal))},
        {2, rhi::VertexFormat::Float4, static_cast<uint32_t>(offsetof(MeshVertex, tangent))},
        {3, rhi::VertexFormat::Float2, static_cast<uint32_t>(offsetof(MeshVertex, uv0))},
        {4, rhi::VertexFormat::Float2, static_cast<uint32_t>(offsetof(MeshVertex, uv1))},
        {5, rhi::VertexFormat::Float4, static_cast<uint32_t>(offsetof(MeshVertex, color))},
    };
    return layout;
}

Result<std::shared_ptr<GpuMesh>> GpuMesh::create(rhi::Device& device, std::span<const MeshVertex> vertices,
                                                 std::span<const uint32_t> indices, std::string name) {
    if (vertices.empty() || indices.empty() || indices.size() % 3 != 0) {
        return make_error(ErrorCode::InvalidArgument, "mesh '" + name + "': needs vertices and a triangle list (" +
                                                          std::to_string(vertices.size()) + " vertices, " +
                                                          std::to_string(indices.size()) + " indices)");
    }
    if (vertices.size() > std::numeric_limits<uint32_t>::max()) {
        return make_error(ErrorCode::InvalidArgument, "mesh '" + name + "': too many vertices");
    }
    for (std::size_t i = 0; i < indices.size(); ++i) {
        if (indices[i] >= vertices.size()) {
            return make_error(ErrorCode::InvalidArgument, "mesh '" + name + "': index " + std::to_string(i) + " is " +
                                                              std::to_string(indices[i]) + ", but there are only " +
                                                              std::to_string(vertices.size()) + " vertices");
        }
    }
    std::shared_ptr<GpuMesh> mesh(new GpuMesh(device, std::move(name)));
    rhi::BufferDesc vb;
    vb.name = mesh->name_ + " vertices";
    vb.size = vertices.size_bytes();
    vb.usage = rhi::BufferUsage::Vertex;
    auto vertex_buffer = device.create_buffer(vb);
    if (!vertex_buffer) return vertex_buffer.take_error();
    mesh->vertices_ = *vertex_buffer;
    LOOM_TRY(device.write_buffer(mesh->vertices_, 0, std::as_bytes(vertices)));
    rhi::BufferDesc ib;
    ib.name = mesh->name_ + " indices";
    ib.size = indices.size_bytes();
    ib.usage = rhi::BufferUsage::Index;
    auto index_buffer = device.create_buffer(ib);
    if (!index_buffer) return index_buffer.take_error();
    mesh->indices_ = *index_buffer;
    LOOM_TRY(device.write_buffer(mesh->indices_, 0, std::as_bytes(indices)));
    mesh->vertex_count_ = static_cast<uint32_t>(vertices.size());
    mesh->index_count_ = static_cast<uint32_t>(indices.size());
    for (const MeshVertex& v : vertices) mesh->bounds_.extend(v.position);
    return mesh;
}

GpuMesh::~GpuMesh() {
    if (vertices_) (void)device_->destroy(vertices_);
    if (indices_) (void)device_->destroy(indices_);
}

std::shared_ptr<const ObjectKind> pbr_mesh_kind() {
    return std::make_shared<const ObjectKind>(
        "pbr-mesh",
        std::vector<ShaderPart>{standard_part("mesh-geometry").shader, standard_part("pbr-material").shader},
        std::vector<rhi::VertexBufferLayout>{mesh_vertex_layout()});
}

std::shared_ptr<const ObjectKind> checker_mesh_kind() {
    return std::make_shared<const ObjectKind>(
        "checker-mesh",
        std::vector<ShaderPart>{standard_part("mesh-geometry").shader, standard_part("checker-material").shader},
        std::vector<rhi::VertexBufferLayout>{mesh_vertex_layout()});
}

MeshObject::MeshObject(std::string name, std::shared_ptr<const ObjectKind> kind, std::shared_ptr<const GpuMesh> mesh,
                       const glm::mat4& model, const MeshSurface& surface, MeshRange range)
    : name_(std::move(name)), kind_(std::move(kind)), mesh_(std::move(mesh)), model_(model), surface_(surface),
      range_(range) {}

rhi::RasterState MeshObject::raster() const {
    rhi::RasterState state;
    state.cull = surface_.material.double_sided ? rhi::CullMode::None : rhi::CullMode::Back;
    state.front_face =
        glm::determinant(glm::mat3(model_)) < 0.0f ? rhi::FrontFace::Clockwise : rhi::FrontFace::CounterClockwise;
    return state;
}

Status MeshObject::render(DrawContext& context) const {
    if (!mesh_) return make_error(ErrorCode::InvalidState, "mesh object '" + name_ + "' has no mesh");
    ObjectUniforms uniforms;
    // The record a RetainedScene uploads for the same matrix: both paths give the same bits.
    const ObjectRecord record = object_record(model_);
    uniforms.model = record.model;
    uniforms.normal_matrix = record.normal_matrix;
    uniforms.surface = mesh_surface_uniforms(surface_);
    Bindings object_set(context.program, context.commands, kObjectSet);
    LOOM_TRY(object_set.uniforms("ObjectUniforms", uniforms).bind());

    const uint32_t first = range_.first_index;
    const uint32_t count = range_.index_count != 0 ? range_.index_count
                                                   : (first < mesh_->index_count() ? mesh_->index_count() - first : 0);
    if (first + count > mesh_->index_count()) {
        return make_error(ErrorCode::InvalidArgument, "mesh object '" + name_ + "': indices " + std::to_string(first) +
                                                          ".." + std::to_string(first + count) + " exceed mesh '" +
                                                          mesh_->name() + "' (" +
                                                          std::to_string(mesh_->index_count()) + " indices)");
    }
    context.commands.set_vertex_buffer(0, mesh_->vertex_buffer());
    context.commands.set_index_buffer(mesh_->index_buffer(), rhi::IndexType::Uint32);
    context.commands.draw_indexed(count, 1, first, range_.base_vertex);
    return {};
}

scene::Bounds MeshObject::world_bounds() const {
    return mesh_->bounds().transformed(model_);
}

}  // namespace loom::passes
