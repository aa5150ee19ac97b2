// The per-draw uniforms of mesh objects (object parts "mesh-geometry" and the materials that
// build on it): one block, the object's resource LOOM_BINDING(0) in set 1.
#ifndef LOOM_PASSES_MESH_OBJECT_GLSL
#define LOOM_PASSES_MESH_OBJECT_GLSL

layout(set = LOOM_SET, binding = LOOM_BINDING(0)) uniform ObjectUniforms {
    mat4 model;            // object to world
    mat4 normal_matrix;    // upper 3x3: normals to world (cofactor matrix, sign-corrected)
    vec4 base_color;       // linear RGBA
    vec4 secondary_color;  // linear RGBA (second colour of patterned materials)
    vec4 emissive;         // rgb: emitted radiance
    vec4 material;         // x metallic, y roughness, z pattern scale (cells per world unit)
} object;

#endif
