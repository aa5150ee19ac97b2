// Object part "gltf-geometry" (vertex stage): a glTF vertex placed in the world by the draw
// item's model matrix (gltf_vertex.glsl), from the object's GltfObjectUniforms, whose alpha.z is
// the mirror sign.
#include "loom/parts/gltf_object.glsl"
#include "loom/parts/gltf_vertex.glsl"

ObjectVertex object_vertex() {
    return gltf_vertex(gltf.model, gltf.normal_matrix, gltf.alpha.z);
}
