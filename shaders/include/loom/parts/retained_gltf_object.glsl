// The uniform sets of retained glTF mesh objects (object kind "retained-gltf-mesh", drawn by a
// loom::passes::RetainedScene), declared by the "retained-gltf-geometry" part as its resources
// LOOM_BINDING(0) and (1) in set 1, as the retained convention asks (loom/passes/retained_object.glsl):
//   - per object (vertex stage): the ObjectRecords storage buffer, found through the per-instance
//     in_object_index;
//   - per material (fragment stage): MaterialUniforms, bound at the material's offset. Its
//     instance is named `gltf` and its members are those of GltfObjectUniforms
//     (loom/parts/gltf_object.glsl) after the two matrices, so the "gltf-material" part reads it
//     unchanged. Mirrored in C++ by loom::renderer (retained_gltf_scene.cpp).
#ifndef LOOM_PARTS_RETAINED_GLTF_OBJECT_GLSL
#define LOOM_PARTS_RETAINED_GLTF_OBJECT_GLSL

#include "loom/passes/object_records.glsl"
#include "loom/parts/gltf_material_constants.glsl"

#ifdef LOOM_STAGE_FRAGMENT
layout(std140, set = LOOM_SET, binding = LOOM_BINDING(1)) uniform MaterialUniforms {
    vec4 base_color_factor;   // linear RGBA
    vec4 emissive_factor;     // rgb: linear emitted radiance factor
    vec4 factors;             // x metallic, y roughness, z normal scale, w occlusion strength
    vec4 alpha;               // x alpha mode (0 opaque, 1 mask, 2 blend), y cutoff
    ivec4 uv_sets;            // UV set (0 or 1) of base colour, metallic-roughness, normal, occlusion
    ivec4 textures;           // x UV set of emissive, y which textures are bound (kGltf* bits)
    vec4 uv_transform[10];    // two rows of each texture's KHR_texture_transform matrix
} gltf;
#endif

#endif
