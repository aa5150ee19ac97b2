// Object part "gltf-skinned-geometry" (fragment stage): the object's uniforms, for its material part.
#include "loom/parts/gltf_object.glsl"
