// Object part "retained-gltf-skinned-geometry" (fragment stage): the material's set, for "gltf-material".
#include "loom/parts/retained_gltf_object.glsl"
