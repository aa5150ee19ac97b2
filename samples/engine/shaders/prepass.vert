#version 450
// The scene's vertices for the depth prepass: the position as scene.vert computes it, and what
// alpha-masked materials need to cut out.
#include "engine/scene_position.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 3) in vec2 in_uv0;
layout(location = 4) in vec2 in_uv1;
layout(location = 5) in vec4 in_color;

layout(location = 3) out vec2 uv0;
layout(location = 4) out vec2 uv1;
layout(location = 5) out vec4 vertex_color;

void main() {
    vec3 world_position;
    gl_Position = scene_clip_position(in_position, world_position);
    uv0 = in_uv0;
    uv1 = in_uv1;
    vertex_color = in_color;
}
