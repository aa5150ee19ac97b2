// Skinning for the skinned glTF geometry parts ("gltf-skinned-geometry",
// "retained-gltf-skinned-geometry"): a vertex's four joints and weights (loom::scene::
// SkinInfluences, a vertex buffer of their own at locations 8 and 9) and its skinning matrix, the
// weighted sum of its joints' matrices in the JointMatrices storage buffer (joint's world matrix
// times its inverse bind matrix, loom::renderer::SkinPalette). The part declares that buffer, as
// `joint_palette`, at its own binding before including this file. Summed in one fixed order
// without fused multiply-adds, so both backends place the vertex alike.
#ifndef LOOM_PARTS_GLTF_SKINNING_GLSL
#define LOOM_PARTS_GLTF_SKINNING_GLSL

layout(location = 8) in uvec4 in_joints;
layout(location = 9) in vec4 in_weights;

mat4 skinning_matrix() {
    precise mat4 m = joint_palette.joints[in_joints.x] * in_weights.x;
    m += joint_palette.joints[in_joints.y] * in_weights.y;
    m += joint_palette.joints[in_joints.z] * in_weights.z;
    m += joint_palette.joints[in_joints.w] * in_weights.w;
    return m;
}

// The vertex placed by its skin, then by `model` and `normal_matrix` (the identity for a glTF
// skinned mesh, whose node transform is ignored). Normals and tangents follow the skinning
// matrix's upper 3x3 (normalised later), as glTF viewers do for joints without shear.
ObjectVertex gltf_skinned_vertex(mat4 model, mat4 normal_matrix, float mirror) {
    const mat4 skin = skinning_matrix();
    return gltf_vertex_at(model, normal_matrix, mirror, transform_point(skin, in_position).xyz,
                          transform_vector(mat3(skin), in_normal), transform_vector(mat3(skin), in_tangent.xyz));
}

#endif
