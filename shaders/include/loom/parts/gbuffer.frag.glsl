// Pass part "g-buffer" (fragment stage): evaluates the object's material and writes the
// position, normal and albedo maps (packing: loom/passes/gbuffer.glsl).
#include "loom/passes/gbuffer.glsl"

layout(location = 0) out vec4 out_position;
layout(location = 1) out vec4 out_normal;
layout(location = 2) out vec4 out_albedo;

void main() {
    SurfaceInput s = surface_input();
    MaterialSample m = object_material(s);
    out_position = vec4(s.world_position, m.metallic);
    out_normal = vec4(s.world_normal, m.roughness);
    out_albedo = vec4(m.albedo, emission_strength(m));
}
