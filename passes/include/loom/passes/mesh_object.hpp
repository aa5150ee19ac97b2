#pragma once
// Mesh objects: indexed triangle meshes with a metallic-roughness material, the objects the
// standard passes draw. Two kinds share the "mesh-geometry" part and differ in their material
// part: "pbr-mesh" (uniform material) and "checker-mesh" (a world-space checkerboard). The
// vertex layout is loom::scene::Vertex's, so a glTF primitive becomes a MeshObject as it is.

#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include <glm/glm.hpp>

#include "loom/passes/object.hpp"
#include "loom/passes/view.hpp"
#include "loom/rhi/device.hpp"
#include "loom/rhi/result.hpp"
#include "loom/scene/material.hpp"

namespace loom::passes {

/// One vertex, laid out exactly as loom::scene::Vertex (72 bytes; position, normal, tangent,
/// uv0, uv1, colour at locations 0..5).
struct MeshVertex {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 0.0f, 1.0f};
    glm::vec4 tangent{1.0f, 0.0f, 0.0f, 1.0f};
    glm::vec2 uv0{0.0f};
    glm::vec2 uv1{0.0f};
    glm::vec4 color{1.0f};
};
static_assert(sizeof(MeshVertex) == 72, "MeshVertex must match loom::scene::Vertex");

/// The vertex buffer layout of MeshVertex (one per-vertex slot).
rhi::VertexBufferLayout mesh_vertex_layout();

/// A mesh's vertex and index buffers on a device, destroyed with the GpuMesh.
class GpuMesh {
public:
    /// Uploads `vertices` and `indices` (a u32 triangle list). Errors: empty data, an index out
    /// of range (naming the mesh), the device's errors.
    static Result<std::shared_ptr<GpuMesh>> create(rhi::Device& device, std::span<const MeshVertex> vertices,
                                                   std::span<const uint32_t> indices, std::string name);
    ~GpuMesh();
    GpuMesh(const GpuMesh&) = delete;
    GpuMesh& operator=(const GpuMesh&) = delete;

    [[nodiscard]] const std::string& name() const { return name_; }
    [[nodiscard]] rhi::BufferHandle vertex_buffer() const { return vertices_; }
    [[nodiscard]] rhi::BufferHandle index_buffer() const { return indices_; }
    [[nodiscard]] uint32_t vertex_count() const { return vertex_count_; }
    [[nodiscard]] uint32_t index_count() const { return index_count_; }
    /// scene::Bounds of the vertex positions (object space).
    [[nodiscard]] const scene::Bounds& bounds() const { return bounds_; }

private:
    GpuMesh(rhi::Device& device, std::string name) : device_(&device), name_(std::move(name)) {}

    rhi::Device* device_;
    std::string name_;
    rhi::BufferHandle vertices_;
    rhi::BufferHandle indices_;
    uint32_t vertex_count_ = 0;
    uint32_t index_count_ = 0;
    scene::Bounds bounds_;
};

/// The pattern of the "checker-mesh" kind: cells of the material's base colour alternate with
/// cells of `secondary_color`.
struct CheckerPattern {
    glm::vec4 secondary_color{0.0f, 0.0f, 0.0f, 1.0f};
    float cells_per_unit = 1.0f;  ///< checker cells per world unit
};

/// What the built-in mesh kinds draw a surface with: a metallic-roughness material, of which
/// they use the factors (base colour, metallic, roughness, emissive) and double_sided (drawn
/// without back-face culling), not the textures; and the checker kind's pattern.
struct MeshSurface {
    scene::Material material;
    CheckerPattern checker;
};

/// A MeshSurface as the mesh kinds' shaders read it (std140): the material half of a
/// MeshObject's ObjectUniforms, and the retained mesh kinds' per-material set.
struct MeshSurfaceUniforms {
    glm::vec4 base_color;
    glm::vec4 secondary_color;
    glm::vec4 emissive;
    glm::vec4 material;  ///< metallic, roughness, checker cells per unit
};
static_assert(sizeof(MeshSurfaceUniforms) == 64);

/// The one packing of a MeshSurface, so that MeshObject and the retained mesh kinds upload the
/// same bits.
MeshSurfaceUniforms mesh_surface_uniforms(const MeshSurface& surface);

/// The kind "pbr-mesh": parts "mesh-geometry" and "pbr-material".
std::shared_ptr<const ObjectKind> pbr_mesh_kind();
/// The kind "checker-mesh": parts "mesh-geometry" and "checker-material".
std::shared_ptr<const ObjectKind> checker_mesh_kind();

/// Which indices of a GpuMesh an object draws.
struct MeshRange {
    uint32_t first_index = 0;
    uint32_t index_count = 0;  ///< 0: every index from first_index on
    int32_t base_vertex = 0;
};

/// A mesh placed in the world with a material.
class MeshObject final : public Object {
public:
    MeshObject(std::string name, std::shared_ptr<const ObjectKind> kind, std::shared_ptr<const GpuMesh> mesh,
               const glm::mat4& model, const MeshSurface& surface, MeshRange range = {});

    [[nodiscard]] const std::shared_ptr<const ObjectKind>& kind() const override { return kind_; }
    [[nodiscard]] std::string name() const override { return name_; }
    /// Back faces culled unless double-sided; a mirroring model matrix flips the front face.
    [[nodiscard]] rhi::RasterState raster() const override;
    /// Binds ObjectUniforms (set 1), the buffers, and draws the range.
    Status render(DrawContext& context) const override;

    [[nodiscard]] const glm::mat4& model() const { return model_; }
    void set_model(const glm::mat4& model) { model_ = model; }
    [[nodiscard]] const MeshSurface& surface() const { return surface_; }
    void set_surface(const MeshSurface& surface) { surface_ = surface; }
    /// World-space bounds (of the transformed corners of the mesh's bounds).
    [[nodiscard]] scene::Bounds world_bounds() const;

private:
    std::string name_;
    std::shared_ptr<const ObjectKind> kind_;
    std::shared_ptr<const GpuMesh> mesh_;
    glm::mat4 model_;
    MeshSurface surface_;
    MeshRange range_;
};

}  // namespace loom::passes
