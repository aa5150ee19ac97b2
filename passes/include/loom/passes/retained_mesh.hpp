#pragma once
// The retained mesh kinds: the standard mesh objects (MeshVertex geometry, metallic-roughness
// materials) as a RetainedScene draws them. Their part "retained-mesh" reads the object's
// ObjectRecord from the scene's record buffer through a per-instance object index and the
// material's MaterialUniforms from the scene's material buffer (shaders/include/loom/passes/
// retained_object.glsl); their material parts are those of "pbr-mesh" and "checker-mesh", so a
// retained object looks exactly like the MeshObject it replaces.
//
// Any kind can be drawn by a RetainedScene when it follows the same convention: its last vertex
// buffer slot is per-instance with one Uint attribute at kObjectIndexLocation (object_index_layout()),
// the object records are the storage buffer "ObjectRecords" and the material's set is the
// uniform block "MaterialUniforms" (both optional: a pass may leave them out, as the shadow map
// leaves out the material).

#include <cstdint>
#include <memory>
#include <string>

#include <glm/glm.hpp>

#include "loom/passes/mesh_object.hpp"
#include "loom/passes/object.hpp"
#include "loom/passes/param.hpp"
#include "loom/passes/shape.hpp"

namespace loom::passes {

/// Vertex input location of the per-instance object index.
inline constexpr uint32_t kObjectIndexLocation = 15;

/// The per-object uniform set of retained objects (std430 in the record buffer).
struct ObjectRecord {
    glm::mat4 model{1.0f};
    glm::mat4 normal_matrix{1.0f};
};
static_assert(sizeof(ObjectRecord) == 128);

/// The record of a model matrix: the matrix and its normal matrix (scene::normal_matrix: the
/// cofactor matrix of its upper 3x3, sign-corrected, which is the inverse transpose up to a
/// positive factor and is defined for singular matrices too). MeshObject and GltfObject upload
/// the same matrices.
ObjectRecord object_record(const glm::mat4& model);

/// The per-instance vertex buffer slot carrying the object index (stride 4, one Uint at
/// kObjectIndexLocation).
rhi::VertexBufferLayout object_index_layout();

/// The kind "retained-pbr-mesh": parts "retained-mesh" and "pbr-material".
std::shared_ptr<const ObjectKind> retained_pbr_mesh_kind();
/// The kind "retained-checker-mesh": parts "retained-mesh" and "checker-material".
std::shared_ptr<const ObjectKind> retained_checker_mesh_kind();

/// A material for the retained mesh kinds whose values follow `params` (set it to change
/// them: only this material's set is uploaded again). Double-sided materials draw without
/// culling (fixed at creation, from the value `params` has now).
std::shared_ptr<GpuMaterial> make_mesh_material(std::string name, std::shared_ptr<Param<MeshSurface>> params);
/// make_mesh_material of a fixed value.
std::shared_ptr<GpuMaterial> make_mesh_material(std::string name, const MeshSurface& value);

}  // namespace loom::passes
