// Pass part "blend-render" (fragment stage): lights a blended surface (glTF alphaMode BLEND) as
// the forward pass lights an opaque one, and writes the colour with the surface's alpha, for
// "over" blending onto the lit frame. Objects drawn with it provide object_alpha() (the
// "gltf-material" part does). With "shadow-render" the light is shadowed; with
// "high-pass-render" (composed before this part) the bright part goes to the high-pass output
// with the same alpha, so bloom sees the blended frame too.
#include "loom/passes/lighting.glsl"

layout(location = 0) out vec4 out_color;

void main() {
    SurfaceInput s = surface_input();
    MaterialSample m = object_material(s);
    float alpha = object_alpha();
    float visibility = 1.0;
#ifdef LOOM_PART_SHADOW_RENDER
    visibility = shadow_visibility(s.world_position, s.world_normal);
#endif
    vec3 color = shade(s.world_position, s.world_normal, m, visibility);
    out_color = vec4(color, alpha);
#ifdef LOOM_PART_HIGH_PASS_RENDER
    out_high_pass = vec4(high_pass(color), alpha);
#endif
}
