// Object part "retained-gltf-geometry" (fragment stage): the material's set, for "gltf-material".
#include "loom/parts/retained_gltf_object.glsl"
