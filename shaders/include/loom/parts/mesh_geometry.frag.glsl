// Object part "mesh-geometry" (fragment stage): the object's uniforms, for its material part.
#include "loom/passes/mesh_object.glsl"
