// The vertex stage shared by the glTF geometry parts ("gltf-geometry", which reads its matrices
// from GltfObjectUniforms, and "retained-gltf-geometry", which reads them from the object's
// record): a glTF vertex (loom::scene::Vertex: position, normal, tangent, uv0, uv1, colour at
// locations 0..5) placed in the world. Besides the ObjectVertex it hands the fragment stage the
// world tangent (for normal maps) and the second UV set through varyings of its own, at
// locations past the camera part's 0..3 — only in passes with that part (elsewhere, e.g. the
// standard shadow map, no fragment stage would read them).
#ifndef LOOM_PARTS_GLTF_VERTEX_GLSL
#define LOOM_PARTS_GLTF_VERTEX_GLSL

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec4 in_tangent;
layout(location = 3) in vec2 in_uv0;
layout(location = 4) in vec2 in_uv1;
layout(location = 5) in vec4 in_color;

#ifdef LOOM_PART_CAMERA
layout(location = 6) out vec4 v_gltf_tangent;  // xyz: world tangent, w: world handedness
layout(location = 7) out vec2 v_gltf_uv1;
#endif

// The vertex with the given object-space position, normal and tangent direction (the inputs',
// or where a skin moved them). `mirror`: -1 when `model` mirrors (negative determinant), else +1.
ObjectVertex gltf_vertex_at(mat4 model, mat4 normal_matrix, float mirror, vec3 position, vec3 normal, vec3 tangent) {
    ObjectVertex v;
    v.world_position = transform_point(model, position).xyz;
    v.world_normal = transform_vector(mat3(normal_matrix), normal);
    v.uv = in_uv0;
    v.color = in_color;
#ifdef LOOM_PART_CAMERA
    // Tangents are surface directions: they follow the model matrix. A mirroring matrix turns
    // cross(normal, tangent) around, so the handedness flips with it.
    v_gltf_tangent = vec4(transform_vector(mat3(model), tangent), in_tangent.w * mirror);
    v_gltf_uv1 = in_uv1;
#endif
    return v;
}

ObjectVertex gltf_vertex(mat4 model, mat4 normal_matrix, float mirror) {
    return gltf_vertex_at(model, normal_matrix, mirror, in_position, in_normal, in_tangent.xyz);
}

#endif
