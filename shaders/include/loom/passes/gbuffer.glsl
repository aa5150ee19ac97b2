// How the G-buffer packs a material into three RGBA16F maps (the paper's position, normal and
// albedo maps, Listing 6), so that deferred lighting reads back the same MaterialSample:
//   position: xyz world position, a metallic
//   normal:   xyz unit world normal (zero where nothing was drawn), a roughness
//   albedo:   rgb albedo, a emission strength (emissive = albedo * strength)
// Emission is stored as a multiple of the albedo: exact for materials that glow in their own
// colour; other emissive colours keep their luminance and take the albedo's hue.
#ifndef LOOM_PASSES_GBUFFER_GLSL
#define LOOM_PASSES_GBUFFER_GLSL

#include "loom/passes/interface.glsl"

float emission_strength(MaterialSample m) {
    return luminance(m.emissive) / max(luminance(m.albedo), 1e-4);
}

MaterialSample unpack_material(vec4 position, vec4 normal, vec4 albedo) {
    MaterialSample m;
    m.albedo = albedo.rgb;
    m.metallic = position.a;
    m.roughness = normal.a;
    m.emissive = albedo.rgb * albedo.a;
    return m;
}

#endif
