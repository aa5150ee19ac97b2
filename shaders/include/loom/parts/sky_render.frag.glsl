// Pass part "sky-render" (fragment stage): the sky exactly as the deferred pass shows it where
// its G-buffer is empty, for a pass that draws it behind its objects (the forward pass draws it
// first, full screen). With "high-pass-render" the sky's bright part also goes to the high pass.
#include "loom/passes/lighting.glsl"

layout(set = LOOM_SET, binding = LOOM_BINDING(1)) uniform SkyUniforms {
    vec4 viewport;  // xy: the target's size in pixels
} sky;

layout(location = 0) out vec4 out_color;

void main() {
    vec2 uv = gl_FragCoord.xy / sky.viewport.xy;  // (0,0) top-left, as in deferred-render
    vec3 color = sky_radiance(view_ray(uv));
    out_color = vec4(color, 1.0);
#ifdef LOOM_PART_HIGH_PASS_RENDER
    emit_high_pass(color);
#endif
}
