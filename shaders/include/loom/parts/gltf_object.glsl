// The per-draw uniforms of glTF mesh objects (object kind "gltf-mesh"): one block, declared by
// the "gltf-geometry" part as its resource LOOM_BINDING(0) in set 1 and read by its vertex stage
// and by the "gltf-material" part. Mirrored in C++ by loom::renderer (gltf_object.cpp).
#ifndef LOOM_PARTS_GLTF_OBJECT_GLSL
#define LOOM_PARTS_GLTF_OBJECT_GLSL

#include "loom/parts/gltf_material_constants.glsl"

layout(set = LOOM_SET, binding = LOOM_BINDING(0)) uniform GltfObjectUniforms {
    mat4 model;               // object to world
    mat4 normal_matrix;       // upper 3x3: normals to world (cofactor matrix, sign-corrected)
    vec4 base_color_factor;   // linear RGBA
    vec4 emissive_factor;     // rgb: linear emitted radiance factor
    vec4 factors;             // x metallic, y roughness, z normal scale, w occlusion strength
    vec4 alpha;               // x alpha mode (0 opaque, 1 mask, 2 blend), y cutoff,
                              // z -1 when the model matrix mirrors, else +1
    ivec4 uv_sets;            // UV set (0 or 1) of base colour, metallic-roughness, normal, occlusion
    ivec4 textures;           // x UV set of emissive, y which textures are bound (kGltf* bits)
    // Per texture (base colour, metallic-roughness, normal, occlusion, emissive) the two rows
    // of its KHR_texture_transform matrix: uv' = (dot(row0.xyz, (u, v, 1)), dot(row1.xyz, ...)).
    // The identity gives back u and v exactly (products by 1 and 0), so untransformed textures
    // sample as before.
    vec4 uv_transform[10];
} gltf;

#endif
