// How the G-buffer packs a material into four RGBA16F maps (the paper's position, normal and
// albedo maps, Listing 6, and an emission map), so that deferred lighting reads back the same
// MaterialSample:
//   position: xyz world position, a metallic
//   normal:   xyz unit world normal (zero where nothing was drawn), a roughness
//   albedo:   rgb albedo, a 0 (unused)
//   emission: rgb emitted radiance (linear, HDR: strengths above 1 are kept), a 0 (unused)
// Emission has a map of its own because its colour is independent of the albedo's (a black
// button glowing red, a white panel glowing cyan); half floats keep HDR values.
#ifndef LOOM_PASSES_GBUFFER_GLSL
#define LOOM_PASSES_GBUFFER_GLSL

#include "loom/passes/interface.glsl"

MaterialSample unpack_material(vec4 position, vec4 normal, vec4 albedo, vec4 emission) {
    MaterialSample m;
    m.albedo = albedo.rgb;
    m.metallic = position.a;
    m.roughness = normal.a;
    m.emissive = emission.rgb;
    return m;
}

#endif
