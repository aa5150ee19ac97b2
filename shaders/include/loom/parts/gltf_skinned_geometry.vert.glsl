// Object part "gltf-skinned-geometry" (vertex stage): "gltf-geometry" for a skinned draw item —
// the vertex moved by its joints (gltf_skinning.glsl) before the object's model matrix (the
// identity: glTF ignores a skinned mesh's node). Its second resource is the joint palette,
// bound at the range of the item's skin.
#include "loom/parts/gltf_object.glsl"
#include "loom/parts/gltf_vertex.glsl"

layout(std430, set = LOOM_SET, binding = LOOM_BINDING(1)) readonly buffer JointMatrices {
    mat4 joints[];
} joint_palette;

#include "loom/parts/gltf_skinning.glsl"

ObjectVertex object_vertex() {
    return gltf_skinned_vertex(gltf.model, gltf.normal_matrix, gltf.alpha.z);
}
