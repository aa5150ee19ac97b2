#version 450
// The scene's vertices for the shading pass (prepass.vert is its depth-only twin).
#include "engine/scene_position.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec4 in_tangent;
layout(location = 3) in vec2 in_uv0;
layout(location = 4) in vec2 in_uv1;
layout(location = 5) in vec4 in_color;

layout(location = 0) out vec3 world_position;
layout(location = 1) out vec3 world_normal;
layout(location = 2) out vec4 world_tangent;
layout(location = 3) out vec2 uv0;
layout(location = 4) out vec2 uv1;
layout(location = 5) out vec4 vertex_color;

void main() {
    gl_Position = scene_clip_position(in_position, world_position);
    world_normal = transform_vector(mat3(draw.normal_matrix), in_normal);
    world_tangent = vec4(transform_vector(mat3(draw.model), in_tangent.xyz), in_tangent.w);
    uv0 = in_uv0;
    uv1 = in_uv1;
    vertex_color = in_color;
}
