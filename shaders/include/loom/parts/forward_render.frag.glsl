// Pass part "forward-render" (fragment stage): lights each object while it is drawn, with the
// same lighting as the deferred pass. Combines with "shadow-render" and "high-pass-render"
// exactly as "deferred-render" does.
#include "loom/passes/lighting.glsl"

layout(location = 0) out vec4 out_color;

void main() {
    SurfaceInput s = surface_input();
    MaterialSample m = object_material(s);
    float visibility = 1.0;
#ifdef LOOM_PART_SHADOW_RENDER
    visibility = shadow_visibility(s.world_position, s.world_normal);
#endif
    vec3 color = shade(s.world_position, s.world_normal, m, visibility);
    out_color = vec4(color, 1.0);
#ifdef LOOM_PART_HIGH_PASS_RENDER
    emit_high_pass(color);
#endif
}
