// The contract between objects and passes (Hafner, ELS 2019, §4): an object's shader parts say
// how to build a vertex and how to evaluate its material; a pass's parts decide what to do with
// them. loom::passes composes every program from parts and includes this file first, with
// LOOM_STAGE_VERTEX or LOOM_STAGE_FRAGMENT, LOOM_OBJECT (when an object's parts take part) and
// one LOOM_PART_<NAME> per part defined.
//
// Resources: pass parts use descriptor set 0, object parts set 1. A part never writes a
// binding number itself: it writes LOOM_BINDING(k) for its k-th resource (and LOOM_SET for the
// set), and the composer numbers the parts' resources one after another, so parts combine
// without clashes. The C++ side binds resources by the names reflection reports.
#ifndef LOOM_PASSES_INTERFACE_GLSL
#define LOOM_PASSES_INTERFACE_GLSL

#include "loom/common.glsl"

// An object's vertex in world space, as its vertex part builds it.
struct ObjectVertex {
    vec3 world_position;
    vec3 world_normal;  // not necessarily unit length
    vec2 uv;
    vec4 color;
};

// What a pass's fragment stage knows about a surface point; handed to the object's material.
struct SurfaceInput {
    vec3 world_position;
    vec3 world_normal;  // unit length, facing the viewer
    vec2 uv;
    vec4 color;
};

// A material evaluated at a surface point (glTF metallic-roughness model, linear RGB).
struct MaterialSample {
    vec3 albedo;
    float metallic;
    float roughness;
    vec3 emissive;
};

// transform_point and transform_vector (the same bits on both backends) are in loom/common.glsl.

#if defined(LOOM_OBJECT) && defined(LOOM_STAGE_VERTEX)
// Provided by the object's vertex part.
ObjectVertex object_vertex();
#endif

#if defined(LOOM_OBJECT) && defined(LOOM_STAGE_FRAGMENT)
// Provided by the object's material part.
MaterialSample object_material(SurfaceInput surface);
#endif

#if defined(LOOM_PART_SHADOW_RENDER) && defined(LOOM_STAGE_FRAGMENT)
// Provided by the shadow-receiving part: the fraction (0..1) of the directional light that
// reaches a point, from the shadow map.
float shadow_visibility(vec3 world_position, vec3 world_normal);
#endif

#if defined(LOOM_PART_HIGH_PASS_RENDER) && defined(LOOM_STAGE_FRAGMENT)
// Provided by the high-pass part: writes the bright part of `color` to the high-pass output.
void emit_high_pass(vec3 color);
#endif

#endif
