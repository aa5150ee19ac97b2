// Object part "retained-gltf-geometry" (vertex stage): "gltf-geometry" for a RetainedScene. The
// same glTF vertex and arithmetic (gltf_vertex.glsl), with the model and normal matrices of the
// object's record, found through the per-instance object index at location 15
// (loom::passes::kObjectIndexLocation), so a retained glTF object lands on the same pixels as
// the GltfObject it replaces. The record has no mirror sign: the model matrix's determinant
// gives it.
#include "loom/parts/retained_gltf_object.glsl"
#include "loom/parts/gltf_vertex.glsl"

layout(location = 15) in uint in_object_index;

ObjectVertex object_vertex() {
    const ObjectRecord record = object_records.records[in_object_index];
    return gltf_vertex(record.model, record.normal_matrix, determinant(mat3(record.model)) < 0.0 ? -1.0 : 1.0);
}
