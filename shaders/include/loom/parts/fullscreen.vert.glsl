// Pass part "fullscreen" (vertex stage): a triangle covering the viewport from gl_VertexIndex
// alone (draw 3 vertices, no vertex buffer); uv is (0,0) at the top-left of the framebuffer.
layout(location = 0) out vec2 uv;

void main() {
    vec2 ndc = fullscreen_triangle_position(gl_VertexIndex);
    uv = ndc_to_uv(ndc);
    gl_Position = vec4(ndc, 0.0, 1.0);
}
