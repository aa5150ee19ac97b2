// Per-draw data of the scene passes (set 1): the object's transform and its glTF material.
// Mirrors DrawUniforms in samples/engine/engine_frame.cpp (std140).
#ifndef ENGINE_DRAW_GLSL
#define ENGINE_DRAW_GLSL

// Bits of `textures.y`: which material textures are bound (the rest read the white fallback).
const int kBaseColorTexture = 1;
const int kMetallicRoughnessTexture = 2;
const int kNormalTexture = 4;
const int kOcclusionTexture = 8;
const int kEmissiveTexture = 16;

layout(set = 1, binding = 0, std140) uniform Draw {
    mat4 model;
    mat4 normal_matrix;
    vec4 base_color;   // linear rgba factor
    vec4 emissive;     // linear rgb factor (strength included), 0
    vec4 factors;      // metallic, roughness, normal scale, occlusion strength
    vec4 alpha;        // mode (0 opaque, 1 mask, 2 blend), cutoff, 0, 0
    ivec4 uv_sets;     // base colour, metallic-roughness, normal, occlusion
    ivec4 textures;    // emissive UV set, texture bits, 0, 0
} draw;

vec2 pick_uv(int set, vec2 uv0, vec2 uv1) { return set == 1 ? uv1 : uv0; }

#endif
