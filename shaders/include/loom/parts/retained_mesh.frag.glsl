// Object part "retained-mesh" (fragment stage): the object's material set, for its material part.
#include "loom/passes/retained_object.glsl"
