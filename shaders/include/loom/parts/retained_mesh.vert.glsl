// Object part "retained-mesh" (vertex stage): a mesh vertex (position, normal, uv, colour at the
// locations of loom::scene::Vertex) placed in the world by its object's record, found through
// the per-instance object index at location 15 (loom::passes::kObjectIndexLocation). The same
// arithmetic as "mesh-geometry", so a retained object lands on the same pixels.
#include "loom/passes/retained_object.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 3) in vec2 in_uv;
layout(location = 5) in vec4 in_color;
layout(location = 15) in uint in_object_index;

ObjectVertex object_vertex() {
    mat4 model = object_records.records[in_object_index].model;
    mat4 normal_matrix = object_records.records[in_object_index].normal_matrix;
    ObjectVertex v;
    v.world_position = transform_point(model, in_position).xyz;
    v.world_normal = transform_vector(mat3(normal_matrix), in_normal);
    v.uv = in_uv;
    v.color = in_color;
    return v;
}
