// Pass part "fullscreen" (vertex stage): a triangle covering the viewport from gl_VertexIndex
// alone (draw 3 vertices, no vertex buffer). It hands nothing to the fragment stage: the
// post-process parts address their inputs by gl_FragCoord (texelFetch), which reads the same
// texel on every backend.
void main() {
    gl_Position = vec4(fullscreen_triangle_position(gl_VertexIndex), 0.0, 1.0);
}
