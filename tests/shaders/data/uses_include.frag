#version 450
#include "lib/tint.glsl"

layout(location = 0) out vec4 frag_color;

void main() {
    frag_color = vec4(tint(vec3(1.0)), 1.0);
}
