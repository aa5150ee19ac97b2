// The uniform sets of retained mesh objects (object part "retained-mesh", loom::passes::
// RetainedScene), its resources LOOM_BINDING(0) and (1) in set 1:
//   - per object (vertex stage): one ObjectRecord per submitted object, all in one storage buffer; a draw
//     finds its object's record through the per-instance attribute in_object_index (the
//     scene's instance list, offset by each draw's first instance);
//   - per material (fragment stage): MaterialUniforms, bound at the material's offset in the scene's material
//     buffer. Its instance is named `object` and its members are those of ObjectUniforms
//     (loom/passes/mesh_object.glsl), so the material parts of the mesh kinds ("pbr-material",
//     "checker-material") read it unchanged.
#ifndef LOOM_PASSES_RETAINED_OBJECT_GLSL
#define LOOM_PASSES_RETAINED_OBJECT_GLSL

// Each stage declares only what it reads, so that a pass leaving the object's fragment parts out
// (the shadow map) has no material block in its program and binds no material.
#include "loom/passes/object_records.glsl"

#ifdef LOOM_STAGE_FRAGMENT
layout(std140, set = LOOM_SET, binding = LOOM_BINDING(1)) uniform MaterialUniforms {
    vec4 base_color;       // linear RGBA
    vec4 secondary_color;  // linear RGBA (second colour of patterned materials)
    vec4 emissive;         // rgb: emitted radiance
    vec4 material;         // x metallic, y roughness, z pattern scale (cells per world unit)
} object;
#endif

#endif
