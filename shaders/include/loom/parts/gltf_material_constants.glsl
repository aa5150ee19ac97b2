// The constants of glTF material blocks (GltfObjectUniforms in gltf_object.glsl and the retained
// kind's MaterialUniforms in retained_gltf_object.glsl), read by the "gltf-material" part.
#ifndef LOOM_PARTS_GLTF_MATERIAL_CONSTANTS_GLSL
#define LOOM_PARTS_GLTF_MATERIAL_CONSTANTS_GLSL

// Indices of the textures in gltf.uv_transform (two rows each).
const int kGltfBaseColorIndex = 0;
const int kGltfMetallicRoughnessIndex = 1;
const int kGltfNormalIndex = 2;
const int kGltfOcclusionIndex = 3;
const int kGltfEmissiveIndex = 4;

// Bits of gltf.textures.y.
const int kGltfBaseColor = 1;
const int kGltfMetallicRoughness = 2;
const int kGltfNormal = 4;
const int kGltfOcclusion = 8;
const int kGltfEmissive = 16;

// alpha.x
const float kGltfAlphaMask = 1.0;
const float kGltfAlphaBlend = 2.0;

#endif
