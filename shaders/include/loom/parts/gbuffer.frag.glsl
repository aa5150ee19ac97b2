// Pass part "g-buffer" (fragment stage): evaluates the object's material and writes the
// position, normal, albedo and emission maps (packing: loom/passes/gbuffer.glsl).
#include "loom/passes/gbuffer.glsl"

layout(location = 0) out vec4 out_position;
layout(location = 1) out vec4 out_normal;
layout(location = 2) out vec4 out_albedo;
layout(location = 3) out vec4 out_emission;

void main() {
    SurfaceInput s = surface_input();
    MaterialSample m = object_material(s);
    out_position = vec4(s.world_position, m.metallic);
    out_normal = vec4(s.world_normal, m.roughness);
    out_albedo = vec4(m.albedo, 0.0);
    out_emission = vec4(m.emissive, 0.0);
}
