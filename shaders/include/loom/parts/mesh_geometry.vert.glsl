// Object part "mesh-geometry" (vertex stage): a mesh vertex (position, normal, uv, colour at the
// locations of loom::scene::Vertex) placed in the world by the object's model matrix.
#include "loom/passes/mesh_object.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 3) in vec2 in_uv;
layout(location = 5) in vec4 in_color;

ObjectVertex object_vertex() {
    ObjectVertex v;
    v.world_position = transform_point(object.model, in_position).xyz;
    v.world_normal = transform_vector(mat3(object.normal_matrix), in_normal);
    v.uv = in_uv;
    v.color = in_color;
    return v;
}
