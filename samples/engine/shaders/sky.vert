#version 450
// A triangle covering the viewport at the far plane (depth 1): with the depth test EQUAL it
// lands exactly where the prepass left the cleared depth, i.e. where no geometry is.
#include "loom/common.glsl"

layout(location = 0) out vec2 ndc;

void main() {
    ndc = fullscreen_triangle_position(gl_VertexIndex);
    gl_Position = vec4(ndc, 1.0, 1.0);
}
