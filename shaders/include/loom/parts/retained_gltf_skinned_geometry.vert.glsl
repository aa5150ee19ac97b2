// Object part "retained-gltf-skinned-geometry" (vertex stage): "retained-gltf-geometry" for a
// skinned draw item — the vertex moved by its joints (gltf_skinning.glsl), then placed by its
// object's record. Its third resource is the whole joint palette (RetainedScene's shared buffer
// "JointMatrices"): the geometry's joint indices already point at its skin's joints there.
#include "loom/parts/retained_gltf_object.glsl"
#include "loom/parts/gltf_vertex.glsl"

layout(location = 15) in uint in_object_index;

layout(std430, set = LOOM_SET, binding = LOOM_BINDING(2)) readonly buffer JointMatrices {
    mat4 joints[];
} joint_palette;

#include "loom/parts/gltf_skinning.glsl"

ObjectVertex object_vertex() {
    const ObjectRecord record = object_records.records[in_object_index];
    return gltf_skinned_vertex(record.model, record.normal_matrix, determinant(mat3(record.model)) < 0.0 ? -1.0 : 1.0);
}
