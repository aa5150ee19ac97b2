#version 450
// A triangle covering the viewport; uv (0,0) at the top-left.
#include "loom/common.glsl"

layout(location = 0) out vec2 uv;

void main() {
    vec2 ndc = fullscreen_triangle_position(gl_VertexIndex);
    uv = ndc_to_uv(ndc);
    gl_Position = vec4(ndc, 0.0, 1.0);
}
