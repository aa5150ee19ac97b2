#version 450
// Depth prepass: depth only; alpha-masked materials cut out as glTF says.
#include "engine/draw.glsl"

layout(set = 1, binding = 1) uniform sampler2D base_color_map;

layout(location = 3) in vec2 uv0;
layout(location = 4) in vec2 uv1;
layout(location = 5) in vec4 vertex_color;

void main() {
    if (draw.alpha.x == 1.0) {
        float alpha = draw.base_color.a * vertex_color.a;
        if ((draw.textures.y & kBaseColorTexture) != 0) alpha *= texture(base_color_map, pick_uv(draw.uv_sets.x, uv0, uv1)).a;
        if (alpha < draw.alpha.y) discard;
    }
}
